#!/usr/bin/env python3
"""Grades a tree (this one, the starter, or a student's) for one stage or all.

    tools/grade.py TREE [--stage N ...] [--out DIR] [--work DIR] [--jobs N] [--no-hidden]
    tools/grade.py --make-references [--build DIR]

It copies TREE to a work folder with the instructor's tests (hidden ones included) and assets,
builds it (release, stage by stage, so a stage that does not compile costs only its own points),
runs each stage's tests with a time limit per test, checks the stage programs' renders against the
references by statistics, measures the BVH's speed for the leaderboard, and scores everything from
grading/manifest.json. It writes DIR/results.json (Gradescope's autograder format), DIR/report.md
and DIR/report.html, and prints the total. Exit code 0 when grading ran (whatever the score), 1
when it could not (no such tree, no cmake).

--make-references renders the references of the render checks with this tree's own release build
(build/release by default) into grading/references/. docs/instructors.md has the whole workflow.
"""
import argparse
import pathlib
import shutil
import sys
import tempfile
import time

try:
    import numpy  # noqa: F401  (the render checks' statistics)
except ModuleNotFoundError:
    sys.exit(f"tools/grade.py: this Python ({sys.executable}) has no numpy; run the grader with "
             "Debian's /usr/bin/python3, which has it once tools/setup.sh installed python3-numpy")

from grading import build, manifest, renders, report

ROOT = pathlib.Path(__file__).resolve().parent.parent
MANIFEST = ROOT / "grading" / "manifest.json"


def grade(tree, stages, out, work, jobs, hidden):
    spec = manifest.load(MANIFEST)
    stages = stages or sorted(spec["stages"])
    start = time.monotonic()
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    source = build.prepare_tree(tree, ROOT, work)
    if not hidden:
        shutil.rmtree(source / "tests" / "hidden", ignore_errors=True)
    binary = work / "build"
    log = work / "build.log"
    log.write_text("")
    configured = build.configure(source, binary, log)
    grade = {"tree": str(tree), "groups": [], "renders": [], "tests": [], "unclaimed": [], "build_problems": {}}
    for stage in stages:
        stage_spec = spec["stages"][stage]
        problem = None
        stage_log = work / f"stage{stage}.log"
        stage_log.write_text("")
        if not configured:
            problem = "cmake could not configure the tree:\n" + log.read_text()[-3000:]
        elif not build.build_stage(binary, stage, stage_log, jobs):
            problem = "the stage did not build:\n" + stage_log.read_text()[-3000:]
        if problem:
            grade["build_problems"][stage] = problem
        results = {} if problem else build.run_stage_tests(binary, stage, work / f"junit-stage{stage}.xml", stage_log,
                                                            jobs, spec.get("test_timeout_seconds", 120))
        if not hidden:
            stage_spec = dict(stage_spec, groups=[g for g in stage_spec["groups"] if not g.get("hidden")])
        groups, unclaimed = manifest.score_stage(stage, stage_spec, results, problem)
        grade["groups"] += groups
        group_of = {name: g.tests for g in groups for name in g.members}
        grade["tests"] += [{"stage": stage, "name": r.name, "passed": r.passed, "seconds": r.seconds,
                            "group": group_of.get(r.name), "output": "" if r.passed else report.clip(r.output)}
                           for r in results.values()]
        grade["unclaimed"] += unclaimed
        for check in stage_spec.get("renders", []):
            grade["renders"].append(renders.check_render(binary / "bin", source, ROOT, stage, check))
        print(f"grade: stage {stage}: {sum(g.score for g in groups) + sum(r.score for r in grade['renders'] if r.stage == stage):.2f}"
              f" of {sum(g.points for g in groups) + sum(r.points for r in grade['renders'] if r.stage == stage):g}",
              flush=True)
    # The BVH is timed only once its stage renders right: a tree that does not work has no speed
    # worth ranking (and an unsplit one would take hours on the bunny).
    board = spec.get("leaderboard")
    stage_renders = [r for r in grade["renders"] if board and r.stage == board["stage"]]
    if stage_renders and all(r.score == r.points for r in stage_renders):
        grade["rays_per_second"], _ = renders.bvh_rays_per_second(binary / "bin", source, board)
    total = sum(g.score for g in grade["groups"]) + sum(r.score for r in grade["renders"])
    possible = sum(g.points for g in grade["groups"]) + sum(r.points for r in grade["renders"])
    grade["seconds"] = time.monotonic() - start
    grade["summary"] = f"{total:.2f} of {possible:g} points (stages {', '.join(map(str, stages))})"
    report.write_reports(grade, out)
    print(f"grade: {grade['summary']}; reports in {out}")
    return grade


def make_references(build_dir):
    spec = manifest.load(MANIFEST)
    for stage in sorted(spec["stages"]):
        for check in spec["stages"][stage].get("renders", []):
            print(f"grade: reference for stage {stage}, {check['name']} ({check.get('reference_runs', 1)} runs)", flush=True)
            renders.make_reference(pathlib.Path(build_dir) / "bin", ROOT, check)


def main():
    parser = argparse.ArgumentParser(description="Grade a tree of the ray tracing course.")
    parser.add_argument("tree", nargs="?", help="the tree to grade (a folder with CMakeLists.txt)")
    parser.add_argument("--stage", type=int, action="append", help="grade this stage (repeatable; default all)")
    parser.add_argument("--out", default="grade-report", help="folder for the reports (default grade-report)")
    parser.add_argument("--work", help="folder for the copy and its build (default: a temporary one)")
    parser.add_argument("--jobs", type=int, default=2, help="parallel build and test jobs (default 2)")
    parser.add_argument("--no-hidden", action="store_true", help="leave the hidden tests out (a student's self-check)")
    parser.add_argument("--make-references", action="store_true", help="render the render checks' references")
    parser.add_argument("--build", default=str(ROOT / "build" / "release"), help="build used by --make-references")
    args = parser.parse_args()
    if args.make_references:
        make_references(args.build)
        return 0
    if not args.tree:
        parser.error("give the tree to grade")
    tree = pathlib.Path(args.tree)
    if not (tree / "CMakeLists.txt").is_file():
        print(f"grade: {tree}: not a tree of this course (no CMakeLists.txt)", file=sys.stderr)
        return 1
    if shutil.which("cmake") is None or shutil.which("ctest") is None:
        print("grade: cmake and ctest are needed (tools/setup.sh installs them)", file=sys.stderr)
        return 1
    spec = manifest.load(MANIFEST)
    unknown = [s for s in args.stage or [] if s not in spec["stages"]]
    if unknown:
        print(f"grade: {MANIFEST}: no stage {unknown[0]}", file=sys.stderr)
        return 1
    if args.work:
        grade(tree, args.stage, args.out, args.work, args.jobs, not args.no_hidden)
    else:
        with tempfile.TemporaryDirectory(prefix="grade-") as work:
            grade(tree, args.stage, args.out, work, args.jobs, not args.no_hidden)
    return 0


if __name__ == "__main__":
    sys.exit(main())
