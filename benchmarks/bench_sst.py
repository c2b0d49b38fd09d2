"""SST's measurements: first solutions on every problem it plans for, and the cost at
1 s against 10 s with an objective.

    python -m benchmarks.bench_sst first [--seeds 20] [--time 30] [--only PART] [--json F] [--page]
    python -m benchmarks.bench_sst cost [--seeds 20] [--only PART] [--json F] [--page]
    python -m benchmarks.bench_sst remove   (in this interpreter: interpreted)

Two runs at a time, each in its own interpreter with the compiled build where it is fresh;
every answer is checked with the validator's own checks. Prints a Markdown table; with
``--page`` also writes it as its results page, docs/results/sst-first.md or sst-cost.md,
with the run's date, commit and machine.
"""

from __future__ import annotations

import argparse
import datetime
import json
import random
import statistics
import subprocess
import sys
import time
from multiprocessing.pool import ThreadPool
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

FAMILY = ["pendulum-t3", "pendulum-t5", "pendulum-t10", "car2-corridors", "unicycle-circles",
          "car1-scene1", "car1-scene2", "car1-scene3"]
COURSE = ["simple-0", "space-0", "space-1", "space-2", "space-3"]
PAGES = {"first": ("sst-first.md", "SST's first solutions",
                   "Every problem SST plans for (the kinodynamic family's and both ships on "
                   "the course maps), seeds 0 to N - 1, each run to its first solution (no "
                   "objective) within the time limit; cost: the first solution's (seconds "
                   "for the family, map units for the ships)."),
         "cost": ("sst-cost.md", "SST's cost at 1 s and 10 s",
                  "With `-optimize`, 10 s a run, seeds 0 to N - 1; the cost at 1 s is the best "
                  "found by then; \"cheaper at 10 s\": runs whose cost at 10 s is below their "
                  "cost at 1 s, of those solved by 1 s.")}
"""Per table: its results page in docs/results/, title and what its rows are."""
COST_CASES = [("family/pendulum-t5.kp", None), ("family/car1-scene2.kp", None),
              ("course/space-1.sw", "spaceship")]


# Each run in a fresh interpreter with the compiled build where it is fresh (benchmarks
# do not import the launchers' start-up: tests/test_import_layers.py).
CHILD = ("import json, sys; from rrt_startup.compiled import activate; activate(); "
         "from benchmarks.bench_sst import run; print(json.dumps(run(json.loads(sys.argv[1]))))")


def run_in_child(job: list) -> dict:
    done = subprocess.run([sys.executable, "-c", CHILD, json.dumps(job)], cwd=ROOT,
                          capture_output=True, text=True, check=True)
    result: dict = json.loads(done.stdout)
    return result


def run(job: list) -> dict:
    """One SST run: ``[[path, vehicle], seed, time limit, optimize]`` -> what the
    tables need."""
    from cli_common import parse_any_problem
    from planning_core.plan_text import format_plan
    from planning_core.problem_definition import Objective
    from planning_core.setups import grid_setup, kinoplan_setup
    from rrt_cli.planners import sst
    from rrt_cli.planners.base import StopCondition
    from validator.checks import validate_plan
    (path, vehicle), seed, limit, optimize = job
    problem = parse_any_problem((ROOT / "benchmarks" / "problems" / path).read_text())
    setup = kinoplan_setup(problem) if vehicle is None else grid_setup(problem, vehicle)
    pdef = setup.pdef.with_objective(Objective()) if optimize else setup.pdef
    result = sst.solve(setup.si, pdef, StopCondition(time_limit=limit), random.Random(seed))
    valid = result.solved and validate_plan(setup, format_plan(result.trajectory,
                                                               result.tree)).valid
    return dict(case=f"{path.rsplit('/', 1)[-1]} {vehicle or ''}".strip(), seed=seed,
                solved=result.solved, valid=valid, first=result.stats.first_solution_seconds,
                improvements=result.stats.improvements)


def removal_costs() -> list[str]:
    """What taking an inactive node out of the nearest index costs beside a query (20 000
    states, 10 000 queries of ``within`` the selection radius and ``nearest``, 10 000
    removals), in the family's kd-tree and the grid's quadtree."""
    from cli_common import parse_any_problem
    from planning_core.setups import grid_setup, kinoplan_setup
    rows = ["| index | query (within + nearest), us | remove, us |", "|---|---|---|"]
    for path, vehicle in [("family/car2-corridors.kp", None), ("course/space-3.sw", "spaceship")]:
        problem = parse_any_problem((ROOT / "benchmarks" / "problems" / path).read_text())
        si = (kinoplan_setup(problem) if vehicle is None else grid_setup(problem, vehicle)).si
        rng, index = random.Random(1), si.new_nearest()
        for _ in range(20000):
            index.add(tuple(si.sample_target(rng)) + (0.0, 0.0) * (vehicle is not None))
        queries = [si.sample_target(rng) for _ in range(10000)]
        began = time.perf_counter()
        for query in queries:
            index.within(query, si.selection_radius)
            index.nearest(query)
        queried = time.perf_counter()
        for k in rng.sample(range(20000), 10000):
            index.remove(k)
        removed = time.perf_counter()
        rows.append(f"| {path} | {(queried - began) * 100:.1f} | {(removed - queried) * 100:.1f} |")
    return rows


