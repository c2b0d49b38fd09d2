"""``./run.sh`` (``python -m rrt_cli``): read a problem on stdin, print a trajectory and
the motion tree.

The problem is a `.sw` grid (SPEC 1, its first word an integer) or a ``kinoplan 1``
problem (SPEC 5, its first word ``kinoplan``): then its ``system`` line names the
system and the vehicle flags are a usage error. A planner plans for the kinds of
system (geometric, kinodynamic) its registry line names (``rrt_cli.planners``), and
``-smooth`` shortens a geometric system's path.

Exit status: 0 solved, 1 the answer could not be written (stdout closed, full or
its reader gone), 2 bad usage or bad problem, 3 no solution within the limits (or
the goal is certainly unreachable), 130 interrupted (Ctrl-C, one line). Writes to
stderr never change the status.

The usual command lines (exact option names, valid values) are read without
argparse (:func:`quick_parse`, a start-up saving); argparse reads every other one
and words its errors and help.
"""

from __future__ import annotations

import random
import sys
from types import SimpleNamespace

import cli_common
from cli_common import (EXIT_USAGE, add_vehicle_flags, bounded_integer, describe_os_error,
                        is_kinoplan, parse_any_problem, positive_float, positive_int,
                        read_problem_from_stdin, reject_vehicle_flags, reserve_standard_fds,
                        say, turning_radius, vehicle_from_flags, vehicle_options,
                        write_stdout)
from planning_core.plan_text import format_plan
from planning_core.problem_definition import Objective
from planning_core.setups import grid_setup, kinoplan_setup
from rrt_cli.planners import PLANNERS
from rrt_cli.planners.base import OUT_OF_MEMORY_MESSAGE, PlanStatus, StopCondition

EXIT_SOLVED = 0
EXIT_OUTPUT_FAILED = 1
EXIT_NO_SOLUTION = 3
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT), as shells report it
DEFAULT_TIME_LIMIT = 30.0
DEFAULT_ITERATIONS = 5_000_000
DEFAULT_PLANNER = "rrt"
SEED_LIMIT = 2 ** 64
"""Seeds are integers in [0, SEED_LIMIT): random.Random(-n) would equal Random(n)."""


def seed(text: str) -> int:
    """A random seed: an integer in [0, 2^64)."""
    return bounded_integer(text, 0, SEED_LIMIT - 1, "a seed is an integer in [0, 2^64)")


def build_parser() -> cli_common.OneLineErrorParser:
    parser = cli_common.OneLineErrorParser(
        prog="./run.sh", name="rrt_cli",
        description="Plan for a problem read from stdin (a .sw grid map, or a kinoplan 1 "
                    "problem); print the trajectory and the motion tree on stdout.",
        epilog="Exit status: 0 solved, 1 the answer could not be written to stdout, "
               "2 bad usage or bad problem, 3 no solution within the limits, 130 interrupted "
               "(Ctrl-C).")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-planner", default=DEFAULT_PLANNER, choices=sorted(PLANNERS),
                        help="planning algorithm (default: rrt)")
    parser.add_argument("-seed", type=seed, default=None, metavar="N",
                        help="random seed, an integer in [0, 2^64); the same seed gives the "
                             "same output byte for byte")
    parser.add_argument("-time", type=positive_float, default=DEFAULT_TIME_LIMIT,
                        metavar="S",
                        help=f"time limit in seconds, set-up included (default: "
                             f"{DEFAULT_TIME_LIMIT:g})")
    parser.add_argument("-iterations", type=positive_int, default=DEFAULT_ITERATIONS,
                        metavar="N", help=f"iteration limit (default: {DEFAULT_ITERATIONS})")
    parser.add_argument("-smooth", action="store_true",
                        help="geometric systems (point vehicle, arm2, rigid2): shorten the "
                             "solution by shortcuts (off by default)")
    parser.add_argument("-optimize", action="store_true",
                        help="optimizing planners (sst, rrtstar, informed): keep improving "
                             "the answer's cost until -time, then print the best found")
    parser.add_argument("-cost", type=positive_float, default=None, metavar="C",
                        help="with an optimizing planner: stop as soon as the cost is at "
                             "most C (implies -optimize)")
    parser.add_argument("-stats", action="store_true",
                        help="print one line of key=value statistics on stderr")
    return parser


