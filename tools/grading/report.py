"""The grader's three reports: results.json in the Gradescope autograder format, report.md, and
report.html (per stage: the score, each failed test with its message, each render beside its
reference with a heat map of the difference and the error metric)."""
import base64
import html
import json
import pathlib

import numpy as np

from . import files, images

MAX_OUTPUT = 4000  # characters of a failed test's output kept in the reports


def clip(text):
    return text if len(text) <= MAX_OUTPUT else text[:MAX_OUTPUT] + "\n[... cut]"


def group_title(group):
    return f"stage {group.stage}: {group.tests}" + (" (hidden)" if group.hidden else "")


def gradescope(grade):
    """Gradescope's results.json: one entry per test group and per render check; hidden groups are
    shown to students only once the instructor publishes the grades."""
    tests = []
    for g in grade["groups"]:
        output = "\n\n".join(f"{name}:\n{clip(text)}" for name, text in g.failures) or "all passed"
        tests.append({"name": group_title(g), "score": g.score, "max_score": g.points,
                      "output": f"{g.passed} of {g.count} passed. Tasks: {', '.join(g.tasks) or '-'}\n{output}",
                      "tags": g.tasks, "visibility": "after_published" if g.hidden else "visible"})
    for r in grade["renders"]:
        tests.append({"name": f"stage {r.stage}: render {r.name}", "score": r.score, "max_score": r.points,
                      "output": "\n".join(r.problems) or f"matches the reference (RMSE {r.rmse:.4g})",
                      "visibility": "visible"})
    if grade.get("flags"):
        tests.append({"name": "for the instructor: calls a task has no business making", "score": 0, "max_score": 0,
                      "output": "\n".join(f"{f.file}:{f.line}: {f.why}: {f.text}" for f in grade["flags"]),
                      "visibility": "hidden"})
    output = "\n".join([grade["summary"], *notes(grade)])
    result = {"score": round(sum(t["score"] for t in tests), 2), "execution_time": round(grade["seconds"], 1),
              "output": output, "visibility": "visible", "stdout_visibility": "hidden", "tests": tests}
    if grade.get("rays_per_second"):
        result["leaderboard"] = [{"name": "BVH rays/s", "value": round(grade["rays_per_second"]), "order": "desc"}]
    return result


def notes(grade):
    """Lines about the submission as a whole: files refused, the time cap."""
    lines = list(grade.get("notes", []))
    if grade.get("cap_reached"):
        lines.append(f"The time cap of {grade['time_cap']:g} s was reached: what had not run by then counts as failed.")
    return lines


def stage_scores(grade):
    stages = {}
    for item in [*grade["groups"], *grade["renders"]]:
        score, points = stages.get(item.stage, (0.0, 0.0))
        stages[item.stage] = (score + item.score, points + item.points)
    return stages


def markdown(grade):
    lines = [f"# Grade: {grade['tree']}", "", grade["summary"], "",
             f"Graded in {grade['seconds']:.0f} s of a {grade['time_cap']:g} s cap.", ""]
    lines += [f"- {line}" for line in notes(grade)] + ([""] if notes(grade) else [])
    lines += ["| stage | score | of |", "|---|---:|---:|"]
    for stage, (score, points) in sorted(stage_scores(grade).items()):
        lines.append(f"| {stage} | {score:.2f} | {points:g} |")
    for stage in sorted(stage_scores(grade)):
        lines += ["", f"## Stage {stage}", ""]
        if grade["build_problems"].get(stage):
            lines += ["Build failed:", "```", clip(grade["build_problems"][stage]), "```", ""]
        for g in (g for g in grade["groups"] if g.stage == stage):
            lines.append(f"- {'ok' if not g.failures else 'FAILED'} `{g.tests}`{' (hidden)' if g.hidden else ''}: "
                         f"{g.score:g} / {g.points:g} ({g.passed} of {g.count} passed)")
            for name, text in g.failures:
                lines += [f"  - `{name}`:", "    ```", *("    " + l for l in clip(text).splitlines()), "    ```"]
        for r in (r for r in grade["renders"] if r.stage == stage):
            if not r.checked:
                lines.append(f"- not checked: render {r.name} (its reference is the instructor's)")
                continue
            lines.append(f"- {'ok' if not r.problems else 'FAILED'} render {r.name}: {r.score:g} / {r.points:g}, "
                         f"RMSE {r.rmse:.4g}" + "".join(f"\n  - {p}" for p in r.problems))
    if grade.get("rays_per_second"):
        lines += ["", f"Leaderboard: BVH {grade['rays_per_second'] / 1e6:.2f} M rays/s (bunny, 1 thread)."]
    if grade["unclaimed"]:
        lines += ["", "Tests not in the manifest (worth nothing): " + ", ".join(f"`{n}`" for n in grade["unclaimed"])]
    lines += time_section(grade)
    lines += instructor_section(grade)
    return "\n".join(lines) + "\n"


