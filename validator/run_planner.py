"""Run a planner as a subprocess: problem on its stdin, its stdout read back.

Written for hostile planners. The planner starts in its own session (so its
own process group); its stdin, stdout and stderr are driven by one ``poll``
loop, so a planner that never reads its input, or floods either output, cannot
block us. Its stdout is read up to a cap (past it the planner is stopped); its
stderr is passed on to ours up to another cap, the rest counted and dropped, and
one line says so.

Containment: at the timeout, when stdout passes the cap, and once the planner
has exited, its process group is killed and, on Linux, every other process it
started too. For that, while the planner runs, the caller is a child subreaper
(``prctl(PR_SET_CHILD_SUBREAPER)``), so a descendant that leaves the group
(``setsid``) and loses its parent is re-parented to us, not to init, and a walk
of /proc still finds it; and the planner's parent-death signal is SIGKILL, so
killing the validator, even with SIGKILL, kills the planner (what the planner
started survives that: nothing of ours is left to kill it). The
walk takes every process descended from the caller that started after the
planner and is not under a child the caller had before: it assumes no other
thread of the caller starts processes meanwhile. Where ``prctl`` or /proc is
missing, only the group is killed.
"""

from __future__ import annotations

import _signal as signal  # signal's own C module: the validator starts the planner before
import os                 # anything imports the enum the signal module wraps it in
import math
import select
import sys
import time
from collections.abc import Callable, Sequence
from errno import ENOENT, ENOTDIR

DEFAULT_TIMEOUT = 60.0
DEFAULT_OUTPUT_CAP = 64 * 1024 * 1024
DEFAULT_STDERR_CAP = 1024 * 1024
STDERR_TAIL = 4096  # the last bytes of the planner's stderr kept, to show in the picture
_READ_SIZE = 1 << 16
_STDERR_WRITE = 4096  # at most PIPE_BUF: a pipe that polls writable takes it whole
# After the planner exits, how long a process it left behind may keep stdout open.
_DRAIN_GRACE = 0.5
# How long the passed-on stderr may take to drain into a slow reader at the end.
_STDERR_FLUSH_TIME = 1.0
# How long the sweep of the planner's descendants keeps killing what it finds.
_SWEEP_TIME = 2.0
_PR_SET_PDEATHSIG = 1
_PR_SET_CHILD_SUBREAPER = 36
_PR_GET_CHILD_SUBREAPER = 37


class PlannerRun:
    """What happened to the planner. (A plain class, not a dataclass: the validator
    imports this module before it starts the planner, and ``dataclasses`` with
    ``inspect`` would cost that wait about 10 ms.)"""

    def __init__(self, command: tuple[str, ...], output: bytes | bytearray, started: bool,
                 start_error: str = "", exit_code: int | None = None,
                 signal: int | None = None, timed_out: bool = False,
                 output_cap_exceeded: bool = False, output_cap: int = DEFAULT_OUTPUT_CAP,
                 timeout: float = DEFAULT_TIMEOUT, wall_time: float = 0.0,
                 stderr_bytes: int = 0, stderr_cap: int = DEFAULT_STDERR_CAP,
                 stderr_tail: bytes = b"", launched: bool = False) -> None:
        self.command = command
        self.output = output            # its stdout, at most ``output_cap`` bytes
        self.started = started          # False: it could not be started (``start_error``)
        self.start_error = start_error
        self.exit_code = exit_code      # its own exit status, when it exited by itself
        self.signal = signal            # the signal that ended it, when not ours
        self.timed_out = timed_out
        self.output_cap_exceeded = output_cap_exceeded
        self.output_cap = output_cap
        self.timeout = timeout
        self.wall_time = wall_time      # seconds from start to its exit (or to our kill)
        self.stderr_bytes = stderr_bytes  # what it wrote on stderr; ``stderr_cap`` passed on
        self.stderr_cap = stderr_cap
        self.stderr_tail = stderr_tail  # its last STDERR_TAIL bytes there (for the picture)
        self.launched = launched        # started by the launcher (validator/launch.c)

    @property
    def ran_to_completion(self) -> bool:
        """Started, not timed out: its output can be validated."""
        return self.started and not self.timed_out

    @property
    def stderr_cut(self) -> bool:
        """It wrote more on stderr than was passed on."""
        return self.stderr_bytes > self.stderr_cap


def _kill_group(pgid: int) -> None:
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass  # the group is already gone