def _known_planner(name: str) -> str:
    if name not in PLANNERS:
        raise ValueError(name)
    return name


_SWITCHES = (*cli_common.VEHICLE_SWITCHES, "-smooth", "-stats", "-optimize")
_VALUED = {"-planner": _known_planner, "-seed": seed, "-time": positive_float,
           "-iterations": positive_int, "-cost": positive_float, "-radius": turning_radius}
_DEFAULTS = {**cli_common.VEHICLE_DEFAULTS, "smooth": False, "stats": False,
             "optimize": False, "cost": None, "planner": DEFAULT_PLANNER, "seed": None,
             "time": DEFAULT_TIME_LIMIT, "iterations": DEFAULT_ITERATIONS}


def quick_parse(argv: list[str]) -> SimpleNamespace | None:
    """What ``build_parser().parse_args(argv)`` gives when every word is an exact
    option name or a valid value of one; None for anything else (argparse decides)."""
    return cli_common.quick_parse(argv, _SWITCHES, _VALUED, _DEFAULTS)


def parse_command_line(argv: list[str] | None):
    """The options and the parser (or its stand-in) for later usage errors."""
    args = quick_parse(sys.argv[1:] if argv is None else argv)
    if args is not None:
        return args, cli_common.ParserOnError(build_parser)
    parser = build_parser()
    return parser.parse_args(argv), parser


def _setup(parser, args, entry):
    """The problem on stdin as a :class:`~planning_core.setups.Setup` and the name of
    its system or vehicle; None after one line on stderr (exit 2)."""
    vehicle = vehicle_from_flags(parser, args)
    if args.smooth and vehicle.system.kinodynamic:
        parser.error("-smooth works on geometric systems only (the point vehicle, arm2, rigid2)")
    if (args.optimize or args.cost is not None) and not entry.optimizing:
        optimizing = " or ".join(name for name, e in sorted(PLANNERS.items()) if e.optimizing)
        say(f"rrt_cli: error: planner {args.planner!r} stops at its first solution; "
            f"-optimize and -cost work with -planner {optimizing}")
        return None
    flags_given = args.ugrad or args.grad or args.left or args.dubins
    if flags_given and not entry.plans_for(vehicle.system):  # refused before reading stdin
        say(f"rrt_cli: error: planner {args.planner!r} does not support the "
            f"{vehicle.value} vehicle")
        return None
    problem = read_problem_from_stdin("rrt_cli", parse_any_problem)
    if problem is None:
        return None
    if is_kinoplan(problem):
        reject_vehicle_flags(parser, args)
        if args.smooth and problem.system.kinodynamic:
            parser.error("-smooth works on geometric systems only")
        name = problem.system_name
        if not entry.plans_for_kinoplan(problem.system):
            say(f"rrt_cli: error: planner {args.planner!r} does not plan for kinoplan "
                f"problems of the {name} system ({_kinoplan_planners(problem.system)})")
            return None
        return kinoplan_setup(problem), name
    if not entry.plans_for(vehicle.system):
        say(f"rrt_cli: error: planner {args.planner!r} does not support the "
            f"{vehicle.value} vehicle")
        return None
    return grid_setup(problem, vehicle.value, vehicle_options(args)), vehicle.value


def _kinoplan_planners(system) -> str:
    names = [name for name, entry in sorted(PLANNERS.items()) if entry.plans_for_kinoplan(system)]
    return "use -planner " + " or ".join(names) if names else "no planner does yet"


