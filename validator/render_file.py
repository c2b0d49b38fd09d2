"""Writing a picture to a path whole or not at all: into a temporary file in the
same folder, renamed over the path when complete, so that a reader (or a second
validator writing the same path) never sees half a file and a failed render leaves
none. No drawing library: every format's writer uses it.
"""

from __future__ import annotations

import os
import stat
import tempfile
from typing import BinaryIO, Callable, TypeVar

T = TypeVar("T")
MEMORY_FOLDERS = ("/dev/shm/",)
"""Folders under /dev that hold ordinary files (a memory file system): written
atomically, as any other folder."""


def write_atomically(path: str, write: Callable[[BinaryIO], T]) -> T:
    """``write`` into a temporary file beside ``path``, then os.replace; the mode is
    what ``open`` would give. A device, FIFO or /proc path, or a folder we cannot
    create a file in (the file itself may still be writable), is written directly.
    What ``write`` raises is raised as it was, the temporary file removed."""
    temporary = _temporary_beside(path)
    if temporary is None:
        with open(path, "wb") as out:
            return write(out)
    fd, temporary_path, target = temporary
    try:
        with os.fdopen(fd, "wb") as out:
            result = write(out)
        os.chmod(temporary_path, _new_file_mode(target))
        os.replace(temporary_path, target)
    except BaseException:
        try:
            os.unlink(temporary_path)
        except OSError:
            pass
        raise
    return result


def _temporary_beside(path: str) -> tuple[int, str, str] | None:
    """(fd, name) of a new temporary file in the folder of ``path``'s target (through
    symlinks, as ``open`` writes) and that target; None when ``path`` is not a
    regular file (nor absent) or no file can be made there."""
    where = os.path.abspath(path)
    if where.startswith(("/dev/", "/proc/")) and not where.startswith(MEMORY_FOLDERS):
        return None
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
    except FileNotFoundError:
        pass
    except OSError:
        return None
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    try:
        fd, temporary_path = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    except OSError:
        return None
    return fd, temporary_path, target


def _new_file_mode(target: str) -> int:
    """The existing file's permissions, or 0o666 less the umask (mkstemp gives 0o600)."""
    try:
        return os.stat(target).st_mode & 0o7777
    except OSError:
        pass
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask
