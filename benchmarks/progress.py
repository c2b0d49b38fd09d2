"""The harness's progress on stderr, from tqdm: a live bar on a terminal, and
elsewhere (a log, CI) one line per tenth of the runs, in the bar's own words."""

from __future__ import annotations

import sys
import time
from typing import TextIO

from tqdm import tqdm

from benchmarks.rows import RunRow

LOG_STEPS = 10
"""Lines written when stderr is no terminal: one per 1/LOG_STEPS of the runs."""


class Progress:
    """A progress callback for :func:`benchmarks.harness.run_all`: runs done, runs
    not solved, elapsed and estimated time left."""

    def __init__(self, total: int, stream: TextIO | None = None):
        self.stream = stream or sys.stderr
        self.total = total
        self.unsolved = 0
        self.began = time.perf_counter()
        self.last_step = -1
        self.live = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.bar = tqdm(total=total, unit="run", desc="benchmarks", file=self.stream,
                        dynamic_ncols=True, disable=not self.live)

    def __call__(self, done: int, total: int, row: RunRow) -> None:
        if not row.solved:
            self.unsolved += 1
        if self.live:
            self.bar.set_postfix(unsolved=self.unsolved, refresh=False)
            self.bar.update(done - self.bar.n)
            return
        step = done * LOG_STEPS // total if total else LOG_STEPS
        if step != self.last_step:
            self.last_step = step
            line = tqdm.format_meter(done, total, time.perf_counter() - self.began,
                                     prefix="benchmarks", unit="run",
                                     postfix=f"unsolved={self.unsolved}")
            self.stream.write(line + "\n")
            self.stream.flush()

    def close(self) -> None:
        self.bar.close()