def main(argv: list[str] | None = None) -> int:
    args, parser = parse_command_line(argv)
    entry = PLANNERS[args.planner]
    found = _setup(parser, args, entry)
    if found is None:
        return EXIT_USAGE
    setup, vehicle_name = found

    run_seed = args.seed if args.seed is not None else random.SystemRandom().randrange(2 ** 63)
    rng = random.Random(run_seed)
    planner = entry.load()
    stop = StopCondition(time_limit=args.time, max_iterations=args.iterations)
    pdef = setup.pdef
    if args.optimize or args.cost is not None:
        pdef = pdef.with_objective(Objective(args.cost or 0.0))
    result = planner.solve(setup.si, pdef, stop, rng, planner.Params())
    if args.smooth and result.solved:
        from rrt_cli.smoothing import smooth_path  # only with -smooth: start-up
        result = result.with_path(smooth_path(setup.si, result.path, rng), result.path_controls)
    stats = result.stats
    if args.stats:
        say_stats(setup.si, result, f"planner={args.planner} vehicle={vehicle_name} "
                                    f"seed={run_seed}")
        from planning_core.kernels import describe  # only with -stats: start-up
        say(f"rrt_cli kernels: {describe(setup)}")
        if stats.improvements:
            say("rrt_cli progress: " + " ".join(f"{seconds:.6f}:{cost:.9g}"
                                                for seconds, cost in stats.improvements))
    if result.status is PlanStatus.OUT_OF_MEMORY:
        say(f"rrt_cli: out of memory: {result.message} (after "
            f"{stats.planning_seconds:.2f} s, seed {run_seed})")
        return EXIT_NO_SOLUTION
    if not result.solved:
        detail = f": {result.message}" if result.message else ""
        say(f"rrt_cli: no solution ({result.status.value}{detail}) after "
            f"{stats.iterations} iterations, {stats.planning_seconds:.2f} s "
            f"(seed {run_seed})")
        return EXIT_NO_SOLUTION
    failure = write_stdout(format_plan(result.trajectory, result.tree,
                                       ends_in_count=setup.rows_end_in_count))
    if failure is None:
        return EXIT_SOLVED
    if not isinstance(failure, BrokenPipeError):  # a reader that left (| head) wants no note
        say(f"rrt_cli: cannot write the answer to stdout: {describe_os_error(failure)}")
    return EXIT_OUTPUT_FAILED


def say_stats(si, result, names: str) -> None:
    """The -stats line: key=value pairs, stable for scripts (the benchmark harness
    parses it); cost and first_solution_seconds are "none" without a solution. (An
    optimizing run adds a line ``rrt_cli progress: SECONDS:COST ...``, one pair per
    better solution found, after the kernels' line.)"""
    stats = result.stats
    cost = first = "none"
    if result.solved:
        from planning_core.costs import path_cost
        cost = f"{path_cost(si, result.path, result.path_controls):.9g}"
        seconds = stats.first_solution_seconds
        first = f"{stats.planning_seconds if seconds is None else seconds:.6f}"
    say(f"rrt_cli stats: status={result.status.name.lower()} {names} "
        f"iterations={stats.iterations} tree_nodes={stats.tree_nodes} "
        f"planning_seconds={stats.planning_seconds:.6f} cost={cost} "
        f"first_solution_seconds={first}")


def entry_point() -> None:
    reserve_standard_fds()
    try:
        status = main()
    except KeyboardInterrupt:
        say("rrt_cli: interrupted")
        status = EXIT_INTERRUPTED
    except MemoryError:  # reading a huge problem, or printing a huge answer
        say(f"rrt_cli: out of memory: {OUT_OF_MEMORY_MESSAGE}")
        status = EXIT_NO_SOLUTION
    except SystemExit as done:  # -h, or a usage error
        status = done.code
    if status == EXIT_SOLVED and write_stdout("") is not None:  # e.g. -h into a full stdout
        status = EXIT_OUTPUT_FAILED
    raise SystemExit(status)


if __name__ == "__main__":
    entry_point()
