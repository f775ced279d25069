#!/usr/bin/env python3
"""Mutation testing of the task regions: do a stage's tests catch a student's plausible bug?

Plants one small bug at a time in the solution lines of a stage's task regions (between BEGIN TASK
and PLACEHOLDER; docs/solution-markers.md), rebuilds that stage's test programs incrementally,
runs the stage's tests (ctest label stageN, visible and hidden) with a time limit, and reports
each bug ("mutant") as killed (some test fails or times out), survived, or not compiling.

The bugs are the ones students make: a comparison flipped (< for <=, < for >, == for !=, && for
||), + for -, * for /, min for max, a constant halved or doubled, a condition negated, the two
arguments of a call swapped (not of dot, min, max and the like, whose result is the same), an index
off by one, a term of a sum dropped. Each is one edit of one line, found by a small tokenizer (strings and comments are never touched; template brackets are
told from comparisons by what lies between them).

A survivor is either equivalent (no input can tell it from the solution: grading/
equivalent-mutants.json lists each with a reason an instructor can check) or a hole in the tests.
The score of a stage is killed / (killed + holes); the target is 95 % (docs/instructors.md,
"How strong the tests are").

The work happens in a copy of the tree (default /tmp/rt-mutation), never in this one:

  tools/mutation.py --list [--stages 1 2]          the mutants, without building anything
  tools/mutation.py [--stages 1 2] [--sample 60]   build, run, print the table and the holes
      [--seed 1] [--work DIR] [--write-doc] [--check]
  tools/mutation.py --stages 1 --only sphere_       every mutant whose name contains the text
  tools/mutation.py --stages 2 --recheck           the holes of stage 2's last run, run again

--sample N tests a fixed-seed sample of N mutants per stage (all of them when a stage has fewer);
--write-doc rewrites the measured stages' lines of the table in docs/instructors.md; --check exits
1 when a stage scores below 95 %. Results go to WORK/results.json, a stage's replacing that stage's
earlier ones; --report reads them again, so that survivors newly listed as equivalent count without
a new run. --recheck runs the holes of the last run again after a test was added: a hole a test
now kills counts as killed, and the table's date says when the holes were re-run.
"""
import argparse
import dataclasses
import json
import pathlib
import random
import re
import shutil
import signal
import subprocess
import sys
import time

import make_starter
import task_regions

ROOT = pathlib.Path(__file__).resolve().parent.parent
EQUIVALENT = ROOT / "grading" / "equivalent-mutants.json"
DOC = ROOT / "docs" / "instructors.md"
TABLE_BEGIN, TABLE_END = "<!-- mutation table: begin (tools/mutation.py --write-doc) -->", "<!-- mutation table: end -->"
TARGET = 0.95

TOKEN = re.compile(r"""
   (?P<space>\s+)
  |(?P<comment>//.*|/\*.*?\*/)
  |(?P<string>"(?:\\.|[^"\\])*"|'(?:\\.|[^'\\])*')
  |(?P<hex>0[xX][0-9a-fA-F']+[uUlL]*)
  |(?P<number>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fFuUlL]*)
  |(?P<name>[A-Za-z_]\w*)
  |(?P<op>::|->|<<=|>>=|<<|>>|<=|>=|==|!=|&&|\|\||\+\+|--|[-+*/%&|^]=|[-+*/%<>=!&|^~?:;,.()\[\]{}#])
""", re.X)

RELATIONAL = {"<": ["<=", ">"], "<=": ["<", ">="], ">": [">=", "<"], ">=": [">", "<="], "==": ["!="], "!=": ["=="]}
SWAPPED = {"+": "-", "-": "+", "*": "/", "/": "*", "+=": "-=", "-=": "+=", "*=": "/=", "/=": "*=",
           "&&": "||", "||": "&&"}
MIN_MAX = {"min": "max", "max": "min", "fmin": "fmax", "fmax": "fmin", "min4": "max4", "max4": "min4",
           "min_component": "max_component", "max_component": "min_component"}
