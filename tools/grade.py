#!/usr/bin/env python3
"""Grades a submission (a student's tree, the starter, or this one) for one stage or all.

    tools/grade.py --prepare PREPARED [--jobs N] [--container-is-sandbox] [--sandbox-user UID]
    tools/grade.py TREE [--stage N ...] [--out DIR] [--prepared PREPARED] [--work DIR] [--jobs N]
                   [--no-hidden] [--time-cap S] [--test-timeout S] [--memory-limit MIB]
                   [--container-is-sandbox] [--sandbox-user UID]
    tools/grade.py --make-references [--build DIR]
    tools/grade.py --list-tests [--build DIR]

It takes from TREE only the files students edit (the stage sources with task regions; anything
else, links and oversized files refused, comes from this tree: tools/grading/submission.py), builds
the result stage by stage in a sandbox (tools/grading/sandbox.py: bubblewrap, no network, its own
PID namespace, a read-only view but for one scratch folder, limits on memory, CPU time, file size
and processes), runs exactly the tests grading/tests.json lists, each in a sandbox of its own and
passed only when its judge's report says so (the starter's test program replaying the values the
submission's run recorded: tools/grading/build.py), checks the stage programs' renders against the
references by statistics, measures the BVH's speed for the leaderboard, all within one time cap
for the whole submission, and scores everything from grading/manifest.json. It writes, outside
the sandbox and atomically, DIR/results.json (Gradescope's autograder format), DIR/report.md,
DIR/report.html and DIR/outcomes.json, and prints the total. Exit code 0 when grading ran (whatever
the score), 1 when it could not (no such tree, no cmake, no sandbox).

--prepare builds the instructor's tree once, every task as the starter's placeholder, into
PREPARED (about three minutes on 2 cores), and keeps its test programs as the judges
(PREPARED/judges); --prepared PREPARED then grades a submission by
compiling only its files that differ from the starter's against that build and relinking (a class
shares one prepared folder; each submission works on a copy). Without --prepared, the starter is
built in the work folder first (for its judges), and the submission's files then on top of it.
report.md gives each step's time.

--make-references renders the render checks' references with this tree's own release build
(build/release by default) into grading/references/; --list-tests writes grading/tests.json from
it. docs/instructors.md has the whole workflow.
"""
import argparse
import json
import os
import pathlib
import shutil
import sys
import tempfile
import time

try:
    import numpy  # noqa: F401  (the render checks' statistics)
except ModuleNotFoundError:
    # A python3 earlier on PATH (pyenv, a virtual environment) may lack numpy; Debian's has it.
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3", *sys.argv])
    sys.exit(f"tools/grade.py: this Python ({sys.executable}) has no numpy; run the grader with "
             "Debian's /usr/bin/python3, which has it once tools/setup.sh installed python3-numpy")

from grading import build, files, manifest, renders, report, sandbox, submission

ROOT = pathlib.Path(__file__).resolve().parent.parent
MANIFEST = ROOT / "grading" / "manifest.json"
TESTS = ROOT / "grading" / "tests.json"


class StepTimes:
    """How long each step of a grading took, for report.md."""

    def __init__(self):
        self.steps = []

    def timed(self, name, function, *arguments):
        start = time.monotonic()
        try:
            return function(*arguments)
        finally:
            self.steps.append([name, time.monotonic() - start])


