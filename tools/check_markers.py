#!/usr/bin/env python3
"""Checks the solution markers of every stage (docs/solution-markers.md).

Each task region must read

    // BEGIN TASK <id>
    ...solution...
    // PLACEHOLDER
    // ...placeholder code, every line commented out with "// "...
    // END TASK

with <id> of the form stageN.topic.task, N matching the stage folder, ids unique across the tree,
no nesting, only in .cpp files (a header is compiled into the test programs, so a task there
would let a submission's code rewrite the tests, and each edit would rebuild every file that
includes it; docs/instructors.md), and every id listed in that stage's handout docs/stageN.md (and every id the handout
lists present in the code). Exits 1 with one line per problem.
"""
import sys

import task_regions


def main(root):
    problems, seen = [], {}
    for stage, folder in task_regions.stage_folders(root):
        found = set()
        for path in task_regions.source_files(folder):
            for region in task_regions.parse(path, problems):
                where = f"{path}:{region.begin + 1}"
                if path.suffix != ".cpp":
                    problems.append(f"{where}: task {region.task_id} is in a header; tasks live in .cpp files")
                if region.stage != stage:
                    problems.append(f"{where}: task {region.task_id} lives in the folder of stage {stage}")
                if region.task_id in seen:
                    problems.append(f"{where}: task {region.task_id} already defined at {seen[region.task_id]}")
                seen[region.task_id] = where
                found.add(region.task_id)
        handout = f"{root}/docs/stage{stage}.md"
        listed = task_regions.handout_ids(root, stage)
        for task_id in sorted(found - listed):
            problems.append(f"{handout}: does not list task {task_id}")
        for task_id in sorted(listed - found):
            problems.append(f"{handout}: lists task {task_id}, which no code marks")
        for task_id in sorted(listed - set(task_regions.handout_tasks(root, stage))):
            problems.append(f"{handout}: the row of task {task_id} is not a Tasks row (| id | file | what | tests |)")
    for problem in problems:
        print(problem)
    print(f"{len(seen)} tasks checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