# After these a * or & declares a pointer or a reference: no arithmetic to mutate.
TYPE_WORDS = {"const", "float", "double", "int", "unsigned", "char", "bool", "auto", "void", "long", "short"}
# Functions whose two arguments can be swapped without changing the result: no mutant for them.
SYMMETRIC = {"dot", "min", "max", "fmin", "fmax", "min4", "max4", "hypot", "distance", "swap"}
NOT_CALLS = {"if", "while", "for", "switch", "return", "sizeof", "alignof", "decltype", "static_assert",
             "static_cast", "reinterpret_cast", "const_cast", "catch"}
# In a template's brackets: names, ::, commas, numbers, * and &, nested brackets.
TEMPLATE_INSIDE = {"name", "number", "::", ",", "*", "&", "<", ">"}


@dataclasses.dataclass
class Token:
    kind: str  # name, number, hex, op, string
    text: str
    start: int
    end: int


def tokenize(line):
    tokens = []
    for m in TOKEN.finditer(line):
        kind = m.lastgroup
        if kind in ("space", "comment"):
            continue
        text = m.group()
        tokens.append(Token("op" if kind == "op" else kind, text, m.start(), m.end()))
    return tokens


def key(token):
    return token.text if token.kind == "op" else token.kind


def template_brackets(tokens):
    """Indices of < and > that are template brackets, not comparisons."""
    found = set()
    for i, t in enumerate(tokens):
        if t.text != "<" or i == 0 or tokens[i - 1].kind != "name":
            continue
        depth, j = 1, i + 1
        while j < len(tokens) and key(tokens[j]) in TEMPLATE_INSIDE:
            depth += {"<": 1, ">": -1}.get(tokens[j].text, 0)
            if depth == 0:
                found.update(k for k in range(i, j + 1) if tokens[k].text in ("<", ">"))
                break
            j += 1
    return found


def matching(tokens, i, open_, close):
    """The index of the bracket closing tokens[i] on the same line, or None."""
    depth = 0
    for j in range(i, len(tokens)):
        depth += (tokens[j].text == open_) - (tokens[j].text == close)
        if depth == 0:
            return j
    return None


def operand_end(tokens, i):
    """The end (exclusive token index) of the term that starts at tokens[i], up to the next +, -,
    comparison or separator at its own depth."""
    depth, j = 0, i
    stops = {"+", "-", ",", ";", "?", ":", "<", "<=", ">", ">=", "==", "!=", "&&", "||", "=", "+=", "-=",
             "*=", "/=", "&", "|", "^", "}"}
    while j < len(tokens):
        t = tokens[j].text
        if t in ("(", "[", "{"):
            depth += 1
        elif t in (")", "]", "}"):
            if depth == 0:
                return j
            depth -= 1
        elif depth == 0 and t in stops and j > i:
            return j
        j += 1
    return j


def is_binary(tokens, i):
    return i > 0 and (tokens[i - 1].kind in ("name", "number", "hex") and tokens[i - 1].text not in TYPE_WORDS |
                      NOT_CALLS or tokens[i - 1].text in (")", "]"))


def scaled_literal(text, factor):
    m = re.fullmatch(r"([0-9.eE+-]+?)([fFuUlL]*)", text)
    if not m:
        return None
    number, suffix = m.groups()
    if re.fullmatch(r"\d+", number) and "f" not in suffix.lower():
        value = int(number)
        scaled = value * 2 if factor > 1 else value // 2
        return None if scaled == value else str(scaled) + suffix
    value = float(number)
    if value == 0.0:
        return None
    scaled = format(value * factor, ".9g")
    if not re.search(r"[.eE]", scaled):
        scaled += ".0"
    return scaled + suffix


