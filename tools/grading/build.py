"""The tree the grader builds, the build, and one stage's tests, each step in the sandbox.

The tree (work/src) is the instructor's (its build files, common/, stages/, tests/ with the hidden
ones, assets/) with only the submission's editable files put in (submission.py), so a student's
CMakeLists.txt, tests or references never count. A file whose bytes are already there is left
alone and every other one is written anew, so a build folder kept from an earlier grading
recompiles exactly what changed (ninja goes by modification times).

The build folder is written only by cmake, ninja and the compiler: test discovery is deferred to
ctest (which the grader does not use), so building runs none of the code it compiles, and a build
folder can be kept from one grading to the next. While a student's code is compiled, the hidden
tests' sources read as empty files, so a compile error cannot print them into the visible report;
they are compiled in a step of their own, whose log only the instructor sees.

A prepared build (`tools/grade.py --prepare DIR`) is the instructor's tree with every editable
file as the starter's, configured and built once for every stage and its hidden tests. Grading a
submission with it copies DIR/src and DIR/build (modification times kept) into the submission's
work folder, puts the submission's files in, and lets ninja compile only the files that differ
from the starter's and relink: a stage a student did not touch costs nothing. Every step sees the
copy at DIR's own paths (the build files name them), through the sandbox's bind mounts.

Tests run one by one, each in a sandbox of its own that sees the assets, its test program and the
stage programs only. A test passes only when its process ends with 0 AND GoogleTest's XML report,
which it writes after the last test of a normal run, says that the test ran and passed: a test
that ends its process early (exit, _exit, a crash, a kill) has no report and fails.

A judged test program (grading/manifest.json, "judged_programs") runs each test twice
(tests/support/subject.h): the subject, the program built with the submission, records the values
its code gives the test; the judge, the same program built from the starter (copied into the
prepared folder's judges/ before any submission's file is compiled), reads them back without
running any of the submission's code, decides, and writes the report that alone counts. The judge
runs in a sandbox of its own, as another user, seeing the assets, its program and the record only:
what the subject writes, its own report included, never counts.
"""
import concurrent.futures
import dataclasses
import hashlib
import json
import os
import pathlib
import re
import shutil
import subprocess
import xml.etree.ElementTree as ElementTree

from . import files

INSTRUCTOR_PARTS = ("CMakeLists.txt", "CMakePresets.json", "cmake/", "common/", "stages/", "tests/", "assets/",
                    "tools/merge/")
NEVER_COPIED = ("tests/grading/",)  # the grader's proofs hold solution lines
MAX_REPORT_BYTES = 4 << 20
MAX_RECORD_BYTES = 1 << 30  # tests/support/subject.cpp refuses more
JUDGES = "judges"  # in a prepared folder: the starter's test programs, which judge (see above)
REPLAY_FAILED = 86  # a judge's exit code when the subject's record is not what the test asked for


def instructor_files(root, hidden):
    """Relative path -> path of the instructor's files the graded tree is made of."""
    root = pathlib.Path(root)
    skipped = {".git", "build", "out", "__pycache__"}
    found = {}
    for path in root.rglob("*"):
        relative = path.relative_to(root).as_posix()
        if skipped & set(path.relative_to(root).parts) or not path.is_file() or path.is_symlink():
            continue
        if not relative.startswith(INSTRUCTOR_PARTS) or relative.startswith(NEVER_COPIED):
            continue
        if not hidden and relative.startswith("tests/hidden/"):
            continue
        found[relative] = path
    return found


def tree_files(taken, root, hidden):
    """Relative path -> bytes of the tree to build: the instructor's files, the taken ones in place."""
    wanted = {name: path.read_bytes() for name, path in instructor_files(root, hidden).items()}
    wanted.update(taken.files)
    return wanted


def fingerprint(wanted):
    """A digest of a tree's files (tree_files): a prepared build's judges are this tree's only while
    the starter tree it was made from has the same one."""
    digest = hashlib.sha256()
    for name in sorted(wanted):
        digest.update(name.encode() + b"\0" + hashlib.sha256(wanted[name]).digest())
    return digest.hexdigest()


def prepare_tree(taken, root, source, hidden):
    """Makes `source` the instructor's files with the submission's taken files in their place."""
    source = pathlib.Path(source)
    source.mkdir(parents=True, exist_ok=True)
    source.chmod(0o755)
    wanted = tree_files(taken, root, hidden)
    present = {p.relative_to(source).as_posix(): p for p in source.rglob("*") if p.is_file() or p.is_symlink()}
    for name in present.keys() - wanted.keys():
        present[name].unlink()
    for name, data in wanted.items():
        target = source / name
        if name in present and not target.is_symlink() and target.read_bytes() == data:
            continue
        files.write_beneath(source, name, data)
    return source


