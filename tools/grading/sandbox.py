"""Where a submission's code runs: a bubblewrap sandbox with resource limits, one per step.

Everything that executes code a student wrote, or that a student's code could have changed, runs
here: the build, every test, every render, the leaderboard's timing. A step sees a read-only
system (/usr and the few files of /etc the tools need), the folders and files the step names
read-only, one scratch folder it may write, a private /tmp, no network, its own PID namespace (so
nothing it starts outlives it: when the step's first process ends, the kernel ends the rest) and
no way back to the grader's files, reports or other steps. It runs as an unprivileged user
(`nobody` when the grader is root, so that the process limit counts only the sandbox's processes),
with limits on address space, CPU time, file size, processes and open files.

When bubblewrap cannot make namespaces (an unprivileged container such as a hosted autograder's may
forbid them), Sandbox.check() says so in one line; `container_is_sandbox` then runs the steps
without it, still as the unprivileged user and with the same limits and timeouts, trusting the
container to be the isolation (docs/instructors.md says what is then still guaranteed).
"""
import dataclasses
import os
import pathlib
import shutil
import signal
import subprocess
import time

SANDBOX_USER = 65534  # nobody, on Debian
# The user a test's judge runs as when the grader is root (build.py): not the one the submission's
# code runs as, so that nothing a submission leaves behind (in a container without PID namespaces)
# can write the judge's report or signal it.
JUDGE_USER = 65533
SYSTEM_LINKS_OR_FOLDERS = ("/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32")
# What the compiler, cmake, ninja and the dynamic loader read in /etc.
ETC_FILES = ("/etc/alternatives", "/etc/ld.so.cache", "/etc/ld.so.conf", "/etc/ld.so.conf.d", "/etc/passwd", "/etc/group")


@dataclasses.dataclass
class Limits:
    memory_bytes: int = 4 << 30      # address space per process
    file_bytes: int = 1 << 30        # largest file a step may write
    processes: int = 512             # processes and threads of the sandbox user
    open_files: int = 1024


@dataclasses.dataclass
class Result:
    code: int          # the exit code; 124 when the step ran out of time, -N when signal N ended it
    seconds: float
    timed_out: bool


class Deadline:
    """One submission's overall time cap: every step's time limit is cut to what is left of it."""

    def __init__(self, cap):
        self.cap, self.start = cap, time.monotonic()

    def elapsed(self):
        return time.monotonic() - self.start

    def timeout(self, limit):
        """The step's own limit or what is left of the cap, whichever is less (<= 0: none left)."""
        return min(limit, self.cap - self.elapsed())

    def reached(self):
        return self.elapsed() >= self.cap


class SandboxError(Exception):
    """The sandbox cannot be made here; the message is one line."""


