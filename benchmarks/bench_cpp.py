"""Each of our planners against OMPL in C++'s same planner, problem by problem.

    python -m benchmarks.bench_cpp [--seeds 20] [--time 10]
                                   [--systems point spaceship left family]
                                   [--problems PATTERN ...] [--planners NAME ...]
                                   [--page docs/results/cpp.md]

Problems: the quick preset's problems of the point vehicle and the two ships (course maps
and suite maps) and the family's problems (``benchmarks/problems/family``). Planners:
every planner of ours with a same-planner counterpart in the C++ programs of
``benchmarks/ompl_cpp/`` (benchmarks/ompl_cpp_planner.py's ``GRID_MODES`` and
``FAMILY_PLANNERS``: geometric or control RRT, RRT-Connect, PRM, PRM*, RRT*, Informed
RRT*, KPIECE1, SST), the C++ program built on first use (g++, libompl-dev). Per seed our
compiled run (``./run.sh``) and the C++ run take turns as whole processes, the order
swapped every seed, with the same seed and time limit; each run's own planning time and
iterations are read from its ``-stats`` line (an unsolved run counts its whole limit).
Prints, per problem and planner, the medians of both, their ratio (ours over C++), the
solved counts and our median time to a first path (PRM* goes on after it; OMPL's PRM*
stops there, as every C++ planner here), as a Markdown table; with ``--page`` also a
results page with the run's date, commit, machine, load and command. Compare the ratios,
taken in the same turns, rather than the milliseconds: load on the machine slows both
sides. ``--jobs 2`` measures two cases at a time (each case's runs still alternate)."""

from __future__ import annotations

import argparse
import datetime
import fnmatch
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from benchmarks.bench_compiled import VEHICLE_FLAGS
from benchmarks.family import FAMILY_DIR
from benchmarks.generator import problem_id
from benchmarks.harness import parse_stats
from benchmarks.ompl_cpp_planner import FAMILY_PLANNERS, GRID_MODES
from benchmarks.ompl_cpp_programs import binary, family_input, grid_input
from benchmarks.presets import PRESETS, select_problems
from planning_core.vehicles import Vehicle

ROOT = Path(__file__).resolve().parent.parent
GRID_SYSTEMS = ("point", "spaceship", "left")
GEOMETRIC_FAMILY = ("arm2", "rigid2")


@dataclass(frozen=True)
class Case:
    """One problem and planner: our run's flags and the C++ program's mode."""

    system: str
    """The vehicle (point, spaceship, left) or the family's system (arm2, car1, ...)."""
    problem: Path
    planner: str
    program: str
    """grid_ompl or family_ompl."""
    mode: str
    """The program's first argument."""


@dataclass(frozen=True)
class Run:
    seconds: float
    """The run's own planning time (its time limit when it did not solve)."""
    solved: bool
    iterations: int
    first: float
    """Seconds to its first path (its time limit when it did not solve): an optimizing
    planner, or our PRM*, may go on after it."""


def grid_problems(vehicle: str) -> list[Path]:
    plan = next(plan for plan in PRESETS["quick"].plans if plan.vehicle.value == vehicle)
    return select_problems(plan)


def cases(systems: list[str], patterns: list[str], planners: list[str]) -> list[Case]:
    """Every (problem, planner) pair of ``systems`` with a C++ counterpart, narrowed to
    the problems matching ``patterns`` and the ``planners`` (empty: all)."""
    found = []
    for system in systems:
        if system == "family":
            for path in sorted(FAMILY_DIR.glob("*.kp")):
                name = path.stem.split("-")[0]
                for planner in FAMILY_PLANNERS[name not in GEOMETRIC_FAMILY]:
                    found.append(Case(name, path, planner, "family_ompl", planner))
            continue
        modes = GRID_MODES[Vehicle(system)]
        for path in grid_problems(system):
            found += [Case(system, path, planner, "grid_ompl", mode)
                      for planner, mode in modes.items()]
    return [case for case in found
            if (not patterns or any(fnmatch.fnmatchcase(problem_id(case.problem), p)
                                    for p in patterns))
            and (not planners or case.planner in planners)]


def run_once(case: Case, ours: bool, seed: int, limit: float) -> Run:
    """One whole-process run, ours (compiled) or the C++ program's."""
    if ours:
        argv = [str(ROOT / "run.sh"), *VEHICLE_FLAGS.get(case.system, []), "-planner",
                case.planner, "-seed", str(seed), "-time", str(limit), "-stats"]
        stdin = case.problem.read_bytes()
    else:
        argv = [str(binary(case.program)), case.mode, str(limit), str(seed)]
        flat = family_input if case.program == "family_ompl" else grid_input
        stdin = flat(case.problem.read_text())
    done = subprocess.run(argv, input=stdin, capture_output=True, timeout=limit * 3 + 30)
    stderr = done.stderr.decode(errors="replace")
    if ours and "rrt_cli build: compiled" not in stderr:
        raise SystemExit(f"bench_cpp: the compiled modules are not in use: "
                         f"{stderr.splitlines()[:1]} (run ./make.sh)")
    stats = parse_stats(stderr)
    if "status" not in stats:
        raise SystemExit(f"bench_cpp: no stats from {' '.join(argv)}: {stderr.strip()[-300:]}")
    solved = stats["status"] == "solved"
    return Run(float(stats["planning_seconds"]) if solved else limit, solved,
               int(stats["iterations"]),
               float(stats["first_solution_seconds"]) if solved else limit)