def grade(tree, stages, out, work, options):
    spec = manifest.load(MANIFEST)
    listed = manifest.load_tests(TESTS, options.hidden)
    stages = stages or sorted(spec["stages"])
    deadline = sandbox.Deadline(options.time_cap)
    times = StepTimes()
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    work.chmod(0o755)
    box = sandbox.Sandbox(sandbox.Limits(memory_bytes=options.memory_limit << 20), options.container_is_sandbox,
                          options.sandbox_user)
    box.check(work)
    taken = submission.take(tree, ROOT, spec)
    judged = spec.get("judged_programs", [])
    if options.prepared:
        times.timed("copy the prepared build", build.copy_prepared, options.prepared, work)
        judges = options.prepared / build.JUDGES
    elif judged:  # the starter is built here first, for its judges; the submission's files then build on it
        judges = work / build.JUDGES
        if not times.timed("build the starter (the judges)", build_starter, work, stages, options, box, deadline,
                           work / "starter.log"):
            judges = None  # every judged test then fails: without its judge no test can pass
    else:
        judges = None
    builder = build.Builder(box, work, options.jobs, deadline, seen_at=options.prepared, judges=judges, judged=judged)
    build.prepare_tree(taken, ROOT, builder.source, options.hidden)
    log = work / "build.log"
    log.write_text("")
    configured = times.timed("configure", builder.configure, log)
    grade = {"tree": str(tree), "groups": [], "renders": [], "tests": [], "unclaimed": [], "build_problems": {},
             "hidden_build_problems": {}, "notes": taken.notes, "flags": taken.flags, "time_cap": options.time_cap,
             "steps": times.steps, "prepared": bool(options.prepared)}
    for stage in stages:
        stage_spec = spec["stages"][stage]
        problem = None
        stage_log = work / f"stage{stage}.log"
        stage_log.write_text("")
        if not configured:
            problem = "cmake could not configure the tree:\n" + files.tail_of(log, 3000)
        elif not times.timed(f"stage {stage}: build", builder.build_stage, stage, stage_log):
            problem = "the stage did not build:\n" + files.tail_of(stage_log, 3000)
        if problem:
            grade["build_problems"][stage] = problem
        tests = [t for t in listed.get(stage, []) if not t["program"].endswith("_hidden_tests")]
        hidden_tests = [t for t in listed.get(stage, []) if t["program"].endswith("_hidden_tests")]
        results = {} if problem else times.timed(f"stage {stage}: {len(tests)} tests", builder.run_tests, tests,
                                                 work / f"logs-stage{stage}", options.test_timeout)
        if hidden_tests and not problem:
            hidden_log = work / f"stage{stage}-hidden.log"
            hidden_log.write_text("")
            if times.timed(f"stage {stage}: build the hidden tests", builder.build_hidden, stage, hidden_log):
                results.update(times.timed(f"stage {stage}: {len(hidden_tests)} hidden tests", builder.run_tests,
                                           hidden_tests, work / f"logs-stage{stage}-hidden", options.test_timeout))
            else:
                grade["hidden_build_problems"][stage] = files.tail_of(hidden_log, 3000)
        if not options.hidden:
            stage_spec = dict(stage_spec, groups=[g for g in stage_spec["groups"] if not g.get("hidden")])
        hidden_problem = "the hidden tests did not build (the log is in the instructor's report)" \
            if stage in grade["hidden_build_problems"] else None
        groups, unclaimed, outcomes = manifest.score_stage(stage, stage_spec, listed.get(stage, []), results,
                                                           problem or hidden_problem)
        grade["groups"] += groups
        group_of = {name: g.tests for g in groups for name in g.members}
        grade["tests"] += [{"stage": stage, "name": r.name, "passed": r.passed, "seconds": r.seconds,
                            "group": group_of.get(r.name), "output": "" if r.passed else report.clip(r.output)}
                           for r in outcomes.values()]
        grade["unclaimed"] += unclaimed
        for check in stage_spec.get("renders", []):
            grade["renders"].append(times.timed(f"stage {stage}: render {check['name']}", renders.check_render,
                                                builder, ROOT, stage, check))
        print(f"grade: stage {stage}: {sum(g.score for g in groups) + sum(r.score for r in grade['renders'] if r.stage == stage):.2f}"
              f" of {sum(g.points for g in groups) + sum(r.points for r in grade['renders'] if r.stage == stage):g}",
              flush=True)
    # The BVH is timed only once its stage renders right: a tree that does not work has no speed
    # worth ranking (and an unsplit one would take hours on the bunny).
    board = spec.get("leaderboard")
    stage_renders = [r for r in grade["renders"] if board and r.stage == board["stage"]]
    if stage_renders and all(r.score == r.points for r in stage_renders):
        grade["rays_per_second"], _ = times.timed("the BVH's speed", renders.bvh_rays_per_second, builder, board)
    total = sum(g.score for g in grade["groups"]) + sum(r.score for r in grade["renders"])
    possible = sum(g.points for g in grade["groups"]) + sum(r.points for r in grade["renders"])
    grade["seconds"] = deadline.elapsed()
    grade["cap_reached"] = deadline.reached()
    grade["summary"] = f"{total:.2f} of {possible:g} points (stages {', '.join(map(str, stages))})"
    report.write_reports(grade, out)
    print(f"grade: {grade['summary']}; {grade['seconds']:.0f} s of the {options.time_cap:g} s cap"
          f"{' (reached)' if grade['cap_reached'] else ''}; reports in {out}")
    return grade