def line_mutants(line):
    """(start, end, replacement, description) for each mutant of one line of code."""
    tokens = tokenize(line)
    if not tokens or tokens[0].text == "#":
        return []
    templates = template_brackets(tokens)
    out = []

    def span(i, j):  # the text of tokens[i:j]
        return line[tokens[i].start:tokens[j - 1].end]

    for i, t in enumerate(tokens):
        if t.kind == "op" and t.text in RELATIONAL and i not in templates:
            for r in RELATIONAL[t.text]:
                out.append((t.start, t.end, r, f"`{t.text}` → `{r}`"))
        if t.kind == "op" and t.text in SWAPPED and (t.text in ("&&", "||") or t.text.endswith("=") or is_binary(tokens, i)):
            r = SWAPPED[t.text]
            out.append((t.start, t.end, r, f"`{t.text}` → `{r}`"))
        if t.kind == "name" and t.text in MIN_MAX:
            out.append((t.start, t.end, MIN_MAX[t.text], f"`{t.text}` → `{MIN_MAX[t.text]}`"))
        if t.kind == "number":
            for factor, word in ((0.5, "halved"), (2.0, "doubled")):
                r = scaled_literal(t.text, factor)
                if r is not None:
                    out.append((t.start, t.end, r, f"`{t.text}` {word} (`{r}`)"))
        if t.kind == "name" and t.text in ("if", "while") and i + 1 < len(tokens) and tokens[i + 1].text == "(":
            j = matching(tokens, i + 1, "(", ")")
            if j is not None and j > i + 2:
                condition = span(i + 2, j)
                out.append((tokens[i + 1].start, tokens[j].end, f"(!({condition}))", f"`{t.text}` condition negated"))
        if (t.kind == "name" and t.text not in NOT_CALLS | SYMMETRIC and i + 1 < len(tokens) and tokens[i + 1].text == "(" and
                (i == 0 or tokens[i - 1].kind != "name" or tokens[i - 1].text == "return")):
            j = matching(tokens, i + 1, "(", ")")
            if j is not None:
                commas, depth = [], 0
                for k in range(i + 2, j):
                    depth += (tokens[k].text in ("(", "[", "{")) - (tokens[k].text in (")", "]", "}"))
                    if depth == 0 and tokens[k].text == ",":
                        commas.append(k)
                if len(commas) == 1 and commas[0] > i + 2 and j > commas[0] + 1:
                    a, b = span(i + 2, commas[0]), span(commas[0] + 1, j)
                    if a != b:
                        out.append((tokens[i + 2].start, tokens[j - 1].end, f"{b}, {a}", f"`{t.text}` arguments swapped"))
        if t.text == "[" and i > 0 and (tokens[i - 1].kind == "name" or tokens[i - 1].text in (")", "]")):
            j = matching(tokens, i, "[", "]")
            if j is not None and j > i + 1:
                index = span(i + 1, j)
                out.append((tokens[i + 1].start, tokens[j - 1].end, f"{index} + 1", f"index `[{index}]` off by one"))
        if t.kind == "op" and t.text in ("+", "-") and is_binary(tokens, i):
            j = operand_end(tokens, i + 1)
            if j > i + 1:
                out.append((t.start, tokens[j - 1].end, "", f"term `{t.text} {span(i + 1, j)}` dropped"))
    # The same edit at two places of a line: numbered, so that each mutant has a name of its own.
    seen = {}
    for k, (start, end, replacement, description) in enumerate(out):
        seen.setdefault(description, []).append(k)
    for description, ks in seen.items():
        if len(ks) > 1:
            for n, k in enumerate(ks, 1):
                start, end, replacement, _ = out[k]
                out[k] = (start, end, replacement, f"{description} (occurrence {n})")
    return out


@dataclasses.dataclass
class Mutant:
    stage: int
    task: str
    file: str  # relative to the tree's root
    line: int  # 0-based
    start: int
    end: int
    replacement: str
    description: str
    code: str  # the line as it is, stripped: with `description`, how the equivalent list names a mutant

    def apply(self, lines):
        text = lines[self.line]
        return lines[:self.line] + [text[:self.start] + self.replacement + text[self.end:]] + lines[self.line + 1:]

    def name(self):
        return f"{self.file}:{self.line + 1}: {self.description} in `{self.code}`"


def mutants_of(root, stages):
    found = []
    for stage, folder in task_regions.stage_folders(root):
        if stage not in stages:
            continue
        for path in task_regions.source_files(folder):
            lines = path.read_text().splitlines()
            problems = []
            for region in task_regions.parse(path, problems):
                for number in range(region.begin + 1, region.placeholder):
                    for start, end, replacement, description in line_mutants(lines[number]):
                        found.append(Mutant(stage, region.task_id, str(path.relative_to(root)), number, start, end,
                                            replacement, description, lines[number].strip()))
    return found


def load_equivalent():
    entries = json.loads(EQUIVALENT.read_text())["mutants"] if EQUIVALENT.exists() else []
    return {(e["file"], e["code"], e["mutation"]): e["reason"] for e in entries}


