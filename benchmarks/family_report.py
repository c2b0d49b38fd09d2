"""The family presets' Markdown report: SPEC 5.6's layout (Success % | Time (s) | Path
length | Tree nodes, mean ± std) per table, path length both as control duration
(seconds, OMPL's ``PathControl::length()``) and in the problem's metric, the ratio of
medians against OMPL's RRT (control RRT for kinodynamic systems, geometric RRT for
arm2 and rigid2) on the same problem and seeds, the targets (benchmarks/targets.py), and
the solved-and-validated share per planner and problem (the seed sweep's table).

Conventions as in ``report.py``: time over all runs (an unsolved run counts the time
it used), path length and control duration over solved runs.
"""

from __future__ import annotations

import math
import statistics
from typing import Sequence

from benchmarks.catalog import GEOMETRIC_SYSTEMS, OMPL_PREFIX, label
from benchmarks.family import FamilyPreset, table_planners, table_problems
from benchmarks.report import (MIN_RUNS, TARGETS_NOTE, Spread, _fmt, _pm, _ratio,
                               check_targets, failures_table, fewest_runs, group,
                               markdown_table, median_ratio, not_judged, summarize)
from benchmarks.rows import RunRow
from benchmarks.targets import FAMILY_TARGETS

REFERENCE = OMPL_PREFIX + "rrt"
NOT_AVAILABLE = "not available"
TABLE_HEADER = ("Planner", "Success %", "Time (s)", "Path length (s)", "Path length (metric)",
                "Tree nodes", "Median time (s)", "vs OMPL RRT (median)")
PENDULUM_PUBLISHED_SECONDS = 0.0123
"""SPEC 5.6: OMPL's RRT in C++ on the pendulum at torque 3, mean time."""
SPEED_FACTOR = 0.5
"""Issues 14 and 15: our median planning time at most this times OMPL RRT's."""
PENDULUM_FACTOR = 2.0
BLOSSOM_SECONDS = 5.0
PRMSTAR_PATH_FACTOR = 1.1


def _planner_line(name: str, system: str, runs: Sequence[RunRow],
                  reference: Sequence[RunRow]) -> tuple[str, ...]:
    if not runs:
        return (label(name, system), NOT_AVAILABLE, *["–"] * 6)
    s = summarize(runs)
    duration = Spread.of(r.path_duration for r in runs if r.solved)
    ratio = median_ratio(runs, reference) if name != REFERENCE else math.nan
    return (label(name, system), f"{s.success_percent:.0f}", _pm(s.time, 4),
            _pm(duration, 4), _pm(s.path_length, 4), _pm(s.tree_nodes, 4),
            _fmt(s.time.median, 4), _ratio(ratio))


def problem_block(rows: Sequence[RunRow], problem: str, planners: Sequence[str],
                  published=()) -> list[str]:
    """One problem's table: a line per planner the preset names, then SPEC 5.6's."""
    mine = [r for r in rows if r.problem == problem]
    system = mine[0].vehicle if mine else ""
    by_planner = group(mine, "planner")
    reference = by_planner.get((REFERENCE,), [])
    body = [_planner_line(name, system, by_planner.get((name,), []), reference)
            for name in planners]
    body += [(name, success, time, length, "–", nodes, "–", "–")
             for name, success, time, length, nodes in published]
    if system in GEOMETRIC_SYSTEMS:  # no control duration: drop its column
        return markdown_table(TABLE_HEADER[:3] + TABLE_HEADER[4:],
                              [line[:3] + line[4:] for line in body], "l" + "r" * 6)
    return markdown_table(TABLE_HEADER, body, "l" + "r" * 7)


def _median_time(rows: Sequence[RunRow]) -> float:
    return statistics.median(r.time_seconds for r in rows) if rows else math.nan


def targets_table(rows: Sequence[RunRow], min_runs: int = MIN_RUNS) -> list[str]:
    """Issue 14's and 15's measurable targets and ``FAMILY_TARGETS``, judged on this
    run's rows (a speed target is met only when every run of the planner on that
    problem was solved);
    one measured with fewer than ``min_runs`` runs of a planner is not judged."""
    def judged(target: str, measured: str, met: bool, *runs: Sequence[RunRow]):
        fewest = fewest_runs(*runs)
        return ((target, measured, _verdict(met)) if fewest >= min_runs
                else (target, not_judged(fewest, min_runs), "–"))
    body = []
    by_key = group(rows, "problem", "planner")
    problems = sorted({r.problem for r in rows})
    for problem in problems:
        reference = by_key.get((problem, REFERENCE), [])
        if not reference:
            continue
        system = reference[0].vehicle
        ours = sorted(p for (q, p) in by_key if q == problem and not p.startswith(OMPL_PREFIX)
                      and (system not in GEOMETRIC_SYSTEMS or p in ("rrt", "rrtconnect")))
        for planner in ours:
            runs = by_key[(problem, planner)]
            ratio, solved = median_ratio(runs, reference), sum(r.solved for r in runs)
            measured = _ratio(ratio) + ("" if solved == len(runs)
                                        else f" ({solved}/{len(runs)} solved)")
            body.append(judged(f"{problem}: {planner} median time ≤ {SPEED_FACTOR}× OMPL "
                               "RRT's", measured, ratio <= SPEED_FACTOR and solved == len(runs),
                               runs, reference))
    pendulum = [rows for (q, p), rows in by_key.items()
                if q == "pendulum-t3" and not p.startswith(OMPL_PREFIX)]
    if pendulum:
        best = min(_median_time(r) for r in pendulum)
        body.append(judged(f"pendulum-t3: best planner median ≤ {PENDULUM_FACTOR:g}× "
                           f"{PENDULUM_PUBLISHED_SECONDS} s (seed, C++)", f"{best:.4g} s",
                           best <= PENDULUM_FACTOR * PENDULUM_PUBLISHED_SECONDS, *pendulum))
    for (problem, planner), runs in sorted(by_key.items()):
        if planner == "blossom" and problem.startswith("car1-scene"):
            median = _median_time(runs)
            body.append(judged(f"{problem}: blossom b = 5 median < {BLOSSOM_SECONDS:g} s",
                               f"{median:.3g} s", median < BLOSSOM_SECONDS, runs))
    body += [judged(*target) for target in _prmstar_targets(by_key, problems)]
    for check in check_targets(rows, targets=FAMILY_TARGETS):
        body.append((check.target, check.detail, _verdict(check.met)) if check.runs >= min_runs
                    else (check.target, not_judged(check.runs, min_runs), "–"))
    if not body:
        return ["No targets to judge in this run (OMPL's RRT or the planners left out)."]
    return markdown_table(("Target", "Measured", "Met"), body, "lrc")