def instructor_builder(build_dir, scratch, box):
    """A Builder over this tree's own build (the instructor's programs), for references and lists."""
    builder = build.Builder(box, scratch, 1, sandbox.Deadline(3600))
    builder.source, builder.build = ROOT, pathlib.Path(build_dir).resolve()
    builder.seen = {builder.source: builder.source, builder.build: builder.build}
    return builder


def build_starter(folder, stages, options, box, deadline, log):
    """Builds the instructor's tree, every task as the starter's placeholder, with the stages' tests
    and hidden tests, into `folder` (src, build), and keeps its test programs as the judges
    (build.py). True when it built."""
    spec = manifest.load(MANIFEST)
    builder = build.Builder(box, folder, options.jobs, deadline)
    build.prepare_tree(submission.starter(ROOT, spec), ROOT, builder.source, options.hidden)
    log.write_text("")
    built = builder.configure(log)
    for stage in stages or sorted(spec["stages"]):
        built = built and builder.build_stage(stage, log) and (not options.hidden or builder.build_hidden(stage, log))
    if built:
        build.keep_judges(builder.build, folder)
    return built


def starter_fingerprint():
    """The digest of the starter tree this tree makes (build.fingerprint), hidden tests included."""
    return build.fingerprint(build.tree_files(submission.starter(ROOT, manifest.load(MANIFEST)), ROOT, hidden=True))


def prepare(folder, options, box):
    """Builds the starter with every stage's tests and hidden tests into `folder` (src, build,
    judges): what --prepared grades against."""
    folder = pathlib.Path(folder).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    folder.chmod(0o755)
    box.check(folder)
    files.remove_tree(folder / build.PREPARED_MARK)
    start = time.monotonic()
    log = folder / "prepare.log"
    options.hidden = True
    if not build_starter(folder, None, options, box, sandbox.Deadline(3600), log):
        print(f"grade: the prepared build in {folder} failed; its log is {log}:\n{files.tail_of(log, 3000)}",
              file=sys.stderr)
        return 1
    seconds = time.monotonic() - start
    files.write_atomically(folder / build.PREPARED_MARK,
                           json.dumps({"seconds": round(seconds, 1), "starter": starter_fingerprint()}) + "\n")
    print(f"grade: prepared {folder} in {seconds:.0f} s; grade with --prepared {folder}")
    return 0


def make_references(build_dir, box):
    spec = manifest.load(MANIFEST)
    with tempfile.TemporaryDirectory(prefix="grade-references-") as scratch:
        os.chmod(scratch, 0o755)
        builder = instructor_builder(build_dir, scratch, box)
        for stage in sorted(spec["stages"]):
            for check in spec["stages"][stage].get("renders", []):
                print(f"grade: reference for stage {stage}, {check['name']} ({check.get('reference_runs', 1)} runs)", flush=True)
                renders.make_reference(builder, ROOT, check)


def write_test_list(build_dir):
    listed = build.list_tests(build_dir)
    about = ("Every test the grader runs and scores, per stage, with its test program: made from the instructor's "
             "build by tools/grade.py --list-tests; ctest grading_test_list checks it is current.")
    files.write_atomically(TESTS, json.dumps({"about": about, "stages": listed}, indent=1) + "\n")
    print(f"grade: wrote {TESTS} ({sum(map(len, listed.values()))} tests)")


