#!/usr/bin/env python3
"""The coursework tooling's proofs (issue: starter tree and grading). CI runs it after the test
suite. Every grading shares one prepared build (tools/grade.py --prepare), as a class does, and
there is no other build: the prepared build is the starter tree built.

    tests/grading/check_grading.py WORK     (a folder outside the repository)

 1. The starter tree (tools/make_starter.py) configures with the README's preset, and builds
    warning-free: the prepared build, whose editable files are the starter's byte for byte, logs
    no warning.
 2. Graded with tools/grade.py it scores zero; every graded test fails with a message that names a
    task; no test crashes or runs into its time limit; every render check's program still writes
    an image.
 3. This tree scores full marks.
 4. Each planted bug (a wrong sign in the sphere quadratic, a BVH that skips the far child, a
    missing 1/pdf) loses exactly the points of the tests that cover it: the failed tests are
    exactly the ones listed for it below, and the points lost are theirs.
 5. Hostile submissions (tests/grading/hostile.py) score exactly what the honest trees beside them
    score, test by test and render by render, within the time cap, and leave the grader's
    machine untouched: no command of theirs ran outside the sandbox, no process of theirs
    outlived the grading, the reports are the grader's.
Exits 1 with one line per broken promise.
"""
import fnmatch
import re
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import hostile  # puts tools/ on the path

from grading import submission  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
TASK_NAMED = re.compile(r"stage\d\.[a-z0-9_*]+\.[a-z0-9_*]+")  # what a failure must mention
PYTHON = sys.executable

# Each bug: the task, the file, the correct line and the broken one, and every test (or render
# check) that covers it, as globs over the grader's test names ("render:" + check name for renders).
PLANTED_BUGS = [
    {"task": "stage1.sphere.textbook", "file": "stages/01-ray-casting/sphere_intersection.cpp",
     "old": "  const float b = 2.0f * glm::dot(f, ray.direction);",
     "new": "  const float b = -2.0f * glm::dot(f, ray.direction);",
     "covered_by": ["Sphere/BothSphereForms.*/textbook", "HiddenSphere.*"]},
    {"task": "stage3.bvh.closest_hit", "file": "stages/03-acceleration/bvh_traversal.cpp",
     "old": "        stack[stack_size++] = first_is_nearer ? Entry{second, *t_second} : Entry{first, *t_first};\n",
     "new": "",
     # Builders.* as the handout says: the 4-wide trees have their own traversal, but their
     # bunny test compares them with a binary SAH tree, which uses this one; stage 4's disks are
     # checked in a binary tree too
     "covered_by": ["BvhAgainstNaive.*", "Bvh/Builders.*", "HiddenBvh.*", "Stage3Cli.*", "render:bunny",
                    "LightingScene.DisksInTheBvhAgreeWithBruteForce"]},
    {"task": "stage4.direct.light_sampling", "file": "stages/04-radiometry/direct_lighting.cpp",
     "old": "  result.value = f * le * (result.wi.z / result.pdf);",
     "new": "  result.value = f * le * result.wi.z;",
     "covered_by": ["DirectClosedForm.*", "DirectEstimators.*", "DirectDelta.*", "render:Cornell box, direct light*",
                    # stage 5's path tracer samples the lights through it
                    "Furnace.*", "PathClosedForm.*", "CornellBox.*", "RussianRoulette.*", "HiddenFurnace.*",
                    "render:Cornell box, path traced*",
                    # and stage 6's photon mapping at its visible points, and its comparisons with
                    # stage 5's path tracer
                    "CornellAgreement.*", "SppmFurnace.*", "SppmConvergence.*", "CausticScene.*", "Stage6Cli.*",
                    "BdptStrategies.*",
                    # and stage 7's VCM on the Cornell box, whose chosen budget is stage 5's path tracer
                    "VcmCornell.ABudgetChosenByTheFirstIterationFindsTheReference"]},
]


