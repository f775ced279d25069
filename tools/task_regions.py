"""Student task regions (docs/solution-markers.md) and the handouts' task tables.

What the marker check (tools/check_markers.py), the starter-tree generator (tools/make_starter.py)
and the grader (tools/grade.py) share: where each task's solution and placeholder are in the code,
and what each stage's handout says about the task (file, what to write, the tests that check it).
"""
import dataclasses
import pathlib
import re

BEGIN = re.compile(r"^(\s*)// BEGIN TASK (\S+)\s*$")
PLACEHOLDER = re.compile(r"^\s*// PLACEHOLDER\s*$")
END = re.compile(r"^\s*// END TASK\s*$")
TASK_ID = re.compile(r"^stage(\d+)\.[a-z0-9_]+\.[a-z0-9_]+$")
# A Tasks table row: | `task id` | file | what | tests | and, optionally, the tasks its tests also
# reach (tools/task_prerequisites.py). The id's cell may say more after the id ("(optional:
# speed)"); a cell may hold escaped bars (\|).
_CELL = r"((?:[^|\\]|\\.)*)"
HANDOUT_ROW = re.compile(r"^\|\s*`(stage\d+\.[a-z0-9_]+\.[a-z0-9_]+)`[^|`]*\|" + rf"{_CELL}\|{_CELL}\|{_CELL}\|(?:{_CELL}\|)?\s*$")
HANDOUT_ID = re.compile(r"`(stage\d+\.[a-z0-9_]+\.[a-z0-9_]+)`")


@dataclasses.dataclass
class Region:
    """One task region. Line numbers index `lines` of the file (0-based)."""
    task_id: str
    indent: str
    begin: int        # the BEGIN TASK line
    placeholder: int  # the PLACEHOLDER line
    end: int          # the END TASK line

    @property
    def stage(self):
        return int(TASK_ID.match(self.task_id).group(1))

    def solution(self, lines):
        return lines[self.begin + 1:self.placeholder]

    def placeholder_code(self, lines):
        """The placeholder lines with their comment marker removed: the code the starter tree gets."""
        return [re.sub(r"^(\s*)// ?", r"\1", line) for line in lines[self.placeholder + 1:self.end]]


def parse(path, problems):
    """The regions of one source file; malformed markers are appended to `problems`."""
    regions = []
    state, begin, indent, task_id, placeholder = "outside", 0, "", None, 0
    for number, line in enumerate(pathlib.Path(path).read_text().splitlines()):
        where = f"{path}:{number + 1}"
        if m := BEGIN.match(line):
            if state != "outside":
                problems.append(f"{where}: BEGIN TASK inside task {task_id}")
            indent, task_id, state, begin = m.group(1), m.group(2), "solution", number
            if not TASK_ID.match(task_id):
                problems.append(f"{where}: task id '{task_id}' is not of the form stageN.topic.task")
        elif PLACEHOLDER.match(line):
            if state != "solution":
                problems.append(f"{where}: PLACEHOLDER outside a task's solution")
            state, placeholder = "placeholder", number
        elif END.match(line):
            if state != "placeholder":
                problems.append(f"{where}: END TASK without a PLACEHOLDER section")
            elif TASK_ID.match(task_id):
                regions.append(Region(task_id, indent, begin, placeholder, number))
            state = "outside"
        elif state == "placeholder" and not line.strip().startswith("//"):
            problems.append(f"{where}: placeholder line is not commented out")
    if state != "outside":
        problems.append(f"{path}:{begin + 1}: task {task_id} is never closed")
    return regions


def stage_folders(root):
    """(stage number, folder) for every stages/NN-name folder."""
    return [(int(d.name[:2]), d) for d in sorted((pathlib.Path(root) / "stages").glob("[0-9][0-9]-*"))]


def source_files(folder):
    return [p for p in sorted(pathlib.Path(folder).rglob("*")) if p.suffix in {".h", ".cpp"}]


@dataclasses.dataclass
class HandoutTask:
    file: str
    what: str
    tests: list  # GoogleTest name patterns, as the handout writes them


def handout_tasks(root, stage):
    """The task table of docs/stageN.md: task id -> HandoutTask."""
    handout = pathlib.Path(root) / "docs" / f"stage{stage}.md"
    tasks = {}
    if handout.exists():
        for line in handout.read_text().splitlines():
            if m := HANDOUT_ROW.match(line):
                tests = re.findall(r"`([^`]+)`", m.group(4))
                what = m.group(3).strip().replace("\\|", "|")  # a table cell escapes its bars
                tasks[m.group(1)] = HandoutTask(m.group(2).strip().strip("`"), what, tests)
    return tasks


def handout_ids(root, stage):
    """Every task id the handout mentions anywhere (the table or the text)."""
    handout = pathlib.Path(root) / "docs" / f"stage{stage}.md"
    return set(HANDOUT_ID.findall(handout.read_text())) if handout.exists() else set()
