"""One flat row per benchmark run, and its CSV form.

A run is one planner on one problem for one vehicle with one seed. The row
holds what the harness measured (whole-process wall time, peak memory, exit
status), what the planner reported on its ``-stats`` line (planning time, tree
size, iterations) and what the validator found (valid, path length).
``solved`` is true only for a run that exited 0 with an output the validator's
checks accept: an invalid solution counts as a failure.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import asdict, dataclass, fields
from enum import Enum
from pathlib import Path
from typing import Iterable


class RunStatus(str, Enum):
    """How a run ended, from the harness's point of view."""

    SOLVED = "solved"                  # exit 0 and the validator accepts the output
    INVALID = "invalid"                # exit 0 but the validator rejects the output
    TIME_LIMIT = "time_limit"          # the planner gave up at its time limit
    ITERATION_LIMIT = "iteration_limit"
    UNREACHABLE = "unreachable"        # the planner proved the goal unreachable
    NO_SOLUTION = "no_solution"        # exit 3 without a recognised reason
    KILLED = "killed"                  # the harness killed it past the hard limit
    BAD_INPUT = "bad_input"            # exit 2
    CRASHED = "crashed"                # any other exit status or signal


@dataclass(frozen=True)
class RunRow:
    problem: str              # e.g. "maze-100", or "course-space-1" for course/space-1.sw
    family: str               # "random-d20", "maze", "narrow", "open", "course"
    width: int
    height: int
    vehicle: str              # Vehicle value: point | spaceship | left
    planner: str              # harness id: "rrt", "kpiece", "ompl-rrt", ...
    implementation: str       # "ours" | "ompl"
    seed: int
    time_limit: float         # seconds, passed to the planner as -time
    solved: bool
    status: str               # a RunStatus value
    exit_status: int          # negative: killed by that signal
    valid: bool | None        # the validator's verdict; None when nothing was printed
    failure: str              # first failed check, or the planner's last stderr line
    planning_seconds: float | None   # from the planner's stats line
    process_seconds: float    # wall time of the whole planner process
    path_length: float | None        # from the validator (solved runs)
    tree_nodes: int | None
    iterations: int | None
    trajectory_lines: int | None
    peak_memory_mb: float | None     # the process's maximum resident set size
    corner_cuts: int          # validator warnings: segments cutting a blocked corner
    validation_seconds: float
    path_duration: float | None = None
    """Kinodynamic family, solved runs: total control duration in seconds (sum of K x DT)."""
    first_solution_seconds: float | None = None
    """Planning time of the first solution (the stats line's); None when unsolved."""
    best_cost: float | None = None
    """Solved runs: the answer's cost as the validator computes it (planning_core.costs:
    path length, or a kinodynamic family answer's duration)."""
    progress: str = ""
    """An optimizing run's improvements, ``SECONDS:COST ...`` (the progress line's)."""

    @property
    def time_seconds(self) -> float:
        """Planning time, or the process time when the planner printed no stats."""
        if self.planning_seconds is not None and math.isfinite(self.planning_seconds):
            return self.planning_seconds
        return self.process_seconds


FIELD_NAMES = tuple(f.name for f in fields(RunRow))
_ADDED_LATER = frozenset({"path_duration", "first_solution_seconds", "best_cost",
                          "progress"})
"""Columns an older runs.csv may lack (read as their default)."""
_TYPES = {f.name: f.type for f in fields(RunRow)}


def _to_text(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _from_text(name: str, text: str):
    kind = _TYPES[name]
    optional = "None" in kind
    if text == "":
        if optional:
            return None
        if kind.startswith("str"):
            return ""
        raise ValueError(f"column {name!r} is empty")
    if kind.startswith("bool"):
        if text not in ("0", "1"):
            raise ValueError(f"column {name!r}: {text!r} is not 0 or 1")
        return text == "1"
    if kind.startswith("int"):
        return int(text)
    if kind.startswith("float"):
        return float(text)
    return text


def _record(row: RunRow) -> list[str]:
    values = asdict(row)
    return [_to_text(values[name]) for name in FIELD_NAMES]


def write_csv(rows: Iterable[RunRow], path: Path) -> None:
    """The whole file at once: written beside ``path``, then renamed over it."""
    partial = path.with_name(path.name + ".partial")
    with open(partial, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(FIELD_NAMES)
        writer.writerows(_record(row) for row in rows)
    os.replace(partial, path)


class Closing:
    """Closed at the end of a ``with`` block: a subclass defines ``close``."""

    def close(self) -> None:
        raise NotImplementedError

    def __enter__(self):
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()


class CsvAppender(Closing):
    """A CSV written as runs finish: the header at once, then each row as it is
    given, flushed, so that a run stopped at any moment leaves the finished rows."""

    def __init__(self, path: Path):
        self._handle = open(path, "w", newline="")
        self._writer = csv.writer(self._handle, lineterminator="\n")
        self._writer.writerow(FIELD_NAMES)
        self._handle.flush()

    def append(self, row: RunRow) -> None:
        self._writer.writerow(_record(row))
        self._handle.flush()

    def close(self) -> None:
        self._handle.close()


def read_csv(path: Path) -> list[RunRow]:
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader, None)
        if header is None:
            return []
        missing = [name for name in FIELD_NAMES
                   if name not in header and name not in _ADDED_LATER]
        if missing:
            raise ValueError(f"{path}: missing columns {missing}")
        index = {name: header.index(name) for name in FIELD_NAMES if name in header}
        return [RunRow(**{name: _from_text(name, record[index[name]])
                          for name in index}) for record in reader if record]