def run(command, cwd=None):
    print("$", " ".join(map(str, command)), flush=True)
    return subprocess.run(command, cwd=cwd).returncode


PREPARED = None  # the prepared build every grading here uses (main sets it)


def grade(tree, out, work, *flags):
    """Grades `tree` against the prepared build; returns (results.json, outcomes.json) as dictionaries."""
    if run([PYTHON, ROOT / "tools" / "grade.py", tree, "--out", out, "--work", work, "--prepared", PREPARED,
            *flags]) != 0:
        raise SystemExit(f"check_grading: grading {tree} failed to run")
    out = pathlib.Path(out)
    return json.loads((out / "results.json").read_text()), json.loads((out / "outcomes.json").read_text())


def failures_and_points(outcomes):
    """The failed tests (and "render:" + name for failed render checks), each with its points."""
    per_test = {(g["stage"], g["tests"]): g["points"] / g["count"] for g in outcomes["groups"] if g["count"]}
    failed = {t["name"]: per_test.get((t["stage"], t["group"]), 0.0) for t in outcomes["tests"] if not t["passed"]}
    failed.update({"render:" + r["name"]: r["points"] for r in outcomes["renders"] if r["score"] < r["points"]})
    return failed


def check_starter(work, problems):
    starter = work / "starter"
    shutil.rmtree(starter, ignore_errors=True)
    if run([PYTHON, ROOT / "tools" / "make_starter.py", starter]) != 0:
        problems.append("make_starter.py failed")
        return starter, None
    # The starter builds warning-free: the prepared build is the starter tree built (checked here
    # file by file), with the warnings of every build and without -Werror, so its log must hold
    # no warning. Building the starter once more with the README's commands would cost minutes of
    # CI for the same compiler messages; configuring it with the README's preset checks the rest.
    prepared_source = PREPARED / "src"
    for name in submission.editable_files(ROOT, json.loads((ROOT / "grading" / "manifest.json").read_text())):
        if (prepared_source / name).read_bytes() != (starter / name).read_bytes():
            problems.append(f"the prepared build's {name} is not the starter's")
    warnings = [line for line in (PREPARED / "prepare.log").read_text(errors="replace").splitlines()
                if "warning:" in line]
    if warnings:
        problems.append(f"the starter tree does not build warning-free: {warnings[0]}")
    if run(["cmake", "--preset", "release"], cwd=starter) != 0:
        problems.append("the starter tree does not configure with cmake --preset release")
        return starter, None
    results, outcomes = grade(starter, work / "starter-report", work / "starter-grade")
    check_starter_outcomes(outcomes, problems)
    return starter, outcomes


def check_starter_outcomes(outcomes, problems):
    results = {"score": sum(g["score"] for g in outcomes["groups"]) + sum(r["score"] for r in outcomes["renders"])}
    if results["score"] != 0:
        problems.append(f"the starter tree scores {results['score']}, not 0")
    for render in outcomes["renders"]:
        if any(s in p for p in render["problems"] for s in ("exited with", "wrote no readable image", "was not built",
                                                             "ran longer", "not checked")):
            problems.append(f"starter: render {render['name']}: the program wrote no image: {render['problems'][0]}")
    timeout = json.loads((ROOT / "grading" / "manifest.json").read_text())["test_timeout_seconds"]
    for test in outcomes["tests"]:
        if any(s in test["output"] for s in ("Timeout", "without GoogleTest's report", "truncated")) or \
                test["seconds"] >= timeout:
            problems.append(f"starter: {test['name']}: crashed or ran into its time limit")
        if test["group"] and not test["passed"] and not TASK_NAMED.search(test["output"]):
            problems.append(f"starter: {test['name']}: fails without naming a task")