def main():
    parser = argparse.ArgumentParser(description="Grade a submission of the ray tracing course.")
    parser.add_argument("tree", nargs="?", help="the submission to grade (a folder with the course's layout)")
    parser.add_argument("--stage", type=int, action="append", help="grade this stage (repeatable; default all)")
    parser.add_argument("--out", default="grade-report", help="folder for the reports (default grade-report)")
    parser.add_argument("--work", help="folder for the graded tree and its build (default: a temporary one; with "
                        "--prepared and --container-is-sandbox, the prepared folder itself)")
    parser.add_argument("--prepare", metavar="PREPARED", help="build the instructor's tree once into PREPARED")
    parser.add_argument("--prepared", metavar="PREPARED",
                        help="grade against the build --prepare made: only the submission's changed files compile")
    parser.add_argument("--jobs", type=int, default=2, help="parallel build and test jobs (default 2)")
    parser.add_argument("--no-hidden", dest="hidden", action="store_false",
                        help="leave the hidden tests out (a student's self-check)")
    parser.add_argument("--time-cap", type=float, default=1800,
                        help="seconds for the whole submission: builds, tests, renders (default 1800)")
    parser.add_argument("--test-timeout", type=float, help="seconds per test (default: the manifest's)")
    parser.add_argument("--memory-limit", type=int, default=4096, help="MiB of address space per process (default 4096)")
    parser.add_argument("--container-is-sandbox", action="store_true",
                        help="run without bubblewrap: this container is the isolation (docs/instructors.md)")
    parser.add_argument("--sandbox-user", type=int, help="uid the steps run as when the grader is root (default 65534)")
    parser.add_argument("--make-references", action="store_true", help="render the render checks' references")
    parser.add_argument("--list-tests", action="store_true", help="write grading/tests.json from --build")
    parser.add_argument("--build", default=str(ROOT / "build" / "release"), help="build for --make-references, --list-tests")
    args = parser.parse_args()
    box = sandbox.Sandbox(container_is_sandbox=args.container_is_sandbox, user=args.sandbox_user)
    try:
        if args.list_tests:
            write_test_list(args.build)
            return 0
        if args.make_references:
            make_references(args.build, box)
            return 0
        if args.prepare:
            return prepare(args.prepare, args, box)
        if not args.tree:
            parser.error("give the tree to grade")
        tree = pathlib.Path(args.tree)
        if not tree.is_dir():
            print(f"grade: {tree}: not a folder", file=sys.stderr)
            return 1
        if shutil.which("cmake") is None or shutil.which("ninja") is None:
            print("grade: cmake and ninja are needed (tools/setup.sh installs them)", file=sys.stderr)
            return 1
        spec = manifest.load(MANIFEST)
        unknown = [s for s in args.stage or [] if s not in spec["stages"]]
        if unknown:
            print(f"grade: {MANIFEST}: no stage {unknown[0]}", file=sys.stderr)
            return 1
        args.test_timeout = args.test_timeout or spec.get("test_timeout_seconds", 120)
        out = pathlib.Path(args.out).resolve()
        if args.prepared:
            args.prepared = pathlib.Path(args.prepared).resolve()
            if not (args.prepared / build.PREPARED_MARK).is_file():
                print(f"grade: --prepared {args.prepared}: not a finished prepared build (make it with --prepare)",
                      file=sys.stderr)
                return 1
            # Its judges replay the tests as they were when it was made: a test changed since would
            # ask for values in another order than its subject records them, and fail.
            made_from = json.loads((args.prepared / build.PREPARED_MARK).read_text()).get("starter")
            if made_from != starter_fingerprint():
                print(f"grade: --prepared {args.prepared} was made from another version of this tree (its tests, "
                      "build files or starter changed since): make it again with --prepare", file=sys.stderr)
                return 1
            if args.container_is_sandbox:  # no bind mounts: the build is graded where it was built
                args.work = args.work or str(args.prepared)
                if pathlib.Path(args.work).resolve() != args.prepared:
                    print("grade: with --container-is-sandbox, --prepared is graded in place: leave out --work",
                          file=sys.stderr)
                    return 1
        if args.work:
            work = pathlib.Path(args.work).resolve()
            if out == work or work in out.parents:
                print(f"grade: --out {args.out} lies inside --work {args.work}, where the submission's code writes",
                      file=sys.stderr)
                return 1
            grade(tree, args.stage, out, work, args)
        else:
            with tempfile.TemporaryDirectory(prefix="grade-") as work:
                grade(tree, args.stage, out, work, args)
    except sandbox.SandboxError as e:
        print(f"grade: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
