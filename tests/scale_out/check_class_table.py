#!/usr/bin/env python3
"""ctest class_table: tools/class_table.py turns the grader's results.json files of a class into one
CSV and one HTML table: per-stage sums, totals and percentages right, names escaped, and a student
without readable or consistent results listed (not dropped) with exit code 1."""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "class_table.py"


def results(tests, rays=None, seconds=12.5):
    data = {"score": sum(t[1] for t in tests), "execution_time": seconds, "output": "", "visibility": "visible",
            "tests": [{"name": n, "score": s, "max_score": m, "output": "", "visibility": "visible"} for n, s, m in tests]}
    if rays is not None:
        data["leaderboard"] = [{"name": "BVH rays/s", "value": rays, "order": "desc"}]
    return json.dumps(data)


def run(*args):
    return subprocess.run([sys.executable, str(TOOL), *map(str, args)], capture_output=True, text=True)


def main():
    failures = []

    def check(condition, what):
        if not condition:
            failures.append(what)

    with tempfile.TemporaryDirectory() as tmp:
        grades = pathlib.Path(tmp) / "grades"
        students = {
            "ann": results([("stage 1: Sphere.*", 3, 3), ("stage 1: render spheres", 5, 5),
                            ("stage 2: Triangle.*", 4, 4)], rays=2000000),
            "ben": results([("stage 1: Sphere.*", 1, 3), ("stage 1: render spheres", 0, 5),
                            ("stage 2: Triangle.*", 2.5, 4)]),
            "<script>x": results([("stage 1: Sphere.*", 3, 3), ("stage 2: Triangle.*", 0, 4)]),
            "cy": "{ not json",
            "dee": None,
        }
        for name, text in students.items():
            (grades / name).mkdir(parents=True)
            if text is not None:
                (grades / name / "results.json").write_text(text)
        (grades / "ann" / "report.html").write_text("<p>ann</p>")
        out_csv, out_html = pathlib.Path(tmp) / "class.csv", pathlib.Path(tmp) / "class.html"
        r = run(grades, "--csv", out_csv, "--html", out_html)
        check(r.returncode == 1, f"exit code {r.returncode} with two students lacking results (want 1)")
        check("grades/cy/results.json: unreadable results" in r.stderr, f"cy's broken file not named: {r.stderr}")
        check("grades/dee/results.json: no results" in r.stderr, f"dee's missing file not named: {r.stderr}")
        rows = {row["student"]: row for row in csv.DictReader(out_csv.read_text().splitlines())}
        check(sorted(rows) == sorted(students), f"students in the CSV: {sorted(rows)}")
        ann, ben = rows["ann"], rows["ben"]
        check((ann["stage 1"], ann["stage 2"], ann["score"], ann["max_score"], ann["percent"]) == ("8", "4", "12", "12", "100.0"),
              f"ann's row: {ann}")
        check(ann["bvh_rays_per_second"] == "2000000" and ann["grading_seconds"] == "12.5", f"ann's extras: {ann}")
        check((ben["stage 1"], ben["stage 2"], ben["score"], ben["max_score"], ben["percent"]) == ("1", "2.5", "3.5", "12", "29.2"),
              f"ben's row: {ben}")
        check(rows["dee"]["score"] == "" and "no results" in rows["dee"]["problem"], f"dee's row: {rows['dee']}")
        page = out_html.read_text()
        check("&lt;script&gt;x" in page and "<script>" not in page, "a student's name is not escaped in the HTML")
        check('href="grades/ann/report.html"' in page, "no link to ann's own report")
        check(page.count("<tr>") == 1 + len(students), f"{page.count('<tr>')} table rows for {len(students)} students")

        # A student whose grading job failed before it made a grade folder: --submissions lists them.
        submissions = pathlib.Path(tmp) / "submissions"
        for name in [*students, "eve"]:
            (submissions / name).mkdir(parents=True)
        r = run(grades, "--submissions", submissions, "--csv", out_csv)
        rows = {row["student"]: row for row in csv.DictReader(out_csv.read_text().splitlines())}
        check("eve" in rows and "grades/eve/results.json: no results" in rows["eve"]["problem"],
              f"a submission without a grade folder is missing from the table: {sorted(rows)}")
        check(r.returncode == 1 and len(rows) == len(students) + 1, f"--submissions: exit {r.returncode}, {len(rows)} rows")

        # Forged results (a total that is not its tests' sum, a test above its maximum, no tests at
        # all) are named, not added to the table.
        forged = pathlib.Path(tmp) / "forged"
        for name, text in {"fay": json.dumps({"score": 175, "tests": []}),
                           "gus": results([("stage 1: Sphere.*", 3, 3)]).replace('"score": 3', '"score": 175', 1),
                           "hal": results([("stage 1: Sphere.*", 6, 5)])}.items():
            (forged / name).mkdir(parents=True)
            (forged / name / "results.json").write_text(text)
        r = run(forged, "--csv", out_csv)
        rows = {row["student"]: row for row in csv.DictReader(out_csv.read_text().splitlines())}
        check(r.returncode == 1, f"forged results: exit code {r.returncode} (want 1)")
        for name, said in (("fay", "no tests, yet a score of 175"), ("gus", "a score of 175, but its tests add up to 3"),
                           ("hal", "stage 1: Sphere.* scores 6 of 5")):
            check(f"inconsistent results: {said}" in rows[name]["problem"] and rows[name]["score"] == "",
                  f"{name}'s forged results: {rows[name]}")

        # Only good students: exit 0; a single student's folder works too.
        for name in ("cy", "dee"):
            for f in (grades / name).iterdir():
                f.unlink()
            (grades / name).rmdir()
        r = run(grades, "--csv", out_csv)
        check(r.returncode == 0, f"exit code {r.returncode} with every student graded: {r.stderr}")
        r = run(grades / "ann")
        check(r.returncode == 0 and r.stdout.splitlines()[1].startswith("ann,8,4,12,12,100.0"), f"one folder: {r.stdout}")
        r = run(pathlib.Path(tmp) / "nowhere")
        check(r.returncode == 1 and r.stderr.strip().endswith("nowhere: not a folder"), f"missing folder: {r.stderr}")

    for failure in failures:
        print(f"FAIL: {failure}")
    print("class_table: " + ("all checks passed" if not failures else f"{len(failures)} checks failed"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