def check_full_and_bugs(work, problems):
    full, full_outcomes = grade(ROOT, work / "full-report", work / "bug-grade")
    all_stages = sorted({g["stage"] for g in full_outcomes["groups"]})
    possible = sum(t["max_score"] for t in full["tests"])
    if full["score"] != possible:
        problems.append(f"the full tree scores {full['score']} of {possible}: {sorted(failures_and_points(full_outcomes))}")
    for bug in PLANTED_BUGS:
        tree = work / "bug-tree"
        shutil.rmtree(tree, ignore_errors=True)
        shutil.copytree(ROOT, tree, ignore=shutil.ignore_patterns(".git", "build", "__pycache__"))
        path = tree / bug["file"]
        text = path.read_text()
        if text.count(bug["old"]) != 1:
            problems.append(f"{bug['file']}: the line to break for {bug['task']} is not there once")
            continue
        path.write_text(text.replace(bug["old"], bug["new"]))
        # The full tree's work folder: only what the bug touches is rebuilt. Only the bug's stage and
        # the later ones are graded: an earlier stage's test programs do not link its code (arrows
        # point backwards only), so they fare as in the full tree.
        stages = [s for s in all_stages if s >= int(bug["task"].split(".")[0].removeprefix("stage"))]
        results, outcomes = grade(tree, work / "bug-report", work / "bug-grade",
                                  *[flag for s in stages for flag in ("--stage", str(s))])
        failed = failures_and_points(outcomes)
        if not failed:
            problems.append(f"{bug['task']}: the planted bug loses no points")
        for name in sorted(failed):
            if not any(fnmatch.fnmatchcase(name, g) for g in bug["covered_by"]):
                problems.append(f"{bug['task']}: {name} failed, but is not among the tests that cover the task")
        full_score = sum(g["score"] for g in full_outcomes["groups"] if g["stage"] in stages) + \
            sum(r["score"] for r in full_outcomes["renders"] if r["stage"] in stages)
        lost, expected = full_score - results["score"], sum(failed.values())
        if abs(lost - expected) > 0.02:
            problems.append(f"{bug['task']}: lost {lost:g} points, but its failed tests are worth {expected:g}")
        print(f"check_grading: {bug['task']}: {len(failed)} tests failed, {lost:g} points lost", flush=True)


def same_outcomes(label, got, expected, stages, problems):
    """Every test and render check of `stages` fares in `got` as in `expected`, and the totals agree."""
    def table(outcomes):
        tests = {t["name"]: t["passed"] for t in outcomes["tests"] if t["stage"] in stages and t["group"]}
        renders = {r["name"]: r["score"] for r in outcomes["renders"] if r["stage"] in stages}
        score = sum(g["score"] for g in outcomes["groups"] if g["stage"] in stages) + sum(renders.values())
        return tests, renders, score
    (tests, renders, score), (want_tests, want_renders, want_score) = table(got), table(expected)
    for name in sorted(want_tests.keys() | tests.keys()):
        if tests.get(name) != want_tests.get(name):
            problems.append(f"{label}: {name} {'passed' if tests.get(name) else 'failed'}, but "
                            f"{'passes' if want_tests.get(name) else 'fails'} in the honest tree")
    for name in sorted(want_renders):
        if renders.get(name) != want_renders[name]:
            problems.append(f"{label}: render {name} scored {renders.get(name)}, the honest tree {want_renders[name]}")
    if abs(score - want_score) > 0.005:
        problems.append(f"{label}: scored {score:g}, the honest tree {want_score:g}")
    print(f"check_grading: {label}: {score:g} points, the honest tree {want_score:g}", flush=True)


def processes_running_from(folder):
    """Processes whose program or working folder lies in `folder` (a submission's survivors)."""
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        for link in ("exe", "cwd"):
            try:
                # A path inside `folder`, not one that merely starts with its name (/tmp/work2).
                if pathlib.Path(os.readlink(entry / link)).is_relative_to(folder):
                    found.append(f"{entry.name} ({os.readlink(entry / 'exe')})")
                    break
            except OSError:
                pass
    return found


