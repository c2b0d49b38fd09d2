"""Containment of a submission's program beyond the validator's: resource limits
set before it starts, its folder as working directory, its stderr into a log, and
on Linux user, mount and network namespaces in which only its folder and a private
temporary folder are writable (everything else read-only, capabilities dropped) and
there is no network.

The command becomes ``sh -c SCRIPT ...``: a few execs, no fork, so the process
the validator starts (and whose group it kills) is the program itself.
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from grading.config import Limits

# $1 phase (outer|inner), $2 stderr log, $3 the submission's folder, $4 its tmp folder.
_SCRIPT = r'''
phase=$1 log=$2 dir=$3 tmp=$4; shift 4
if [ "$phase" = outer ]; then
    exec 2>>"$log" || exit 125
    export TMPDIR="$tmp"
    cd "$dir" || exit 125
    exec "$@"
fi
if [ "$phase" = ns ]; then
    exec 2>>"$log" || exit 125
    export TMPDIR="$tmp"
    exec unshare --user --map-root-user --mount --net --propagation private \
        sh -c "$0" "$0" inner "$log" "$dir" "$tmp" "$@"
fi
mount --bind "$dir" "$dir" && mount --bind "$tmp" "$tmp" || {
    echo "grading sandbox: cannot bind $dir" >&2; exit 125; }
while read -r _ _ _ _ mp _; do
    case $mp in "$dir"|"$tmp"|/proc|/proc/*|/sys|/sys/*) continue ;; esac
    mount -o remount,bind,ro "$mp" 2>/dev/null ||
        echo "grading sandbox: could not make $mp read-only" >&2
done < /proc/self/mountinfo
cd "$dir" || exit 125
exec setpriv --bounding-set=-all --inh-caps=-all --no-new-privs -- "$@"
'''


FULL = "namespaces: read-only file system, no network"


@dataclass(frozen=True)
class Sandbox:
    """What containment this machine gives; ``note`` says what is missing and why."""

    namespaces: bool   # user, mount, network namespaces: read-only, no network
    rlimits: bool      # prlimit is there to set the limits
    note: str          # one line for the report of each run

    def command(self, folder: Path, tmp: Path, log: Path, program: Sequence[str],
                limits: Limits, timeout: float) -> list[str]:
        """``program`` run in ``folder`` under the limits, stderr appended to ``log``."""
        inner = list(program)
        if self.rlimits:
            cpu = limits.cpu_seconds or math.ceil(timeout) + 1
            inner = ["prlimit", f"--cpu={cpu}", f"--as={limits.memory_bytes}",
                     f"--fsize={limits.file_bytes}", f"--nproc={limits.processes}",
                     "--", *inner]
        phase = "ns" if self.namespaces else "outer"
        return ["sh", "-c", _SCRIPT, _SCRIPT, phase, str(log), str(folder), str(tmp), *inner]


def probe(wanted: bool = True) -> Sandbox:
    """Try the namespaces once on a scratch folder: what works here."""
    rlimits = shutil.which("prlimit") is not None
    missing = [] if rlimits else ["no resource limits (prlimit not found)"]
    if rlimits and os.geteuid() == 0:
        missing.append("process count not limited (RLIMIT_NPROC does not bind root)")
    if not wanted:
        return Sandbox(False, rlimits, "; ".join(["no sandbox (turned off)", *missing]))
    tools = [name for name in ("unshare", "setpriv") if shutil.which(name) is None]
    if tools:
        return Sandbox(False, rlimits, "; ".join(
            [f"no sandbox ({' and '.join(tools)} not found)", *missing]))
    why = _try_namespaces()
    if why:
        return Sandbox(False, rlimits, "; ".join([f"no sandbox ({why})", *missing]))
    return Sandbox(True, rlimits, "; ".join([FULL, *missing]))


def _try_namespaces() -> str:
    """'' when a program in the sandbox can write its folder and not outside it."""
    with tempfile.TemporaryDirectory(prefix="rrt-grade-probe-") as scratch:
        base = Path(scratch)
        (base / "dir").mkdir()
        (base / "tmp").mkdir()
        test = 'echo x > inside && ! (echo x > "$1") 2>/dev/null'
        command = Sandbox(True, False, "").command(
            base / "dir", base / "tmp", base / "log", ["sh", "-c", test, "sh",
                                                       str(base / "outside")],
            Limits(), 10.0)
        try:
            done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True,
                                  timeout=10)
        except (OSError, subprocess.SubprocessError) as error:
            return f"the namespaces could not be tried: {error}"
        if done.returncode == 0 and (base / "dir" / "inside").exists():
            return ""
        log = (base / "log").read_text(errors="replace").strip().splitlines() \
            if (base / "log").exists() else []
        return ("the kernel refused unprivileged user namespaces: " + log[-1] if log
                else f"the sandbox test exited {done.returncode}")