def run_planner(command: Sequence[str], stdin_data: bytes, timeout: float = DEFAULT_TIMEOUT,
                output_cap: int = DEFAULT_OUTPUT_CAP,
                stderr_cap: int = DEFAULT_STDERR_CAP, stderr_fd: int = 2) -> PlannerRun:
    """Start ``command``, feed it ``stdin_data``, collect its stdout; its stderr is
    passed on to ``stderr_fd`` (ours by default).

    Never raises for anything the planner does; returns within about ``timeout``
    seconds (plus the time the kernel takes to kill what it started, and at most
    a second for a slow reader of our stderr).
    """
    started = start_planner(command, stdin_data, timeout, output_cap, stderr_cap, stderr_fd)
    return started.finish() if isinstance(started, StartedPlanner) else started


def start_planner(command: Sequence[str], stdin_data: bytes, timeout: float = DEFAULT_TIMEOUT,
                  output_cap: int = DEFAULT_OUTPUT_CAP, stderr_cap: int = DEFAULT_STDERR_CAP,
                  stderr_fd: int = 2) -> StartedPlanner | PlannerRun:
    """:func:`run_planner`'s first half: the planner started, contained, and given
    as much of ``stdin_data`` as its pipe takes at once; the caller may work
    meanwhile (the timeout counts from here) and then calls
    :meth:`StartedPlanner.finish`, or :meth:`StartedPlanner.stop` if it fails
    first. A planner that cannot be started: its :class:`PlannerRun` at once."""
    command = tuple(command)
    if sys.stderr is not None:
        sys.stderr.flush()  # what we wrote before comes before what the planner writes
    stderr = _StderrSink(stderr_cap, stderr_fd)  # before the pipes: they may reuse a closed fd 2
    containment = _Containment()
    began = time.monotonic()
    try:
        process = _spawn(command, containment.preexec())
    except (OSError, ValueError) as error:
        containment.close()
        return PlannerRun(command, b"", False, start_error=str(error), output_cap=output_cap,
                          timeout=timeout, stderr_cap=stderr_cap)
    return _pumped(StartedPlanner(command, process, containment, began, timeout, stderr_cap),
                   stdin_data, output_cap, stderr)


def _pumped(started: StartedPlanner, stdin_data: bytes, output_cap: int,
            stderr: _StderrSink) -> StartedPlanner:
    """``started`` with its containment told the pid and its pipes' pump, given as
    much of ``stdin_data`` as its pipe takes at once (stopped on any failure)."""
    try:
        started.containment.started(started.process.pid)
        started.pump = _Pump(started.process, stdin_data, output_cap, stderr)
        started.pump.write_now()
    except BaseException:
        started.stop()
        raise
    return started


def adopt_planner(command: tuple[str, ...], pid: int, stdin: int, stdin_rest: bytes,
                  stdout: int, stderr: int, began: float, timeout: float,
                  output_cap: int = DEFAULT_OUTPUT_CAP, stderr_cap: int = DEFAULT_STDERR_CAP,
                  stderr_fd: int = 2) -> StartedPlanner:
    """:func:`start_planner`'s value for a planner validator/launch.c started as
    ``_spawn`` would (our child, its own session, its parent-death signal set, we a
    child subreaper since before it started) at ``began`` (``time.monotonic()``'s
    clock): its pipes' fds (``stdin`` -1 when closed), ``stdin_rest`` what is still
    to be written to it (validator/launched.py)."""
    if sys.stderr is not None:
        sys.stderr.flush()
    sink = _StderrSink(stderr_cap, stderr_fd)
    started = StartedPlanner(command, _Child(pid, stdin, stdout, stderr),
                             _Containment(launched=pid), began, timeout, stderr_cap)
    started.launched = True
    return _pumped(started, stdin_rest, output_cap, sink)


