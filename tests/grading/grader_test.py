#!/usr/bin/env python3
"""Unit tests of the grader's defences (ctest grader_defences, label common; seconds).

What tools/grading/ promises against a hostile submission, one piece at a time: files are read and
written without following links, a test passes only on its own complete report, only the listed
tests are scored, the time cap cuts every step, and the sandbox keeps a step inside its scratch
folder, off the network, within its limits and without survivors. The whole grader is proved end
to end by check_grading.py (CI).
"""
import json
import os
import pathlib
import shutil
import stat
import subprocess
import sys
import tempfile
import time
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
# The grader needs numpy, which Debian's Python has (tools/setup.sh); another python3 may come first.
GRADER_PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
sys.path.insert(0, str(ROOT / "tools"))
from grading import build, files, manifest, sandbox, submission  # noqa: E402


class Folder:
    """A temporary folder every user may enter (the sandbox's user reads what a step binds)."""

    def __enter__(self):
        self.path = pathlib.Path(tempfile.mkdtemp(prefix="grader-test-"))
        self.path.chmod(0o755)
        return self.path

    def __exit__(self, *_):
        files.remove_tree(self.path)


class ReadingAndWriting(unittest.TestCase):
    def test_a_regular_file_is_read(self):
        with Folder() as d:
            (d / "a").mkdir()
            (d / "a" / "f.cpp").write_bytes(b"int x;\n")
            self.assertEqual(files.read_beneath(d, "a/f.cpp", 100), b"int x;\n")

    def test_links_fifos_devices_and_big_files_are_refused(self):
        with Folder() as d:
            (d / "secret").write_text("solution")
            (d / "tree" / "sub").mkdir(parents=True)
            (d / "tree" / "link.cpp").symlink_to(d / "secret")
            (d / "tree" / "folder").symlink_to(d / "tree" / "sub")
            (d / "tree" / "sub" / "f.cpp").write_text("x")
            os.mkfifo(d / "tree" / "fifo.cpp")
            (d / "tree" / "big.cpp").write_bytes(b"x" * 101)
            (d / "tree" / "kmsg.cpp").symlink_to("/proc/kmsg")
            for name, why in [("link.cpp", "a symbolic link"), ("folder/f.cpp", "is a symbolic link"),
                              ("fifo.cpp", "a FIFO"), ("big.cpp", "101 bytes"), ("kmsg.cpp", "a symbolic link"),
                              ("../secret", "a path through")]:
                with self.assertRaises(files.Refused, msg=name) as refused:
                    files.read_beneath(d / "tree", name, 100)
                self.assertIn(why, str(refused.exception), name)
            with self.assertRaises(files.Refused) as refused:
                files.read_beneath("/dev", "zero", 100)
            self.assertEqual(str(refused.exception), "a device")
            with self.assertRaises(FileNotFoundError):
                files.read_beneath(d / "tree", "none.cpp", 100)
            self.assertEqual(files.read_beneath(d / "tree", "big.cpp", 101), b"x" * 101)  # the limit itself

    def test_a_planted_link_never_sends_a_write_elsewhere(self):
        with Folder() as d:
            (d / "victim").write_text("precious")
            (d / "outside").mkdir()
            (d / "src").mkdir()
            (d / "src" / "f.cpp").symlink_to(d / "victim")
            (d / "src" / "dir").symlink_to(d / "outside")
            files.write_beneath(d / "src", "f.cpp", b"new")
            self.assertEqual((d / "victim").read_text(), "precious")
            self.assertEqual((d / "src" / "f.cpp").read_bytes(), b"new")
            self.assertFalse((d / "src" / "f.cpp").is_symlink())
            with self.assertRaises(OSError):
                files.write_beneath(d / "src", "dir/g.cpp", b"new")
            self.assertEqual(list((d / "outside").iterdir()), [])

    def test_an_atomic_write_leaves_the_new_file_and_nothing_else(self):
        with Folder() as d:
            (d / "results.json").write_text("old")
            files.write_atomically(d / "results.json", "new")
            self.assertEqual((d / "results.json").read_text(), "new")
            self.assertEqual([p.name for p in d.iterdir()], ["results.json"])

    def test_a_tree_a_step_locked_up_is_removed(self):
        with Folder() as d:
            (d / "t" / "locked").mkdir(parents=True)
            (d / "t" / "locked" / "f").write_text("x")
            (d / "t" / "link").symlink_to(d)
            (d / "t" / "locked").chmod(0)
            files.remove_tree(d / "t")
            self.assertFalse((d / "t").exists())
            self.assertTrue(d.exists(), "the link's target survives")


