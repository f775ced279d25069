"""The grading manifest (grading/manifest.json): what each stage's tests and renders are worth, and
the list of the tests themselves (grading/tests.json, made from the instructor's build by
`tools/grade.py --list-tests`): only those tests are run and scored, whatever a submission does.

Per stage:
  groups:   {"tests": glob over test names, "points": what the whole group is worth, "tasks": the
             task ids it checks, "hidden": true for instructor-only tests}. A group earns
             points * passed / count, count being the listed tests it holds; a listed test that
             did not run (its stage did not build, the time cap was reached) counts as failed.
  ungraded: globs of tests that pass without any task done (bad-input handling, file formats):
            they are reported, worth nothing.
  renders:  render checks (tools/grading/renders.py), each with its points.
A test that an ungraded glob fits is ungraded; any other test counts in the first group whose glob fits it.

judged_programs: the test programs whose tests are decided by a judge that runs none of the
submission's code (build.py, tests/support/subject.h); a program's tests must all take what they
check through subject() before it is listed.
"""
import dataclasses
import fnmatch
import json
import pathlib


@dataclasses.dataclass
class GroupScore:
    stage: int
    tests: str
    points: float
    score: float
    passed: int
    count: int
    tasks: list
    hidden: bool
    failures: list  # (test name, output)
    members: list   # the names of its tests that ran


def load(path):
    manifest = json.loads(pathlib.Path(path).read_text())
    manifest["stages"] = {int(k): v for k, v in manifest["stages"].items()}
    return manifest


def load_tests(path, hidden=True):
    """grading/tests.json: stage -> [{"name", "program"}], without the hidden tests unless `hidden`."""
    listed = json.loads(pathlib.Path(path).read_text())["stages"]
    return {int(stage): [t for t in tests if hidden or not t["program"].endswith("_hidden_tests")]
            for stage, tests in listed.items()}


def matches(name, pattern):
    return fnmatch.fnmatchcase(name, pattern)


def score_stage(stage, spec, expected, results, build_problem=None):
    """Scores one stage's groups. `expected` lists the stage's tests, `results` maps names to the
    TestResults of those that ran. Returns (groups, listed tests that no group or ungraded glob
    claims)."""
    not_run = build_problem or "did not run"
    outcomes = {t["name"]: results.get(t["name"]) or TestResultLike(t["name"], False, 0.0, not_run) for t in expected}
    ungraded = {name for name in outcomes if any(matches(name, pattern) for pattern in spec.get("ungraded", []))}
    claimed, groups = set(ungraded), []
    for group in spec["groups"]:
        mine = [r for name, r in sorted(outcomes.items()) if name not in claimed and matches(name, group["tests"])]
        claimed.update(r.name for r in mine)
        passed = sum(r.passed for r in mine)
        failures = [(r.name, r.output) for r in mine if not r.passed]
        score = round(group["points"] * passed / len(mine), 2) if mine else 0.0
        groups.append(GroupScore(stage, group["tests"], group["points"], score, passed, len(mine), group.get("tasks", []),
                                 group.get("hidden", False), failures, [r.name for r in mine]))
    return groups, [name for name in outcomes if name not in claimed], outcomes


@dataclasses.dataclass
class TestResultLike:
    """A listed test that never ran, scored as failed."""
    name: str
    passed: bool
    seconds: float
    output: str
