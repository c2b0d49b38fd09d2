"""Run a planner as a subprocess: problem on its stdin, its stdout read back.

Written for hostile planners. The planner starts in its own session (so its
own process group); its stdin and stdout are driven by one ``selectors`` loop,
so a planner that never reads its input cannot block us; its stdout is read
incrementally up to a cap; at the timeout, or when the output passes the cap,
the whole process group is killed. Once the planner has exited, anything it
left running in its group is killed too (such a leftover would otherwise keep
the pipe open). The planner's stderr is passed through to ours.
"""

from __future__ import annotations

import os
import selectors
import signal
import subprocess
import time
from dataclasses import dataclass
from typing import Sequence

DEFAULT_TIMEOUT = 60.0
DEFAULT_OUTPUT_CAP = 64 * 1024 * 1024
_READ_SIZE = 1 << 16
# After the planner exits, how long a process it left behind may keep stdout open.
_DRAIN_GRACE = 0.5


@dataclass(frozen=True)
class PlannerRun:
    """What happened to the planner."""

    command: tuple[str, ...]
    output: bytes | bytearray   # its stdout, at most ``output_cap`` bytes
    started: bool               # False: it could not be started (see ``start_error``)
    start_error: str = ""
    exit_code: int | None = None  # its own exit status, when it exited by itself
    signal: int | None = None     # the signal that ended it, when not ours
    timed_out: bool = False
    output_cap_exceeded: bool = False
    output_cap: int = DEFAULT_OUTPUT_CAP
    timeout: float = DEFAULT_TIMEOUT
    wall_time: float = 0.0      # seconds from start to its exit (or to our kill)

    @property
    def ran_to_completion(self) -> bool:
        """Started, not timed out: its output can be validated."""
        return self.started and not self.timed_out


def _kill_group(pgid: int) -> None:
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass  # the group is already gone


def run_planner(command: Sequence[str], stdin_data: bytes, timeout: float = DEFAULT_TIMEOUT,
                output_cap: int = DEFAULT_OUTPUT_CAP) -> PlannerRun:
    """Start ``command``, feed it ``stdin_data``, collect its stdout.

    Never raises for anything the planner does; returns within about ``timeout``
    seconds (plus the time the kernel takes to kill the group).
    """
    command = tuple(command)
    began = time.monotonic()
    try:
        process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                   start_new_session=True)
    except (OSError, ValueError, subprocess.SubprocessError) as error:
        return PlannerRun(command, b"", False, start_error=str(error), output_cap=output_cap,
                          timeout=timeout)
    pgid = process.pid  # start_new_session: the planner leads its own group
    deadline = began + timeout
    pump = _Pump(process, stdin_data, output_cap)
    exit_time: float | None = None
    try:
        while pump.stdout_open:
            now = time.monotonic()
            if exit_time is None and process.poll() is not None:
                exit_time = now
            if now >= deadline:
                break
            if exit_time is not None and now >= exit_time + _DRAIN_GRACE:
                break  # it exited, something it left behind holds stdout open
            limit = deadline if exit_time is None else min(deadline, exit_time + _DRAIN_GRACE)
            pump.step(min(limit - now, 0.1))
        # Its stdout is done with (EOF, cap, or abandoned); the planner itself may run on.
        if process.poll() is None and not pump.cap_exceeded:
            try:
                process.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                pass
        exited_by_itself = process.poll() is not None
        if exited_by_itself and exit_time is None:
            exit_time = time.monotonic()
    finally:
        # Also on Ctrl-C or SIGTERM: in its own session, the planner would not get them.
        _kill_group(pgid)  # the planner if it is still running, and anything it left behind
        process.wait()
        pump.close()
    wall = (exit_time if exited_by_itself else time.monotonic()) - began
    code = process.returncode if exited_by_itself else None
    return PlannerRun(command, pump.output, True,  # no copy: it may be 64 MiB
                      exit_code=code if code is not None and code >= 0 else None,
                      signal=-code if code is not None and code < 0 else None,
                      timed_out=not exited_by_itself and not pump.cap_exceeded,
                      output_cap_exceeded=pump.cap_exceeded, output_cap=output_cap,
                      timeout=timeout, wall_time=wall)


class _Pump:
    """Writes the planner's stdin and reads its stdout without ever blocking."""

    def __init__(self, process: subprocess.Popen, stdin_data: bytes, output_cap: int):
        self.process = process
        self.output = bytearray()
        self.output_cap = output_cap
        self.cap_exceeded = False
        self.to_write = memoryview(stdin_data)
        self.stdin_fd, self.stdout_fd = process.stdin.fileno(), process.stdout.fileno()
        os.set_blocking(self.stdin_fd, False)
        os.set_blocking(self.stdout_fd, False)
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.stdout_fd, selectors.EVENT_READ)
        self.stdout_open = True
        self.stdin_open = True
        if self.to_write:
            self.selector.register(self.stdin_fd, selectors.EVENT_WRITE)
        else:
            self.close_stdin()

    def close_stdin(self) -> None:
        if self.stdin_open:
            if self.to_write is not None and self.stdin_fd in self.selector.get_map():
                self.selector.unregister(self.stdin_fd)
            try:
                self.process.stdin.close()
            except OSError:
                pass  # EPIPE on the flush of a planner that never read
            self.stdin_open = False

    def step(self, wait: float) -> None:
        for key, _ in self.selector.select(timeout=max(wait, 0.0)):
            if key.fd == self.stdin_fd:
                self._write()
            elif self.stdout_open:
                self._read()

    def _write(self) -> None:
        try:
            written = os.write(self.stdin_fd, self.to_write[:_READ_SIZE])
        except (BlockingIOError, InterruptedError):
            return
        except OSError:  # EPIPE: it does not read its input, which is its business
            self.close_stdin()
            return
        self.to_write = self.to_write[written:]
        if not self.to_write:
            self.close_stdin()

    def _read(self) -> None:
        try:
            chunk = os.read(self.stdout_fd, _READ_SIZE)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            chunk = b""
        if not chunk:
            self._close_stdout()
            return
        room = self.output_cap - len(self.output)
        if len(chunk) > room:
            self.output += chunk[:room]
            self.cap_exceeded = True
            self._close_stdout()
            return
        self.output += chunk

    def _close_stdout(self) -> None:
        if self.stdout_open:
            self.selector.unregister(self.stdout_fd)
            self.stdout_open = False

    def close(self) -> None:
        self.close_stdin()
        self.selector.close()
        self.process.stdout.close()