def case(name="T.a", status="run", result="completed", failure=None, extra=""):
    suite, test = name.split(".", 1)
    inner = f'<failure message="{failure}"/>' if failure else ""
    return (f'<?xml version="1.0"?><testsuites tests="1"><testsuite name="{suite}">'
            f'<testcase name="{test}" classname="{suite}" status="{status}" result="{result}">{inner}</testcase>'
            f'{extra}</testsuite></testsuites>')


class TheTestVerdict(unittest.TestCase):
    def verdict(self, xml, code=0, timed_out=False):
        with Folder() as d:
            if xml is not None:
                (d / "report.xml").write_text(xml)
            return build.judge("T.a", sandbox.Result(code, 0.1, timed_out), d)

    def test_a_passing_report_and_exit_0_pass(self):
        self.assertIsNone(self.verdict(case()))

    def test_exit_0_without_a_report_fails(self):
        # What a task that calls _exit(0) leaves: ctest would have counted it as passed.
        self.assertIn("without GoogleTest's report", self.verdict(None, code=0))

    def test_a_truncated_or_entity_laden_report_fails(self):
        self.assertIn("truncated", self.verdict(case()[:60]))
        laughs = '<?xml version="1.0"?><!DOCTYPE t [<!ENTITY a "aaaaaaaaaa">]>' + case().split("?>", 1)[1]
        self.assertIn("declares entities", self.verdict(laughs))

    def test_a_failure_in_the_report_fails_with_its_message(self):
        self.assertEqual(self.verdict(case(failure="Expected 1, got 2"), code=1), "Expected 1, got 2")

    def test_a_report_of_another_or_more_tests_fails(self):
        self.assertIn("exactly this test", self.verdict(case(name="T.b")))
        extra = '<testcase name="c" classname="T" status="run" result="completed"/>'
        self.assertIn("exactly this test", self.verdict(case(extra=extra)))

    def test_a_skipped_test_or_a_bad_exit_code_fails(self):
        self.assertIn("did not run to completion", self.verdict(case(result="skipped")))
        self.assertIn("exited with 3", self.verdict(case(), code=3))
        self.assertIn("Timeout", self.verdict(case(), timed_out=True))


class Scoring(unittest.TestCase):
    def test_only_listed_tests_count_and_unrun_ones_fail(self):
        spec = {"groups": [{"tests": "A.*", "points": 4}], "ungraded": ["A.free"]}
        expected = [{"name": n, "program": "p"} for n in ("A.one", "A.two", "A.free", "A.three", "A.four")]
        passed = lambda name: build.TestResult(name, True, 0.0, "")  # noqa: E731
        # A forged pass of a test that is not listed, and no result at all for A.four.
        results = {n: passed(n) for n in ("A.one", "A.two", "A.three", "A.free", "A.forged", "A.extra")}
        groups, unclaimed, outcomes = manifest.score_stage(1, spec, expected, results)
        self.assertEqual((groups[0].passed, groups[0].count, groups[0].score), (3, 4, 3.0))
        self.assertNotIn("A.forged", outcomes)
        self.assertFalse(outcomes["A.four"].passed)
        self.assertEqual(unclaimed, [])