class _Child:
    """The planner's process: what the module needs of ``subprocess.Popen`` (its
    pid, its end of the three pipes, its exit status), without importing
    subprocess, whose threading, locale and selectors would delay the planner's
    start by milliseconds. ``returncode``: None while it runs, else as Popen's
    (negative: the signal that ended it)."""

    def __init__(self, pid: int, stdin: int, stdout: int, stderr: int) -> None:
        self.pid, self.stdin, self.stdout, self.stderr = pid, stdin, stdout, stderr
        self.returncode: int | None = None

    def poll(self) -> int | None:
        return self._wait(os.WNOHANG)

    def wait(self, timeout: float | None = None) -> int | None:
        """Its status, after at most ``timeout`` seconds (None: still running)."""
        if timeout is None:
            return self._wait(0)
        # A planner whose outputs closed is usually gone within microseconds: look
        # again soon, then less and less often.
        deadline, delay = time.monotonic() + timeout, 0.00005
        while self.poll() is None:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            delay = min(delay * 2, left, 0.05)
            time.sleep(delay)
        return self.returncode

    def _wait(self, flags: int) -> int | None:
        if self.returncode is None:
            try:
                pid, status = os.waitpid(self.pid, flags)
            except ChildProcessError:  # reaped elsewhere: its status is lost (as Popen says)
                self.returncode = 0
                return 0
            if pid == self.pid:
                self.returncode = os.waitstatus_to_exitcode(status)
        return self.returncode


def _spawn(command: tuple[str, ...], preexec: Callable[[], None] | None) -> _Child:
    """Start ``command`` as ``subprocess.Popen(command, stdin=PIPE, stdout=PIPE,
    stderr=PIPE, start_new_session=True, preexec_fn=preexec)`` does: in its own
    session, SIGPIPE and SIGXFSZ back to their defaults, no other file of ours open,
    found on PATH as Popen finds it; OSError (worded as Popen's) or ValueError when
    it cannot be started."""
    if any("\0" in arg for arg in command):
        raise ValueError("embedded null byte")
    program = os.fsencode(command[0])
    paths = ([program] if os.path.dirname(program) else
             [os.path.join(os.fsencode(folder), program) for folder in os.get_exec_path()])
    argv = [os.fsencode(arg) for arg in command]
    max_fd = os.sysconf("SC_OPEN_MAX")
    opened: list[int] = []
    try:
        for _ in range(4):  # stdin, stdout, stderr, and the exec error report
            opened += os.pipe()  # not inherited: closed by exec
        child_ends = (opened[0], opened[3], opened[5])
        error_read, error_write = opened[6], opened[7]
        pid = os.fork()
        if pid == 0:  # the child: never returns
            _exec_child(child_ends, error_write, max_fd, paths, argv, preexec)
    except BaseException:
        for fd in opened:
            os.close(fd)
        raise
    for fd in (*child_ends, error_write):
        os.close(fd)
    try:
        report = _read_all(error_read)  # empty when the exec took place
    except BaseException:
        _kill(pid)
        os.waitpid(pid, 0)
        for fd in (opened[1], opened[2], opened[4]):
            os.close(fd)
        raise
    finally:
        os.close(error_read)
    child = _Child(pid, opened[1], opened[2], opened[4])
    if report:
        child.wait()
        for fd in (child.stdin, child.stdout, child.stderr):
            os.close(fd)
        number, _, stage = report.partition(b":")
        errno = int(number)
        if stage == b"exec":
            raise OSError(errno, os.strerror(errno), command[0])
        raise OSError(errno, os.strerror(errno)) if errno else OSError(
            "the planner's process failed before it could run the command")
    return child


def _read_all(fd: int) -> bytes:
    data = b""
    while True:
        chunk = os.read(fd, 64)
        if not chunk:
            return data
        data += chunk


def _exec_child(child_ends: tuple[int, int, int], error_write: int, max_fd: int,
                paths: list[bytes], argv: list[bytes],
                preexec: Callable[[], None] | None) -> None:
    """In the forked child: the pipes on fds 0-2, its own session, ``preexec``, every
    other fd closed, then exec; on failure the errno (and whether exec itself
    failed) goes back through ``error_write``. Never returns."""
    stage, errno = b"noexec", 0
    try:
        moved = list(child_ends)
        for index, fd in enumerate(moved):
            while moved[index] <= 2:  # off 0-2 first, so that no dup2 below overwrites it
                moved[index] = os.dup(moved[index])
        for target, fd in enumerate(moved):
            os.dup2(fd, target)  # the copy on 0-2 is inherited by the exec
        for name in ("SIGPIPE", "SIGXFSZ"):  # Python ignores them; a program expects neither
            if hasattr(signal, name):
                signal.signal(getattr(signal, name), signal.SIG_DFL)
        os.setsid()
        if preexec is not None:
            preexec()
        os.closerange(3, error_write)
        os.closerange(error_write + 1, max_fd)
        stage, saved = b"exec", 0
        for path in paths:
            try:
                os.execv(path, argv)
            except OSError as error:  # as Popen: the first error but "not there", else the last
                errno = error.errno or 0
                if not saved and errno not in (ENOENT, ENOTDIR):
                    saved = errno
        errno = saved or errno
    except OSError as error:
        errno = error.errno or 0
    except BaseException:
        pass
    finally:
        try:
            os.write(error_write, b"%d:%s" % (errno, stage))
        finally:
            os._exit(255)