def check_hostile(work, starter, starter_outcomes, problems):
    """The hostile submissions of hostile.py, graded for stage 1 in the work folders of the trees
    they copy (only what they change is rebuilt)."""
    cap, flags = 900, ["--stage", "1", "--test-timeout", "10", "--time-cap", "900"]
    marker = work / "escaped"  # written or touched only by hostile code that got out
    honest, attack = work / "honest-tree", work / "hostile-tree"
    hostile.honest_tree(honest)
    _, honest_outcomes = grade(honest, work / "honest-report", work / "bug-grade", *flags)
    report = work / "hostile-report"
    hostile.hostile_tree(attack, report / "results.json", marker)
    results, outcomes = grade(attack, report, work / "bug-grade", *flags)
    written = (report / "results.json").read_bytes()
    same_outcomes("hostile submission A", outcomes, honest_outcomes, {1}, problems)
    if outcomes["seconds"] > cap or outcomes["cap_reached"]:
        problems.append(f"hostile submission A: graded in {outcomes['seconds']:.0f} s, past its cap of {cap} s")
    if not any("sphere_intersection.cpp: refused (a symbolic link)" in note for note in outcomes["notes"]):
        problems.append("hostile submission A: the link to the solution file is not reported as refused")
    flagged = {f["why"] for f in outcomes["flags"]}
    for why in ("ends the process (a test would end before its report)", "starts another process"):
        if why not in flagged:
            problems.append(f"hostile submission A: no flag for code that {why}")
    time.sleep(5)  # the detached process would have written after 3 s
    if (report / "results.json").read_bytes() != written:
        problems.append("hostile submission A: results.json changed after the grader wrote it")
    if marker.exists():
        problems.append(f"hostile submission A: {marker} exists: hostile code ran outside the sandbox")
    for survivor in processes_running_from(work):
        problems.append(f"hostile submission A: process {survivor} outlived the grading")

    # B: references replaced by the starter's own renders, which would then match them exactly.
    if starter_outcomes is None:
        return
    spec = json.loads((ROOT / "grading" / "manifest.json").read_text())
    check = spec["stages"]["1"]["renders"][0]
    own = work / "starter-render.pfm"
    subprocess.run([PREPARED / "build/bin/stage1", "--scene", starter / check["scene"], "--out", own,
                    "--seed", "1", *check["args"]], check=True, capture_output=True)
    forged = {f"{check['reference']}-mean.pfm": own.read_bytes()}
    hostile.replaced_references(work / "references-tree", starter, forged, marker)
    _, outcomes = grade(work / "references-tree", work / "references-report", work / "starter-grade", "--stage", "1")
    same_outcomes("hostile submission B", outcomes, starter_outcomes, {1}, problems)
    if marker.exists():
        problems.append(f"hostile submission B: {marker} exists: its CMakeLists.txt ran")


def main():
    if len(sys.argv) != 2:
        print("usage: check_grading.py WORK", file=sys.stderr)
        return 2
    work = pathlib.Path(sys.argv[1]).resolve()
    work.mkdir(parents=True, exist_ok=True)
    work.chmod(0o755)  # the sandbox's user enters the work folders below it
    problems = []
    global PREPARED
    PREPARED = work / "prepared"
    start = time.monotonic()
    if run([PYTHON, ROOT / "tools" / "grade.py", "--prepare", PREPARED]) != 0:
        print("check_grading: the prepared build failed")
        return 1
    print(f"check_grading: prepared build: {time.monotonic() - start:.0f} s", flush=True)
    start = time.monotonic()
    starter, starter_outcomes = check_starter(work, problems)
    print(f"check_grading: the starter checked and graded: {time.monotonic() - start:.0f} s", flush=True)
    start = time.monotonic()
    check_full_and_bugs(work, problems)
    print(f"check_grading: this tree and the planted bugs graded: {time.monotonic() - start:.0f} s", flush=True)
    start = time.monotonic()
    check_hostile(work, starter, starter_outcomes, problems)
    print(f"check_grading: the hostile submissions graded: {time.monotonic() - start:.0f} s", flush=True)
    for problem in problems:
        print(f"check_grading: {problem}")
    print(f"check_grading: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
