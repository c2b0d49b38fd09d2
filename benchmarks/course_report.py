"""The course report's table on the course maps: RRT against RRT* path lengths, for the
point vehicle and the Dubins car (turning radius 2, as the report's, and 0.5), with times.

    python -m benchmarks.course_report [--seeds 100] [--jobs 2] [--budget 1]
        [--out benchmarks/results/course-report] [--page docs/results/course-report.md]
        [--page-only]

Each run is ``./run.sh [-dubins -radius R] -planner P -seed S -stats`` on a map of
``benchmarks/problems/course/``, in three settings: ``rrt`` and ``rrtstar`` stopping at
their first solution (``-time 5``: the report's RRT and RRT* each stop at the goal),
and ``rrtstar -optimize -time B`` (the best answer in a budget of B s, as a user asks for
one). Every answer is checked by the validator's own checks (the Dubins car's turning
check included: ``validator.checks.validate_plan``); its length is the validator's,
the polyline through the printed points, which the course's validator measures too.

Runs are appended to ``OUT/runs.csv`` as they finish, seeds in blocks of 10 over every
map and setting, and a rerun of the same code keeps the runs stored there
(:func:`keep_runs_of_this_code`): an interrupted run goes on where it stopped, and the
page made from what is stored says how many seeds each cell has. The page (``--page``)
carries its date, commit and machine, as ``benchmarks/results_page.py``'s do.
"""

from __future__ import annotations

import csv
import json
import datetime
import math
import re
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from benchmarks.catalog import ROOT
from benchmarks.cli import finish_script_meta, script_meta
from benchmarks.results_page import run_table
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup
from planning_core.systems.dubins import DubinsOptions
from validator.checks import validate_plan

COURSE = ROOT / "benchmarks" / "problems" / "course"
OUT = ROOT / "benchmarks" / "results" / "course-report"
PAGE = ROOT / "docs" / "results" / "course-report.md"
FIRST_LIMIT = 5.0
"""Seconds a first-solution run may take (the machine is shared: a failure costs all of it)."""
SEED_BLOCK = 10
"""Seeds run over every cell before the next block: an interrupted run stays balanced."""
FIELDS = ("map", "vehicle", "setting", "seed", "solved", "valid", "length", "first_seconds",
          "planning_seconds")
_STATS = re.compile(r"planning_seconds=(\S+) cost=(\S+) first_solution_seconds=(\S+)")


@dataclass(frozen=True)
class Vehicle:
    name: str
    flags: tuple[str, ...]
    radius: float | None
    """The Dubins car's turning radius; None for the point."""


VEHICLES = (Vehicle("point", (), None),
            Vehicle("dubins R=2", ("-dubins", "-radius", "2"), 2.0),
            Vehicle("dubins R=0.5", ("-dubins", "-radius", "0.5"), 0.5))


def settings(budget: float) -> dict[str, tuple[str, ...]]:
    """The planner flags of each setting, by its name in the table."""
    return {"rrt": ("-planner", "rrt", "-time", f"{FIRST_LIMIT:g}"),
            "rrtstar": ("-planner", "rrtstar", "-time", f"{FIRST_LIMIT:g}"),
            f"rrtstar {budget:g} s": ("-planner", "rrtstar", "-optimize", "-time",
                                      f"{budget:g}")}


def run_once(text: str, setup, vehicle: Vehicle, flags: tuple[str, ...],
             seed: int) -> dict:
    """One run's row (without map, vehicle and setting): solved, valid, the validator's
    length, the first-solution and planning seconds from ``-stats``."""
    done = subprocess.run([str(ROOT / "run.sh"), *vehicle.flags, *flags, "-seed", str(seed),
                           "-stats"], input=text.encode(), capture_output=True, timeout=120)
    stats = _STATS.search(done.stderr.decode())
    row = {"seed": seed, "solved": done.returncode == 0, "valid": False, "length": "",
           "first_seconds": stats.group(3) if stats else "",
           "planning_seconds": stats.group(1) if stats else ""}
    if row["solved"]:
        report = validate_plan(setup, done.stdout.decode())
        row["valid"] = report.valid
        row["length"] = repr(report.cost) if report.valid else ""
    return row


def _setup(problem, vehicle: Vehicle):
    if vehicle.radius is None:
        return grid_setup(problem, "point")
    return grid_setup(problem, "dubins", DubinsOptions(vehicle.radius))


