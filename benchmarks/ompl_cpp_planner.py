"""OMPL in C++ as a peer command-line planner: same input, output and exit codes as
``rrt_cli`` and ``benchmarks/ompl_planner.py`` (OMPL's Python bindings).

    python -m benchmarks.ompl_cpp_planner [-grad] [-left]
        [-planner rrt|rrtconnect|prm|prmstar|rrtstar|informed|kpiece|sst] [-seed N]
        [-time S] [-stats]
        [-optimize] < problem

Reads a ``.sw`` or ``kinoplan 1`` problem on stdin, hands it as flat text to the C++
program of ``benchmarks/ompl_cpp/`` (built on first use: benchmarks/ompl_cpp_programs.py)
and passes its answer (SPEC 2, SPEC 5.4; no tree) to stdout, so that the validator and
the benchmark harness treat OMPL in C++ as they treat the other planners. ``-stats``
passes the program's stats line (planning time, tree size, iterations, cost, first
solution) to stderr and, with ``-optimize``, its progress line (each improvement's time
and cost, as ``rrt_cli``'s).

What plans for what: the point vehicle ``rrt``, ``rrtconnect``, ``prm``, ``prmstar``,
``rrtstar``, ``informed``; the ships ``rrt`` (control), ``kpiece`` and ``sst``; arm2 and
rigid2 ``rrt``, ``rrtconnect``, ``prm``, ``prmstar``, ``rrtstar``, ``informed``; the
kinodynamic family ``rrt`` (control), ``kpiece`` and ``sst``.
``-optimize`` applies to ``rrtstar``, ``informed`` and ``sst``.

Exit status: 0 solved, 2 bad usage or bad problem, 3 no solution within the time
limit, 4 the program could not be built (no g++ or no libompl-dev).
"""

from __future__ import annotations

import random
import subprocess
import sys

from cli_common import (EXIT_USAGE, OneLineErrorParser, ProblemFormatError, add_vehicle_flags,
                        is_kinoplan, parse_any_problem, positive_float,
                        read_problem_text_from_stdin, reject_vehicle_flags, say,
                        vehicle_from_flags)
from planning_core.vehicles import Vehicle

EXIT_NO_PROGRAM = 4
OPTIMIZING = ("rrtstar", "informed", "sst")
GRID_MODES = {
    Vehicle.POINT: {"rrt": "point", "rrtconnect": "rrtconnect", "prm": "prm",
                    "prmstar": "prmstar", "rrtstar": "rrtstar", "informed": "informed"},
    Vehicle.SPACESHIP: {"rrt": "ship", "kpiece": "kpiece", "sst": "sst"},
    Vehicle.LEFT_SPACESHIP: {"rrt": "left", "kpiece": "kpiece-left", "sst": "sst-left"},
}
"""grid_ompl's mode per vehicle and planner."""
FAMILY_PLANNERS = {True: ("rrt", "kpiece", "sst"),
                   False: ("rrt", "rrtconnect", "prm", "prmstar", "rrtstar", "informed")}
"""family_ompl's planners for a kinodynamic (True) or geometric system."""


def build_parser():
    parser = OneLineErrorParser(prog="ompl_cpp_planner",
                                description="Plan with OMPL in C++ on a problem read from "
                                            "stdin; print the answer on stdout.")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-planner", default="rrt",
                        choices=sorted({"rrt", "rrtconnect", "prm", "prmstar", "rrtstar",
                                        "informed", "kpiece", "sst"}))
    parser.add_argument("-seed", type=int, default=None)
    parser.add_argument("-time", type=positive_float, default=30.0, metavar="S")
    parser.add_argument("-stats", action="store_true",
                        help="print the program's stats line on stderr")
    parser.add_argument("-optimize", action="store_true",
                        help="rrtstar, informed, sst: keep improving until -time")
    return parser


def program_and_input(parser, args, text: str) -> tuple[str, str, bytes] | None:
    """(program name, mode, flat input) for the problem, or None after one line when
    the planner does not plan for it."""
    from benchmarks.ompl_cpp_programs import family_input, grid_input
    problem = parse_any_problem(text)
    if is_kinoplan(problem):
        reject_vehicle_flags(parser, args)
        kinodynamic = problem.system.kinodynamic
        if args.planner in FAMILY_PLANNERS[kinodynamic]:
            return "family_ompl", args.planner, family_input(text)
        what = f"the {problem.system_name} system"
    else:
        vehicle = vehicle_from_flags(parser, args)
        mode = GRID_MODES.get(vehicle, {}).get(args.planner)
        if mode is not None:
            return "grid_ompl", mode, grid_input(text)
        what = f"the {vehicle.value} vehicle"
    say(f"ompl_cpp_planner: error: planner {args.planner!r} does not plan for {what}")
    return None


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.optimize and args.planner not in OPTIMIZING:
        parser.error(f"-optimize works with -planner {', '.join(OPTIMIZING)}")
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(2 ** 31)
    text = read_problem_text_from_stdin("ompl_cpp_planner")
    if text is None:
        return EXIT_USAGE
    try:
        found = program_and_input(parser, args, text)
    except ProblemFormatError as error:
        say(f"ompl_cpp_planner: bad problem: {error}")
        return EXIT_USAGE
    if found is None:
        return EXIT_USAGE
    from benchmarks.ompl_cpp_programs import binary
    name, mode, flat = found
    program = binary(name)
    if program is None:
        say(f"ompl_cpp_planner: {name} could not be built (g++ and libompl-dev: "
            "apt-get install libompl-dev)")
        return EXIT_NO_PROGRAM
    done = subprocess.run([str(program), mode, repr(args.time), str(seed),
                           *(["optimize"] if args.optimize else [])],
                          input=flat, capture_output=True)
    for line in done.stderr.decode(errors="replace").splitlines():
        if args.stats or not line.startswith(("ompl_cpp stats:", "ompl_cpp progress:")):
            say(line)
    if done.returncode == 3:
        say(f"ompl_cpp_planner: no solution after {args.time:g} s (seed {seed})")
    sys.stdout.buffer.write(done.stdout)
    return done.returncode


if __name__ == "__main__":
    sys.exit(main())