def sample(mutants, count, seed):
    if count is None or len(mutants) <= count:
        return mutants
    picked = random.Random(seed).sample(range(len(mutants)), count)
    return [mutants[i] for i in sorted(picked)]


def run(command, cwd, timeout):
    try:
        done = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=timeout)
        return done.returncode, done.stdout
    except subprocess.TimeoutExpired as e:
        return None, (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")


class Workspace:
    """A copy of the tree with a release build, in which one mutant at a time is planted."""

    def __init__(self, work, test_timeout):
        self.src = pathlib.Path(work) / "src"
        self.build = self.src / "build" / "release"
        self.test_timeout = test_timeout
        # The tree's files, hidden tests included; an earlier copy keeps its build, and a file that
        # changed since gets a new time stamp, so that the build sees the change.
        for name in make_starter.repository_files(ROOT):
            path, target = ROOT / name, self.src / name
            if not path.is_file() or (target.exists() and target.read_bytes() == path.read_bytes()):
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(path, target)
        # The standard library's bounds checks on (_GLIBCXX_ASSERTIONS): a mutant that indexes past
        # an array's end then stops its test, as the sanitize preset would, instead of scribbling
        # on the stack unseen. tools/grade.py builds students' trees the same way.
        code, out = run(["cmake", "--preset", "release", "-DCMAKE_CXX_FLAGS=-D_GLIBCXX_ASSERTIONS"], self.src, 600)
        if code != 0:
            sys.exit(f"mutation.py: configuring the copy in {self.src} failed:\n{out[-2000:]}")

    def targets(self, stage):
        return [f"stage{stage}_tests"] + ([f"stage{stage}_hidden_tests"]
                                          if (self.src / "tests" / "hidden").exists() else [])

    def build_stage(self, stage):
        return run(["cmake", "--build", str(self.build), "--target", *self.targets(stage)], self.src, 1800)

    def check_baseline(self, stage):
        """Builds the stage's tests on the unmutated tree and stops the run unless they all pass."""
        code, out = self.build_stage(stage)
        if code != 0 or self.test_stage(stage):
            sys.exit(f"mutation.py: stage {stage}'s tests do not pass on the unmutated tree; fix that first")

    def test_stage(self, stage):
        """None when every test passes, else the first failing test (or 'timeout')."""
        code, out = run(["ctest", "--test-dir", str(self.build), "-L", f"^stage{stage}$", "-j2", "--stop-on-failure",
                         "--timeout", str(self.test_timeout), "--output-on-failure"], self.src, 3600)
        if code == 0:
            return None
        failed = re.findall(r"\d+ - (\S+) \((Failed|Timeout|SEGFAULT|Subprocess aborted|Exception|Child aborted)", out)
        return f"{failed[0][0]} ({failed[0][1].lower()})" if failed else "the test run failed"


def measure(workspace, mutants, log):
    """Plants each mutant in turn (grouped by file, so a file is rebuilt once per mutant) and
    returns {index: (status, detail)}."""
    results = {}
    by_file = {}
    for index, m in enumerate(mutants):
        by_file.setdefault(m.file, []).append(index)
    for file, indices in by_file.items():
        path = workspace.src / file
        original = path.read_text()
        lines = original.splitlines()
        try:
            for index in indices:
                m = mutants[index]
                path.write_text("\n".join(m.apply(lines)) + "\n")
                started = time.monotonic()
                code, out = workspace.build_stage(m.stage)
                if code != 0:
                    results[index] = ("not compiling", "")
                else:
                    failed = workspace.test_stage(m.stage)
                    results[index] = ("killed", failed) if failed else ("survived", "")
                log(f"[{len(results)}/{len(mutants)}] {results[index][0]:13} {time.monotonic() - started:5.1f} s  "
                    f"{m.name()}" + (f"  <- {results[index][1]}" if results[index][1] else ""))
        finally:
            path.write_text(original)
    return results


TABLE_HEAD = ["| stage | mutants | killed | equivalent | holes | not compiling | score | measured |",
              "|---|---:|---:|---:|---:|---:|---:|---|"]


def table_rows(rows):
    """{stage: the table's line} for the stages measured."""
    out = {}
    for stage, r in sorted(rows.items()):
        scored = r["killed"] + r["holes"]
        score = f"{100.0 * r['killed'] / scored:.1f} %" if scored else "–"
        sampled = f"{r['tested']} of {r['all']}" if r["tested"] < r["all"] else str(r["all"])
        out[stage] = (f"| {stage} | {sampled} | {r['killed']} | {r['equivalent']} | {r['holes']} | "
                      f"{r['not compiling']} | {score} | {r.get('measured', '?')} |")
    return out


def write_doc(lines):
    """Rewrites the measured stages' lines of the table in docs/instructors.md, keeping the others."""
    doc = DOC.read_text()
    if TABLE_BEGIN not in doc or TABLE_END not in doc:
        sys.exit(f"mutation.py: {DOC} lacks the table markers")
    head, rest = doc.split(TABLE_BEGIN)
    old, tail = rest.split(TABLE_END)
    kept = {int(m.group(1)): line for line in old.splitlines() if (m := re.match(r"\| (\d+) \|", line))}
    kept.update(lines)
    table = "\n".join(TABLE_HEAD + [kept[s] for s in sorted(kept)])
    DOC.write_text(head + TABLE_BEGIN + "\n" + table + "\n" + TABLE_END + tail)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--stages", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6, 7])
    parser.add_argument("--sample", type=int, help="test a fixed-seed sample of this many mutants per stage")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--work", default="/tmp/rt-mutation")
    parser.add_argument("--test-timeout", type=int, default=120, help="seconds per test (ctest --timeout)")
    parser.add_argument("--only", metavar="TEXT", help="only the mutants whose name (file:line: what in `code`) "
                        "contains TEXT, all of them (no sample)")
    parser.add_argument("--list", action="store_true", help="print the mutants and stop")
    parser.add_argument("--report", action="store_true", help="no run: the table and the holes of the last run "
                        "in --work, its survivors judged against today's equivalent list")
    parser.add_argument("--write-doc", action="store_true", help="rewrite the table in docs/instructors.md")
    parser.add_argument("--check", action="store_true", help="exit 1 when a stage scores below 95 %%")
    parser.add_argument("--recheck", action="store_true", help="run the holes of the last run of these stages "
                        "again, against today's tests")
    args = parser.parse_args()
    # Stopped (ctest's time limit, kill), the planted mutant is still taken out: `finally` runs.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("mutation.py: stopped"))

    everything = mutants_of(ROOT, set(args.stages))
    equivalent = load_equivalent()
    known = {(m.file, m.code, m.description) for m in everything}
    stale = [k for k in equivalent if k not in known and int(pathlib.Path(k[0]).parts[1][:2]) in args.stages]
    for file, code, mutation in stale:
        print(f"mutation.py: {EQUIVALENT.name} names a mutant the tool no longer makes: {file}: {mutation} "
              f"in `{code}`", file=sys.stderr)
    per_stage = {s: [m for m in everything if m.stage == s] for s in args.stages}
    chosen = {s: [m for m in ms if args.only in m.name()] if args.only else sample(ms, args.sample, args.seed + s)
              for s, ms in per_stage.items()}
    if args.list:
        for s in args.stages:
            print(f"stage {s}: {len(per_stage[s])} mutants" +
                  (f", {len(chosen[s])} sampled" if len(chosen[s]) < len(per_stage[s]) else ""))
            for m in chosen[s]:
                print("  " + m.name() + ("  [equivalent]" if (m.file, m.code, m.description) in equivalent else ""))
        return 1 if stale else 0

    results_file = pathlib.Path(args.work) / "results.json"
    earlier = json.loads(results_file.read_text()) if results_file.exists() else {"stages": {}, "mutants": []}
    if args.report:
        results = earlier
    elif args.recheck:
        results = recheck_holes(args, earlier, everything, equivalent)
        results_file.write_text(json.dumps(results, indent=1, ensure_ascii=False))
    else:
        measured = measure_stages(args, per_stage, chosen)
        if args.only:  # a few mutants tried again: shown, not stored as the stage's results
            return summarize(measured, equivalent, stale, argparse.Namespace(**{**vars(args), "write_doc": False}))
        # This run's stages replace their earlier results; the other stages' are kept.
        results = {"stages": {**earlier["stages"], **measured["stages"]},
                   "mutants": [m for m in earlier["mutants"] if str(m["stage"]) not in measured["stages"]] +
                   measured["mutants"]}
        results_file.write_text(json.dumps(results, indent=1, ensure_ascii=False))
    shown = {s: info for s, info in results["stages"].items() if int(s) in args.stages}
    return summarize({"stages": shown, "mutants": [m for m in results["mutants"] if str(m["stage"]) in shown]},
                     equivalent, stale, args)


def when_measured():
    """Today's date and commit, marked when the tree has changes not yet committed."""
    commit = run(["git", "rev-parse", "--short", "HEAD"], ROOT, 60)[1].strip() or "?"
    dirty = run(["git", "status", "--porcelain", "--untracked-files=no"], ROOT, 60)[1].strip()
    return f"{time.strftime('%Y-%m-%d')}, {commit}{' + changes' if dirty else ''}"


def key_of(record):
    """How a stored result names its mutant: file, line text and description, as the equivalent list does."""
    return record["file"], record["code"], record["description"]


def recheck_holes(args, results, everything, equivalent):
    """Runs the holes of the last run of args.stages again, with today's tests, and records the
    outcome (a mutant is found again by its file, line text and description)."""
    today = {(m.file, m.code, m.description): m for m in everything}
    holes = [r for r in results["mutants"] if r["stage"] in args.stages and r["status"] == "survived" and
             key_of(r) not in equivalent]
    missing = [r for r in holes if key_of(r) not in today]
    if missing:
        sys.exit("mutation.py: the tool no longer makes " + "; ".join(
            f"{r['file']}: {r['description']} in `{r['code']}`" for r in missing) + ": measure the stage again")
    workspace = Workspace(args.work, args.test_timeout)
    for s in sorted({r["stage"] for r in holes}):
        workspace.check_baseline(s)
    mutants = [today[key_of(r)] for r in holes]
    outcomes = measure(workspace, mutants, lambda text: print(text, flush=True))
    for index, r in enumerate(holes):
        r["status"], r["killed_by"] = outcomes[index]
        r["line"] = mutants[index].line + 1
    for s in {str(r["stage"]) for r in holes}:
        workspace.build_stage(int(s))
        results["stages"][s]["measured"] += f"; holes re-run {when_measured()}"
    return results


def measure_stages(args, per_stage, chosen):
    """Builds the copy, checks that the unmutated tests pass, and runs every chosen mutant."""
    workspace = Workspace(args.work, args.test_timeout)
    results = {"stages": {}, "mutants": []}
    for s in args.stages:
        print(f"stage {s}: baseline build and tests", flush=True)
        workspace.check_baseline(s)
        outcomes = measure(workspace, chosen[s], lambda text: print(text, flush=True))
        results["stages"][str(s)] = {"all": len(per_stage[s]), "tested": len(chosen[s]), "measured": when_measured()}
        for index, (status, detail) in sorted(outcomes.items()):
            m = chosen[s][index]
            results["mutants"].append({**dataclasses.asdict(m), "line": m.line + 1, "status": status,
                                       "killed_by": detail})
        workspace.build_stage(s)  # the unmutated tree again
    return results


def summarize(results, equivalent, stale, args):
    """The table and the holes, survivors judged against today's equivalent list."""
    rows = {}
    for s, info in results["stages"].items():
        rows[int(s)] = {**info, "killed": 0, "equivalent": 0, "holes": 0, "not compiling": 0}
    holes = []
    for r in results["mutants"]:
        status = r["status"]
        if status == "survived":
            status = "equivalent" if key_of(r) in equivalent else "hole"
        rows[r["stage"]][{"hole": "holes"}.get(status, status)] += 1
        if status == "hole":
            holes.append(r)
    lines = table_rows(rows)
    print("\n".join(TABLE_HEAD + list(lines.values())))
    for r in holes:
        print(f"hole: {r['file']}:{r['line']}: {r['description']} in `{r['code']}` ({r['task']})")
    if args.write_doc:
        write_doc(lines)
    low = [s for s, r in rows.items() if r["killed"] + r["holes"] and r["killed"] / (r["killed"] + r["holes"]) < TARGET]
    if args.check and (low or stale):
        print(f"mutation.py: below {TARGET:.0%}: stages {low}" if low else "mutation.py: stale equivalent entries",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
