#!/usr/bin/env python3
"""Times a student's edit-build-test loop for one task, as docs/students.md tells it:

    cmake --build --preset stageN && ctest --preset stageN -R 'TESTS'

after a change to the task's file, where TESTS are the tests the stage's handout lists for the
task. Each round appends a different `static_assert` line to the file, so that the code the
compiler sees changes as an edit's does (a touch, or a comment, would let ccache return the
objects compiled before); the file is restored at the end. The tree must be configured (cmake --preset release); the
first, untimed round builds whatever is missing.

    tools/student_loop.py TASK [--rounds N] [--tree DIR]     e.g. tools/student_loop.py stage1.sphere.stable

Prints each round's build and test seconds and the median of the loop. A failing build stops it
(exit 1); failing tests do not: on a starter tree they fail, and that run is the student's loop too.
"""
import argparse
import pathlib
import re
import signal
import statistics
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import task_regions  # noqa: E402


def task_file_and_tests(tree, task):
    stage = int(task_regions.TASK_ID.match(task).group(1))
    for _, folder in task_regions.stage_folders(tree):
        for path in task_regions.source_files(folder):
            if any(r.task_id == task for r in task_regions.parse(path, [])):
                listed = task_regions.handout_tasks(tree, stage).get(task)
                return stage, path, (listed.tests if listed else [])
    raise SystemExit(f"student_loop: no task {task} in {tree}/stages")


def ctest_regex(patterns):
    """GoogleTest name patterns (Suite.*, Suite/Param.*/x) as one ctest regular expression."""
    return "|".join("^" + re.escape(p).replace(r"\*", ".*").replace(r"\?", ".") + "$" for p in patterns)


def timed(command, tree):
    """Seconds the command took and its exit code; a failing build's output is shown."""
    start = time.monotonic()
    done = subprocess.run(command, cwd=tree, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if done.returncode != 0 and command[1] == "--build":
        sys.stdout.write(done.stdout.decode(errors="replace")[-4000:])
    return time.monotonic() - start, done.returncode


def main():
    parser = argparse.ArgumentParser(description="Time the edit-build-test loop of one task.")
    parser.add_argument("task", help="a task id, such as stage1.sphere.stable")
    parser.add_argument("--rounds", type=int, default=3, help="timed rounds (default 3)")
    parser.add_argument("--tree", default=".", help="the tree (default: the current folder)")
    args = parser.parse_args()
    tree = pathlib.Path(args.tree).resolve()
    if not task_regions.TASK_ID.match(args.task):
        parser.error(f"{args.task}: not a task id (stageN.topic.task)")
    stage, path, tests = task_file_and_tests(tree, args.task)
    build = ["cmake", "--build", "--preset", f"stage{stage}"]
    test = ["ctest", "--preset", f"stage{stage}"] + (["-R", ctest_regex(tests)] if tests else [])
    print(f"student_loop: {args.task} in {path.relative_to(tree)}; {' '.join(build)} && {' '.join(test)}")
    if timed(build, tree)[1] != 0:
        raise SystemExit(f"student_loop: {' '.join(build)} failed (configure first: cmake --preset release)")
    loops = []
    original = path.read_bytes()
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("student_loop: stopped"))  # restores the file too
    try:
        for round_ in range(1, args.rounds + 1):
            path.write_bytes(original + f'static_assert(true, "student_loop.py round {round_} at {time.time()}");\n'.encode())
            build_seconds, code = timed(build, tree)
            if code != 0:
                raise SystemExit(f"student_loop: {' '.join(build)} failed")
            test_seconds, _ = timed(test, tree)
            loops.append(build_seconds + test_seconds)
            print(f"student_loop: round {round_}: build {build_seconds:.1f} s, tests {test_seconds:.1f} s, "
                  f"loop {loops[-1]:.1f} s", flush=True)
    finally:
        path.write_bytes(original)
    print(f"student_loop: {args.task}: median loop {statistics.median(loops):.1f} s over {len(loops)} rounds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
