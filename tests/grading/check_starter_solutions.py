#!/usr/bin/env python3
"""No solution survives in the starter tree (ctest starter_has_no_solutions, label common).

Makes the starter tree in a temporary folder and searches it for every marked region's solution:
the region's whole text anywhere in the tree, and each of its lines in the file the region was in,
unless that line also appears in the same file outside every solution (a closing brace, a return
that the placeholder has too). Also checks that each region still has its markers and its TODO,
and that the instructor-only folders are absent. Exits 1 with one line per leak.
"""
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import task_regions  # noqa: E402
from make_starter import INSTRUCTOR_ONLY  # noqa: E402


def main():
    problems, regions_checked = [], 0
    with tempfile.TemporaryDirectory() as temp:
        starter = pathlib.Path(temp) / "starter"
        subprocess.run([sys.executable, ROOT / "tools" / "make_starter.py", starter], check=True, capture_output=True)
        starter_texts = {p: p.read_text(errors="replace") for p in starter.rglob("*") if p.is_file()}
        everything = "\n".join(starter_texts.values())
        for folder in INSTRUCTOR_ONLY:
            if (starter / folder).exists():
                problems.append(f"{folder}: instructor-only, but in the starter tree")
        for _, folder in task_regions.stage_folders(ROOT):
            for path in task_regions.source_files(folder):
                lines = path.read_text().splitlines()
                regions = task_regions.parse(path, problems)
                inside = {i for r in regions for i in range(r.begin + 1, r.placeholder)}
                outside = {lines[i].strip() for i in range(len(lines)) if i not in inside}
                outside |= {line.strip() for r in regions for line in r.placeholder_code(lines)}
                relative = path.relative_to(ROOT)
                starter_file = starter_texts.get(starter / relative, "")
                starter_lines = {line.strip() for line in starter_file.splitlines()}
                for region in regions:
                    regions_checked += 1
                    solution = region.solution(lines)
                    text = "\n".join(solution).strip()
                    if text and text in everything:
                        problems.append(f"{relative}: the solution of {region.task_id} is in the starter tree")
                    for line in solution:
                        if line.strip() and line.strip() not in outside and line.strip() in starter_lines:
                            problems.append(f"{relative}: {region.task_id}: solution line survives: {line.strip()}")
                    if f"// TODO({region.task_id})" not in starter_file:
                        problems.append(f"{relative}: {region.task_id}: no TODO in the starter tree")
    for problem in problems:
        print(problem)
    print(f"{regions_checked} task regions searched for in the starter tree, {len(problems)} leaks")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