def hidden_sources(source):
    return sorted(p for p in (pathlib.Path(source) / "tests" / "hidden").glob("*") if p.suffix in {".cpp", ".h"})


PREPARED_MARK = "prepared.json"


def keep_judges(build, folder):
    """Copies the starter build's test programs into folder/judges, read-only, before any
    submission's file is built there."""
    judges = pathlib.Path(folder) / JUDGES
    files.remove_tree(judges)
    judges.mkdir()
    for program in sorted((pathlib.Path(build) / "bin").glob("*_tests")):
        shutil.copy2(program, judges / program.name)
        (judges / program.name).chmod(0o555)
    judges.chmod(0o555)


def copy_prepared(prepared, work):
    """Copies a prepared build's src and build into `work`, modification times and owners kept,
    unless `work` already holds a build (an earlier grading's, which ninja brings up to date)."""
    prepared, work = pathlib.Path(prepared), pathlib.Path(work)
    if (work / "build" / "build.ninja").exists():
        return
    for part in ("src", "build"):
        files.remove_tree(work / part)
        subprocess.run(["cp", "-a", "--reflink=auto", str(prepared / part), str(work / part)], check=True)


class Builder:
    """The build of one tree in `work` (src, build, scratch) through a sandbox. The steps see src
    and build under `seen_at` (default: `work` itself): a prepared build's folder, for a copy."""

    def __init__(self, sandbox, work, jobs, deadline, seen_at=None, judges=None, judged=()):
        self.sandbox, self.jobs, self.deadline = sandbox, jobs, deadline
        self.judges, self.judged = judges, set(judged)  # a folder of judges; the programs they judge
        self.work = pathlib.Path(work)
        self.source, self.build = self.work / "src", self.work / "build"
        seen_at = pathlib.Path(seen_at or work)
        self.seen = {self.source: seen_at / "src", self.build: seen_at / "build"}
        self.scratch = self.work / "scratch"
        for folder in (self.build, self.scratch):
            folder.mkdir(parents=True, exist_ok=True)
            self.own(folder)

    def seen_path(self, path):
        """Where a step sees `path` (a host path, under src or build or elsewhere)."""
        path = pathlib.Path(path)
        for host, seen in self.seen.items():
            if path == host or host in path.parents:
                return seen / path.relative_to(host)
        return path

    def bound(self, path):
        """`path` as a sandbox entry: (host path, path the step sees)."""
        return pathlib.Path(path), self.seen_path(path)

    def _step(self, command, log, limit, masked=()):
        timeout = self.deadline.timeout(limit)
        if timeout <= 0:
            with open(log, "a") as out:
                out.write(f"not run: the time cap of {self.deadline.cap:g} s was reached\n")
            return False
        # The build folder is the step's one writable folder (its HOME and TMPDIR too).
        result = self.sandbox.run(command, log, timeout, read_only=[self.bound(self.source)],
                                  writable=[self.bound(self.build)], masked=[self.seen_path(p) for p in masked],
                                  cwd=self.seen_path(self.build))
        return result.code == 0

    def own(self, path, judge=False):
        """Hands a folder a step writes to the sandbox's user (or the judges')."""
        owner = self.sandbox.owner_of_scratch(judge)
        if owner is not None:
            os.chown(path, owner, owner)

    def configure(self, log):
        """Release, warnings not errors (a warning costs a student nothing here; CI checks the
        instructor's tree with -Werror), test discovery deferred to ctest time. The standard
        library's bounds checks are on (_GLIBCXX_ASSERTIONS): an index past the end of a std::array
        or std::vector stops the test that made it, where a plain release build would go on with
        whatever it overwrote."""
        return self._step(["cmake", "-S", str(self.seen_path(self.source)), "-B", str(self.seen_path(self.build)),
                           "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS=-D_GLIBCXX_ASSERTIONS",
                           "-DRT_BUILD_BENCHMARKS=OFF", "-DRT_WARNINGS_AS_ERRORS=OFF", "-DRT_USE_CCACHE=OFF",
                           "-DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST"], log, 300)

    def build_stage(self, stage, log):
        """The stage's program and tests (every stage program: the tests of a stage run them)."""
        targets = [f"stage{stage}", f"stage{stage}_tests"]
        return self._step(["cmake", "--build", str(self.seen_path(self.build)), "-j", str(self.jobs), "--target",
                           *targets], log, 1800,
                          masked=hidden_sources(self.source))

    def build_hidden(self, stage, log):
        if not hidden_sources(self.source):
            return True
        return self._step(["cmake", "--build", str(self.seen_path(self.build)), "-j", str(self.jobs), "--target",
                           f"stage{stage}_hidden_tests"], log, 1800)

    def programs(self):
        return [p for p in sorted((self.build / "bin").glob("stage[0-9]")) if p.is_file()]

    def run_tests(self, tests, logs, timeout):
        """Runs each test ({"name", "program"}) in its own sandbox; name -> TestResult."""
        logs = pathlib.Path(logs)
        files.remove_tree(logs)  # a kept work folder holds the last grading's
        logs.mkdir(parents=True)
        slots = [self.scratch / f"test{slot}" for slot in range(self.jobs)]
        free = list(slots)
        results = {}

        def one(index, test):
            slot = free.pop()
            try:
                return run_one_test(self, test, slot, logs / f"{index:04d}.log", timeout)
            finally:
                free.append(slot)

        with concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs) as pool:
            for result in pool.map(lambda item: one(*item), enumerate(tests)):
                results[result.name] = result
        return results