def _prmstar_targets(by_key, problems) -> list[tuple]:
    """(target, measured, met, prmstar's runs) per problem prmstar solved."""
    body = []
    for problem in problems:
        runs = by_key.get((problem, "prmstar"), [])
        lengths = [r.path_length for r in runs if r.solved]
        every = [r.path_length for (q, _), rs in by_key.items() if q == problem
                 for r in rs if r.solved]
        if lengths and every:
            ratio = statistics.median(lengths) / min(every)
            body.append((f"{problem}: prmstar median path ≤ {PRMSTAR_PATH_FACTOR}× the "
                         "shortest of the run", _ratio(ratio), ratio <= PRMSTAR_PATH_FACTOR,
                         runs))
    return body


def _verdict(met: bool | None) -> str:
    """None: the run cannot decide it (a zero median)."""
    return "n/a" if met is None else "yes" if met else "**no**"


def sweep_table(rows: Sequence[RunRow]) -> list[str]:
    """Solved and validated % per problem and planner (the acceptance sweep's table)."""
    by_key = group(rows, "problem", "planner")
    body = []
    for (problem, planner), runs in sorted(by_key.items()):
        solved = sum(r.solved for r in runs)
        body.append((problem, label(planner, runs[0].vehicle), f"{solved}/{len(runs)}",
                     f"{100.0 * solved / len(runs):.0f}", _fmt(_median_time(runs), 3)))
    totals = []
    for (planner,), runs in sorted(group(rows, "planner").items()):
        solved = sum(r.solved for r in runs)
        totals.append(("every problem", label(planner, runs[0].vehicle),
                       f"{solved}/{len(runs)}", f"{100.0 * solved / len(runs):.0f}",
                       _fmt(_median_time(runs), 3)))
    return markdown_table(("Problem", "Planner", "Solved and valid", "%", "Median time (s)"),
                          body + totals, "llrrr")


def markdown_report(rows: Sequence[RunRow], meta: dict[str, str],
                    preset: FamilyPreset) -> str:
    out = [f"# Family benchmark: preset {preset.name}", ""]
    out += [f"- {key}: {value}" for key, value in meta.items()] + [""]
    out += ["Time: planning time (the planner's own clock), mean ± std over all runs (an "
            "unsolved run counts the time it used); path length over solved runs: control "
            "duration in seconds (sum of K x DT, OMPL's measure) and metric length (the "
            "validator's, along every slice or segment); vs OMPL RRT: our median over "
            "OMPL RRT's (control RRT for kinodynamic systems, geometric for arm2 and "
            "rigid2), Python callbacks, same problems and seeds. A planner marked "
            f"\"{NOT_AVAILABLE}\" does not plan for that system (yet).", ""]
    out += ["## Targets", "", TARGETS_NOTE, ""] + targets_table(rows)
    out += [""]
    for table in preset.tables:
        out += [f"## {table.title}", ""]
        # A planner the run left out (--planners) has no line: "not available" says
        # that a planner does not plan for the problem's system.
        chosen = meta.get("planners", "").split()
        planners = [name for name in table_planners(table, [])
                    if not chosen or name in chosen]
        ran = [p.stem for p in table_problems(table) if any(r.problem == p.stem for r in rows)]
        if not ran:
            out += [f"No runs: none of {', '.join(planners) or 'its planners'} is available "
                    "for these problems (yet), or the run left them out.", ""]
        for problem in ran:
            named = planners or sorted({r.planner for r in rows if r.problem == problem})
            out += [f"### {problem}", ""]
            out += problem_block(rows, problem, named, table.published) + [""]
    out += ["## Solved and validated, per problem and planner", ""] + sweep_table(rows) + [""]
    failures = failures_table(rows)
    if failures:
        out += ["## Failures (other than limits)", ""] + failures + [""]
    return "\n".join(out)
