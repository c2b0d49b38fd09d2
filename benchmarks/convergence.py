"""Cost against time for optimizing runs, and the ``optimal*`` presets' report.

A run's cost at time t is the last improvement of its progress line at or before t
(:func:`cost_at`); a run with no solution by then costs infinity, so the median over
all runs is finite once more than half of them have solved, and a planner that
solves less often cannot look better for it. The band around a median is its 95%
confidence interval by order statistics (:func:`median_interval`: distribution-free,
the ranks of a binomial(n, 1/2) around n/2).
"""

from __future__ import annotations

import math
import statistics
from typing import Mapping, Sequence

from benchmarks.catalog import OMPL_CPP_PREFIX, OMPL_PREFIX, label
from benchmarks.harness import parse_progress
from benchmarks.report import (_fmt, _ratio, first_solution_median, group, markdown_table,
                               planner_order, problem_order)
from benchmarks.rows import RunRow

PROGRESS_INTERVAL = 0.05
"""Seconds between two samples of a run's best cost (OMPL's Benchmark's default
``timeBetweenUpdates``)."""
SHORTEST_SYSTEMS = ("point", "arm2")
"""The systems whose shortest paths the benchmarks compute: the point vehicle's
(``benchmarks/shortest_path.py``) and arm2's (``benchmarks/arm2_shortest_path.py``)."""
Z_95 = 1.959963984540054
"""The standard normal's 97.5th percentile: a two-sided 95% interval."""


def improvements(row: RunRow) -> tuple[tuple[float, float], ...]:
    """A solved run's (seconds, cost) improvements: its progress line's, or (a planner
    that stops at its first solution) its first solution's time and its cost."""
    if not row.solved:
        return ()
    found = progress_pairs(row)
    if found:
        return found
    first = row.first_solution_seconds if row.first_solution_seconds is not None \
        else row.time_seconds
    return ((first, row.best_cost),) if row.best_cost is not None else ()


def progress_pairs(row: RunRow) -> tuple[tuple[float, float], ...]:
    """The (seconds, cost) pairs of the row's ``progress`` field."""
    return parse_progress(f"x progress: {row.progress}")


def progress_samples(row: RunRow, interval: float = PROGRESS_INTERVAL
                     ) -> list[tuple[float, float]]:
    """(seconds, best cost) of an optimizing run: every improvement at its instant, and
    the best cost so far every ``interval`` seconds from the first improvement to the
    run's end (its planning time, at most its time limit: times are the planner's
    word), as OMPL's Benchmark samples progress."""
    improvements = progress_pairs(row)
    if not improvements:
        return []
    samples = dict(improvements)
    end = min(max(row.time_seconds, improvements[-1][0]), row.time_limit)
    index, tick = 0, math.ceil(improvements[0][0] / interval)
    while (at := round(tick * interval, 9)) <= end:  # 0.15, not 0.15000000000000002
        while index + 1 < len(improvements) and improvements[index + 1][0] <= at:
            index += 1
        samples.setdefault(at, improvements[index][1])
        tick += 1
    return sorted(samples.items())


def cost_at(row: RunRow, seconds: float) -> float:
    """The run's best cost at ``seconds`` of planning: its last improvement at or before
    then; infinity before its first solution or when it never solved."""
    best = math.inf
    for when, cost in improvements(row):
        if when > seconds:
            break
        best = cost
    return best


def median_interval(values: Sequence[float], z: float = Z_95) -> tuple[float, float, float]:
    """(median, low, high): the median and its confidence interval by order statistics,
    the ``n/2 - z sqrt(n)/2``-th and ``1 + n/2 + z sqrt(n)/2``-th smallest values (ranks
    rounded to the nearest, 1-based, clamped to 1..n: ranks 6 and 15 of 20, as the exact
    binomial interval). Infinite values are allowed."""
    data = sorted(values)
    n = len(data)
    if n == 0:
        return math.nan, math.nan, math.nan
    half = z * math.sqrt(n) / 2
    low = min(n, max(1, round(n / 2 - half)))
    high = min(n, max(1, round(1 + n / 2 + half)))
    return statistics.median(data), data[low - 1], data[high - 1]


def counterpart(planner: str, prefix: str = OMPL_PREFIX) -> str | None:
    """OMPL's planner our optimizing planner is compared with (``prefix`` + its id:
    ``ompl-`` the Python bindings' peer, ``ompl-cpp-`` the C++ one)."""
    return None if planner.startswith(OMPL_PREFIX) else prefix + planner