@dataclasses.dataclass
class TestResult:
    name: str
    passed: bool
    seconds: float
    output: str


def run_one_test(builder, test, slot, log, timeout):
    name, program = test["name"], builder.build / "bin" / test["program"]
    if not program.is_file():
        return TestResult(name, False, 0.0, f"{test['program']} was not built")
    step = builder.deadline.timeout(timeout)
    if step <= 0:
        return TestResult(name, False, 0.0, f"not run: the time cap of {builder.deadline.cap:g} s was reached")
    if test["program"] in builder.judged:
        return run_judged_test(builder, test, slot, log, step)
    fresh_folder(builder, slot)
    report = slot / "report.xml"
    read_only = [builder.bound(p) for p in dict.fromkeys([builder.source / "assets", program, *builder.programs()])]
    result = builder.sandbox.run([str(builder.seen_path(program)), f"--gtest_filter={name}",
                                  f"--gtest_output=xml:{report}"], log, step, read_only=read_only, writable=[slot],
                                 cwd=slot)
    verdict = judge(name, result, slot)
    files.remove_tree(slot)
    return TestResult(name, verdict is None, result.seconds, test_output(files.head_and_tail_of(log, 20000), verdict))


def fresh_folder(builder, path, judge=False):
    """An empty folder at `path`, owned by the sandbox's user (or the judges')."""
    files.remove_tree(path)
    path.mkdir()
    builder.own(path, judge)
    return path


def run_judged_test(builder, test, slot, log, step):
    """The subject run, then the judge's (see the top of this file); the judge's report decides.
    Both runs work in the same folder (their working directory and TMPDIR), made anew for each and
    owned by its user, so that the paths a test builds (a scratch folder named in an error message)
    come out the same in both."""
    name, program = test["name"], builder.build / "bin" / test["program"]
    fresh_folder(builder, slot)
    here = fresh_folder(builder, slot.with_name(slot.name + "-here"))
    read_only = [builder.bound(p) for p in dict.fromkeys([builder.source / "assets", program, *builder.programs()])]
    subject = builder.sandbox.run([str(builder.seen_path(program)), f"--gtest_filter={name}"], log, step,
                                  read_only=read_only, writable=[slot, here], cwd=here,
                                  environment={"RT_GRADING_RECORD": str(slot / "record.bin"), "TMPDIR": str(here)})
    files.remove_tree(here)
    said = files.head_and_tail_of(log, 20000)
    if subject.timed_out:
        files.remove_tree(slot)
        return TestResult(name, False, subject.seconds, test_output(said, "Timeout: the test ran longer than its "
                                                                          "limit and was killed"))
    try:
        record = files.read_beneath(slot, "record.bin", MAX_RECORD_BYTES)
    except FileNotFoundError:
        record = b""
    except (files.Refused, OSError) as e:
        record = None
        refused = f"the test's record of its values was refused ({e})"
    files.remove_tree(slot)
    if record is None:
        return TestResult(name, False, subject.seconds, test_output(said, refused))
    # The judge's own folder, which the subject never saw, with the record read-only in it.
    bench = fresh_folder(builder, slot.with_name(slot.name + "-judge"), judge=True)
    (bench / "record.bin").write_bytes(record)
    (bench / "record.bin").chmod(0o444)
    judge_program = builder.judges / test["program"] if builder.judges else None
    if judge_program is None or not judge_program.is_file():
        files.remove_tree(bench)
        return TestResult(name, False, subject.seconds, test_output(said, "the test's judge was not built (the "
                                                                         "starter's build failed or was cut short)"))
    judge_log = log.with_suffix(".judge.log")
    judge_log.write_text("")
    remaining = builder.deadline.timeout(step)
    result = builder.sandbox.run([str(judge_program), f"--gtest_filter={name}",
                                  f"--gtest_output=xml:{bench / 'report.xml'}"], judge_log, max(remaining, 1),
                                 read_only=[builder.bound(builder.source / "assets"), judge_program],
                                 writable=[bench, fresh_folder(builder, here, judge=True)], cwd=here,
                                 environment={"RT_GRADING_REPLAY": str(bench / "record.bin"), "TMPDIR": str(here)},
                                 judge=True)
    judged = files.head_and_tail_of(judge_log, 20000)
    verdict = judge(name, result, bench)
    if result.code == REPLAY_FAILED:
        verdict = "\n".join(line[len("grading: "):] for line in judged.splitlines() if line.startswith("grading: ")) \
            or verdict
    files.remove_tree(bench)
    files.remove_tree(here)
    return TestResult(name, verdict is None, subject.seconds + result.seconds, test_output(said, verdict))


