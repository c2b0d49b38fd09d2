"""What a grading is doing, on stderr, whatever stderr is: on a terminal a bar (tqdm's
when it is installed, else one line rewritten in place); otherwise a line at least
every ``every`` seconds, also while no run finishes (a hanging submission), with the
tasks done, the valid ones so far, the time elapsed and an estimate of the rest."""

from __future__ import annotations

import time
from typing import Callable, TextIO

from grading.text import terminal_text

TICK = 0.5  # seconds: how often the grading loop reports that it is still waiting


def duration(seconds: float) -> str:
    """``45s``, ``4m10s``, ``2h03m``."""
    seconds = max(0, round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"


class Progress:
    """The phases (builds, calibration, runs) as they go: ``start``, then ``done`` for
    each task that finished and ``idle`` whenever the loop waited ``TICK`` for nothing."""

    tick = TICK

    def __init__(self, stream: TextIO | None, every: float = 10.0,
                 clock: Callable[[], float] = time.monotonic, terminal: bool | None = None):
        self.stream = stream
        self.every = every
        self.clock = clock
        self.terminal = (terminal if terminal is not None
                         else bool(stream is not None and _isatty(stream)))
        self.began = clock()
        self.bar = None

    def start(self, phase: str, total: int, kept: int = 0, kept_good: int = 0) -> None:
        """A phase of ``total`` tasks, ``kept`` of them (``kept_good`` valid or built)
        found finished in the store."""
        self.phase, self.total, self.kept = phase, total, kept
        self.count, self.good, self.phase_began = kept, kept_good, self.clock()
        self.last_line = None
        if self.terminal:
            self.bar = _bar(self.stream, phase, total, kept)
        self._show(force=True)

    def done(self, row: dict) -> None:
        self.count += 1
        self.good += bool(row.get("valid", row.get("ok")))
        if self.bar is not None:
            self.bar.update(self.line(), row.get("submission", ""))
        self._show()

    def idle(self) -> None:
        self._show()

    def finish(self) -> None:
        if self.bar is not None:
            self.bar.close(self.line())
            self.bar = None
        else:
            self._show(force=True)

    def line(self) -> str:
        """``runs 37/300 done (12 kept), 35 valid, 1m02s elapsed, about 4m10s left``."""
        text = f"{self.phase} {self.count}/{self.total} done"
        text += f" ({self.kept} kept)" if self.kept else ""
        text += f", {self.good} {'built' if self.phase == 'builds' else 'valid'}"
        now = self.clock()
        text += f", {duration(now - self.began)} elapsed"
        done_now = self.count - self.kept
        if 0 < done_now and self.count < self.total:
            rest = (now - self.phase_began) / done_now * (self.total - self.count)
            text += f", about {duration(rest)} left"
        return text

    def _show(self, force: bool = False) -> None:
        """A line when ``every`` has (nearly: within a tick) passed since the last one."""
        now = self.clock()
        if self.bar is not None:
            self.bar.refresh(self.line())
            return
        if not force and self.last_line is not None and now - self.last_line < self.every - TICK:
            return
        self.last_line = now
        _write(self.stream, f"rrt-grade: {self.line()}\n")


def _isatty(stream: TextIO) -> bool:
    try:
        return stream.isatty()
    except (OSError, ValueError):
        return False


def _write(stream: TextIO | None, text: str) -> None:
    """Progress never stops a grading: a stderr that is closed or full is let be."""
    if stream is None:
        return
    try:
        stream.write(text)
        stream.flush()
    except (OSError, ValueError):
        pass


def _bar(stream: TextIO, phase: str, total: int, kept: int):
    """tqdm's bar when it is installed, else a plain line rewritten in place."""
    try:
        from tqdm import tqdm  # optional
    except ImportError:
        return _Line(stream)
    return _Tqdm(tqdm(total=total, initial=kept, desc=f"rrt-grade {phase}", file=stream,
                      unit="task", leave=True, dynamic_ncols=True))


class _Line:
    """The progress line rewritten in place (``\\r``) on a terminal, without tqdm."""

    def __init__(self, stream: TextIO):
        self.stream = stream

    def update(self, line: str, name: str) -> None:
        self.refresh(f"{line}; last: {terminal_text(name)[:24]}")

    def refresh(self, line: str) -> None:
        _write(self.stream, f"\r\x1b[2Krrt-grade: {line}")

    def close(self, line: str) -> None:
        self.refresh(line)
        _write(self.stream, "\n")


class _Tqdm:
    def __init__(self, bar):
        self.bar = bar

    def update(self, line: str, name: str) -> None:
        self.bar.set_postfix_str(terminal_text(name)[:24], refresh=False)
        self.bar.update(1)

    def refresh(self, line: str) -> None:
        self.bar.refresh()

    def close(self, line: str) -> None:
        self.bar.close()
