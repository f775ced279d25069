#!/usr/bin/env python3
"""Collects the grader's Gradescope results (tools/grade.py --out DIR writes DIR/results.json) of a
whole class into one table, as CSV and as HTML.

    tools/class_table.py GRADES... [--submissions DIR] [--csv FILE] [--html FILE]

Each GRADES is a student's grade folder (holding results.json) or a folder of them, one
sub-folder per student, as a job per student leaves them (docs/scale-out.md). The student is the
folder's name. With --submissions, every sub-folder of DIR is a student too, so that one whose
grading job failed before it made a grade folder is not forgotten. A student without a readable
results.json (the grading job failed or has not run) gets a row that says so, and a line on
stderr; the tables are still written whole, and the exit code is then 1 so that a scheduler's
dependent job notices. So does a results.json that is not consistent with itself (a total that is
not the sum of its tests, a test above its maximum): a table of a whole class takes no total on
trust. Only the standard library is used.
"""
import argparse
import csv
import html
import io
import json
import os
import pathlib
import re
import sys
import urllib.parse

STAGE = re.compile(r"^stage (\d+):")


def folder_or_exit(path):
    if not path.is_dir():
        raise SystemExit(f"class_table: error: {path}: not a folder")
    return path


def student_folders(inputs, submissions):
    """(student, grade folder) for every grade folder named on the command line or inside one, and
    for every student in `submissions` (a grade folder beside the others, which may not exist)."""
    found = {}
    for given in map(pathlib.Path, inputs):
        if (folder_or_exit(given) / "results.json").exists():
            found[given.name] = given
        else:
            found.update((sub.name, sub) for sub in sorted(given.iterdir()) if sub.is_dir())
    if submissions:
        grades = pathlib.Path(inputs[0])
        for sub in sorted(folder_or_exit(pathlib.Path(submissions)).iterdir()):
            if sub.is_dir():
                found.setdefault(sub.name, grades / sub.name)
    return sorted(found.items())


def read_row(student, folder):
    """One student's scores per stage, total, leaderboard value and time, or why there are none."""
    path = folder / "results.json"
    row = {"student": student, "folder": folder, "stages": {}, "problem": None}
    try:
        results = json.loads(path.read_text())
        for test in results["tests"]:
            match = STAGE.match(test["name"])
            stage = int(match.group(1)) if match else 0
            score, points = row["stages"].get(stage, (0.0, 0.0))
            row["stages"][stage] = (score + float(test["score"]), points + float(test["max_score"]))
        row["score"] = float(results["score"])
        row["max_score"] = sum(points for _, points in row["stages"].values())
        row["problem"] = inconsistency(results, row)
        row["time"] = results.get("execution_time")
        board = {entry["name"]: entry["value"] for entry in results.get("leaderboard", [])}
        row["rays"] = board.get("BVH rays/s")
    except FileNotFoundError:
        row["problem"] = f"{path}: no results (the grading job failed or has not run)"
    except (OSError, ValueError, KeyError, TypeError) as e:
        row["problem"] = f"{path}: unreadable results ({type(e).__name__}: {e})"
    return row


def inconsistency(results, row):
    """Why a results.json cannot be the grader's, or None. The grader writes it where no submission
    can, but a table of a whole class should not take a total on trust: it must be the sum of the
    tests' scores, none of them negative or above its maximum."""
    tests = results["tests"]
    if not tests:
        return f"{row['folder'] / 'results.json'}: inconsistent results: no tests, yet a score of {row['score']:g}"
    for test in tests:
        if not 0 <= float(test["score"]) <= float(test["max_score"]):
            return (f"{row['folder'] / 'results.json'}: inconsistent results: {test['name']} scores "
                    f"{float(test['score']):g} of {float(test['max_score']):g}")
    total = sum(float(test["score"]) for test in tests)
    if abs(total - row["score"]) > 0.01 * len(tests) + 1e-9:
        return (f"{row['folder'] / 'results.json'}: inconsistent results: a score of {row['score']:g}, but its tests "
                f"add up to {total:g}")
    return None


def stage_header(stage):
    return f"stage {stage}" if stage else "other"


