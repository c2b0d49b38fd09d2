"""Proofs of solvability for the family problems: a stored answer per problem,
``benchmarks/problems/family/solutions/NAME.out``, that the validator accepts.

    python -m benchmarks.family_solutions [--check] [--time S] [NAME ...]

Without ``--check``: for every problem without a stored answer (or those named),
run planners in turn, each with seeds 1..3 (ours: ``rrt``, then OMPL's RRT when
installed), keep the first answer the validator accepts, its tree left out (M = 0:
tree lines are for drawing; the trajectory is the proof), and record who made it in
``solutions/SOURCES.txt`` (``NAME planner seed``). ``--check`` plans nothing: it
validates every stored answer against its problem and exits 1 when a problem has
none or one is rejected (``tests/benchmarks/test_bench_family_problems.py`` does
the same).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

from benchmarks.catalog import ROOT, ompl_installed
from benchmarks.family import FAMILY_DIR, SOLUTIONS_DIR, family_problems
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.setups import kinoplan_setup

SOURCES = SOLUTIONS_DIR / "SOURCES.txt"
SEEDS = (1, 2, 3)


def solution_path(problem: Path) -> Path:
    return SOLUTIONS_DIR / f"{problem.stem}.out"


def check(problem: Path, answer_text: str):
    """The validator's report on ``answer_text`` for ``problem``."""
    from validator.checks import validate_plan
    return validate_plan(kinoplan_setup(parse_kinoplan(problem.read_text())), answer_text)


def problems_without_valid_answer(directory: Path = FAMILY_DIR) -> dict[str, str]:
    """Problem name -> why its stored answer is missing or rejected."""
    bad = {}
    for problem in family_problems(directory):
        stored = directory / "solutions" / f"{problem.stem}.out"
        if not stored.exists():
            bad[problem.stem] = "no stored answer"
            continue
        report = check(problem, stored.read_text())
        if not report.valid:
            first = report.first_failure
            bad[problem.stem] = f"rejected: {first.message} {first.detail}" if first else \
                "rejected"
    return bad


def without_tree(answer: str) -> str:
    """The answer with its tree section emptied (``M = 0``)."""
    lines = answer.splitlines()
    count = int(lines[0])
    return "\n".join(lines[:count + 1] + ["0"]) + "\n"


def _commands(time_limit: float) -> list[tuple[str, list[str]]]:
    common = ["-time", repr(time_limit)]
    tried = [("rrt", [sys.executable, "-m", "rrt_cli", "-planner", "rrt", *common])]
    if ompl_installed():
        tried.append(("ompl-rrt", [sys.executable, "-m", "benchmarks.ompl_planner",
                                   "-planner", "rrt", *common]))
    return tried


def solve(problem: Path, time_limit: float) -> tuple[str, int, str] | None:
    """(planner, seed, answer) of the first run the validator accepts, or None."""
    for planner, command in _commands(time_limit):
        for seed in SEEDS:
            done = subprocess.run([*command, "-seed", str(seed)], input=problem.read_bytes(),
                                  capture_output=True, cwd=ROOT, timeout=time_limit * 2 + 30)
            if done.returncode == 0 and check(problem, done.stdout.decode()).valid:
                return planner, seed, without_tree(done.stdout.decode())
            sys.stderr.write(f"family_solutions: {problem.stem}: {planner} seed {seed}: "
                             f"no valid answer (exit {done.returncode})\n")
    return None


def _record(name: str, planner: str, seed: int) -> None:
    lines = SOURCES.read_text().splitlines() if SOURCES.exists() else []
    lines = [line for line in lines if line.split()[:1] != [name]] + [f"{name} {planner} {seed}"]
    SOURCES.write_text("\n".join(sorted(lines)) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="validate the stored answers")
    parser.add_argument("--time", type=float, default=60.0, help="seconds per planner run")
    parser.add_argument("names", nargs="*", help="problems to (re)solve (default: unsolved)")
    args = parser.parse_args(argv)
    if args.check:
        bad = problems_without_valid_answer()
        for name, why in sorted(bad.items()):
            sys.stderr.write(f"family_solutions: {name}: {why}\n")
        return 1 if bad else 0
    SOLUTIONS_DIR.mkdir(exist_ok=True)
    failed = 0
    for problem in family_problems():
        if args.names and problem.stem not in args.names:
            continue
        if not args.names and solution_path(problem).exists():
            continue
        found = solve(problem, args.time)
        if found is None:
            failed += 1
            continue
        planner, seed, answer = found
        solution_path(problem).write_text(answer)
        _record(problem.stem, planner, seed)
        sys.stderr.write(f"family_solutions: {problem.stem}: {planner} seed {seed}\n")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
