"""Containment of a submission's program beyond the validator's: the command that
starts it through ``grading/jail.py`` (namespaces, its own uid, a private
size-capped folder, resource limits), the uid each run gets, and the probe of what
this machine allows.

The command is ``python -S -I jail.py SPEC PROGRAM...``: the process the validator
starts, times and kills is the jail's; killing its process group ends everything
the program started (see ``grading/jail.py``).
"""

from __future__ import annotations

import contextlib
import fcntl
import math
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

from grading.config import Limits

JAIL = Path(__file__).resolve().with_name("jail.py")
FULL = "namespaces: own pids, uid, /dev and /tmp; read-only host; no network"
USERNS = ("namespaces: own pids, /dev and /tmp; read-only host; no network; "
          "the grader's own uid (not root): the process cap counts all its processes")
ROOT_NPROC = "process count not limited (RLIMIT_NPROC does not bind root)"
# Runs as root get the uid FIRST_UID + slot (a slot per run in flight on this machine)
# and all share the group GROUP, which owns the built folders.
GROUP = 1_900_000_000
FIRST_UID = GROUP + 1
SLOTS = 4096


@dataclass(frozen=True)
class Place:
    """Where a program runs: its folder and what fills it."""

    folder: Path               # its working directory, at the submission's own path
    source: Path               # a build: copied in; a run: the read-only layer (namespaces)
    keep: Path | None = None   # a build: the folder its result is copied into, as NAME
    hide: tuple[Path, ...] = ()  # folders it must not see (--out, the submissions)
    tmp: Path | None = None    # TMPDIR without namespaces (a private folder)


@dataclass(frozen=True)
class Sandbox:
    """What containment this machine gives; ``note`` says what is missing and why."""

    level: str   # "full" (root: namespaces, own uid), "userns" (not root), "none"
    note: str    # one line for the report of each run

    @property
    def namespaces(self) -> bool:
        return self.level != "none"

    def command(self, place: Place, program: Sequence[str], limits: Limits,
                timeout: float, identity: tuple[int, int] | None = None) -> list[str]:
        """``program`` started in its place under the limits, as ``identity`` (uid, gid:
        the ``full`` level's)."""
        cpu = limits.cpu_seconds or math.ceil(timeout) + 1
        spec = [f"level={self.level}", f"folder={place.folder}", f"source={place.source}",
                *(f"hide={path}" for path in place.hide), f"disk={limits.disk_bytes}",
                f"inodes={limits.entries}", f"cpu={cpu}", f"as={limits.memory_bytes}",
                f"fsize={limits.file_bytes}", f"nproc={limits.processes}"]
        if self.namespaces and place.keep is not None:
            spec.append(f"keep={place.keep}")
        if place.tmp is not None and not self.namespaces:
            spec.append(f"tmpdir={place.tmp}")
        if self.level == "full":
            assert identity is not None, "the full level runs as a uid of its own"
            spec += [f"uid={identity[0]}", f"gid={identity[1]}"]
        return [sys.executable, "-S", "-I", str(JAIL), *spec, "--", *program]

    @contextlib.contextmanager
    def identity(self) -> Iterator[tuple[int, int] | None]:
        """A uid no other run on this machine holds meanwhile (``full``), and the group."""
        if self.level != "full":
            yield None
            return
        with _slot() as slot:
            yield FIRST_UID + slot, GROUP


def _slot_folder() -> Path:
    """Root's folder of slot locks, shared by every rrt-grade on this machine."""
    for base in (Path("/run"), Path(tempfile.gettempdir())):
        folder = base / "rrt-grade-uids"
        try:
            folder.mkdir(mode=0o700, exist_ok=True)
            info = folder.lstat()
        except OSError:
            continue
        if folder.is_dir() and not folder.is_symlink() and info.st_uid == 0 \
                and not info.st_mode & 0o022:
            return folder
    raise OSError("no folder for the sandbox's uid slots (/run or the temporary folder)")


@contextlib.contextmanager
def _slot() -> Iterator[int]:
    """The first slot whose lock file no other process holds; held until the end."""
    folder = _slot_folder()
    for slot in range(SLOTS):
        fd = os.open(folder / str(slot), os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            continue
        try:
            yield slot
        finally:
            os.close(fd)
        return
    raise OSError(f"all {SLOTS} sandbox uid slots are in use")


def probe(wanted: bool = True) -> Sandbox:
    """Try the sandbox once on a scratch folder: the best level that works here."""
    root_note = [ROOT_NPROC] if os.geteuid() == 0 else []
    if not wanted:
        return Sandbox("none", "; ".join(["no sandbox (turned off)", *root_note]))
    why = ""
    for level in ("full", "userns") if os.geteuid() == 0 else ("userns",):
        why = _try(Sandbox(level, ""))
        if not why:
            return Sandbox(level, FULL if level == "full" else USERNS)
    return Sandbox("none", "; ".join([f"no sandbox ({why})", *root_note]))


# The probe's program: reads its layer, writes its folder, cannot write /etc or see /tmp.
_TEST = ('read -r given < given && echo x > inside && [ "$(cat inside)" = x ] && '
         '! (echo x > /etc/rrt-grade-probe) 2>/dev/null && [ ! -e "$1" ] && '
         '[ "$(cat /proc/self/stat | cut -d" " -f1)" -lt 100 ] && echo "ok $given"')


def _try(sandbox: Sandbox) -> str:
    """'' when a program in the sandbox sees and may write only what it should."""
    with tempfile.TemporaryDirectory(prefix="rrt-grade-probe-") as scratch:
        base = Path(scratch)
        for name in ("lower", "sub/folder"):
            (base / name).mkdir(parents=True)
        (base / "lower" / "given").write_text("layer\n")
        os.chmod(base / "lower", 0o775)
        if sandbox.level == "full":
            os.chown(base / "lower", -1, GROUP)
        place = Place(base / "sub" / "folder", base / "lower", hide=(base,))
        try:
            with sandbox.identity() as identity:
                done = subprocess.run(
                    sandbox.command(place, ["sh", "-c", _TEST, "sh", str(base / "lower")],
                                    Limits(), 10.0, identity),
                    stdin=subprocess.DEVNULL, capture_output=True, timeout=10)
        except (OSError, subprocess.SubprocessError) as error:
            return f"the namespaces could not be tried: {error}"
        if done.stdout == b"ok layer\n":
            return ""
        lines = done.stderr.decode(errors="replace").strip().splitlines()
        return f"{sandbox.level}: " + (lines[-1] if lines else
                                       f"the sandbox test exited {done.returncode}")
