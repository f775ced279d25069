#!/usr/bin/env python3
"""Checks the solution markers of every stage (docs/solution-markers.md).

Each task region must read

    // BEGIN TASK <id>
    ...solution...
    // PLACEHOLDER
    // ...placeholder code, every line commented out with "// "...
    // END TASK

with <id> of the form stageN.topic.task, N matching the stage folder, ids unique across the tree,
no nesting, and every id listed in that stage's handout docs/stageN.md (and every id the handout
lists present in the code). Exits 1 with one line per problem.
"""
import pathlib
import re
import sys

BEGIN = re.compile(r"^\s*// BEGIN TASK (\S+)\s*$")
PLACEHOLDER = re.compile(r"^\s*// PLACEHOLDER\s*$")
END = re.compile(r"^\s*// END TASK\s*$")
ID = re.compile(r"^stage(\d+)\.[a-z0-9_]+\.[a-z0-9_]+$")
HANDOUT_ID = re.compile(r"`(stage\d+\.[a-z0-9_]+\.[a-z0-9_]+)`")


def scan(path, problems):
    """Returns the task ids found in one source file."""
    ids = []
    state, current, line_of_begin = "outside", None, 0
    for number, line in enumerate(path.read_text().splitlines(), 1):
        where = f"{path}:{number}"
        if m := BEGIN.match(line):
            if state != "outside":
                problems.append(f"{where}: BEGIN TASK inside task {current}")
            current, state, line_of_begin = m.group(1), "solution", number
            ids.append((current, where))
            if not ID.match(current):
                problems.append(f"{where}: task id '{current}' is not of the form stageN.topic.task")
        elif PLACEHOLDER.match(line):
            if state != "solution":
                problems.append(f"{where}: PLACEHOLDER outside a task's solution")
            state = "placeholder"
        elif END.match(line):
            if state != "placeholder":
                problems.append(f"{where}: END TASK without a PLACEHOLDER section")
            state = "outside"
        elif state == "placeholder" and not line.strip().startswith("//"):
            problems.append(f"{where}: placeholder line is not commented out")
    if state != "outside":
        problems.append(f"{path}:{line_of_begin}: task {current} is never closed")
    return ids


def main(root):
    root = pathlib.Path(root)
    problems, seen = [], {}
    for stage_dir in sorted((root / "stages").glob("[0-9][0-9]-*")):
        stage = int(stage_dir.name[:2])
        found = set()
        for path in sorted(stage_dir.rglob("*")):
            if path.suffix not in {".h", ".cpp"}:
                continue
            for task_id, where in scan(path, problems):
                m = ID.match(task_id)
                if m and int(m.group(1)) != stage:
                    problems.append(f"{where}: task {task_id} lives in the folder of stage {stage}")
                if task_id in seen:
                    problems.append(f"{where}: task {task_id} already defined at {seen[task_id]}")
                seen[task_id] = where
                found.add(task_id)
        handout = root / "docs" / f"stage{stage}.md"
        listed = set(HANDOUT_ID.findall(handout.read_text())) if handout.exists() else set()
        for task_id in sorted(found - listed):
            problems.append(f"{handout}: does not list task {task_id}")
        for task_id in sorted(listed - found):
            problems.append(f"{handout}: lists task {task_id}, which no code marks")
    for problem in problems:
        print(problem)
    print(f"{len(seen)} tasks checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