class TheTimeCap(unittest.TestCase):
    def test_every_step_gets_what_is_left(self):
        deadline = sandbox.Deadline(10)
        self.assertEqual(deadline.timeout(3), 3)
        deadline.start -= 9
        self.assertLessEqual(deadline.timeout(3), 1)
        deadline.start -= 2
        self.assertLessEqual(deadline.timeout(3), 0)
        self.assertTrue(deadline.reached())


class FileSelection(unittest.TestCase):
    def test_only_editable_files_are_taken_and_refused_ones_are_the_starters(self):
        spec = {}
        editable = submission.editable_files(ROOT, spec)
        self.assertIn("stages/01-ray-casting/sphere_intersection.cpp", editable)
        self.assertNotIn("CMakeLists.txt", editable)
        self.assertNotIn("stages/01-ray-casting/main.cpp", editable, "no task region in it")
        self.assertEqual([f for f in editable if not f.endswith(".cpp")], [], "a header is never taken")
        with Folder() as d:
            sphere = "stages/01-ray-casting/sphere_intersection.cpp"
            plane = "stages/01-ray-casting/plane_intersection.cpp"
            camera = "stages/01-ray-casting/camera_rays.cpp"
            (d / "stages" / "01-ray-casting").mkdir(parents=True)
            (d / sphere).symlink_to(ROOT / sphere)  # the instructor's solution, on the grading machine
            os.mkfifo(d / plane)
            (d / camera).write_text((ROOT / camera).read_text() + "\nvoid leave() { _exit(0); }\n")
            (d / "CMakeLists.txt").write_text("execute_process(COMMAND touch /tmp/pwned)\n")
            taken = submission.take(d, ROOT, spec)
            self.assertEqual(set(taken.files), set(editable))
            self.assertEqual(taken.files[sphere], submission.starter_version(ROOT, sphere))
            self.assertNotIn(b"BEGIN TASK stage1.sphere.stable\n  const", taken.files[sphere])
            self.assertEqual(taken.files[plane], submission.starter_version(ROOT, plane))
            self.assertTrue(taken.files[camera].endswith(b"_exit(0); }\n"))
            notes = "\n".join(taken.notes)
            self.assertIn(f"{sphere}: refused (a symbolic link); graded as the starter's version", notes)
            self.assertIn(f"{plane}: refused (a FIFO)", notes)
            self.assertIn("stages/02-whitted/optics.cpp: not in the submission", notes)
            self.assertEqual([(f.file, f.text) for f in taken.flags], [(camera, "void leave() { _exit(0); }")])

    def test_a_task_in_a_header_is_refused_by_the_marker_check(self):
        # Test sources include headers, so a task in one would let a submission rewrite the tests.
        with Folder() as d:
            (d / "stages" / "01-ray-casting").mkdir(parents=True)
            (d / "docs").mkdir()
            region = "  // BEGIN TASK stage1.demo.task\n  return 1;\n  // PLACEHOLDER\n  // return 0;\n  // END TASK\n"
            (d / "stages" / "01-ray-casting" / "demo.h").write_text("inline int f() {\n" + region + "}\n")
            (d / "docs" / "stage1.md").write_text("| `stage1.demo.task` | `demo.h` | a demo | `Demo.*` | none |\n")
            check = [sys.executable, str(ROOT / "tools" / "check_markers.py"), str(d)]
            result = subprocess.run(check, capture_output=True, text=True)
            self.assertEqual(result.returncode, 1, result.stdout)
            self.assertIn("task stage1.demo.task is in a header; tasks live in .cpp files", result.stdout)
            (d / "stages" / "01-ray-casting" / "demo.h").rename(d / "stages" / "01-ray-casting" / "demo.cpp")
            result = subprocess.run(check, capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stdout)

    def test_the_graded_tree_has_the_instructors_build_files(self):
        with Folder() as d:
            taken = submission.Taken({"stages/01-ray-casting/camera_rays.cpp": b"// mine\n"}, [], [])
            build.prepare_tree(taken, ROOT, d / "src", hidden=False)
            self.assertEqual((d / "src" / "CMakeLists.txt").read_bytes(), (ROOT / "CMakeLists.txt").read_bytes())
            self.assertEqual((d / "src" / "stages/01-ray-casting/camera_rays.cpp").read_text(), "// mine\n")
            self.assertFalse((d / "src" / "tests" / "hidden").exists())
            self.assertFalse((d / "src" / "tests" / "grading").exists(), "the proofs hold solution lines")
            self.assertFalse((d / "src" / "grading").exists(), "no references for a program to copy")