class Sandbox:
    def __init__(self, limits=None, container_is_sandbox=False, user=None):
        self.limits = limits or Limits()
        self.container_is_sandbox = container_is_sandbox
        # Root runs the steps as `nobody`; anyone else as themselves (they cannot switch user).
        self.uid = (SANDBOX_USER if user is None else user) if os.geteuid() == 0 else None
        self.judge_uid = (JUDGE_USER if self.uid != JUDGE_USER else JUDGE_USER - 1) if self.uid is not None else None
        self.bwrap = shutil.which("bwrap")

    def owner_of_scratch(self, judge=False):
        """The uid that must own a folder a step writes (None: the grader's own)."""
        return self.judge_uid if judge else self.uid

    def check(self, probe_folder):
        """Raises SandboxError unless a step can run here and read `probe_folder` (the work folder)."""
        if not self.container_is_sandbox and not self.bwrap:
            raise SandboxError("bubblewrap (bwrap) is not installed: tools/setup.sh installs it")
        probe = pathlib.Path(probe_folder)
        log = probe / "sandbox-probe.log"
        for folder in ("/", probe):
            log.write_text("")
            result = self.run(["/bin/true"], log=log, timeout=30, read_only=[] if folder == "/" else [folder],
                              writable=[], cwd=folder)
            if result.code == 0:
                continue
            said = [line for line in log.read_text(errors="replace").splitlines() if not line.startswith("$ ")]
            reason = said[-1] if said else f"exit code {result.code}"
            if folder == "/":
                raise SandboxError(f"cannot make the sandbox ({reason}): run where unprivileged user namespaces are "
                                   "allowed, or pass --container-is-sandbox if this container is itself the sandbox "
                                   "(docs/instructors.md)")
            who = f"uid {self.uid}" if self.uid is not None else "this user"
            raise SandboxError(f"the sandbox's user ({who}) cannot reach the work folder {probe} ({reason}): give a "
                               "--work that every user may enter, such as one under /tmp")
        log.unlink()

    def _bwrap_arguments(self, read_only, writable, masked, cwd, environment):
        arguments = [self.bwrap, "--unshare-all", "--unshare-user", "--disable-userns", "--die-with-parent",
                     "--new-session", "--ro-bind", "/usr", "/usr"]
        for path in SYSTEM_LINKS_OR_FOLDERS:
            if os.path.islink(path):
                arguments += ["--symlink", os.readlink(path), path]
            elif os.path.isdir(path):
                arguments += ["--ro-bind", path, path]
        for path in ETC_FILES:
            if os.path.exists(path):
                arguments += ["--ro-bind", path, path]
        arguments += ["--proc", "/proc", "--dev", "/dev", "--size", str(64 << 20), "--tmpfs", "/tmp"]
        for host, seen in map(host_and_seen, read_only):
            arguments += ["--ro-bind", host, seen]
        for host, seen in map(host_and_seen, writable):
            arguments += ["--bind", host, seen]
        for path in masked:  # an empty file in place of each (hidden test sources while students' code builds)
            arguments += ["--ro-bind", "/dev/null", str(path)]
        arguments += ["--clearenv"]
        for key, value in environment.items():
            arguments += ["--setenv", key, value]
        arguments += ["--chdir", str(cwd), "--"]
        return arguments

    def _limit_arguments(self, timeout):
        """prlimit (util-linux) sets the limits on itself and then runs the step, so that every
        process of the step inherits them; RLIMIT_NPROC counts the user's processes machine-wide."""
        processes = self.limits.processes
        if self.uid is None:  # the grader's own user: its other processes count too
            processes += sum(1 for p in pathlib.Path("/proc").iterdir() if p.name.isdigit())
        cpu = int(2 * timeout + 10)  # two threads busy for the whole step, and a margin
        return ["prlimit", f"--as={self.limits.memory_bytes}", f"--fsize={self.limits.file_bytes}",
                f"--nproc={processes}", f"--nofile={self.limits.open_files}", f"--cpu={cpu}", "--core=0", "--"]

    def run(self, command, log, timeout, read_only=(), writable=(), masked=(), cwd=None, environment=None,
            judge=False):
        """Runs `command` in the sandbox with its output appended to `log` (a file of the grader's,
        which the step writes only through its standard output, so the file size limit bounds it).
        `read_only` and `writable` hold paths, or (path, path the step sees) pairs: a prepared build
        (build.py) is always seen where it was built, wherever its copy lies.
        Returns a Result; a step that outlives `timeout` seconds is killed with everything it
        started. `judge` runs it as the judges' user (build.py), not the submission's."""
        cwd = cwd or (host_and_seen(writable[0])[1] if writable else "/")
        home = host_and_seen(writable[0])[1] if writable else "/tmp"
        environment = {"PATH": "/usr/bin:/bin", "HOME": home, "TMPDIR": home, "LANG": "C.UTF-8",
                       "GTEST_COLOR": "no", **(environment or {})}
        if self.container_is_sandbox:
            moved = [f"{host} at {seen}" for host, seen in map(host_and_seen, [*read_only, *writable]) if host != seen]
            if moved:  # without bubblewrap a folder cannot be shown at another path
                raise SandboxError(f"without bubblewrap a step cannot see {moved[0]}: grade in the prepared folder "
                                   "itself (docs/instructors.md)")
            full = [*self._limit_arguments(timeout), *command]
            env = environment
        else:
            full = [*self._limit_arguments(timeout),
                    *self._bwrap_arguments(read_only, writable, masked, cwd, environment), *command]
            env = {"PATH": "/usr/bin:/bin"}
        start = time.monotonic()
        with open(log, "ab") as out:
            out.write(f"$ {' '.join(map(str, command))}\n".encode())
            out.flush()
            uid = self.owner_of_scratch(judge)
            user = {} if uid is None else {"user": uid, "group": uid, "extra_groups": []}
            process = subprocess.Popen(full, stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                                       cwd=str(cwd) if self.container_is_sandbox else "/", env=env,
                                       start_new_session=True, **user)
            timed_out = False
            try:
                code = process.wait(timeout=max(timeout, 0.1))
            except subprocess.TimeoutExpired:
                timed_out = True
                kill_group(process)
                code = 124
                out.write(f"\nkilled after {timeout:.0f} s\n".encode())
            if self.container_is_sandbox:
                kill_group(process)  # without a PID namespace, whatever the step left in its group
        return Result(code, time.monotonic() - start, timed_out)


def host_and_seen(entry):
    """A folder or file given to a step: a path, seen by the step where it is, or a pair (the path
    on the grader's machine, the path the step sees it at)."""
    host, seen = entry if isinstance(entry, tuple) else (entry, entry)
    return str(host), str(seen)


def kill_group(process):
    """Ends the step's process group (bwrap and, with it, its PID namespace) and reaps it."""
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    process.wait()