class StartedPlanner:
    """A planner :func:`start_planner` started: :meth:`finish` drives its pipes to
    the end and gives the :class:`PlannerRun`; :meth:`stop` kills it and everything
    it started (what ``finish`` does at its end too)."""

    def __init__(self, command: tuple[str, ...], process: _Child,
                 containment: _Containment, began: float, timeout: float, stderr_cap: int):
        self.command, self.process, self.containment = command, process, containment
        self.began, self.timeout, self.stderr_cap = began, timeout, stderr_cap
        self.pump: _Pump | None = None
        self.stopped = False
        self.launched = False  # started by the launcher (adopt_planner)

    def finish(self) -> PlannerRun:
        process, pump = self.process, self.pump
        assert pump is not None and not self.stopped
        try:
            exit_time = _pump_until_done(process, pump, self.began + self.timeout)
        finally:
            self.stop()
        exited_by_itself = exit_time is not None
        wall = (exit_time if exited_by_itself else time.monotonic()) - self.began
        code = process.returncode if exited_by_itself else None
        return PlannerRun(self.command, pump.output, True,  # no copy: it may be 64 MiB
                          exit_code=code if code is not None and code >= 0 else None,
                          signal=-code if code is not None and code < 0 else None,
                          timed_out=not exited_by_itself and not pump.cap_exceeded,
                          output_cap_exceeded=pump.cap_exceeded, output_cap=pump.output_cap,
                          timeout=self.timeout, wall_time=wall,
                          stderr_bytes=pump.stderr.total, stderr_cap=self.stderr_cap,
                          stderr_tail=bytes(pump.stderr.tail), launched=self.launched)

    def stop(self) -> None:
        """Kill the planner's group and what left it, reap the planner, close the
        pipes (once; also on Ctrl-C or SIGTERM: in its own session, the planner
        would not get them)."""
        if self.stopped:
            return
        self.stopped = True
        try:
            _kill_group(self.process.pid)  # start_new_session: the planner leads its group
            self.process.wait()
            self.containment.sweep()  # what left the group
        finally:
            self.containment.close()
            if self.pump is not None:
                self.pump.close()
            else:
                for fd in (self.process.stdin, self.process.stdout, self.process.stderr):
                    os.close(fd)


def _pump_until_done(process: _Child, pump: _Pump, deadline: float
                     ) -> float | None:
    """Drive the pipes until both outputs end (or are abandoned) and the planner has
    exited, or the deadline; returns when it exited (None: it has not)."""
    exit_time: float | None = None
    while pump.outputs_open and not pump.cap_exceeded:
        now = time.monotonic()
        if exit_time is None and process.poll() is not None:
            exit_time = now
        if now >= deadline:
            break
        if exit_time is not None and now >= exit_time + _DRAIN_GRACE:
            break  # it exited, something it left behind holds an output open
        limit = deadline if exit_time is None else min(deadline, exit_time + _DRAIN_GRACE)
        pump.step(min(limit - now, 0.1))
    # Its outputs are done with (EOF, cap, or abandoned); the planner itself may run on.
    if process.poll() is None and not pump.cap_exceeded:
        process.wait(timeout=max(0.0, deadline - time.monotonic()))
    if exit_time is None and process.poll() is not None:
        exit_time = time.monotonic()
    return exit_time