def table(rows):
    """The header and one list of cells per student, as both outputs show them."""
    stages = sorted({s for row in rows for s in row["stages"]})
    header = ["student", *map(stage_header, stages), "score", "max_score", "percent", "bvh_rays_per_second",
              "grading_seconds", "problem"]
    body = []
    for row in rows:
        if row["problem"]:
            body.append([row["student"], *[""] * (len(stages) + 5), row["problem"]])
            continue
        percent = 100.0 * row["score"] / row["max_score"] if row["max_score"] else 0.0
        body.append([row["student"], *(f"{row['stages'][s][0]:g}" if s in row["stages"] else "" for s in stages),
                     f"{row['score']:g}", f"{row['max_score']:g}", f"{percent:.1f}",
                     "" if row["rays"] is None else str(row["rays"]), "" if row["time"] is None else str(row["time"]),
                     ""])
    return header, body, stages


def write_csv(header, body):
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(body)
    return out.getvalue()


def write_html(rows, header, body, stages, html_path):
    """A sortable-by-eye table: each stage cell shaded by the fraction of its points, a link to the
    student's own report where the grade folder has one."""
    def cell(text, fraction=None):
        style = ""
        if fraction is not None:
            style = f' style="background: hsl({int(120 * fraction)}, 60%, 85%)"'
        return f"<td{style}>{html.escape(text)}</td>"

    lines = ["<!doctype html>", '<meta charset="utf-8">', "<title>Class grades</title>",
             "<style>body{font-family:sans-serif} table{border-collapse:collapse} "
             "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right} td:first-child{text-align:left}"
             " .problem{color:#a00;text-align:left}</style>",
             f"<h1>Class grades</h1><p>{len(rows)} students, "
             f"{sum(1 for r in rows if r['problem'])} without results.</p>", "<table>",
             "<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header[:-1]) + "<th>report</th></tr>"]
    for row, cells in zip(rows, body):
        if row["problem"]:
            lines.append(f"<tr>{cell(row['student'])}<td class=problem colspan={len(header) - 1}>"
                         f"{html.escape(row['problem'])}</td></tr>")
            continue
        stage_cells = "".join(
            cell(cells[1 + i], row["stages"][s][0] / row["stages"][s][1] if row["stages"][s][1] else 1.0)
            if s in row["stages"] else cell("") for i, s in enumerate(stages))
        report = row["folder"] / "report.html"
        link = ""
        if report.exists():
            href = os.path.relpath(report, html_path.parent) if html_path else str(report)
            link = f'<a href="{html.escape(urllib.parse.quote(pathlib.Path(href).as_posix()))}">report</a>'
        totals = "".join(cell(c) for c in cells[1 + len(stages):-1])
        lines.append(f"<tr>{cell(row['student'])}{stage_cells}{totals}<td>{link}</td></tr>")
    lines.append("</table>")
    return "\n".join(lines) + "\n"


def write_atomically(path, text):
    temporary = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        temporary.write_text(text)
        os.replace(temporary, path)
    except OSError as e:
        temporary.unlink(missing_ok=True)
        raise SystemExit(f"class_table: error: {path}: cannot write ({e.strerror})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("grades", nargs="+", help="a student's grade folder, or a folder of them")
    parser.add_argument("--submissions", help="the folder of the students' trees: each one gets a row")
    parser.add_argument("--csv", type=pathlib.Path, help="write the table as CSV here")
    parser.add_argument("--html", type=pathlib.Path, help="write the table as HTML here")
    args = parser.parse_args()
    folders = student_folders(args.grades, args.submissions)
    if not folders:
        raise SystemExit(f"class_table: error: {', '.join(args.grades)}: no grade folders in it")
    rows = [read_row(student, folder) for student, folder in folders]
    header, body, stages = table(rows)
    text = write_csv(header, body)
    if args.csv:
        write_atomically(args.csv, text)
    if args.html:
        write_atomically(args.html, write_html(rows, header, body, stages, args.html))
    if not args.csv and not args.html:
        sys.stdout.write(text)
    problems = [row["problem"] for row in rows if row["problem"]]
    for problem in problems:
        print(f"class_table: {problem}", file=sys.stderr)
    graded = len(rows) - len(problems)
    print(f"class_table: {graded} of {len(rows)} students graded"
          + "".join(f", wrote {p}" for p in (args.csv, args.html) if p), file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
