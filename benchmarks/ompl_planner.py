"""OMPL as a peer command-line planner: same input, same output, same exit codes.

    python benchmarks/ompl_planner.py [-grad] [-left]
                                      [-planner rrt|rrtconnect|kpiece1|prm|rrtstar|informed]
                                      [-seed N] [-time S] [-stats] [-optimize] < problem

Reads a `.sw` problem or a ``kinoplan 1`` problem (SPEC 5) on stdin, plans with
OMPL's Python bindings (benchmarks/ompl_adapters.py, benchmarks/ompl_family.py)
and prints the trajectory and the tree in our format (SPEC 2, SPEC 5.4), so that
``rrt-validator -- python benchmarks/ompl_planner.py`` checks OMPL's answers and
the benchmark harness times whole processes alike. Spaceship and kinodynamic
family lines are re-propagated from the start with OMPL's controls (a kinodynamic
family answer's tree section is empty: the bindings give no edge controls).

Exit status: 0 solved, 2 bad usage or bad problem, 3 no solution within the
time limit, 4 the ``ompl`` package is not installed.

``-optimize`` (RRT* and Informed RRT*, for the point vehicle, arm2 and rigid2) keeps
improving until ``-time`` as our optimizing planners do; ``-stats`` then adds the best
cost and the first solution's time to the stats line, and a line
``ompl_planner progress: SECONDS:COST ...`` (one pair per improvement, the same
format as ``rrt_cli``'s).
"""

from __future__ import annotations

import argparse
import os
import random
import sys

try:
    from benchmarks import ompl_adapters, ompl_family
except ModuleNotFoundError:  # run as a script from a checkout that is not installed
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from benchmarks import ompl_adapters, ompl_family
from cli_common import (EXIT_USAGE, OneLineErrorParser, add_vehicle_flags, is_kinoplan,
                        parse_any_problem, positive_float, read_problem_from_stdin,
                        reject_vehicle_flags, vehicle_from_flags)
from planning_core.plan_text import format_plan

EXIT_SOLVED = 0
EXIT_NO_SOLUTION = 3
EXIT_NO_OMPL = 4
DEFAULT_TIME_LIMIT = 30.0
PLANNER_CHOICES = sorted(set(ompl_adapters.POINT_PLANNERS + ompl_adapters.SPACESHIP_PLANNERS
                             + ompl_family.KINODYNAMIC_PLANNERS
                             + ompl_family.GEOMETRIC_PLANNERS
                             + ompl_adapters.OPTIMIZING_PLANNERS))


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineErrorParser(prog="ompl_planner",
                     description="Plan with OMPL on a .sw problem read from stdin; print "
                                 "the trajectory and the tree on stdout.")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-planner", default="rrt", choices=PLANNER_CHOICES,
                        help="rrt (geometric or control), rrtconnect (point, arm2, rigid2), "
                             "kpiece1 (spaceship, kinodynamic family), prm (arm2, rigid2), "
                             "rrtstar and informed (point, arm2, rigid2); default rrt")
    parser.add_argument("-seed", type=int, default=None)
    parser.add_argument("-time", type=positive_float, default=DEFAULT_TIME_LIMIT, metavar="S")
    parser.add_argument("-stats", action="store_true",
                        help="print one line of key=value statistics on stderr")
    parser.add_argument("-optimize", action="store_true",
                        help="rrtstar, informed: keep improving the answer until -time")
    return parser


def _plan(parser, args, seed: int):
    """OMPL's result, the name of the vehicle or system and whether its rows end in
    K (a kinodynamic kinoplan system); None after one line on stderr."""
    problem = read_problem_from_stdin("ompl_planner", parse_any_problem)
    if problem is None:
        return None
    if is_kinoplan(problem):
        reject_vehicle_flags(parser, args)
        name, choices = problem.system_name, ompl_family.planners_for_system(problem.system)
    else:
        vehicle = vehicle_from_flags(parser, args)
        name, choices = vehicle.value, ompl_adapters.planners_for(vehicle)
    if args.planner not in choices:
        sys.stderr.write(f"ompl_planner: error: planner {args.planner!r} does not support "
                         f"the {name} {'system' if is_kinoplan(problem) else 'vehicle'}\n")
        return None
    if is_kinoplan(problem):
        return (ompl_family.solve_family(problem, args.planner, args.time, seed,
                                         optimize=args.optimize),
                name, problem.system.kinodynamic)
    return (ompl_adapters.solve(problem, vehicle, args.planner, args.time, seed,
                                optimize=args.optimize), name, False)


def say_stats(args, result, name: str, seed: int) -> None:
    """The stats line (as rrt_cli's: cost and first_solution_seconds "none" when
    unsolved or not known) and, with -optimize, the progress line."""
    status = "solved" if result.solved else "time_limit"
    cost = first = "none"
    if result.solved:
        first = (f"{result.improvements[0][0]:.6f}" if result.improvements
                 else f"{result.planning_seconds:.6f}")
        cost = f"{result.improvements[-1][1]:.9g}" if result.improvements else "none"
    sys.stderr.write(f"ompl_planner stats: status={status} planner=ompl-{args.planner} "
                     f"vehicle={name} seed={seed} iterations={result.iterations} "
                     f"tree_nodes={result.tree_nodes} "
                     f"planning_seconds={result.planning_seconds:.6f} cost={cost} "
                     f"first_solution_seconds={first}\n")
    if args.optimize and result.improvements:
        sys.stderr.write("ompl_planner progress: " + " ".join(
            f"{seconds:.6f}:{cost:.9g}" for seconds, cost in result.improvements) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.optimize and args.planner not in ompl_adapters.OPTIMIZING_PLANNERS:
        parser.error(f"-optimize works with -planner "
                     f"{' or '.join(ompl_adapters.OPTIMIZING_PLANNERS)}")
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(2 ** 31)
    try:
        found = _plan(parser, args, seed)
    except ImportError as error:
        sys.stderr.write(f"ompl_planner: the ompl package is not installed ({error}); "
                         "pip install ompl\n")
        return EXIT_NO_OMPL
    if found is None:
        return EXIT_USAGE
    result, name, ends_in_count = found
    if args.stats:
        say_stats(args, result, name, seed)
    if not result.solved:
        sys.stderr.write(f"ompl_planner: no solution ({result.status}) after "
                         f"{result.planning_seconds:.2f} s (seed {seed})\n")
        return EXIT_NO_SOLUTION
    sys.stdout.write(format_plan(result.trajectory, result.tree, ends_in_count))
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