class _Pump:
    """Writes the planner's stdin, reads its stdout and stderr, never blocking."""

    def __init__(self, process: _Child, stdin_data: bytes, output_cap: int,
                 stderr: _StderrSink):
        self.process = process
        self.output = bytearray()
        self.output_cap = output_cap
        self.cap_exceeded = False
        self.stderr = stderr
        self.to_write = memoryview(stdin_data)
        self.stdin_fd, self.stdout_fd = process.stdin, process.stdout
        self.stderr_fd = process.stderr
        for fd in (self.stdin_fd, self.stdout_fd, self.stderr_fd):
            if fd >= 0:  # stdin -1: closed already (the launcher wrote it all)
                os.set_blocking(fd, False)
        self.selector = _Poller()
        self.selector.register(self.stdout_fd, select.POLLIN)
        self.selector.register(self.stderr_fd, select.POLLIN)
        self.open_outputs = {self.stdout_fd, self.stderr_fd}
        self.stdin_open = self.stdin_fd >= 0
        if self.to_write and self.stdin_open:
            self.selector.register(self.stdin_fd, select.POLLOUT)
        else:
            self.close_stdin()

    @property
    def outputs_open(self) -> bool:
        return bool(self.open_outputs)

    @property
    def stdout_open(self) -> bool:
        return self.stdout_fd in self.open_outputs

    def close_stdin(self) -> None:
        if self.stdin_open:
            if self.stdin_fd in self.selector:
                self.selector.unregister(self.stdin_fd)
            os.close(self.stdin_fd)
            self.stdin_open = False

    def step(self, wait: float) -> None:
        self.stderr.watch(self.selector)
        for fd in self.selector.select(max(wait, 0.0)):
            if fd == self.stdin_fd:
                self._write()
            elif fd == self.stdout_fd:
                self._read_stdout()
            elif fd == self.stderr_fd:
                self._read_stderr()
            else:
                self.stderr.write_some()

    def write_now(self) -> None:
        """Write what the stdin pipe takes without waiting (a problem of less than
        the pipe's 64 KiB: all of it, closing stdin)."""
        if self.stdin_open:
            self._write()

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

    def _read(self, fd: int) -> bytes | None:
        """A chunk, or None when there is nothing yet; b"" at the end (then closed)."""
        try:
            chunk = os.read(fd, _READ_SIZE)
        except (BlockingIOError, InterruptedError):
            return None
        except OSError:
            chunk = b""
        if not chunk:
            self._close_output(fd)
        return chunk

    def _read_stdout(self) -> None:
        chunk = self._read(self.stdout_fd)
        if not chunk:
            return
        room = self.output_cap - len(self.output)
        if len(chunk) > room:
            self.output += chunk[:room]
            self.cap_exceeded = True
            self._close_output(self.stdout_fd)
            return
        self.output += chunk

    def _read_stderr(self) -> None:
        chunk = self._read(self.stderr_fd)
        if chunk:
            self.stderr.take(chunk)

    def _close_output(self, fd: int) -> None:
        if fd in self.open_outputs:
            self.selector.unregister(fd)
            self.open_outputs.discard(fd)

    def close(self) -> None:
        self.close_stdin()
        self.stderr.finish()
        os.close(self.stdout_fd)
        os.close(self.stderr_fd)


class _Poller:
    """``select.poll`` (not epoll: our own stderr may be a regular file, which epoll
    refuses) that knows which fds it watches; :meth:`select` gives the fds with an
    event (hang-up and error included: the read or write then says what it is)."""

    def __init__(self) -> None:
        self.poll = select.poll()
        self.fds: set[int] = set()

    def __contains__(self, fd: int) -> bool:
        return fd in self.fds

    def register(self, fd: int, events: int) -> None:
        self.poll.register(fd, events)
        self.fds.add(fd)

    def unregister(self, fd: int) -> None:
        self.poll.unregister(fd)
        self.fds.discard(fd)

    def select(self, timeout: float) -> list[int]:
        return [fd for fd, _ in self.poll.poll(math.ceil(timeout * 1e3))]