def time_section(grade):
    """Each step's seconds: where a grading's time went."""
    if not grade.get("steps"):
        return []
    built = "against the prepared build (only the changed files compiled)" if grade.get("prepared") else \
        "building the whole tree"
    lines = ["", "## Time", "", f"Graded {built}.", "", "| step | seconds |", "|---|---:|"]
    lines += [f"| {name} | {seconds:.1f} |" for name, seconds in grade["steps"]]
    return lines + [f"| total | {grade['seconds']:.1f} |"]


def instructor_section(grade):
    """What only the instructor reads: hidden builds that failed, and the flagged calls."""
    lines = []
    for stage, log in sorted(grade.get("hidden_build_problems", {}).items()):
        lines += ["", f"## Stage {stage}: the hidden tests did not build", "", "```", clip(log), "```"]
    if grade.get("flags"):
        lines += ["", "## Flags: calls a task has no business making", "",
                  "A test's own process can misbehave in ways no sandbox stops (writing its report and ending "
                  "early, say); these lines of the student's are worth reading.", ""]
        lines += [f"- `{f.file}:{f.line}`: {f.why}: `{f.text}`" for f in grade["flags"]]
    return lines


def png_data_uri(rgb8, scale):
    return "data:image/png;base64," + base64.b64encode(images.png_bytes(rgb8, scale)).decode()


