"""Summaries of run rows and the Markdown report.

Conventions (said again in the report's header):

* Time is planning time (the planner's own clock) unless a column says
  "process" (the whole planner process, start-up and output included).
* Time statistics are over all runs, an unsolved run counting the time it
  used (about its limit): OMPL's benchmark convention. Path length is over
  solved runs only; tree nodes over all runs that reported them.
* "vs OMPL" is the ratio of the median times, ours over OMPL RRT's
  (geometric for the point vehicle, control for the spaceships), on the same
  problems and seeds: below 1 means faster than OMPL.
* Targets are the data of ``benchmarks/targets.py``; a target this run has no
  runs to judge is left out of the table, and one measured with fewer than
  ``MIN_RUNS`` runs of a planner on a problem is listed as not judged.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass
from typing import Iterable, Mapping, Sequence

from tabulate import tabulate

from benchmarks.catalog import label, reference_planner
from benchmarks.rows import RunRow
from benchmarks.targets import (ISSUE_5_TARGETS, TARGETS, FirstSolutionVsPlanner,
                                PathLengthVsPlanner, PlannerVsPlanner, SpeedVsReference,
                                SuccessWithin, Target)
from planning_core.vehicles import Vehicle

MIN_RUNS = 5
"""Runs (seeds) of each planner on each problem a target needs before the report judges it."""
VEHICLE_ORDER = ("point", "spaceship", "left", "dubins")
VEHICLE_TITLES = {"point": "Point vehicle", "spaceship": "Spaceship (-grad)",
                  "left": "Left-only spaceship (-grad -left)",
                  "dubins": "Dubins car (-dubins, radius 0.5)"}


@dataclass(frozen=True)
class Spread:
    """Mean, standard deviation, median and 90th percentile of some values."""

    count: int
    mean: float
    std: float
    median: float
    p90: float

    @classmethod
    def of(cls, values: Iterable[float]) -> "Spread":
        data = sorted(v for v in values if v is not None and math.isfinite(v))
        if not data:
            nan = math.nan
            return cls(0, nan, nan, nan, nan)
        std = statistics.stdev(data) if len(data) > 1 else 0.0
        return cls(len(data), statistics.fmean(data), std, statistics.median(data),
                   percentile(data, 90))


def percentile(sorted_values: Sequence[float], percent: float) -> float:
    """Linear interpolation between closest ranks (numpy's default)."""
    if not sorted_values:
        return math.nan
    position = (len(sorted_values) - 1) * percent / 100.0
    low = math.floor(position)
    high = min(low + 1, len(sorted_values) - 1)
    return sorted_values[low] + (sorted_values[high] - sorted_values[low]) * (position - low)


@dataclass(frozen=True)
class PlannerSummary:
    planner: str
    implementation: str
    runs: int
    solved: int
    time: Spread          # planning time, all runs
    process: Spread       # whole process, all runs
    path_length: Spread   # solved runs
    tree_nodes: Spread
    peak_memory_mb: Spread

    @property
    def success_percent(self) -> float:
        return 100.0 * self.solved / self.runs if self.runs else math.nan


def summarize(rows: Sequence[RunRow]) -> PlannerSummary:
    first = rows[0]
    return PlannerSummary(
        first.planner, first.implementation, len(rows), sum(r.solved for r in rows),
        Spread.of(r.time_seconds for r in rows),
        Spread.of(r.process_seconds for r in rows),
        Spread.of(r.path_length for r in rows if r.solved),
        Spread.of(float(r.tree_nodes) for r in rows if r.tree_nodes is not None),
        Spread.of(r.peak_memory_mb for r in rows if r.peak_memory_mb is not None))


def group(rows: Iterable[RunRow], *keys: str) -> dict[tuple, list[RunRow]]:
    groups: dict[tuple, list[RunRow]] = {}
    for row in rows:
        groups.setdefault(tuple(getattr(row, key) for key in keys), []).append(row)
    return groups


def planner_order(planners: Iterable[str]) -> list[str]:
    """Ours first, then OMPL's, each alphabetically."""
    return sorted(set(planners), key=lambda name: (name.startswith("ompl-"), name))


def median_ratio(ours: Sequence[RunRow], reference: Sequence[RunRow],
                 process: bool = False) -> float:
    """Median time of ``ours`` over the median of ``reference`` (same problems/seeds)."""
    pick = (lambda r: r.process_seconds) if process else (lambda r: r.time_seconds)
    matched = {(r.problem, r.seed) for r in reference}
    mine = [pick(r) for r in ours if (r.problem, r.seed) in matched]
    theirs = [pick(r) for r in reference]
    if not mine or not theirs:
        return math.nan
    denominator = statistics.median(theirs)
    return statistics.median(mine) / denominator if denominator > 0 else math.nan


def first_solution_median(runs: Sequence[RunRow]) -> float:
    """Median time to the first solution over all runs, an unsolved run counting its
    time limit (as the other tables count an unsolved run's time)."""
    return statistics.median(
        (r.first_solution_seconds if r.solved and r.first_solution_seconds is not None
         else r.time_limit) for r in runs) if runs else math.nan


def _fmt(value: float | None, digits: int = 3) -> str:
    """``digits`` significant digits; thousands written out with separators."""
    if value is None or not math.isfinite(value):
        return "–"
    if abs(value) >= 10 ** digits:
        return f"{value:,.0f}"
    return f"{value:.{digits}g}"


def _pm(spread: Spread, digits: int = 3) -> str:
    """Mean ± standard deviation; one value alone (one run has no spread)."""
    if spread.count == 0:
        return "–"
    if spread.count == 1:
        return _fmt(spread.mean, digits)
    return f"{_fmt(spread.mean, digits)} ± {_fmt(spread.std, digits)}"


def _ratio(value: float) -> str:
    return "–" if not math.isfinite(value) else f"{value:.2f}×"


def markdown_table(header: Sequence[str], body: Iterable[Sequence[str]],
                   align: str) -> list[str]:
    """A Markdown (pipe) table of the cells as given, one letter of ``align`` per
    column: ``l`` left, ``r`` right, ``c`` centre."""
    names = {"l": "left", "r": "right", "c": "center"}
    text = tabulate([list(cells) for cells in body], headers=list(header), tablefmt="pipe",
                    colalign=[names[a] for a in align], disable_numparse=True)
    return text.splitlines()


TARGETS_NOTE = (f"A target is judged only on at least {MIN_RUNS} runs (seeds) of each planner "
                "on each problem it compares; with fewer it is listed as not judged.")

SUMMARY_HEADER = ("Planner", "Success %", "Time (s)", "Path length", "Tree nodes",
                  "Median time (s)", "p90 time (s)", "Process median (s)",
                  "vs OMPL RRT, planning", "vs OMPL RRT, process")


def summary_table(rows: Sequence[RunRow], vehicle: str) -> list[str]:
    """The per-vehicle table: one line per planner, mean ± std, median, p90, ratios."""
    by_planner = group((r for r in rows if r.vehicle == vehicle), "planner")
    reference = by_planner.get((reference_planner(Vehicle(vehicle)),), [])
    body = []
    for name in planner_order(key[0] for key in by_planner):
        runs = by_planner[(name,)]
        s = summarize(runs)
        body.append((label(name, vehicle), f"{s.success_percent:.0f}", _pm(s.time),
                     _pm(s.path_length, 4), _pm(s.tree_nodes, 4), _fmt(s.time.median),
                     _fmt(s.time.p90), _fmt(s.process.median),
                     _ratio(median_ratio(runs, reference)),
                     _ratio(median_ratio(runs, reference, process=True))))
    return markdown_table(SUMMARY_HEADER, body, "l" + "r" * 9)


PROBLEM_HEADER = ("Problem", "Planner", "Success %", "Time (s)", "Median", "p90",
                  "Process median (s)", "Path length", "Tree nodes", "Peak MB",
                  "vs OMPL, planning", "vs OMPL, process")


def problem_order(rows: Iterable[RunRow]) -> list[str]:
    sizes = {}
    for row in rows:
        sizes[row.problem] = row.width * row.height
    return sorted(sizes, key=lambda name: (sizes[name], name))


def problem_table(rows: Sequence[RunRow], vehicle: str) -> list[str]:
    mine = [r for r in rows if r.vehicle == vehicle]
    by_key = group(mine, "problem", "planner")
    reference_id = reference_planner(Vehicle(vehicle))
    body = []
    for problem in problem_order(mine):
        reference = by_key.get((problem, reference_id), [])
        for name in planner_order(p for (q, p) in by_key if q == problem):
            runs = by_key[(problem, name)]
            s = summarize(runs)
            body.append((problem, label(name, vehicle), f"{s.success_percent:.0f}",
                         _pm(s.time), _fmt(s.time.median), _fmt(s.time.p90),
                         _fmt(s.process.median), _pm(s.path_length, 4),
                         _fmt(s.tree_nodes.median, 4), _fmt(s.peak_memory_mb.median),
                         _ratio(median_ratio(runs, reference)),
                         _ratio(median_ratio(runs, reference, process=True))))
    return markdown_table(PROBLEM_HEADER, body, "ll" + "r" * 10)


@dataclass(frozen=True)
class TargetCheck:
    target: str
    met: bool | None      # None: this run's data cannot decide it (a zero median)
    detail: str
    runs: int = 0
    """The fewest runs of one planner on one problem among those judged."""


def fewest_runs(*runs: Sequence[RunRow]) -> int:
    """The fewest runs any planner had on any problem in ``runs`` (0 if none)."""
    counts = [len(same) for rows in runs for same in group(rows, "planner", "problem").values()]
    return min(counts, default=0)


def not_judged(runs: int, min_runs: int = MIN_RUNS) -> str:
    """What the targets table says of a target measured with too few runs."""
    return f"not judged: {runs} run{'s' if runs != 1 else ''} (need {min_runs})"


def check_targets(rows: Sequence[RunRow], shortest: Mapping[str, float] | None = None,
                  targets: Iterable[Target] = TARGETS) -> list[TargetCheck]:
    """``targets`` (benchmarks/targets.py), judged on this run's medians, in order;
    those the run has no runs to judge are left out.

    ``shortest``: the point vehicle's shortest path length per problem, when known.
    """
    checks: list[TargetCheck] = []
    for target in targets:
        checks.extend(_EVALUATORS[type(target)](target, rows, shortest))
    return checks


def planner_targets(rows: Sequence[RunRow],
                    shortest: Mapping[str, float] | None = None) -> list[TargetCheck]:
    """Issue 5's targets, each against our own RRT in the same run: on the
    spaceships, KPIECE1 or RG-RRT at least 2x faster (median planning time) on
    the mazes and on the narrow passages; on the point vehicle, PRM* paths at
    least 20% shorter and RRT-Connect faster on the mazes.

    With ``shortest`` (per problem), the PRM* line also says what the shortest
    paths themselves would score against RRT's: no planner can do better."""
    return check_targets(rows, shortest, ISSUE_5_TARGETS)


def _side(row: RunRow) -> int:
    return max(row.width, row.height)


def _our_planners(rows: Sequence[RunRow], vehicle: str) -> list[str]:
    return sorted({r.planner for r in rows
                   if r.implementation == "ours" and r.vehicle == vehicle})


def _runs(rows: Sequence[RunRow], vehicle: str, planner: str, family: str | None = None,
          min_size: int = 1, max_size: float = math.inf) -> list[RunRow]:
    return [r for r in rows if r.vehicle == vehicle and r.planner == planner
            and (family is None or r.family == family) and min_size <= _side(r) <= max_size]


def _ours(rows: Sequence[RunRow], vehicle: str, planner: str,
          family: str | None = None) -> list[RunRow]:
    return [r for r in _runs(rows, vehicle, planner, family) if r.implementation == "ours"]


def _bound(factor: float, whose: str, strict: bool = False) -> str:
    """The bound in words: at most OMPL RRT's, at most 0.5× our rrt's, below our rrt's."""
    return (("below" if strict else "at most") + ("" if factor == 1 else f" {factor:g}×")
            + f" {whose}")


def _solved_within(rows: Sequence[RunRow], seconds: float) -> tuple[int, int]:
    ok = sum(1 for r in rows if r.solved and r.time_seconds <= seconds)
    return ok, len(rows)


def _judge_success(target: SuccessWithin, rows: Sequence[RunRow],
                   shortest: Mapping[str, float] | None) -> list[TargetCheck]:
    """A row per planner of ours that ran maps as large as the target's."""
    checks = []
    for planner in _our_planners(rows, target.vehicle):
        runs = _runs(rows, target.vehicle, planner, max_size=target.max_size)
        if not any(_side(r) == target.max_size for r in runs):
            continue
        misses = []
        for (problem,), group_rows in sorted(group(runs, "problem").items()):
            ok, total = _solved_within(group_rows, target.seconds)
            if ok < total:
                misses.append(f"{problem} {ok}/{total}")
        ok, total = _solved_within(runs, target.seconds)
        checks.append(TargetCheck(
            f"{target.vehicle}: {planner} solves 100% within {target.seconds:g} s up to "
            f"{target.max_size}x{target.max_size}", not misses,
            f"{ok}/{total} runs" + (f"; short on {', '.join(misses)}" if misses else ""),
            fewest_runs(runs)))
    return checks


def _judge_speed(target: SpeedVsReference, rows: Sequence[RunRow],
                 shortest: Mapping[str, float] | None) -> list[TargetCheck]:
    """A row per planner of ours that ran a problem and seed OMPL's RRT ran."""
    def judged(planner: str) -> list[RunRow]:
        return _runs(rows, target.vehicle, planner, target.family, min_size=target.min_size)

    reference = judged(reference_planner(Vehicle(target.vehicle)))
    matched = {(r.problem, r.seed) for r in reference}
    what = "whole-process" if target.process else "planning"
    where = (f"on {target.family} problems" if target.family else
             f"from {target.min_size}x{target.min_size} up" if target.min_size > 1
             else "on all problems")
    bound = _bound(target.factor, "OMPL RRT's")
    checks = []
    for planner in _our_planners(rows, target.vehicle):
        runs = judged(planner)
        if not any((r.problem, r.seed) in matched for r in runs):
            continue
        ratio = median_ratio(runs, reference, process=target.process)
        checks.append(TargetCheck(
            f"{target.vehicle}: {planner} median {what} time {where} {bound}",
            ratio <= target.factor if math.isfinite(ratio) else None,
            f"ratio {_ratio(ratio)}", fewest_runs(runs, reference)))
    return checks


def _judge_planner_vs_planner(target: PlannerVsPlanner, rows: Sequence[RunRow],
                              shortest: Mapping[str, float] | None) -> list[TargetCheck]:
    """One row, if the baseline and one of the planners share a problem and seed."""
    baseline = _ours(rows, target.vehicle, target.baseline, target.family)
    compared = {planner: _ours(rows, target.vehicle, planner, target.family)
                for planner in target.planners}
    ratios = {planner: median_ratio(runs, baseline) for planner, runs in compared.items()}
    ratios = {planner: ratio for planner, ratio in ratios.items() if math.isfinite(ratio)}
    if not baseline or not ratios:
        return []
    best = min(ratios.values())
    if len(target.planners) == 1:
        detail = f"ratio {_ratio(best)}"
    else:
        detail = ", ".join(f"{planner} {_ratio(ratio)}" for planner, ratio in ratios.items())
    bound = _bound(target.factor, f"our {target.baseline}'s", target.strict)
    return [TargetCheck(
        f"{target.vehicle}: {' or '.join(target.planners)} median planning time on "
        f"{target.family} problems {bound}",
        best < target.factor if target.strict else best <= target.factor, detail,
        fewest_runs(baseline, *(compared[planner] for planner in ratios)))]


def _judge_path_length(target: PathLengthVsPlanner, rows: Sequence[RunRow],
                       shortest: Mapping[str, float] | None) -> list[TargetCheck]:
    """One row, if both planners solved a problem."""
    baseline = _ours(rows, target.vehicle, target.baseline)
    ours = _ours(rows, target.vehicle, target.planner)
    ratios = path_length_ratios(ours, baseline)
    if not ratios:
        return []
    shorter = f"{(1 - target.factor) * 100:g}% shorter"
    mean_ratio = statistics.fmean(ratios.values())
    detail = (f"mean ratio {_ratio(mean_ratio)}; {shorter} on "
              f"{_count_within(ratios.values(), target.factor)}/{len(ratios)} problems")
    if target.vehicle == "point" and shortest and all(problem in shortest for problem in ratios):
        baseline_lengths = _median_path_lengths(baseline)
        best = [shortest[problem] / baseline_lengths[problem] for problem in ratios]
        detail += (f"; the shortest paths would score {_ratio(statistics.fmean(best))}, "
                   f"{shorter} on {_count_within(best, target.factor)}/{len(best)}")
    return [TargetCheck(
        f"{target.vehicle}: {target.planner} paths at least {shorter} than our "
        f"{target.baseline}'s (mean over problems of the median-length ratio)",
        mean_ratio <= target.factor, detail, fewest_runs(ours, baseline))]


def _judge_first_solution(target: FirstSolutionVsPlanner, rows: Sequence[RunRow],
                          shortest: Mapping[str, float] | None) -> list[TargetCheck]:
    """A row per problem of the target's systems that both planners ran with a same seed."""
    judged = [r for r in rows if r.vehicle in target.systems and r.implementation == "ours"]
    by_key = group(judged, "problem", "planner")
    checks = []
    for problem in sorted({r.problem for r in judged}):
        mine = by_key.get((problem, target.planner), [])
        theirs = by_key.get((problem, target.baseline), [])
        seeds = {r.seed for r in mine} & {r.seed for r in theirs}
        mine = [r for r in mine if r.seed in seeds]
        theirs = [r for r in theirs if r.seed in seeds]
        if not seeds:
            continue
        ours, base = first_solution_median(mine), first_solution_median(theirs)
        ratio = ours / base if base > 0 else math.nan
        whose = f"our {target.baseline}'s"
        checks.append(TargetCheck(
            f"{problem}: {target.planner} median time to the first solution "
            f"{_bound(target.factor, whose)}",
            ratio <= target.factor if math.isfinite(ratio) else None,
            f"{_ratio(ratio)} ({_fmt(ours * 1e3)} ms over {_fmt(base * 1e3)} ms)",
            fewest_runs(mine, theirs)))
    return checks


def _count_within(ratios: Iterable[float], factor: float) -> int:
    return sum(1 for ratio in ratios if ratio <= factor)


_EVALUATORS = {SuccessWithin: _judge_success, SpeedVsReference: _judge_speed,
               PlannerVsPlanner: _judge_planner_vs_planner,
               PathLengthVsPlanner: _judge_path_length,
               FirstSolutionVsPlanner: _judge_first_solution}


def path_length_ratios(ours: Sequence[RunRow], reference: Sequence[RunRow]) -> dict[str, float]:
    """Per problem solved by both: median path length of ``ours`` over ``reference``'s."""
    mine, theirs = _median_path_lengths(ours), _median_path_lengths(reference)
    return {problem: length / theirs[problem] for problem, length in mine.items()
            if theirs.get(problem, 0.0) > 0.0}


def _median_path_lengths(runs: Sequence[RunRow]) -> dict[str, float]:
    """Per problem: the median path length of the solved runs."""
    lengths = group([r for r in runs if r.solved and r.path_length is not None], "problem")
    return {problem: statistics.median(r.path_length for r in solved)
            for (problem,), solved in lengths.items()}


def targets_table(rows: Sequence[RunRow], shortest: Mapping[str, float] | None = None,
                  min_runs: int = MIN_RUNS) -> list[str]:
    """The targets this run has runs for; those with fewer than ``min_runs`` runs of a
    planner on a problem are listed as not judged."""
    marks = {True: "yes", False: "**no**", None: "n/a"}
    body = [(check.target, marks[check.met], check.detail) if check.runs >= min_runs
            else (check.target, "–", not_judged(check.runs, min_runs))
            for check in check_targets(rows, shortest)]
    if not body:
        return ["No target has runs to judge in this run (OMPL's RRT or the planners left "
                "out, or maps too small)."]
    return markdown_table(("Target", "Met", "Measured"), body, "lcl")


def path_quality_table(rows: Sequence[RunRow], shortest: Mapping[str, float]) -> list[str]:
    """The point vehicle's path lengths over the shortest possible, per problem:
    one column per planner (its median over solved runs), and the mean row."""
    point = [r for r in rows if r.vehicle == "point" and r.problem in shortest]
    names = planner_order(r.planner for r in point)
    medians = {name: _median_path_lengths([r for r in point if r.planner == name])
               for name in names}
    body = []
    for problem in problem_order(point):
        cells = [_fmt(medians[name][problem] / shortest[problem], 4)
                 if problem in medians[name] else "–" for name in names]
        body.append((problem, _fmt(shortest[problem], 4), *cells))
    means = [_fmt(statistics.fmean(length / shortest[problem]
                                   for problem, length in medians[name].items()), 4)
             if medians[name] else "–" for name in names]
    body.append(("mean over problems", "", *means))
    header = ("Problem", "Shortest", *(label(name, "point") for name in names))
    return markdown_table(header, body, "lr" + "r" * len(names))


ACCEPTANCE_NOTE = ("Every answer checked by the validator's own checks (the Dubins car's "
                   "with its turning check); a rejected answer counts as unsolved and in "
                   "\"Invalid\". First solution: the planner's clock (with -optimize, when "
                   "its first answer came).")


def problem_group(row: RunRow) -> str:
    """The course maps, the suite up to 200 cells a side, or the 500-cell maps."""
    if row.problem.startswith("course-"):
        return "course"
    return "suite 500" if max(row.width, row.height) >= 500 else "suite 10-200"


def acceptance_table(rows: Sequence[RunRow]) -> list[str]:
    """Solved and validated out of the runs per vehicle, planner and problem group, the
    invalid answers counted apart and the problems below 100 % named."""
    groups: dict[tuple, list[RunRow]] = {}
    for row in rows:
        groups.setdefault((row.vehicle, row.planner, problem_group(row)), []).append(row)
    body = []
    for (vehicle, planner, kind), runs in sorted(groups.items()):
        by_problem = group(runs, "problem")
        missed = ", ".join(f"{p} {sum(r.solved for r in mine)}/{len(mine)}"
                           for (p,), mine in sorted(by_problem.items())
                           if not all(r.solved for r in mine))
        firsts = [r.first_solution_seconds for r in runs if r.solved
                  and r.first_solution_seconds is not None]
        body.append((vehicle, planner, kind, str(len(by_problem)),
                     f"{sum(r.solved for r in runs)}/{len(runs)}",
                     str(sum(r.status == "invalid" for r in runs)),
                     _fmt(max(firsts) if firsts else None), missed or "-"))
    return markdown_table(("Vehicle", "Planner", "Problems", "Maps", "Solved and valid",
                           "Invalid", "Slowest first solution (s)", "Below 100 %"),
                          body, "lllrrrrl")


def failures_table(rows: Sequence[RunRow], limit: int = 50) -> list[str]:
    """The first ``limit`` runs that failed for another reason than a limit."""
    failed = [r for r in rows if r.status in ("invalid", "crashed", "killed", "bad_input")]
    body = [(r.problem, r.vehicle, r.planner, str(r.seed), r.status,
             r.failure.replace("|", "/")[:120]) for r in failed[:limit]]
    return markdown_table(("Problem", "Vehicle", "Planner", "Seed", "Status", "Detail"),
                          body, "lllrll") if body else []


def markdown_report(rows: Sequence[RunRow], meta: dict[str, str], per_problem: bool = True,
                    shortest: Mapping[str, float] | None = None,
                    acceptance: bool = False) -> str:
    """The whole report: header, targets, a summary table per vehicle, the point
    vehicle's path quality (with ``shortest``, the shortest path length per
    problem), per-problem tables."""
    out = [f"# Benchmark report: {meta.get('preset', 'custom')} run, {meta.get('date', '')}",
           ""]
    for key, value in meta.items():
        if key not in ("preset", "date"):
            out.append(f"- {key}: {value}")
    out += ["",
            "Time = planning time on the planner's own clock, mean ± std over all runs "
            "(an unsolved run counts the time it used); path length over solved runs; "
            "\"vs OMPL RRT\" = our median time / OMPL RRT's median time on the same "
            "problems and seeds (below 1 is faster); \"process\" = wall time of the whole "
            "planner process. A solution the validator rejects counts as unsolved.", ""]
    vehicles = [v for v in VEHICLE_ORDER if any(r.vehicle == v for r in rows)]
    if acceptance:
        out += ["## Solved and validated", "", ACCEPTANCE_NOTE, ""] + acceptance_table(rows) + [""]
    out += ["## Targets", "", TARGETS_NOTE, ""] + targets_table(rows, shortest) + [""]
    for vehicle in vehicles:
        problems = {r.problem for r in rows if r.vehicle == vehicle}
        seeds = {r.seed for r in rows if r.vehicle == vehicle}
        limits = sorted({r.time_limit for r in rows if r.vehicle == vehicle})
        out += [f"## {VEHICLE_TITLES[vehicle]}", "",
                f"{len(problems)} problems x {len(seeds)} seeds, time limit "
                f"{', '.join(f'{t:g}' for t in limits)} s.", ""]
        out += summary_table(rows, vehicle) + [""]
        if vehicle == "point" and shortest:
            out += ["Median path length over the shortest path (benchmarks/shortest_path.py: "
                    "exact, through the corners of the blocked cells), per problem; 1 is "
                    "optimal.", ""] + path_quality_table(rows, shortest) + [""]
    failures = failures_table(rows)
    if failures:
        out += ["## Runs that failed for other reasons than a limit", ""] + failures + [""]
    if per_problem:
        for vehicle in vehicles:
            out += [f"## Per problem: {VEHICLE_TITLES[vehicle]}", ""]
            out += problem_table(rows, vehicle) + [""]
    return "\n".join(out)