class _StderrSink:
    """Passes the planner's stderr on to our fd 2: the first ``cap`` bytes of it, in
    pieces a pipe takes without blocking, so a reader of ours that stalls cannot
    stall the loop; past the cap the bytes are counted, and one line says so."""

    def __init__(self, cap: int, fd: int = 2):
        self.cap = cap
        self.fd = fd
        self.total = 0
        self.pending = bytearray()  # passed on, not yet written: at most ``cap`` bytes
        self.tail = bytearray()     # the last STDERR_TAIL bytes taken
        self.last_byte = b"\n"
        try:
            os.fstat(fd)
            self.broken = False
        except OSError:  # our stderr is closed: drop it all
            self.broken = True

    def take(self, chunk: bytes) -> None:
        self.tail += chunk[-STDERR_TAIL:]
        del self.tail[:-STDERR_TAIL]
        room = self.cap - self.total
        self.total += len(chunk)
        if room > 0 and not self.broken:
            self.pending += chunk[:room]

    def watch(self, selector: _Poller) -> None:
        """Ask ``selector`` for writability of our stderr while there is something to write."""
        registered = self.fd in selector
        if self.pending and not self.broken and not registered:
            selector.register(self.fd, select.POLLOUT)
        elif registered and (not self.pending or self.broken):
            selector.unregister(self.fd)

    def write_some(self) -> None:
        if self.broken or not self.pending:
            return
        try:
            written = os.write(self.fd, self.pending[:_STDERR_WRITE])
        except (BlockingIOError, InterruptedError):
            return
        except OSError:  # EPIPE, EBADF: nobody reads our stderr any more
            self.broken = True
            self.pending.clear()
            return
        self.last_byte = bytes(self.pending[written - 1:written]) or self.last_byte
        del self.pending[:written]

    def finish(self) -> None:
        """Write what is pending and, if it was cut, the notice; give up after
        _STDERR_FLUSH_TIME on a reader that does not read."""
        if self.total > self.cap and not self.broken:
            self.pending += (b"" if (self.pending[-1:] or self.last_byte) == b"\n" else b"\n")
            self.pending += (f"rrt-validator: the planner wrote {self.total} bytes on stderr; "
                             f"only the first {self.cap} were passed on\n").encode()
        if not self.pending or self.broken:
            return
        selector = _Poller()
        selector.register(self.fd, select.POLLOUT)
        deadline = time.monotonic() + _STDERR_FLUSH_TIME
        while self.pending and not self.broken and time.monotonic() < deadline:
            if selector.select(max(0.0, deadline - time.monotonic())):
                self.write_some()


class _Containment:
    """Makes the caller a child subreaper while the planner runs, gives the planner a
    parent-death signal, and kills what the planner left behind (see the module's
    docstring). Does nothing where prctl or /proc is missing."""

    def __init__(self, launched: int | None = None) -> None:
        """``launched``: the pid of a planner the launcher started (validator/launch.c):
        our child already, we its subreaper since before it started (the attribute
        outlives the exec into Python, and the process ends with the run, so it is
        neither set nor cleared here: prctl is not even loaded), and every other child
        of ours its descendant."""
        self.parent = os.getpid()
        self.prctl = _load_prctl() if launched is None else None
        self.planner: int | None = None
        self.since = 0  # the planner's start time, in clock ticks since boot
        table = _proc_table() if launched is None else None
        self.before = frozenset(pid for pid, (ppid, _, _) in (table or {}).items()
                                if ppid == self.parent)
        self.was_subreaper = launched is None and _get_subreaper(self.prctl)
        if self.prctl is not None and not self.was_subreaper:
            self.prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)

    def preexec(self) -> Callable[[], None] | None:
        """For Popen's ``preexec_fn``: SIGKILL the planner when its parent dies."""
        prctl, parent = self.prctl, self.parent
        if prctl is None:
            return None

        def set_parent_death_signal() -> None:
            prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
            if os.getppid() != parent:  # the parent died before the prctl took effect
                os.kill(os.getpid(), signal.SIGKILL)
        return set_parent_death_signal

    def started(self, pid: int) -> None:
        self.planner = pid
        stat = _read_stat(pid)
        self.since = stat[1] if stat is not None else 0

    def sweep(self) -> None:
        """SIGKILL every process descended from the planner, in its group or not, and
        reap those re-parented to us; again until none is left (or _SWEEP_TIME)."""
        deadline = time.monotonic() + _SWEEP_TIME
        while True:
            table = _proc_table()
            if table is None:
                return
            found = _descendants(table, self.parent, self.before, self.since)
            for pid in found:
                if table[pid][2] != b"Z":
                    _kill(pid)
            for pid in found:
                if table[pid][0] == self.parent and pid != self.planner:
                    _reap(pid)
            if not found or time.monotonic() >= deadline:
                return
            time.sleep(0.002)

    def close(self) -> None:
        if self.prctl is not None and not self.was_subreaper:
            self.prctl(_PR_SET_CHILD_SUBREAPER, 0, 0, 0, 0)


