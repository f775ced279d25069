"""The grading manifest (grading/manifest.json): what each stage's tests and renders are worth.

Per stage:
  groups:   {"tests": glob over ctest names, "count": how many tests it holds in the full tree,
             "points": what the whole group is worth, "tasks": the task ids it checks,
             "hidden": true for instructor-only tests}. A group earns points * passed / count;
             a test that did not run (its stage did not build) counts as failed.
  ungraded: globs of tests that pass without any task done (bad-input handling, file formats):
            they are reported, worth nothing.
  renders:  render checks (tools/grading/renders.py), each with its points.
A test that an ungraded glob fits is ungraded; any other test counts in the first group whose glob fits it.
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


def matches(name, pattern):
    return fnmatch.fnmatchcase(name, pattern)


def score_stage(stage, spec, results, build_problem=None):
    """Scores one stage's groups from its test results (name -> TestResult). Returns (groups,
    tests that no group or ungraded glob claims)."""
    ungraded = {name for name in results if any(matches(name, pattern) for pattern in spec.get("ungraded", []))}
    claimed, groups = set(ungraded), []
    for group in spec["groups"]:
        mine = [r for name, r in sorted(results.items()) if name not in claimed and matches(name, group["tests"])]
        claimed.update(r.name for r in mine)
        passed = sum(r.passed for r in mine)
        failures = [(r.name, r.output) for r in mine if not r.passed]
        missing = group["count"] - len(mine)
        if missing > 0:
            failures.append((group["tests"], build_problem or f"{missing} of its {group['count']} tests did not run"))
        count = max(group["count"], len(mine))
        score = round(group["points"] * passed / count, 2) if count else 0.0
        groups.append(GroupScore(stage, group["tests"], group["points"], score, passed, count, group.get("tasks", []),
                                 group.get("hidden", False), failures, [r.name for r in mine]))
    return groups, [name for name in results if name not in claimed]
