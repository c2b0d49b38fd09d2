"""Run rows in OMPL's benchmark log format, one log file per experiment
(a problem with a vehicle), every planner of the run in it.

OMPL's ``ompl_benchmark_statistics.py`` turns the logs into an SQLite
database that Planner Arena (plannerarena.org, or ``plannerarena`` locally)
plots:

    python -m ompl.ompl_benchmark_statistics -d bench.db benchmarks/results/quick/ompl-logs/*.log

The layout follows ompl::tools::Benchmark::saveResultsToStream: a header
(version, experiment, host, date, setup, random seed, limits, enum types),
then per planner its settings, its run properties with SQL types, one line per
run with every value followed by ``"; "``, and for optimizing runs the progress
properties (``time``, ``best cost``) with one line per run of ``"t,c,;"`` samples
(``convergence.progress_samples``: what runs.sqlite's progress table holds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from benchmarks.catalog import label
from benchmarks.convergence import progress_samples
from benchmarks.report import group, planner_order
from benchmarks.rows import RunRow, RunStatus

LIBRARY = "rrt-gridplan"
VERSION = "0.1.0"
# OMPL's PlannerStatus values, in order (the "status" enum of its logs).
STATUS_NAMES = ("Unknown status", "Invalid start", "Invalid goal", "Unrecognized goal type",
                "Timeout", "Approximate solution", "Exact solution", "Crash", "Abort",
                "Infeasible")
STATUS_VALUES = {
    RunStatus.SOLVED.value: 6,
    RunStatus.INVALID.value: 6,     # the planner claimed a solution; "correct solution" = 0
    RunStatus.TIME_LIMIT.value: 4,
    RunStatus.KILLED.value: 4,
    RunStatus.ITERATION_LIMIT.value: 8,
    RunStatus.UNREACHABLE.value: 9,
    RunStatus.NO_SOLUTION.value: 0,
    RunStatus.BAD_INPUT.value: 1,
    RunStatus.CRASHED.value: 7,
}
# (property name, SQL type, value of a row); names as OMPL writes them.
PROPERTIES = (
    ("time", "REAL", lambda r: r.time_seconds),
    ("process time", "REAL", lambda r: r.process_seconds),
    ("solved", "BOOLEAN", lambda r: r.solved),
    ("correct solution", "BOOLEAN", lambda r: r.valid),
    ("status", "ENUM", lambda r: STATUS_VALUES.get(r.status, 0)),
    ("memory", "REAL", lambda r: r.peak_memory_mb),
    ("solution length", "REAL", lambda r: r.path_length),
    ("graph states", "INTEGER", lambda r: r.tree_nodes),
    ("iterations", "INTEGER", lambda r: r.iterations),
    ("seed", "INTEGER", lambda r: r.seed),
)


@dataclass(frozen=True)
class LogHeader:
    hostname: str
    date: str                 # e.g. "2025-11-23T07:40:00"
    cpu_info: str = ""
    total_seconds: float = 0.0
    memory_limit_mb: float = 0.0


def experiment_name(problem: str, vehicle: str) -> str:
    # OMPL's reader takes the last whitespace-separated token of the line.
    return f"{problem}_{vehicle}".replace(" ", "_")


def _value(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float) and not math.isfinite(value):
        return "nan"
    return repr(value) if isinstance(value, float) else str(value)


def format_log(rows: Sequence[RunRow], header: LogHeader) -> str:
    """One experiment's log; all ``rows`` must share a problem and a vehicle."""
    problems = {(r.problem, r.vehicle) for r in rows}
    if len(problems) != 1:
        raise ValueError(f"one experiment per log, got {sorted(problems)}")
    (problem, vehicle), = problems
    by_planner = group(rows, "planner")
    limit = max(r.time_limit for r in rows)
    seeds = sorted({r.seed for r in rows})
    lines = [f"{LIBRARY} version {VERSION}",
             f"Experiment {experiment_name(problem, vehicle)}",
             f"Running on {header.hostname.split()[0] if header.hostname else 'unknown'}",
             f"Starting at {header.date}",
             "<<<|",
             f"problem {problem} ({rows[0].width}x{rows[0].height}), vehicle {vehicle}; "
             f"seeds {', '.join(map(str, seeds))}",
             "|>>>",
             "<<<|",
             header.cpu_info.strip(),
             "|>>>",
             f"{seeds[0]} is the random seed",
             f"{limit!r} seconds per run",
             f"{header.memory_limit_mb!r} MB per run",
             f"{max(len(v) for v in by_planner.values())} runs per planner",
             f"{header.total_seconds!r} seconds spent to collect the data",
             "1 enum types",
             "status|" + "|".join(STATUS_NAMES),
             f"{len(by_planner)} planners"]
    for name in planner_order(key[0] for key in by_planner):
        runs = sorted(by_planner[(name,)], key=lambda r: r.seed)
        lines += [label(name, vehicle),
                  "2 common properties",
                  f"implementation = {runs[0].implementation}",
                  f"harness id = {name}",
                  f"{len(PROPERTIES)} properties for each run"]
        lines += [f"{prop} {kind}" for prop, kind, _ in PROPERTIES]
        lines.append(f"{len(runs)} runs")
        for run in runs:
            lines.append("".join(f"{_value(get(run))}; " for _, _, get in PROPERTIES))
        if any(run.progress for run in runs):
            lines += ["2 progress properties for each run", "time REAL", "best cost REAL",
                      f"{len(runs)} runs"]
            lines += ["".join(f"{t!r},{c!r},;" for t, c in progress_samples(run))
                      for run in runs]
        lines.append(".")
    return "\n".join(lines) + "\n"


def write_logs(rows: Sequence[RunRow], directory: Path, header: LogHeader) -> list[Path]:
    """One ``<problem>_<vehicle>.log`` per experiment; returns the paths."""
    directory.mkdir(parents=True, exist_ok=True)
    paths = []
    for (problem, vehicle), runs in sorted(group(rows, "problem", "vehicle").items()):
        path = directory / f"{experiment_name(problem, vehicle)}.log"
        path.write_text(format_log(runs, header))
        paths.append(path)
    return paths