def _load_prctl() -> Callable[..., int] | None:
    """libc's prctl (Linux), or None. Made as ``ctypes.CDLL(None, use_errno=True).prctl``
    with ``c_int`` arguments and result makes it, from ctypes' own C module:
    ``import ctypes`` (its types, ``struct``) would delay the planner's start
    (docs/setup-and-startup.md has the figures)."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        import _ctypes

        class CInt(_ctypes._SimpleCData):  # ctypes.c_int
            _type_ = "i"

        class CULong(_ctypes._SimpleCData):  # ctypes.c_ulong
            _type_ = "L"

        class Libc:  # what a foreign function is looked up in: a CDLL's handle
            _handle = _ctypes.dlopen(None, _ctypes.RTLD_LOCAL)

        class Function(_ctypes.CFuncPtr):  # CDLL(..., use_errno=True)._FuncPtr
            _flags_ = _ctypes.FUNCFLAG_CDECL | _ctypes.FUNCFLAG_USE_ERRNO
            _restype_ = CInt

        prctl = Function(("prctl", Libc))
        prctl.argtypes = (CInt, CULong, CULong, CULong, CULong)
    except (ImportError, OSError, AttributeError, TypeError):
        return _load_prctl_by_ctypes()  # ctypes' private module changed: the public way
    return prctl


def _load_prctl_by_ctypes() -> Callable[..., int] | None:
    """:func:`_load_prctl` through ``ctypes`` itself, or None."""
    try:
        import ctypes
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (ImportError, OSError, AttributeError):
        return None
    prctl.argtypes = [ctypes.c_int] + [ctypes.c_ulong] * 4
    prctl.restype = ctypes.c_int
    return prctl


def _get_subreaper(prctl: Callable[..., int] | None) -> bool:
    if prctl is None:
        return False
    import _ctypes
    value = prctl.restype(0)  # a C int for prctl to write into
    if prctl(_PR_GET_CHILD_SUBREAPER, _ctypes.addressof(value), 0, 0, 0) != 0:
        return False
    return bool(value.value)


def _read_stat(pid: int) -> tuple[int, int, bytes] | None:
    """(parent pid, start time in clock ticks, state letter) from /proc/PID/stat."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            data = stat.read()
    except OSError:
        return None
    fields = data[data.rfind(b")") + 2:].split()  # the name may hold spaces and ')'
    try:
        return int(fields[1]), int(fields[19]), fields[0]
    except (IndexError, ValueError):
        return None


def _proc_table() -> dict[int, tuple[int, int, bytes]] | None:
    """``_read_stat`` by pid of every process below this one, found through the
    kernel's lists of each process's children (a few files, where reading every
    process's would take milliseconds); of every process where the kernel keeps no
    such lists; None without /proc."""
    below = _processes_below(os.getpid())
    if below is not None:
        return below
    try:
        names = os.listdir("/proc")
    except OSError:
        return None
    table = {}
    for name in names:
        if name.isdigit():
            stat = _read_stat(int(name))
            if stat is not None:
                table[int(name)] = stat
    return table


def _processes_below(root: int) -> dict[int, tuple[int, int, bytes]] | None:
    """``_read_stat`` by pid of every descendant of ``root``, through
    ``/proc/PID/task/TID/children``; None where the kernel has no such files."""
    if not os.path.exists(f"/proc/{root}/task/{root}/children"):
        return None
    table: dict[int, tuple[int, int, bytes]] = {}
    stack = [root]
    while stack:
        for pid in _children(stack.pop()):
            if pid not in table:
                stat = _read_stat(pid)
                if stat is not None:
                    table[pid] = stat
                    stack.append(pid)
    return table


def _children(pid: int) -> list[int]:
    """The children of every thread of ``pid`` (none if it is gone)."""
    try:
        threads = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return []
    children = []
    for thread in threads:
        try:
            with open(f"/proc/{pid}/task/{thread}/children", "rb") as listed:
                children += [int(child) for child in listed.read().split()]
        except (OSError, ValueError):
            continue  # the thread (or the process) has ended
    return children


def _descendants(table: dict[int, tuple[int, int, bytes]], root: int,
                 skip: frozenset[int], since: int) -> list[int]:
    """Processes below ``root`` that started at ``since`` or later, not below ``skip``."""
    children: dict[int, list[int]] = {}
    for pid, (ppid, _, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    found, stack = [], [root]
    while stack:
        for pid in children.get(stack.pop(), ()):
            if pid not in skip and table[pid][1] >= since and pid != root:
                found.append(pid)
                stack.append(pid)
    return found


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def _reap(pid: int) -> None:
    try:
        os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        pass  # not ours (any more), or already reaped