# GoogleTest's frame around one test's run, which says nothing a report needs.
GTEST_FRAME = re.compile(r"^(\$ |Running main\(\) from|Note: Google Test filter|\[==========\]|\[----------\]|"
                         r"\[ RUN      \]|\[       OK \]|\[  PASSED  \]|\[  FAILED  \]| 1 FAILED TEST|$)")


def test_output(said, verdict):
    """What a report shows of a test: its own output (GoogleTest's failures with their lines, a
    placeholder's TODO line) without GoogleTest's frame, up to its summary, and then why it did
    not pass unless its failures already say so."""
    lines = said.split("\n[  FAILED  ] 1 test, listed below:")[0].splitlines()
    output = "\n".join(line for line in lines if not GTEST_FRAME.match(line))
    if verdict and not all(part.strip() in output for part in verdict.splitlines()):
        output += ("\n" if output else "") + verdict
    return output.strip()


def judge(name, result, slot):
    """Why the test did not pass, or None when it did: its exit code and its own report agree."""
    if result.timed_out:
        return "Timeout: the test ran longer than its limit and was killed"
    try:
        xml = files.read_beneath(slot, "report.xml", MAX_REPORT_BYTES)
    except (FileNotFoundError, files.Refused, OSError):
        return (f"the test process ended (exit code {result.code}) without GoogleTest's report: it did not finish "
                "normally (a task that calls exit or _exit, a crash, or a kill)")
    if b"<!DOCTYPE" in xml or b"<!ENTITY" in xml:  # GoogleTest writes none: entity expansion is an attack
        return "GoogleTest's report is malformed (it declares entities): the test did not finish normally"
    try:
        root = ElementTree.fromstring(xml)
    except ElementTree.ParseError:
        return "GoogleTest's report is truncated or malformed: the test did not finish normally"
    cases = [c for c in root.iter("testcase") if f"{c.get('classname')}.{c.get('name')}" == name]
    if len(cases) != 1 or sum(1 for _ in root.iter("testcase")) != 1:
        return "GoogleTest's report does not hold exactly this test"
    case = cases[0]
    failures = [f.get("message") or "" for f in case.iter("failure")] + [e.get("message") or "" for e in case.iter("error")]
    if failures:
        return "\n".join(failures)
    if case.get("status") != "run" or case.get("result", "completed") != "completed":
        return f"the test did not run to completion ({case.get('result') or case.get('status')})"
    if result.code != 0:
        return f"the test process exited with {result.code} after its report said it passed"
    return None


def list_tests(build):
    """The tests of every stage label in an instructor's build: {stage: [{"name", "program"}]}, from
    ctest's listing (which runs the test programs to discover their tests: the instructor's own)."""
    listing = json.loads(subprocess.run(["ctest", "--test-dir", str(build), "--show-only=json-v1"], check=True,
                                        capture_output=True, text=True).stdout)
    stages = {}
    for test in listing["tests"]:
        labels = next((p["value"] for p in test.get("properties", []) if p["name"] == "LABELS"), [])
        for label in labels:
            if m := re.fullmatch(r"stage(\d+)", label):
                name = test["name"].split("  # GetParam()")[0]
                stages.setdefault(m.group(1), []).append({"name": name, "program": pathlib.Path(test["command"][0]).name})
    return {stage: sorted(tests, key=lambda t: (t["program"], t["name"])) for stage, tests in sorted(stages.items())}