def sandbox_or_skip(test):
    box = sandbox.Sandbox()
    with Folder() as d:
        try:
            box.check(d)
        except sandbox.SandboxError as e:
            test.skipTest(str(e))
    return box


class AJudgedTest(unittest.TestCase):
    """The two runs of a judged test (build.run_judged_test) with stand-in programs: the subject's
    own report never counts, its record reaches the judge only as a regular file, and the judge's
    report decides."""

    SUBJECT = """#!/bin/sh
name=${1#--gtest_filter=}
case "$name" in
  T.forges) printf '%s' '""" + case(name="T.forges") + """' > report.xml; : > "$RT_GRADING_RECORD" ;;
  T.links) ln -s /etc/passwd "$RT_GRADING_RECORD" ;;
  *) echo values > "$RT_GRADING_RECORD" ;;
esac
echo "TODO: the task is not done"
"""
    # Passes a test whose record is not empty; without one, ends as a replay that found no value.
    JUDGE = """#!/bin/sh
name=${1#--gtest_filter=}; suite=${name%%.*}; test=${name#*.}
[ -s "$RT_GRADING_REPLAY" ] || { echo "grading: the submission's run ended before it gave the value at x.cpp:1:1" >&2; exit 86; }
printf '<?xml version="1.0"?><testsuites tests="1"><testsuite name="%s"><testcase name="%s" classname="%s" status="run" result="completed"/></testsuite></testsuites>' "$suite" "$test" "$suite" > "${2#--gtest_output=xml:}"
"""

    def test_only_the_judges_report_decides(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            work, judges = d / "work", d / "judges"
            builder = build.Builder(box, work, 1, sandbox.Deadline(60), judges=judges, judged=["fake_tests"])
            (builder.build / "bin").mkdir(parents=True)
            (builder.source / "assets").mkdir(parents=True)
            judges.mkdir()
            for path, text in ((builder.build / "bin" / "fake_tests", self.SUBJECT), (judges / "fake_tests", self.JUDGE)):
                path.write_text(text)
                path.chmod(0o755)
            logs = d / "logs"
            results = builder.run_tests([{"name": n, "program": "fake_tests"} for n in ("T.honest", "T.forges", "T.links")],
                                        logs, 30)
            self.assertTrue(results["T.honest"].passed, results["T.honest"].output)
            self.assertIn("TODO: the task is not done", results["T.honest"].output, "the subject's output is shown")
            self.assertFalse(results["T.forges"].passed, "its own passing report does not count")
            self.assertIn("ended before it gave the value at x.cpp:1:1", results["T.forges"].output)
            self.assertFalse(results["T.links"].passed)
            self.assertIn("record of its values was refused (a symbolic link)", results["T.links"].output)


class APreparedBuild(unittest.TestCase):
    def test_one_made_from_another_version_of_the_tree_is_refused(self):
        # Its judges would replay tests that have changed since: every such test would fail.
        with Folder() as d:
            prepared = d / "prepared"
            prepared.mkdir()
            (prepared / build.PREPARED_MARK).write_text(json.dumps({"seconds": 1.0, "starter": "0" * 64}))
            done = subprocess.run([GRADER_PYTHON, ROOT / "tools" / "grade.py", ROOT, "--prepared", prepared, "--out",
                                   d / "out"], capture_output=True, text=True, timeout=120)
            self.assertEqual(done.returncode, 1, done.stderr)
            self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
            self.assertIn("was made from another version of this tree", done.stderr)
            self.assertFalse((d / "out").exists())


class WithoutASandbox(unittest.TestCase):
    def test_the_grader_says_so_in_one_line_and_stops(self):
        # A bwrap that cannot make namespaces, as in an unprivileged container.
        with Folder() as d:
            fake = d / "bin" / "bwrap"
            fake.parent.mkdir()
            fake.write_text("#!/bin/sh\necho 'bwrap: No permissions to create new namespace' >&2\nexit 1\n")
            fake.chmod(0o755)
            environment = dict(os.environ, PATH=f"{fake.parent}:{os.environ['PATH']}")
            done = subprocess.run([GRADER_PYTHON, ROOT / "tools" / "grade.py", ROOT, "--stage", "1", "--out", d / "out"],
                                  capture_output=True, text=True, env=environment, timeout=120)
            self.assertEqual(done.returncode, 1, done.stderr)
            self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
            self.assertIn("grade: cannot make the sandbox (bwrap: No permissions to create new namespace)", done.stderr)
            self.assertIn("--container-is-sandbox", done.stderr)
            self.assertFalse((d / "out").exists(), "no report of a grading that did not run")

    def test_the_container_mode_keeps_the_limits_and_the_time_limit(self):
        box = sandbox.Sandbox(sandbox.Limits(memory_bytes=256 << 20), container_is_sandbox=True)
        with Folder() as d:
            scratch = d / "scratch"
            scratch.mkdir()
            if box.uid is not None:
                os.chown(scratch, box.uid, box.uid)
            log = d / "log"
            log.write_text("")
            result = box.run(["/bin/sh", "-c", "python3 -c 'x = bytearray(512 << 20)' 2>/dev/null || echo refused-$((1+1)); "
                              "id -u; sleep 30"], log, 2, writable=[scratch], cwd=scratch)
            said = log.read_text()
            self.assertTrue(result.timed_out)
            self.assertIn("refused-2", said)
            if box.uid is not None:
                self.assertIn(f"\n{box.uid}\n", said, "the unprivileged user")


class TheTimeCapEndToEnd(unittest.TestCase):
    def test_grading_stops_at_the_cap_and_says_so(self):
        sandbox_or_skip(self)
        with Folder() as d:
            start = time.monotonic()
            done = subprocess.run([GRADER_PYTHON, ROOT / "tools" / "grade.py", ROOT, "--stage", "1", "--time-cap", "3",
                                   "--out", d / "out"], capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertLess(time.monotonic() - start, 60)
            outcomes = json.loads((d / "out" / "outcomes.json").read_text())
            self.assertTrue(outcomes["cap_reached"])
            self.assertFalse(any(t["passed"] for t in outcomes["tests"]))
            results = json.loads((d / "out" / "results.json").read_text())
            self.assertEqual(results["score"], 0)
            self.assertIn("The time cap of 3 s was reached", results["output"])


class TheSandbox(unittest.TestCase):
    def step(self, box, script, folder, timeout=20, limits=None):
        scratch = folder / "scratch"
        scratch.mkdir(exist_ok=True)
        if box.uid is not None:
            os.chown(scratch, box.uid, box.uid)
        log = folder / "log"
        log.write_text("")
        if limits:
            box.limits = limits
        result = box.run(["/bin/sh", "-c", script], log, timeout, writable=[scratch], cwd=scratch)
        return result, log.read_text()

    def test_a_step_writes_only_its_scratch_folder_and_sees_nothing_of_the_grader(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            (d / "results.json").write_text("grader's")
            result, said = self.step(box, f"echo forged > {d}/results.json; ls {ROOT} /root; "
                                          "echo ok > mine; cat /etc/shadow; touch /usr/x", d)
            self.assertEqual((d / "results.json").read_text(), "grader's")
            self.assertEqual((d / "scratch" / "mine").read_text(), "ok\n")
            self.assertIn("No such file", said)
            self.assertFalse(pathlib.Path("/usr/x").exists())

    def test_a_step_sees_a_copy_where_the_prepared_build_was(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            copy, prepared = d / "copy", d / "prepared"  # the prepared folder is not even on the host
            copy.mkdir()
            (copy / "file").write_text("the copy\n")
            scratch = d / "scratch"
            scratch.mkdir()
            if box.uid is not None:
                os.chown(scratch, box.uid, box.uid)
            log = d / "log"
            log.write_text("")
            result = box.run(["/bin/sh", "-c", f"cat {prepared}/file; ls {copy} || echo no-$((1 + 1))"], log, 20,
                             read_only=[(copy, prepared)], writable=[scratch], cwd=scratch)
            said = log.read_text()
            self.assertIn("\nthe copy\n", said)
            self.assertIn("no-2", said, "the copy is seen only where the prepared build was")
            self.assertEqual(result.code, 0)

    def test_without_bubblewrap_nothing_is_seen_elsewhere_than_where_it_is(self):
        box = sandbox.Sandbox(container_is_sandbox=True)
        with Folder() as d:
            log = d / "log"
            log.write_text("")
            with self.assertRaises(sandbox.SandboxError):
                box.run(["/bin/true"], log, 5, read_only=[(d, d / "elsewhere")])

    def test_a_builder_maps_its_copy_to_the_prepared_paths_and_nothing_else(self):
        with Folder() as d:
            builder = build.Builder(sandbox.Sandbox(container_is_sandbox=True, user=os.geteuid()), d / "work", 1,
                                    sandbox.Deadline(10), seen_at=d / "prepared")
            self.assertEqual(builder.seen_path(d / "work" / "build" / "bin" / "stage1"), d / "prepared" / "build" / "bin" / "stage1")
            self.assertEqual(builder.seen_path(d / "work" / "src"), d / "prepared" / "src")
            self.assertEqual(builder.seen_path(d / "work" / "scratch" / "test0"), d / "work" / "scratch" / "test0")
            self.assertEqual(builder.seen_path(d / "work" / "srcx"), d / "work" / "srcx")

    def test_nothing_a_step_starts_outlives_it(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            marker = d / "scratch" / "late"
            result, _ = self.step(box, f"(setsid sh -c 'sleep 2; echo alive > {marker}' &) ; exit 0", d)
            self.assertEqual(result.code, 0)
            time.sleep(3)
            self.assertFalse(marker.exists(), "a detached process survived its step")

    def test_a_step_past_its_time_is_killed_with_its_children(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            start = time.monotonic()
            result, _ = self.step(box, "sleep 60 & sleep 60", d, timeout=1)
            self.assertTrue(result.timed_out)
            self.assertLess(time.monotonic() - start, 10)

    def test_no_network_and_limits_on_memory_processes_and_files(self):
        box = sandbox_or_skip(self)
        with Folder() as d:
            _, said = self.step(box, "tail -n +3 /proc/net/dev | cut -d: -f1 | tr -d ' '", d)
            self.assertEqual(said.split()[-1], "lo", "only the loopback device")
            self.assertEqual(said.count("\n"), 2, said)
            limits = sandbox.Limits(memory_bytes=256 << 20, file_bytes=1 << 20, processes=64)
            # Markers computed by the shell, so the command line echoed into the log cannot match.
            script = ("python3 -c 'x = bytearray(512 << 20)' 2>/dev/null && echo memory-$((1 + 1)); "
                      "head -c 2000000 /dev/zero > big 2>/dev/null; wc -c < big; "
                      "(for i in $(seq 100); do sleep 5 & done) 2>/dev/null; "
                      "set -- /proc/[0-9]*; echo processes-$((1 + 1)) $#")  # builtins: no fork left
            result, said = self.step(box, script, d, limits=limits)
            self.assertNotIn("memory-2", said, "512 MiB allocated under a 256 MiB limit")
            self.assertIn("\n1048576\n", said, "the file stopped at its limit")
            running = int(said.split("processes-2")[-1].split()[0])
            self.assertLessEqual(running, 64 + 2, said)

if __name__ == "__main__":
    unittest.main(verbosity=2)
