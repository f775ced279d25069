#!/usr/bin/env python3
"""Which other tasks of its stage each task's tests reach, for the handouts' Tasks tables.

A placeholder prints `TODO: task <id> is not implemented yet` the first time it runs, so a test
run alone on a built starter tree names every unfinished task its code reached before it stopped.
For each task of docs/stageN.md, the tasks of the same stage whose code its listed tests run (its
own left out) are those a student meets in their output and, most often, must finish before the
tests can pass (a test that stops at its first failure may reach fewer before it is fixed).
Earlier stages' tasks are left out: a student reaches stage N with them done.

    tools/task_prerequisites.py STARTER [--stage N] [--write]

STARTER is a starter tree (tools/make_starter.py) built with `cmake --build --preset stageN`.
Without --write it prints, per task, the tasks its tests reach; with --write it fills the Tasks
tables' last column ("its tests also reach") of this tree's handouts.
"""
import argparse
import fnmatch
import pathlib
import re
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import task_regions  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
TODO = re.compile(r"TODO: task (stage\d+\.[a-z0-9_]+\.[a-z0-9_]+) is not implemented")
COLUMN = "its tests also reach"


def tests_of(program):
    """Every test of a GoogleTest program, as Suite.Name."""
    listed = subprocess.run([str(program), "--gtest_list_tests"], capture_output=True, text=True, check=True)
    names, suite = [], None
    for line in listed.stdout.splitlines():
        if not line.startswith(" "):
            suite = line.split()[0]
        elif line.strip():
            names.append(suite + line.split()[0])
    return names


def reached_tasks(program, test):
    """The unfinished tasks one test reaches when it runs alone."""
    done = subprocess.run([str(program), f"--gtest_filter={test}"], capture_output=True, text=True, timeout=300)
    return set(TODO.findall(done.stdout + done.stderr))


def prerequisites(starter, stage):
    program = starter / "build" / "release" / "bin" / f"stage{stage}_tests"
    if not program.is_file():
        raise SystemExit(f"task_prerequisites: {program} is missing: build it with cmake --build --preset stage{stage}")
    reached = {test: reached_tasks(program, test) for test in tests_of(program)}
    result = {}
    for task, listed in task_regions.handout_tasks(ROOT, stage).items():
        tasks = set()
        for pattern in listed.tests:
            for test, its_tasks in reached.items():
                if fnmatch.fnmatchcase(test, pattern):
                    tasks |= its_tasks
        result[task] = sorted(t for t in tasks if t != task and t.startswith(f"stage{stage}."))
    return result


def cell(tasks):
    return " " + (", ".join(f"`{t}`" for t in tasks) if tasks else "none") + " "


def first_four_cells(line):
    return "|" + "|".join(re.split(r"(?<!\\)\|", line)[1:5]) + "|"


def write_column(stage, found):
    """Puts the column into docs/stageN.md's Tasks table, replacing the one there."""
    path = ROOT / "docs" / f"stage{stage}.md"
    lines = path.read_text().splitlines()
    for i, line in enumerate(lines):
        if line.startswith("| task id |"):
            lines[i] = first_four_cells(line) + f" {COLUMN} |"
            lines[i + 1] = "|---|---|---|---|---|"
        elif m := task_regions.HANDOUT_ROW.match(line):
            lines[i] = first_four_cells(line) + cell(found.get(m.group(1), [])) + "|"
    path.write_text("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description="The tasks each task's tests also reach.")
    parser.add_argument("starter", type=pathlib.Path, help="a built starter tree")
    parser.add_argument("--stage", type=int, action="append", help="a stage (default: every stage)")
    parser.add_argument("--write", action="store_true", help="fill the handouts' column")
    args = parser.parse_args()
    for stage in args.stage or [s for s, _ in task_regions.stage_folders(ROOT)]:
        found = prerequisites(args.starter.resolve(), stage)
        for task, tasks in found.items():
            print(f"{task}: {', '.join(tasks) or 'none'}")
        if args.write:
            write_column(stage, found)
    return 0


if __name__ == "__main__":
    sys.exit(main())
