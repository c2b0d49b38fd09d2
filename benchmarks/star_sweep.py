"""RRT* and Informed RRT* over seeds: first solutions, and the cost after a time budget.

    python -m benchmarks.star_sweep [--planners rrtstar,informed] [--seeds 20]
        [--budgets 0,1,10] [--jobs 2] PROBLEM ...

Each run is ``./run.sh -planner P -seed S -stats`` (with ``-optimize -time B`` for a
budget B > 0; 0 is the first solution, ``-time 30``), its answer checked by the
validator's own checks and its cost read from ``-stats``. One line per problem,
planner and budget: solved and valid out of the seeds, median first-solution time
and median (and worst) cost, and for a point or arm2 problem the median cost over the
shortest path (``benchmarks/shortest_path.py``, exact; ``benchmarks/arm2_shortest_path.py``,
a valid path refined until it stops falling by 0.1%).
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from benchmarks.catalog import ROOT
from cli_common import parse_any_problem
from planning_core.setups import grid_setup, kinoplan_setup
from validator.checks import validate_plan

_STATS = re.compile(r"cost=(\S+) first_solution_seconds=(\S+)")


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
                costs = [cost for cost, _ in good]
                line = (f"{path.stem:16} {planner:8} budget={budget:>4g}s valid={len(good)}/"
                        f"{seeds}")
                if good:
                    line += (f" first_s(median)={statistics.median(f for _, f in good):.3f}"
                             f" cost(median)={statistics.median(costs):.4f}"
                             f" cost(max)={max(costs):.4f}")
                    if shortest:
                        line += f" /shortest={statistics.median(costs) / shortest:.4f}"
                print(line, flush=True)
                lines.append(line)
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problems", nargs="+", type=Path)
    parser.add_argument("--planners", default="rrtstar,informed")
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--budgets", default="0")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    for path in args.problems:
        sweep(path, args.planners.split(","), args.seeds,
              [float(b) for b in args.budgets.split(",")], args.jobs)


if __name__ == "__main__":
    main()