def convergence_table(rows: Sequence[RunRow], checkpoints: Sequence[float],
                      shortest: Mapping[str, float] | None = None) -> list[str]:
    """Per problem and planner: runs solved, median time to the first solution, the
    median cost at each checkpoint (with its 95% interval), ours over OMPL's (Python
    bindings; and, when the rows have OMPL in C++, over C++'s); with ``shortest`` (the
    shortest path per problem of the point vehicle and arm2: the systems
    :data:`SHORTEST_SYSTEMS` names), the median cost at the last checkpoint over it; when
    an answer cut a blocked cell's corner, how many of each planner's did."""
    times = [t for t in checkpoints if any(t <= r.time_limit for r in rows)]
    cuts = any(r.corner_cuts for r in rows)
    shortest = shortest or {}
    peers = [(OMPL_PREFIX, "OMPL")]
    if any(r.planner.startswith(OMPL_CPP_PREFIX) for r in rows):
        peers.append((OMPL_CPP_PREFIX, "OMPL C++"))
    header = ["System", "Problem", "Planner", "Solved", "First solution (s)",
              *(f"Cost at {t:g} s" for t in times),
              *(column for _, name in peers for column in
                (*(f"vs {name} at {t:g} s" for t in times), f"First solution vs {name}")),
              *([f"vs shortest at {times[-1]:g} s"] if shortest and times else []),
              *(["Answers cutting corners"] if cuts else [])]
    by_key = group(rows, "vehicle", "problem", "planner")
    body = []
    for vehicle, problem in _problems(rows):
        for planner in planner_order(p for (v, q, p) in by_key if (v, q) == (vehicle, problem)):
            runs = by_key[(vehicle, problem, planner)]
            medians = [median_interval([cost_at(r, t) for r in runs]) for t in times]
            body.append((vehicle, problem, label(planner, vehicle),
                         f"{sum(r.solved for r in runs)}/{len(runs)}",
                         _fmt(first_solution_median(runs)),
                         *(_with_interval(m) for m in medians),
                         *(cell for prefix, _ in peers for cell in _against(
                             runs, medians, times,
                             by_key.get((vehicle, problem, counterpart(planner, prefix) or ""),
                                        []))),
                         *([_ratio(_over(medians[-1][0], shortest.get(problem, math.nan)))
                            if vehicle in SHORTEST_SYSTEMS else "–"] if shortest and times
                           else []),
                         *([f"{sum(r.corner_cuts > 0 for r in runs)}/{len(runs)}"] if cuts
                           else [])))
    return markdown_table(header, body, "lll" + "r" * (len(header) - 3))


def _against(runs: Sequence[RunRow], medians, times: Sequence[float],
             theirs: Sequence[RunRow]) -> list[str]:
    """Our median cost at each checkpoint over theirs, and our median first solution
    time over theirs ("–" without their runs)."""
    if not theirs:
        return [_ratio(math.nan)] * (len(times) + 1)
    return [*(_ratio(_over(m[0], median_interval([cost_at(r, t) for r in theirs])[0]))
              for m, t in zip(medians, times)),
            _ratio(_over(first_solution_median(runs), first_solution_median(theirs)))]


def _problems(rows: Sequence[RunRow]) -> list[tuple[str, str]]:
    seen = {(r.vehicle, r.problem) for r in rows}
    return [(v, p) for v in sorted({v for v, _ in seen}) for p in problem_order(rows)
            if (v, p) in seen]


def _over(ours: float, theirs: float) -> float:
    return ours / theirs if math.isfinite(ours) and math.isfinite(theirs) and theirs > 0 \
        else math.nan


def _with_interval(found: tuple[float, float, float]) -> str:
    median, low, high = found
    if not math.isfinite(median):
        return "–"
    return f"{_fmt(median)} [{_fmt(low)}, {_fmt(high) if math.isfinite(high) else '∞'}]"


def markdown_report(rows: Sequence[RunRow], meta: Mapping[str, str],
                    checkpoints: Sequence[float],
                    shortest: Mapping[str, float] | None = None) -> str:
    """The ``optimal*`` presets' report: the run's facts, then the convergence table
    (with ``shortest``, the median cost over the shortest path, point vehicle and arm2)."""
    out = [f"# Benchmark report: {meta.get('preset', 'optimal')} run, {meta.get('date', '')}",
           ""]
    out += [f"- {key}: {value}" for key, value in meta.items() if key not in ("preset", "date")]
    out += ["", "Cost: path length (point, ships, arm2, rigid2) or duration (the family's "
            "kinodynamic systems), as docs/optimal-planning.md defines it. \"Cost at t\" = "
            "the median over all runs of each run's best cost at t s of planning (an "
            "unsolved run counts as infinite, so a median exists once over half have "
            "solved), with its 95% confidence interval by order statistics in brackets. "
            "\"vs OMPL\" = our median over OMPL's same planner's through its Python bindings, "
            "\"vs OMPL C++\" over OMPL's in C++ (below 1 is better). "
            "First solution: median over all runs, an unsolved run counting its limit. "
            "\"vs shortest\" (point vehicle, arm2) = the median cost at the last checkpoint "
            "over the problem's shortest path to the goal point or configuration "
            "(benchmarks/shortest_path.py: exact; benchmarks/arm2_shortest_path.py: a valid "
            "path refined until a round shortens it by under 0.1%, an upper bound); a path "
            "may end anywhere within the goal's tolerance (the point's 0.1), so a ratio a "
            "little under 1 is possible. \"Answers cutting corners\" (when any did): the "
            "runs whose final answer has a segment that cuts a blocked cell's corner between "
            "the course's 0.05 samples (the validator's warning; a failure with -strict): "
            "such a path may be shorter than any exactly free one.",
            "", "## Cost against time", ""]
    out += convergence_table(rows, checkpoints, shortest) + [""]
    return "\n".join(out)