def render_figure(r):
    """The student's render, the reference, and the difference as a heat map, side by side."""
    if r.student is None or r.difference is None:
        return "<p>No image came out.</p>"
    scale = max(1, 192 // r.reference.shape[1])
    if r.statistical:
        # t^2 rather than |t|, so that chance differences (|t| around 1) stay dark and only pixels
        # near the failing level (|t| about 4.5 for 12,288 tests) light up.
        heat = images.heat_map(np.square(r.difference), 25.0)
        caption = "Welch's t squared (white: |t| of 5 or more)"
    else:
        heat = images.heat_map(r.difference, 0.05)
        caption = "|difference| (white: 0.05 or more)"
    cells = [("student (mean of runs)" if r.statistical else "student", images.to_display(r.student)),
             ("reference", images.to_display(r.reference)), (caption, heat)]
    figures = "".join(f"<figure><img src='{png_data_uri(img, scale)}'><figcaption>{html.escape(c)}</figcaption></figure>"
                      for c, img in cells)
    return f"<div class='row'>{figures}</div>"


def html_report(grade):
    parts = [f"<h1>Grade: {html.escape(str(grade['tree']))}</h1><p>{html.escape(grade['summary'])}</p>",
             f"<p>Graded in {grade['seconds']:.0f} s of a {grade['time_cap']:g} s cap.</p>",
             *(f"<p class='bad'>{html.escape(line)}</p>" for line in notes(grade)),
             "<table><tr><th>stage</th><th>score</th><th>of</th></tr>"]
    for stage, (score, points) in sorted(stage_scores(grade).items()):
        parts.append(f"<tr><td>{stage}</td><td>{score:.2f}</td><td>{points:g}</td></tr>")
    parts.append("</table>")
    if grade.get("rays_per_second"):
        parts.append(f"<p>Leaderboard: BVH {grade['rays_per_second'] / 1e6:.2f} M rays/s (bunny, 1 thread).</p>")
    for stage in sorted(stage_scores(grade)):
        score, points = stage_scores(grade)[stage]
        parts.append(f"<h2>Stage {stage}: {score:.2f} of {points:g}</h2>")
        if grade["build_problems"].get(stage):
            parts.append(f"<p class='bad'>Build failed:</p><pre>{html.escape(clip(grade['build_problems'][stage]))}</pre>")
        parts.append("<table><tr><th>tests</th><th>passed</th><th>score</th><th>tasks</th></tr>")
        for g in (g for g in grade["groups"] if g.stage == stage):
            css = "ok" if not g.failures else "bad"
            parts.append(f"<tr class='{css}'><td><code>{html.escape(g.tests)}</code>{' (hidden)' if g.hidden else ''}</td>"
                         f"<td>{g.passed} / {g.count}</td><td>{g.score:g} / {g.points:g}</td>"
                         f"<td>{html.escape(', '.join(g.tasks))}</td></tr>")
        parts.append("</table>")
        for g in (g for g in grade["groups"] if g.stage == stage and g.failures):
            for name, text in g.failures:
                parts.append(f"<details><summary class='bad'>{html.escape(name)}</summary><pre>{html.escape(clip(text))}</pre></details>")
        for r in (r for r in grade["renders"] if r.stage == stage):
            if not r.checked:
                parts.append(f"<h3>Render: {html.escape(r.name)}: not checked (its reference is the instructor's)</h3>")
                continue
            css = "ok" if not r.problems else "bad"
            parts.append(f"<h3 class='{css}'>Render: {html.escape(r.name)}: {r.score:g} / {r.points:g}, RMSE {r.rmse:.4g}</h3>")
            parts += [f"<p class='bad'>{html.escape(p)}</p>" for p in r.problems]
            parts.append(render_figure(r))
    extra = instructor_section(grade)
    if extra:
        parts.append(f"<pre>{html.escape(chr(10).join(extra))}</pre>")
    style = ("body{font-family:sans-serif;max-width:60em;margin:auto} table{border-collapse:collapse} "
             "td,th{border:1px solid #ccc;padding:2px 8px} .bad{color:#b00} .ok{color:#070} "
             ".row{display:flex;gap:1em} figure{margin:0} figcaption{font-size:80%} img{image-rendering:pixelated}")
    return f"<!doctype html><meta charset='utf-8'><title>Grade</title><style>{style}</style>{''.join(parts)}\n"


def outcomes(grade):
    """Every test and render check with its outcome, for scripts (a class table, the grader's proofs)."""
    return {"tree": grade["tree"], "summary": grade["summary"], "tests": grade["tests"],
            "groups": [{"stage": g.stage, "tests": g.tests, "points": g.points, "count": g.count, "score": g.score,
                        "hidden": g.hidden, "tasks": g.tasks} for g in grade["groups"]],
            "renders": [{"stage": r.stage, "name": r.name, "points": r.points, "score": r.score,
                         "rmse": r.rmse if r.rmse == r.rmse else None,
                         "problems": r.problems} for r in grade["renders"]],
            "rays_per_second": grade.get("rays_per_second"), "seconds": grade["seconds"], "steps": grade.get("steps", []),
            "time_cap": grade["time_cap"], "cap_reached": grade.get("cap_reached", False), "notes": grade.get("notes", []),
            "flags": [{"file": f.file, "line": f.line, "why": f.why, "text": f.text} for f in grade.get("flags", [])]}


def write_reports(grade, out):
    """The four reports, each written atomically: a reader (Gradescope, class_table.py) sees the old
    one or the whole new one. They are written here, by the grader, in a folder no sandboxed step
    can see."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for name, text in [("results.json", json.dumps(gradescope(grade), indent=1)), ("report.md", markdown(grade)),
                       ("outcomes.json", json.dumps(outcomes(grade), indent=1)),
                       ("report.html", html_report(grade))]:
        files.write_atomically(out / name, text)
