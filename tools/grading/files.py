"""Files the grader reads from places it does not trust, and files it writes, without following a
link anywhere: a submission's link to a file outside it (the instructor's solution, /etc/passwd) or
to a device (/proc/kmsg, which blocks for ever) is refused, not followed, and a link planted in a
folder the grader writes cannot send a write elsewhere.
"""
import errno
import os
import pathlib
import shutil
import stat
import tempfile


class Refused(Exception):
    """A file that is not taken; the message says why in a few words ("a symbolic link")."""


def _open_folder_beneath(root, parts):
    """A descriptor of root/parts[0]/.../parts[-1], each step opened without following links."""
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    try:
        for part in parts:
            if part in ("", ".", ".."):
                raise Refused(f"a path through '{part}'")
            try:
                next_fd = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
            except OSError as e:
                if e.errno in (errno.ELOOP, errno.ENOTDIR):
                    raise Refused(f"folder '{part}' is a symbolic link or not a folder")
                raise
            os.close(fd)
            fd = next_fd
        return fd
    except BaseException:
        os.close(fd)
        raise


def read_beneath(root, relative, limit):
    """The bytes of root/relative, which must be a regular file of at most `limit` bytes reached
    without any link. Raises Refused with the reason, FileNotFoundError when it is not there."""
    parts = pathlib.PurePosixPath(relative).parts
    folder = _open_folder_beneath(root, parts[:-1])
    try:
        try:
            # O_NONBLOCK: a FIFO would otherwise block the open until a writer came.
            fd = os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC,
                         dir_fd=folder)
        except OSError as e:
            if e.errno == errno.ELOOP:
                raise Refused("a symbolic link")
            raise
    finally:
        os.close(folder)
    try:
        info = os.fstat(fd)
        if stat.S_ISFIFO(info.st_mode):
            raise Refused("a FIFO")
        if stat.S_ISCHR(info.st_mode) or stat.S_ISBLK(info.st_mode):
            raise Refused("a device")
        if not stat.S_ISREG(info.st_mode):
            raise Refused("not a regular file")
        if info.st_size > limit:
            raise Refused(f"{info.st_size} bytes, more than the {limit} a file may have")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > limit:
            raise Refused(f"more than the {limit} bytes a file may have")
        return b"".join(chunks)
    finally:
        os.close(fd)


def write_beneath(root, relative, data, mode=0o644):
    """Writes root/relative (making its folders), following no link on the way, and replacing a
    link or file at the end by a new file."""
    parts = pathlib.PurePosixPath(relative).parts
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    try:
        for part in parts[:-1]:
            try:
                os.mkdir(part, 0o755, dir_fd=fd)
            except FileExistsError:
                pass
            next_fd = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
            os.close(fd)
            fd = next_fd
            os.fchmod(fd, 0o755)  # whatever the umask: the sandbox's user reads the tree
        try:
            os.unlink(parts[-1], dir_fd=fd)
        except FileNotFoundError:
            pass
        out = os.open(parts[-1], os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, mode, dir_fd=fd)
        try:
            os.fchmod(out, mode)
            view = memoryview(data)
            while view:
                view = view[os.write(out, view):]
        finally:
            os.close(out)
    finally:
        os.close(fd)


def write_atomically(path, text):
    """Writes `text` to a new temporary file with an unpredictable name beside `path`, then renames
    it over `path`: a reader sees the old file or the whole new one."""
    path = pathlib.Path(path)
    fd, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as out:
            out.write(text)
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        pathlib.Path(temporary).unlink(missing_ok=True)
        raise


def tail_of(path, size):
    """The last `size` bytes of a log a step wrote (which may be as large as the file size limit),
    as text."""
    with open(path, "rb") as log:
        log.seek(max(0, os.fstat(log.fileno()).st_size - size))
        return log.read(size).decode(errors="replace")


def head_and_tail_of(path, size):
    """The first and the last `size` / 2 bytes of a log, as text: a test's log opens with what
    names its task (a placeholder's TODO line) and ends with its summary."""
    with open(path, "rb") as log:
        length = os.fstat(log.fileno()).st_size
        if length <= size:
            return log.read().decode(errors="replace")
        head = log.read(size // 2)
        log.seek(length - size // 2)
        return (head + b"\n[... cut]\n" + log.read()).decode(errors="replace")


def remove_tree(path):
    """Removes a folder a step wrote, whatever it left there (links are removed, never followed;
    folders it made unreadable are opened up first)."""
    path = pathlib.Path(path)
    if not path.exists() and not path.is_symlink():
        return

    def open_up_and_retry(function, failed, _):
        parent = os.path.dirname(failed)
        os.chmod(parent, 0o700)
        if os.path.isdir(failed) and not os.path.islink(failed):
            os.chmod(failed, 0o700)
        function(failed)

    if path.is_symlink() or not path.is_dir():
        path.unlink()
    else:
        shutil.rmtree(path, onerror=open_up_and_retry)