def measure(case: Case, seeds: int, limit: float) -> tuple[list[Run], list[Run]]:
    """Our runs and the C++ runs, seed by seed, the order swapped every seed."""
    ours, theirs = [], []
    for seed in range(1, seeds + 1):
        for side in ((True, False) if seed % 2 else (False, True)):
            (ours if side else theirs).append(run_once(case, side, seed, limit))
    return ours, theirs


def median_ms(runs: list[Run], first: bool = False) -> float:
    return statistics.median(run.first if first else run.seconds for run in runs) * 1000


HEADER = ["| system | problem | planner | ours (ms) | OMPL C++ (ms) | ours / C++ "
          "| ours: iterations | C++: iterations | solved: ours | solved: C++ "
          "| ours: first path (ms) |",
          "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]


def row(case: Case, ours: list[Run], theirs: list[Run]) -> tuple[str, float]:
    """The case's table row and its ratio of medians (ours over C++)."""
    ratio = median_ms(ours) / median_ms(theirs)
    cells = [case.system, problem_id(case.problem), case.planner, f"{median_ms(ours):.1f}",
             f"{median_ms(theirs):.1f}", f"{ratio:.2f}",
             f"{statistics.median(r.iterations for r in ours):g}",
             f"{statistics.median(r.iterations for r in theirs):g}",
             f"{sum(r.solved for r in ours)}/{len(ours)}",
             f"{sum(r.solved for r in theirs)}/{len(theirs)}", f"{median_ms(ours, True):.1f}"]
    return "| " + " | ".join(cells) + " |", ratio


def summary(rows: list[tuple[str, float]]) -> list[str]:
    """How many rows are at most 1.0x, and the others."""
    above = [text for text, ratio in rows if ratio > 1.0]
    lines = [f"{len(rows) - len(above)} of {len(rows)} rows at most 1.0x OMPL C++'s same "
             f"planner; {len(above)} above:"]
    return lines + (["", *HEADER, *above] if above else [])


def page(table: list[str], meta: dict, seeds: int, limit: float, path: Path) -> str:
    from benchmarks.results_page import run_table
    lines = ["# Results: our planners against OMPL in C++", "",
             f"Written by `python -m benchmarks.bench_cpp --page {path}` (the "
             "command below); earlier runs are this page's git history. Per problem and "
             f"planner, {seeds} seeds, our compiled run and OMPL in C++'s same planner "
             "(benchmarks/ompl_cpp/) taking turns as whole processes, the order swapped "
             "every seed; each run's own planning time and iterations from its -stats line, "
             f"medians; an unsolved run counts its whole limit ({limit:g} s). Why a row is "
             "above 1.0x: [benchmarks.md](../benchmarks.md#against-ompl-in-c).", ""]
    return "\n".join(lines + run_table(meta) + [""] + table) + "\n"


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="bench_cpp", description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--time", type=float, default=10.0, help="every run's time limit (s)")
    parser.add_argument("--systems", nargs="+", choices=[*GRID_SYSTEMS, "family"],
                        default=[*GRID_SYSTEMS, "family"])
    parser.add_argument("--problems", nargs="*", default=[], metavar="PATTERN",
                        help="problem names (shell patterns: narrow-*, course-space-1)")
    parser.add_argument("--planners", nargs="*", default=[], metavar="NAME")
    parser.add_argument("--jobs", type=int, default=1,
                        help="cases measured at a time (each case's runs still take turns)")
    parser.add_argument("--page", type=Path, default=None, metavar="FILE",
                        help="also write the table into this results page (after each "
                             "case: an interrupted run leaves the rows so far)")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    chosen = cases(args.systems, args.problems, args.planners)
    if not chosen:
        raise SystemExit("bench_cpp: no problem and planner matches")
    for program in sorted({case.program for case in chosen}):
        if binary(program) is None:
            raise SystemExit(f"bench_cpp: {program} could not be built (g++ and libompl-dev)")
    from benchmarks.cli import finish_script_meta, script_meta
    given = sys.argv[1:] if argv is None else argv
    meta = script_meta(datetime.datetime.now(datetime.timezone.utc), args.jobs,
                       "python -m benchmarks.bench_cpp " + " ".join(given))
    meta["ompl"] = "C++ " + subprocess.run(["pkg-config", "--modversion", "ompl"],
                                           capture_output=True, text=True).stdout.strip()
    clock = time.monotonic()
    print(f"# ours / OMPL C++, {args.seeds} seeds, limit {args.time:g} s", flush=True)
    print("\n".join(HEADER), flush=True)
    rows: list[tuple[str, float]] = []
    with ThreadPoolExecutor(max(1, args.jobs)) as pool:
        futures = [pool.submit(measure, case, args.seeds, args.time) for case in chosen]
        for case, future in zip(chosen, futures):
            rows.append(row(case, *future.result()))
            print(rows[-1][0], flush=True)
            if args.page is not None:
                finish_script_meta(meta, clock, 2 * args.seeds * len(rows))
                if len(rows) < len(chosen):
                    meta["rows"] = f"{len(rows)} of {len(chosen)} (the run goes on or was cut)"
                else:
                    meta.pop("rows", None)
                table = [*HEADER, *(text for text, _ in rows), "", *summary(rows)]
                args.page.write_text(page(table, meta, args.seeds, args.time, args.page))
    print("\n".join(summary(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
