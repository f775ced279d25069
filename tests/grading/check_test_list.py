#!/usr/bin/env python3
"""grading/tests.json is current and the manifest covers it (ctest grading_test_list, label common).

    tests/grading/check_test_list.py BUILD

The grader runs and scores exactly the tests grading/tests.json lists, so a test added to the suite
but not to the list would never count, and one removed would count as failed for every student.
This compares the list with the tests of every stage label in BUILD (ctest's own listing), and
checks that every listed test is claimed by a manifest group or an ungraded glob, and that every
group holds at least one test. Exits 1 with one line per difference.
"""
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from grading import build, manifest  # noqa: E402


def main():
    if len(sys.argv) != 2:
        print("usage: check_test_list.py BUILD", file=sys.stderr)
        return 2
    problems = []
    current = {int(stage): tests for stage, tests in build.list_tests(sys.argv[1]).items()}
    listed = manifest.load_tests(ROOT / "grading" / "tests.json")
    spec = manifest.load(ROOT / "grading" / "manifest.json")
    for stage in sorted(current.keys() | listed.keys()):
        have = {(t["name"], t["program"]) for t in listed.get(stage, [])}
        want = {(t["name"], t["program"]) for t in current.get(stage, [])}
        problems += [f"stage {stage}: {name} ({program}) is in the build but not in grading/tests.json"
                     for name, program in sorted(want - have)]
        problems += [f"stage {stage}: {name} ({program}) is in grading/tests.json but not in the build"
                     for name, program in sorted(have - want)]
        groups, unclaimed, _ = manifest.score_stage(stage, spec["stages"].get(stage, {"groups": []}),
                                                    listed.get(stage, []), {})
        problems += [f"stage {stage}: {name} is claimed by no group and no ungraded glob" for name in unclaimed]
        problems += [f"stage {stage}: group {g.tests} holds no listed test" for g in groups if g.count == 0]
    for problem in problems:
        print(problem)
    if problems:
        print("run tools/grade.py --list-tests after changing tests, and update grading/manifest.json")
    print(f"{sum(map(len, listed.values()))} listed tests checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
