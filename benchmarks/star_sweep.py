"""RRT* and Informed RRT* over seeds: first solutions, and the cost after a time budget.

    python -m benchmarks.star_sweep [--planners rrtstar,informed] [--seeds 20]
        [--budgets 0,1,10] [--jobs 2] [--page] PROBLEM ...

Each run is ``./run.sh -planner P -seed S -stats`` (with ``-optimize -time B`` for a
budget B > 0; 0 is the first solution, ``-time 30``), its answer checked by the
validator's own checks and its cost read from ``-stats``. One Markdown table row per
problem, planner and budget: solved and valid out of the seeds, median first-solution
time and median (and worst) cost, and for a point or arm2 problem the median cost over
the shortest path (``benchmarks/shortest_path.py``, exact; ``benchmarks/arm2_shortest_path.py``,
a valid path refined until it stops falling by 0.1%). ``--page`` also writes the table
as its results page, docs/results/star-sweep.md, with the run's date, commit and machine.
"""

from __future__ import annotations

import argparse
import datetime
import re
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from benchmarks.catalog import ROOT
from cli_common import parse_any_problem
from planning_core.setups import grid_setup, kinoplan_setup
from validator.checks import validate_plan

_STATS = re.compile(r"cost=(\S+) first_solution_seconds=(\S+)")
HEADER = ["| problem | planner | budget | valid | first solution: median s | cost: median "
          "| cost: worst | median / shortest |", "|---|---|---|---|---|---|---|---|"]
PAGE = ROOT / "docs" / "results" / "star-sweep.md"


def _setup(text: str):
    """The problem's setup for the validator, and its shortest path's length where the
    benchmarks compute one (point vehicle, arm2), else None."""
    problem = parse_any_problem(text)
    if hasattr(problem, "system"):
        if problem.system.name != "arm2":
            return kinoplan_setup(problem), None
        from benchmarks.arm2_shortest_path import arm2_shortest_path
        found = arm2_shortest_path(problem)
        return kinoplan_setup(problem), found.length if found else None
    from benchmarks.shortest_path import shortest_path
    found = shortest_path(problem)
    return grid_setup(problem, "point"), found.length if found else None


def _run(text: str, setup, planner: str, seed: int, budget: float) -> tuple:
    """(valid, cost, first-solution seconds) of one run."""
    flags = ["-optimize", "-time", str(budget)] if budget > 0 else ["-time", "30"]
    done = subprocess.run([str(ROOT / "run.sh"), "-planner", planner, "-seed", str(seed),
                           "-stats", *flags], input=text.encode(), capture_output=True,
                          timeout=budget + 60)
    stats = _STATS.search(done.stderr.decode())
    if done.returncode != 0 or stats is None:
        return False, None, None
    report = validate_plan(setup, done.stdout.decode())
    return report.valid, float(stats.group(1)), float(stats.group(2))


def sweep(path: Path, planners: list[str], seeds: int, budgets: list[float],
          jobs: int) -> list[str]:
    text = path.read_text()
    setup, shortest = _setup(text)
    lines = []
    with ThreadPoolExecutor(jobs) as pool:
        for planner in planners:
            for budget in budgets:
                runs = list(pool.map(lambda seed: _run(text, setup, planner, seed, budget),
                                     range(1, seeds + 1)))
                good = [(cost, first) for valid, cost, first in runs if valid]
                line = _row(path.stem, planner, budget, seeds, good, shortest)
                print(line, flush=True)
                lines.append(line)
    return lines


def _row(problem: str, planner: str, budget: float, seeds: int, good: list,
         shortest) -> str:
    """A table row: ``good`` are the valid runs' (cost, first-solution seconds)."""
    costs = [cost for cost, _ in good]
    figures = ["–"] * 4
    if good:
        median = statistics.median(costs)
        figures = [f"{statistics.median(f for _, f in good):.3g}", f"{median:.4f}",
                   f"{max(costs):.4f}", f"{median / shortest:.4f}" if shortest else "–"]
    setting = f"{budget:g} s" if budget > 0 else "first solution"
    return f"| {problem} | {planner} | {setting} | {len(good)}/{seeds} | " + " | ".join(
        figures) + " |"


def page(table: list[str], meta: dict) -> str:
    """``table`` as its results page: title, the run's facts, what the rows are."""
    from benchmarks.results_page import run_table
    lines = ["# Results: RRT\\* and Informed RRT\\* over seeds (`benchmarks.star_sweep`)", "",
             "Written by `python -m benchmarks.star_sweep --page`; earlier runs are this "
             "page's git history. Each run is `./run.sh -planner P -seed S -stats`, to its "
             "first solution (`-time 30`) or with `-optimize -time B` for a budget B; every "
             "answer checked by the validator's own checks. Cost and the shortest paths: "
             "[optimal-planning.md](../optimal-planning.md).", ""]
    return "\n".join(lines + run_table(meta) + [""] + table) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problems", nargs="+", type=Path)
    parser.add_argument("--planners", default="rrtstar,informed")
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--budgets", default="0")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--page", action="store_true",
                        help="also write the table as docs/results/star-sweep.md")
    args = parser.parse_args()
    from benchmarks.cli import finish_script_meta, script_meta
    started, clock = datetime.datetime.now(), time.monotonic()
    meta = script_meta(started, args.jobs,
                       "python -m benchmarks.star_sweep " + " ".join(sys.argv[1:]))
    print("\n".join(HEADER), flush=True)
    table = HEADER + [row for path in args.problems for row in sweep(
        path, args.planners.split(","), args.seeds,
        [float(b) for b in args.budgets.split(",")], args.jobs)]
    if args.page:
        finish_script_meta(meta, clock, (len(table) - 2) * args.seeds)
        PAGE.write_text(page(table, meta))


if __name__ == "__main__":
    main()
