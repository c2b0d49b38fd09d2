"""The planner ``./rrt-validator``'s launcher (validator/launch.c) started before this
interpreter did, taken over when it is the run the validator would have started.

The launcher passes a token as the first argument: its source's content key, the
planner's pid, its stdin pipe (-1 when all of the problem was written and the pipe
closed), how many bytes were written, its stdout and stderr pipes, a sealed memfd
with the problem's bytes and when the planner started (CLOCK_MONOTONIC, ns).
:func:`receive` takes the token; the validator then reads the problem from the sealed
copy (:func:`problem`), and :func:`take_over` hands the planner to
:mod:`validator.run_planner` when the launcher is this checkout's and the bytes it gave
the planner are those the validator gives; otherwise, and on any way out before
(:func:`discard`), the run is killed with everything it started and the validator
starts the planner itself.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

PREFIX = "--rrt-validator-launched="


class _Launched:
    def __init__(self, fields: list[str]) -> None:
        (self.pid, self.stdin, self.written, self.stdout, self.stderr, self.problem_fd,
         began) = (int(field) for field in fields)
        self.began = began / 1e9  # time.monotonic()'s clock
        self.problem = _read_whole(self.problem_fd)
        os.close(self.problem_fd)


_launched: _Launched | None = None
_problem: bytes | None = None


def receive(token: str, source_key: str) -> None:
    """Take the launcher's token (``sys.argv[1]``); a planner started by a launcher
    built from a source other than the one whose content key is ``source_key`` (a
    stale build) is stopped at once."""
    global _launched, _problem
    key, *fields = token[len(PREFIX):].split(":")
    try:
        launched = _Launched(fields)
    except (ValueError, OSError):
        return  # not a token of ours: nothing was handed over
    from validator.run_planner import _read_stat
    stat = _read_stat(launched.pid)
    if stat is None or stat[0] != os.getpid():
        return
    _launched, _problem = launched, launched.problem
    if key != source_key:
        discard()


def problem() -> bytes | None:
    """The problem's bytes as the launcher read them (None: not launched): what the
    validator judges, whatever the planner does to the file meanwhile."""
    return _problem


def take_over(command: Sequence[str], stdin_data: bytes, timeout: float,
              output_cap: int):
    """The launched planner as :func:`validator.run_planner.start_planner` would have
    started it (a StartedPlanner), or None when there is none to take (then it is
    stopped: the caller starts the planner)."""
    global _launched
    launched, _launched = _launched, None
    if launched is None:
        return None
    if launched.problem != stdin_data:  # e.g. a grid problem not as format_problem writes it
        _stop(launched)
        return None
    from validator.run_planner import adopt_planner
    return adopt_planner(tuple(command), launched.pid, launched.stdin,
                         stdin_data[launched.written:], launched.stdout, launched.stderr,
                         launched.began, timeout, output_cap)


def discard() -> None:
    """Stop a launched planner not taken over (every way out of the validator)."""
    global _launched
    launched, _launched = _launched, None
    if launched is not None:
        _stop(launched)


def _stop(launched: _Launched) -> None:
    from validator.run_planner import adopt_planner
    adopted = adopt_planner((), launched.pid, launched.stdin, b"", launched.stdout,
                            launched.stderr, launched.began, 0.0, 0, stderr_fd=-1)
    adopted.stop()


def _read_whole(fd: int) -> bytes:
    chunks, offset = [], 0
    while True:
        chunk = os.pread(fd, 1 << 20, offset)
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        offset += len(chunk)

