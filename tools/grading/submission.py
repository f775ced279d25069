"""What the grader takes from a submission: only the files students are meant to edit.

Those are the instructor's source files that hold task regions (docs/solution-markers.md), or the
globs of `editable` in grading/manifest.json where an instructor lists them. Each is taken only as a
regular file of at most MAX_FILE_BYTES, reached without a symbolic link; a link (to the
instructor's solution, to /etc/passwd), a FIFO, a device or an oversized file is refused with a
line in the report, and so is a file the submission lacks: in its place the grader uses the
starter's version (every task a placeholder), so a refused file costs exactly its tasks. Everything
else (build files, tests, hidden tests, assets, references, the grader) comes from the
instructor's tree.

The student's lines are also searched for calls a task has no business making (ending the
process, starting others, writing files, assembly): the grader cannot stop code that runs inside a
test's own process from misbehaving, so it points the instructor at it (report.md, "Flags").
"""
import dataclasses
import functools
import fnmatch
import pathlib
import re
import sys

from . import files

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))
import make_starter  # noqa: E402
import task_regions  # noqa: E402

MAX_FILE_BYTES = 1 << 20    # the largest task file of the course is 12 KB
MAX_TOTAL_BYTES = 16 << 20

# (pattern, why an instructor should look) for lines a student wrote.
SUSPICIOUS = [
    (r"\b(_exit|_Exit|quick_exit|exit|abort|std::terminate)\s*\(", "ends the process (a test would end before its report)"),
    (r"\b(fork|vfork|clone|posix_spawnp?|system|popen|exec[lv]p?e?)\s*\(", "starts another process"),
    (r"\b(kill|raise|signal|sigaction|alarm|setrlimit|prlimit|ptrace|syscall|dlopen|mprotect)\s*\(", "reaches into the process or the system"),
    (r"\b(fopen|freopen|open|openat|creat|unlink|remove|rename|chmod|truncate|mkdir|rmdir)\s*\(", "opens or changes files"),
    (r"\bstd::(of|if|f)stream\b|\bstd::filesystem\b|<fstream>|<filesystem>", "opens or changes files"),
    (r"\b(asm|__asm__)\b|__attribute__\s*\(\(\s*constructor", "runs code outside the task's call"),
    (r"\b(getenv|setenv|putenv|environ)\b", "reads or changes the environment"),
    (r"#\s*include\s*[<\"](unistd|sys/|signal|csignal|spawn|dlfcn|fcntl|cstdlib|stdlib)", "includes a system interface"),
]


@dataclasses.dataclass
class Flag:
    file: str
    line: int
    why: str
    text: str


@dataclasses.dataclass
class Taken:
    files: dict     # relative path -> bytes, for every editable file (the student's or the starter's)
    notes: list     # one line per file not taken as handed in
    flags: list     # Flag, for the instructor


def editable_files(root, spec):
    """The instructor's files that a submission supplies, as relative paths."""
    root = pathlib.Path(root)
    sources = [p for _, folder in task_regions.stage_folders(root) for p in task_regions.source_files(folder)]
    if spec.get("editable"):
        return sorted(p.relative_to(root).as_posix() for p in sources
                      if any(fnmatch.fnmatchcase(p.relative_to(root).as_posix(), g) for g in spec["editable"]))
    return sorted(p.relative_to(root).as_posix() for p in sources if task_regions.parse(p, []))


@functools.lru_cache(maxsize=4)
def handouts_of(root):
    """The Tasks tables, from which the starter's TODO comments are written."""
    return {stage: task_regions.handout_tasks(root, stage) for stage, _ in task_regions.stage_folders(root)}


def starter_version(root, relative):
    """The starter tree's text of an editable file, byte for byte what tools/make_starter.py
    writes (a prepared build made from it then compiles nothing for an unchanged file)."""
    path = pathlib.Path(root) / relative
    text = make_starter.strip_file(path, set(range(1, 100)), [], handouts_of(pathlib.Path(root)))
    return (text if text is not None else path.read_text()).encode()


def flags_in(relative, text, starter_text):
    """The student's lines (those not in the starter's version of the file) that SUSPICIOUS finds."""
    given = set(line.strip() for line in starter_text.splitlines())
    found = []
    for number, line in enumerate(text.splitlines(), start=1):
        code = line.split("//")[0]
        if line.strip() in given or not code.strip():
            continue
        for pattern, why in SUSPICIOUS:
            if re.search(pattern, code):
                found.append(Flag(relative, number, why, line.strip()[:200]))
                break
    return found


def take(tree, root, spec):
    """The editable files of `tree`, each checked; the starter's version of any that is refused."""
    taken = Taken({}, [], [])
    total = 0
    for relative in editable_files(root, spec):
        starter = starter_version(root, relative)
        try:
            data = files.read_beneath(tree, relative, MAX_FILE_BYTES)
            if total + len(data) > MAX_TOTAL_BYTES:
                raise files.Refused(f"the submission's files pass {MAX_TOTAL_BYTES} bytes in all")
            data.decode("utf-8")
        except FileNotFoundError:
            taken.notes.append(f"{relative}: not in the submission; graded as the starter's version")
            data = starter
        except (files.Refused, UnicodeDecodeError, OSError) as e:
            why = "not UTF-8 text" if isinstance(e, UnicodeDecodeError) else str(e) if isinstance(e, files.Refused) \
                else e.strerror or str(e)
            taken.notes.append(f"{relative}: refused ({why}); graded as the starter's version")
            data = starter
        else:
            total += len(data)
            taken.flags += flags_in(relative, data.decode(), starter.decode())
        taken.files[relative] = data
    return taken


def starter(root, spec):
    """Every editable file as the starter's version: what a prepared build is built from."""
    return Taken({relative: starter_version(root, relative) for relative in editable_files(root, spec)}, [], [])
