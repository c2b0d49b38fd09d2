"""What every command line of the project shares: an argument parser whose errors
are one usage line and one error line on stderr with exit status 2 (never a
traceback), and the number types its options take."""

from __future__ import annotations

import argparse
import math
import sys

from planning_core.problem import Problem
from planning_core.problem_text import ProblemFormatError, parse_problem
from planning_core.vehicles import Vehicle

EXIT_USAGE = 2


class OneLineErrorParser(argparse.ArgumentParser):
    """``argparse`` with errors as ``usage: ...`` and ``PROG: error: ...``, exit 2."""

    def error(self, message):
        self.print_usage(sys.stderr)
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(EXIT_USAGE)


def positive_float(text: str) -> float:
    """An option value that must be a positive finite number (a time limit)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive finite number")
    return value


def add_vehicle_flags(parser: argparse.ArgumentParser, title: str) -> None:
    """The course's vehicle flags, spelled as the course spells them."""
    group = parser.add_argument_group(title)
    group.add_argument("-ugrad", action="store_true",
                       help="point vehicle <x, y> moving straight (the default)")
    group.add_argument("-grad", action="store_true",
                       help="spaceship <x, y, dx, dy> with thrust <theta, s>")
    group.add_argument("-left", action="store_true",
                       help="spaceship that only thrusts ahead or left (implies -grad)")


def vehicle_from_flags(parser: OneLineErrorParser, args: argparse.Namespace) -> Vehicle:
    """The vehicle the -ugrad/-grad/-left flags name; a contradiction is a usage error."""
    if args.ugrad and (args.grad or args.left):
        parser.error("-ugrad cannot be combined with -grad or -left")
    if args.left:
        return Vehicle.LEFT_SPACESHIP
    return Vehicle.SPACESHIP if args.grad else Vehicle.POINT


def read_problem_from_stdin(prog: str) -> Problem | None:
    """The ``.sw`` problem on stdin; None after one ``PROG: bad problem: ...`` line
    on stderr (the caller exits 2). A terminal on stdin gets a one-line notice."""
    if sys.stdin.isatty():
        sys.stderr.write(f"{prog}: reading the problem from stdin (end it with Ctrl-D)\n")
    raw = sys.stdin.buffer.read()
    try:
        return parse_problem(raw.decode("utf-8", errors="replace"))
    except ProblemFormatError as error:
        sys.stderr.write(f"{prog}: bad problem: {error}\n")
        return None