def stored(path: Path) -> list[dict]:
    if not path.is_file():
        return []
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def keep_runs_of_this_code(out: Path) -> None:
    """Keep ``out/runs.csv`` only when this code made it (``benchmarks.store``'s
    fingerprint, kept in ``out/code``): a rerun resumes an interrupted run and never
    mixes in the runs of other code; else they are dropped, with one line on stderr."""
    from benchmarks.store import code_fingerprint
    fingerprint = code_fingerprint(False)
    runs, mark = out / "runs.csv", out / "code"
    made_by = mark.read_text().strip() if mark.is_file() else None
    if runs.is_file() and made_by != fingerprint:
        print(f"course_report: the runs in {runs} were made by other code: all run again",
              file=sys.stderr, flush=True)
        runs.unlink()
    out.mkdir(parents=True, exist_ok=True)
    mark.write_text(fingerprint + "\n")


def run_all(out: Path, seeds: int, budget: float, jobs: int) -> None:
    """Every map x vehicle x setting x seed not yet in ``out/runs.csv``, appended to it."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / "runs.csv"
    done = {(r["map"], r["vehicle"], r["setting"], int(r["seed"])) for r in stored(path)}
    new = not path.is_file()
    maps = sorted(COURSE.glob("*.sw"))
    with open(path, "a", newline="") as handle, ThreadPoolExecutor(jobs) as pool:
        writer = csv.DictWriter(handle, FIELDS)
        if new:
            writer.writeheader()
        for block in range(1, seeds + 1, SEED_BLOCK):
            for map_path in maps:
                text = map_path.read_text()
                problem = parse_problem(text)
                for vehicle in VEHICLES:
                    setup = _setup(problem, vehicle)
                    for name, flags in settings(budget).items():
                        todo = [s for s in range(block, min(block + SEED_BLOCK, seeds + 1))
                                if (map_path.stem, vehicle.name, name, s) not in done]
                        for row in pool.map(lambda s: run_once(text, setup, vehicle, flags, s),
                                            todo):
                            writer.writerow({"map": map_path.stem, "vehicle": vehicle.name,
                                             "setting": name, **row})
                        handle.flush()
                        print(f"course_report: {map_path.stem} {vehicle.name} {name} seeds "
                              f"{block}-{block + SEED_BLOCK - 1} done", file=sys.stderr,
                              flush=True)


def _median(values: list[float]) -> str:
    return f"{statistics.median(values):.3f}" if values else "–"


def _seconds(values: list[float]) -> str:
    finite = [v for v in values if math.isfinite(v)]
    return f"{statistics.median(finite):.4f}" if finite else "–"


def _mean(values: list[float]) -> str:
    return f"{statistics.fmean(values):.2f}" if values else "–"


def cell(rows: list[dict]) -> dict:
    """A table cell's figures over its runs: valid answers, their mean and median length,
    and the median first-solution and planning seconds over all runs (an unsolved run
    counts its planning time, the limit)."""
    lengths = [float(r["length"]) for r in rows if r["valid"] == "True"]
    first = [float(r["first_seconds"] if r["first_seconds"] not in ("", "none")
                   else r["planning_seconds"] or "nan") for r in rows]
    planning = [float(r["planning_seconds"] or "nan") for r in rows]
    return {"runs": len(rows), "valid": len(lengths), "solved": sum(r["solved"] == "True"
                                                                    for r in rows),
            "lengths": lengths, "first": first, "planning": planning}


def table(rows: list[dict], budget: float) -> list[str]:
    """One line per map and vehicle: each setting's valid runs, mean (median) length and
    median first-solution time, and RRT*'s mean length over RRT's."""
    names = list(settings(budget))
    header = ["map", "vehicle"]
    for name in names:
        header += [f"{name}: valid", f"{name}: mean (median) length", f"{name}: first s"]
    header += [f"{name} / rrt (mean length)" for name in names[1:]]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    keys = sorted({(r["map"], r["vehicle"]) for r in rows},
                  key=lambda k: (k[0], [v.name for v in VEHICLES].index(k[1])))
    for map_name, vehicle in keys:
        cells = {name: cell([r for r in rows if (r["map"], r["vehicle"], r["setting"])
                             == (map_name, vehicle, name)]) for name in names}
        line = [map_name, vehicle]
        for name in names:
            c = cells[name]
            line += [f"{c['valid']}/{c['runs']}",
                     f"{_mean(c['lengths'])} ({_median(c['lengths'])})",
                     _seconds(c["first"])]
        base = cells["rrt"]["lengths"]
        line += [f"{statistics.fmean(cells[n]['lengths']) / statistics.fmean(base):.2f}"
                 if base and cells[n]["lengths"] else "–" for n in names[1:]]
        lines.append("| " + " | ".join(line) + " |")
    return lines


def overall(rows: list[dict], budget: float) -> list[str]:
    """Per vehicle, over every map, the report's kind of figure: each RRT* setting's
    runs solved, and over the runs (map and seed) where both RRT and it gave a valid
    answer, the mean lengths and their ratio (paired, so that a map only one of them
    solves does not move the means)."""
    lines = ["| vehicle | setting | valid (rrt's) | paired runs | rrt: mean length | "
             "rrt\\*: mean length | ratio | median first s (rrt's) |",
             "|---|---|---|---|---|---|---|---|"]
    for vehicle in VEHICLES:
        mine = [r for r in rows if r["vehicle"] == vehicle.name]
        base = {(r["map"], r["seed"]): float(r["length"]) for r in mine
                if r["setting"] == "rrt" and r["valid"] == "True"}
        base_cell = cell([r for r in mine if r["setting"] == "rrt"])
        for name in list(settings(budget))[1:]:
            runs = [r for r in mine if r["setting"] == name]
            if not runs:
                continue
            c = cell(runs)
            pairs = [(base[(r["map"], r["seed"])], float(r["length"])) for r in runs
                     if r["valid"] == "True" and (r["map"], r["seed"]) in base]
            theirs, ours = [p[0] for p in pairs], [p[1] for p in pairs]
            ratio = f"{statistics.fmean(ours) / statistics.fmean(theirs):.2f}" if pairs else "–"
            lines.append(f"| {vehicle.name} | {name} | {c['valid']}/{c['runs']} "
                         f"({base_cell['valid']}/{base_cell['runs']}) | {len(pairs)} | "
                         f"{_mean(theirs)} | {_mean(ours)} | {ratio} | "
                         f"{_seconds(c['first'])} ({_seconds(base_cell['first'])}) |")
    return lines


def page(rows: list[dict], meta: dict, budget: float) -> str:
    seeds = sorted({int(r["seed"]) for r in rows})
    lines = ["# Results: the course report's table (RRT against RRT\\*)", "",
             "Written by `python -m benchmarks.course_report`; earlier runs are this page's "
             "git history. What the settings are and how the figures compare with the "
             "report's: [docs/optimal-planning.md](../optimal-planning.md#the-course-reports-"
             "table).", ""]
    lines += run_table(meta) + [""]
    lines += ["Length: the validator's path length (map units) of the valid answers; "
              "valid: answers that pass every check of the validator (the Dubins car's "
              "turning check too) out of the runs; first s: median seconds to the first "
              f"solution (planning time as `-stats` reports it; an unsolved run counts its "
              f"limit, {FIRST_LIMIT:g} s, or the budget). `rrtstar {budget:g} s` runs "
              f"`-optimize -time {budget:g}`: its planning time is the budget. Seeds "
              f"{seeds[0] if seeds else '–'} to {seeds[-1] if seeds else '–'}.", "",
              "## Over all five maps", ""]
    lines += overall(rows, budget) + ["", "## Per map", ""] + table(rows, budget)
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from cli_common import OneLineErrorParser
    parser = OneLineErrorParser(prog="benchmarks.course_report",
                                description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--budget", type=float, default=1.0,
                        help="RRT*'s -optimize -time budget, seconds")
    parser.add_argument("--out", type=Path, default=OUT)
    parser.add_argument("--page", type=Path, default=PAGE)
    parser.add_argument("--page-only", action="store_true",
                        help="write the page from the stored runs, running none")
    argv = sys.argv[1:] if argv is None else argv
    args = parser.parse_args(argv)
    if args.seeds < 1 or args.jobs < 1 or not args.budget > 0:
        parser.error("--seeds and --jobs take a positive integer, --budget a positive number")
    meta_path = args.out / "meta.json"
    if not args.page_only:
        keep_runs_of_this_code(args.out)
        started, clock = datetime.datetime.now(), time.monotonic()
        meta = script_meta(started, args.jobs,
                           "python -m benchmarks.course_report " + " ".join(argv))
        meta_path.write_text(json.dumps(meta, indent=2) + "\n")  # an interrupted run's too
        run_all(args.out, args.seeds, args.budget, args.jobs)
        finish_script_meta(meta, clock)
        meta_path.write_text(json.dumps(meta, indent=2) + "\n")
    rows = [r for r in stored(args.out / "runs.csv") if int(r["seed"]) <= args.seeds
            and r["setting"] in settings(args.budget)]
    if not meta_path.is_file():
        parser.error(f"{meta_path} does not exist (run without --page-only first)")
    meta = {**json.loads(meta_path.read_text()), "runs": str(len(rows))}
    args.page.write_text(page(rows, meta, args.budget))
    print(args.page)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
