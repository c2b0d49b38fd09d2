"""OMPL as a peer command-line planner: same input, same output, same exit codes.

    python benchmarks/ompl_planner.py [-grad] [-left] [-planner rrt|rrtconnect|kpiece1]
                                      [-seed N] [-time S] [-stats] < problem.sw

Reads a `.sw` problem on stdin, plans with OMPL's Python bindings (see
benchmarks/ompl_adapters.py) and prints the trajectory and the tree in our
format (SPEC 2), so that ``rrt-validator -- python benchmarks/ompl_planner.py``
checks OMPL's answers and the benchmark harness times whole processes alike.
Spaceship lines are re-propagated from the start with OMPL's controls.

Exit status: 0 solved, 2 bad usage or bad problem, 3 no solution within the
time limit, 4 the ``ompl`` package is not installed.
"""

from __future__ import annotations

import argparse
import os
import random
import sys

try:
    from benchmarks import ompl_adapters
except ModuleNotFoundError:  # run as a script from a checkout that is not installed
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from benchmarks import ompl_adapters
from planning_core.cli_args import (EXIT_USAGE, OneLineErrorParser, add_vehicle_flags,
                                    positive_float, read_problem_from_stdin, vehicle_from_flags)
from planning_core.plan_text import format_plan

EXIT_SOLVED = 0
EXIT_NO_SOLUTION = 3
EXIT_NO_OMPL = 4
DEFAULT_TIME_LIMIT = 30.0
PLANNER_CHOICES = sorted(set(ompl_adapters.POINT_PLANNERS + ompl_adapters.SPACESHIP_PLANNERS))


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineErrorParser(prog="ompl_planner",
                     description="Plan with OMPL on a .sw problem read from stdin; print "
                                 "the trajectory and the tree on stdout.")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-planner", default="rrt", choices=PLANNER_CHOICES,
                        help="rrt (geometric or control), rrtconnect (point), kpiece1 "
                             "(spaceship); default rrt")
    parser.add_argument("-seed", type=int, default=None)
    parser.add_argument("-time", type=positive_float, default=DEFAULT_TIME_LIMIT, metavar="S")
    parser.add_argument("-stats", action="store_true",
                        help="print one line of key=value statistics on stderr")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    vehicle = vehicle_from_flags(parser, args)
    if args.planner not in ompl_adapters.planners_for(vehicle):
        sys.stderr.write(f"ompl_planner: error: planner {args.planner!r} does not support "
                         f"the {vehicle.value} vehicle\n")
        return EXIT_USAGE
    problem = read_problem_from_stdin("ompl_planner")
    if problem is None:
        return EXIT_USAGE
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(2 ** 31)
    try:
        result = ompl_adapters.solve(problem, vehicle, args.planner, args.time, seed)
    except ImportError as error:
        sys.stderr.write(f"ompl_planner: the ompl package is not installed ({error}); "
                         "pip install ompl\n")
        return EXIT_NO_OMPL
    if args.stats:
        status = "solved" if result.solved else "time_limit"
        sys.stderr.write(f"ompl_planner stats: status={status} planner=ompl-{args.planner} "
                         f"vehicle={vehicle.value} seed={seed} iterations={result.iterations} "
                         f"tree_nodes={result.tree_nodes} "
                         f"planning_seconds={result.planning_seconds:.6f}\n")
    if not result.solved:
        sys.stderr.write(f"ompl_planner: no solution ({result.status}) after "
                         f"{result.planning_seconds:.2f} s (seed {seed})\n")
        return EXIT_NO_SOLUTION
    sys.stdout.write(format_plan(result.trajectory, result.tree))
    return EXIT_SOLVED


def entry_point() -> None:
    try:
        status = main()
    except KeyboardInterrupt:
        status = 130
    except BrokenPipeError:
        status = 1
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except BrokenPipeError:
        status = 1
    # Skip interpreter teardown: the OMPL bindings print reference-leak reports
    # to stderr at exit, which would bury the one diagnostic line.
    os._exit(status)


if __name__ == "__main__":
    entry_point()