def first_table(results: list[dict]) -> list[str]:
    rows = ["| problem | solved | valid | first solution: median s | max s | cost: median |",
            "|---|---|---|---|---|---|"]
    for case, runs in _by_case(results).items():
        solved = [r for r in runs if r["solved"]]
        firsts = [r["first"] for r in solved] or [float("nan")]
        costs = [r["improvements"][0][1] for r in solved] or [float("nan")]
        rows.append(f"| {case} | {len(solved)}/{len(runs)} | {sum(r['valid'] for r in solved)}"
                    f"/{len(solved)} | {statistics.median(firsts):.2f} | {max(firsts):.2f} | "
                    f"{statistics.median(costs):.4g} |")
    return rows


def cost_table(results: list[dict]) -> list[str]:
    rows = ["| problem | solved by 1 s | cost at 1 s: median | solved by 10 s | "
            "cost at 10 s: median | cheaper at 10 s |", "|---|---|---|---|---|---|"]
    for case, runs in _by_case(results).items():
        at_1 = {r["seed"]: [c for s, c in r["improvements"] if s <= 1.0][-1] for r in runs
                if r["improvements"] and r["improvements"][0][0] <= 1.0}
        at_10 = {r["seed"]: r["improvements"][-1][1] for r in runs if r["improvements"]}
        cheaper = sum(at_10[seed] < cost for seed, cost in at_1.items())
        rows.append(f"| {case} | {len(at_1)}/{len(runs)} | "
                    f"{statistics.median(at_1.values()):.4g} | {len(at_10)}/{len(runs)} | "
                    f"{statistics.median(at_10.values()):.4g} | {cheaper}/{len(at_1)} |")
    return rows


def page(what: str, table: list[str], meta: dict) -> str:
    """``table`` as its results page: title, the run's facts, what the rows are."""
    from benchmarks.results_page import run_table
    _, title, rows = PAGES[what]
    lines = [f"# Results: {title}", "",
             f"Written by `python -m benchmarks.bench_sst {what} --page`; earlier runs are this "
             "page's git history. Every run in its own interpreter, the compiled build where it "
             "is fresh, every answer checked with the validator's own checks. SST and its "
             "cost: [optimal-planning.md](../optimal-planning.md#sst).", ""]
    return "\n".join(lines + run_table(meta) + ["", rows, ""] + table) + "\n"


def _by_case(results: list[dict]) -> dict[str, list[dict]]:
    cases: dict[str, list[dict]] = {}
    for result in results:
        cases.setdefault(result["case"], []).append(result)
    return cases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=["first", "cost", "remove"])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--time", type=float, default=30.0, help="first: the time limit")
    parser.add_argument("--only", default="", help="first, cost: the problems whose path "
                        "holds this (course/, family/, space-1)")
    parser.add_argument("--json", help="also write every run here")
    parser.add_argument("--page", action="store_true", help="first, cost: also write the "
                        "table as its results page (docs/results/sst-first.md, sst-cost.md)")
    args = parser.parse_args()
    if args.what == "remove":
        print("\n".join(removal_costs()))
        return
    if args.what == "first":
        cases = ([(f"family/{name}.kp", None) for name in FAMILY]
                 + [(f"course/{name}.sw", ship) for name in COURSE
                    for ship in ("spaceship", "left")])
        jobs = [(case, seed, args.time, False) for case in cases for seed in range(args.seeds)]
    else:
        jobs = [(case, seed, 10.0, True) for case in COST_CASES for seed in range(args.seeds)]
    jobs = [job for job in jobs if args.only in job[0][0]]
    from benchmarks.cli import finish_script_meta, script_meta
    started, clock = datetime.datetime.now(), time.monotonic()
    meta = script_meta(started, 2, "python -m benchmarks.bench_sst " + " ".join(sys.argv[1:]))
    with ThreadPool(2) as pool:
        results = pool.map(run_in_child, jobs, chunksize=1)
    if args.json:
        with open(args.json, "w") as out:
            json.dump(results, out)
    table = (first_table if args.what == "first" else cost_table)(results)
    print("\n".join(table))
    if args.page:
        finish_script_meta(meta, clock, len(results))
        (ROOT / "docs" / "results" / PAGES[args.what][0]).write_text(
            page(args.what, table, meta))


if __name__ == "__main__":
    main()
