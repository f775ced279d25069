#!/usr/bin/env python3
"""Makes the student starter tree: this repository with every task's solution cut out.

    tools/make_starter.py DEST [--stages 1-7] [--others strip|keep] [--force]

Each task region (docs/solution-markers.md) of the chosen stages keeps its markers, and its solution
becomes its placeholder (which compiles, says "TODO: task <id> is not implemented yet" once, and
returns something harmless) under a TODO comment that names the task, what to write, where its
formula and source are, and the tests that check it (all from the handout's task table).

--stages A-B picks the stages whose tasks are stripped (default: all). Tasks of the other stages are
stripped too unless --others keep is given. Stripping is the default because a starter tree is
handed out: a kept solution would give away a later assignment, and the placeholders already keep
every stage building and running. --others keep is for a class that starts mid-course: e.g.
--stages 3-5 --others keep hands out stages 1 and 2 solved.

Instructor-only material never goes in: the hidden tests (tests/hidden/) and their names in
grading/tests.json, the render checks' references (grading/references/: a stored answer a program
could write instead of rendering), the grader's own proofs (tests/grading/, which plant bugs into
solutions), the mutation tool and its list of equivalent mutants (tools/mutation.py and
grading/equivalent-mutants.json, which quote solution lines) and the repository's CI (.ci/). Only files git tracks or would track are copied (no
build folders). Exits 1 with one line if DEST exists (unless
--force) or the markers are malformed.
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

import task_regions

INSTRUCTOR_ONLY = ("tests/hidden/", "tests/grading/", ".ci/", "grading/references/", "tools/mutation.py",
                   "grading/equivalent-mutants.json", "tools/check_references.py")


def parse_stages(text):
    first, _, last = text.partition("-")
    try:
        stages = range(int(first), int(last or first) + 1)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a stage range like 1-5 or 3")
    if not stages or stages[0] < 1:
        raise argparse.ArgumentTypeError(f"'{text}' is not a stage range like 1-5 or 3")
    return set(stages)


def todo_comment(region, task):
    """The TODO block that replaces a solution: what to write, where the formula is, what checks it."""
    stage = region.stage
    what = task.what if task else "see the handout"
    tests = ", ".join(task.tests) if task and task.tests else f"the tests of label stage{stage}"
    return [
        f"// TODO({region.task_id}): {what}.",
        f"//   Formula and source: the comment on this function in its header; docs/stage{stage}.md, Tasks.",
        f"//   Checked by: {tests} (cmake --build --preset stage{stage} && ctest --preset stage{stage}).",
        "//   Write your code in place of the placeholder lines below, down to PLACEHOLDER.",
    ]


def strip_file(path, stages, problems, handouts):
    """The file's text with the solutions of `stages` replaced, or None if it has no such region."""
    lines = path.read_text().splitlines()
    regions = [r for r in task_regions.parse(path, problems) if r.stage in stages]
    if not regions:
        return None
    out, position = [], 0
    for region in regions:
        out += lines[position:region.begin + 1]
        task = handouts.get(region.stage, {}).get(region.task_id)
        out += [region.indent + line for line in todo_comment(region, task)]
        out += region.placeholder_code(lines)
        out += [lines[region.placeholder], lines[region.end]]
        position = region.end + 1
    out += lines[position:]
    return "\n".join(out) + "\n"


def tracked_files(root):
    """The files git tracks or would track, instructor-only material left out."""
    return [f for f in repository_files(root) if not f.startswith(INSTRUCTOR_ONLY)]


def repository_files(root):
    """The files git tracks or would track; outside a git checkout (an unpacked archive), every
    file but build outputs."""
    try:
        listing = subprocess.run(["git", "-C", str(root), "ls-files", "-co", "--exclude-standard", "-z"],
                                 check=True, capture_output=True, text=True).stdout.split("\0")
    except (OSError, subprocess.CalledProcessError):
        skipped = {".git", "build", "out", "__pycache__"}
        listing = [p.relative_to(root).as_posix() for p in root.rglob("*")
                   if p.is_file() and not skipped & set(p.relative_to(root).parts)]
    return [f for f in listing if f]


def without_hidden_tests(text):
    """grading/tests.json without the hidden tests' names."""
    listed = json.loads(text)
    listed["stages"] = {stage: [t for t in tests if not t["program"].endswith("_hidden_tests")]
                        for stage, tests in listed["stages"].items()}
    return json.dumps(listed, indent=1) + "\n"


def make_starter(root, dest, stages):
    root, dest = pathlib.Path(root).resolve(), pathlib.Path(dest)
    problems = []
    handouts = {stage: task_regions.handout_tasks(root, stage) for stage, _ in task_regions.stage_folders(root)}
    stripped = {}
    for _, folder in task_regions.stage_folders(root):
        for path in task_regions.source_files(folder):
            text = strip_file(path, stages, problems, handouts)
            if text is not None:
                stripped[path.relative_to(root).as_posix()] = text
    if problems:
        raise ValueError(f"{root}: malformed task markers, first: {problems[0]}")
    for name in tracked_files(root):
        source, target = root / name, dest / name
        if not source.is_file():
            continue  # deleted in the working tree but not yet in git
        target.parent.mkdir(parents=True, exist_ok=True)
        if name in stripped:
            target.write_text(stripped[name])
        elif name == "grading/tests.json":
            target.write_text(without_hidden_tests(source.read_text()))
        else:
            shutil.copy2(source, target)
    return len(stripped)


def main():
    parser = argparse.ArgumentParser(description="Make the student starter tree (solutions cut out).")
    parser.add_argument("dest", help="folder to create")
    parser.add_argument("--stages", type=parse_stages, default=set(range(1, 8)),
                        help="stages whose tasks are stripped, e.g. 1-7 (default) or 3-5")
    parser.add_argument("--others", choices=["strip", "keep"], default="strip",
                        help="the other stages' tasks: strip (default) or keep solved")
    parser.add_argument("--force", action="store_true", help="replace DEST if it exists")
    args = parser.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    dest = pathlib.Path(args.dest)
    if dest.exists() and not args.force:
        print(f"make_starter: {dest}: already exists (use --force to replace it)", file=sys.stderr)
        return 1
    if dest.resolve() == root or root in dest.resolve().parents:
        print(f"make_starter: {dest}: must be outside the repository", file=sys.stderr)
        return 1
    stages = args.stages if args.others == "keep" else set(range(1, 100))
    if dest.exists():
        shutil.rmtree(dest)
    try:
        files = make_starter(root, dest, stages)
    except ValueError as error:
        shutil.rmtree(dest, ignore_errors=True)
        print(f"make_starter: {error}", file=sys.stderr)
        return 1
    kept = "" if args.others == "strip" else f"; stages outside {min(args.stages)}-{max(args.stages)} kept solved"
    print(f"make_starter: wrote {dest} ({files} source files with tasks stripped{kept})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
