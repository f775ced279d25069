"""Builds a tree for grading and runs one stage's tests, with time limits.

The tree is copied to a work folder first, so grading never writes into a student's folder. The
copy gets the instructor's tests/ (the visible tests as published, plus tests/hidden/) and assets/
(the scenes and references the tests read), so editing a test or a reference does not change a
grade.
"""
import dataclasses
import filecmp
import pathlib
import shutil
import subprocess
import time
import xml.etree.ElementTree as ElementTree

IGNORED_PARTS = {".git", "build", "out", "__pycache__"}
INSTRUCTOR_FOLDERS = ("tests", "assets")


def files_of(folder):
    """Relative path -> file, for every file under `folder` outside build and version-control folders."""
    folder = pathlib.Path(folder)
    return {p.relative_to(folder).as_posix(): p for p in folder.rglob("*")
            if p.is_file() and not IGNORED_PARTS & set(p.relative_to(folder).parts)}


def prepare_tree(tree, instructor_root, work):
    """Makes work/src a copy of `tree` with the instructor's tests and assets; returns its path.

    A file whose bytes are already there is left alone and every other one is written anew, so a
    build folder kept from an earlier grading recompiles exactly what changed (ninja goes by
    modification times, and a copied file's old time would hide a change)."""
    source = pathlib.Path(work) / "src"
    wanted = {name: path for name, path in files_of(tree).items() if not name.startswith(tuple(f + "/" for f in INSTRUCTOR_FOLDERS))}
    for folder in INSTRUCTOR_FOLDERS:
        wanted.update({f"{folder}/{name}": path for name, path in files_of(pathlib.Path(instructor_root) / folder).items()})
    present = files_of(source) if source.exists() else {}
    for name in present.keys() - wanted.keys():
        present[name].unlink()
    for name, path in wanted.items():
        target = source / name
        if name in present and filecmp.cmp(path, target, shallow=False):
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(path, target)
        shutil.copymode(path, target)
    return source


def run(command, log, timeout, cwd=None):
    """Runs a command with its output appended to `log`; returns (exit code, seconds). A command
    that outlives `timeout` is killed and reported as exit code 124."""
    start = time.monotonic()
    with open(log, "a") as out:
        out.write(f"$ {' '.join(map(str, command))}\n")
        out.flush()
        try:
            code = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, timeout=timeout, cwd=cwd).returncode
        except subprocess.TimeoutExpired:
            out.write(f"killed after {timeout} s\n")
            code = 124
    return code, time.monotonic() - start


def configure(source, build, log):
    """Release build without warnings as errors: a warning costs a student nothing here (CI checks
    the instructor's tree with -Werror)."""
    return run(["cmake", "-S", source, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                "-DRT_BUILD_BENCHMARKS=OFF", "-DRT_WARNINGS_AS_ERRORS=OFF"], log, timeout=300)[0] == 0


def build_stage(build, stage, log, jobs):
    """The stage's program, its tests and its hidden tests (if the tree has them)."""
    targets = [f"stage{stage}", f"stage{stage}_tests"]
    if (pathlib.Path(build) / "tests" / "hidden").exists():
        targets.append(f"stage{stage}_hidden_tests")
    return run(["cmake", "--build", build, "-j", str(jobs), "--target", *targets], log, timeout=1800)[0] == 0


@dataclasses.dataclass
class TestResult:
    name: str
    passed: bool
    seconds: float
    output: str


def run_stage_tests(build, stage, junit, log, jobs, timeout):
    """ctest for the label stageN, each test limited to `timeout` seconds; the results by name."""
    run(["ctest", "--test-dir", build, "-L", f"^stage{stage}$", "-j", str(jobs), "--timeout", str(timeout),
         "--output-junit", junit], log, timeout=3600)
    return read_junit(junit)


def read_junit(path):
    results = {}
    if not pathlib.Path(path).exists():
        return results
    for case in ElementTree.parse(path).getroot().iter("testcase"):
        output = "".join(node.text or "" for node in case.iter("system-out"))
        failure = case.find("failure")
        if failure is not None:
            output = (failure.get("message") or "") + "\n" + output
        passed = case.get("status") == "run" and failure is None and case.find("error") is None
        name = case.get("name").split("  # GetParam()")[0]  # a parameterized test's name, without its value
        results[name] = TestResult(name, passed, float(case.get("time") or 0), output.strip())
    return results
