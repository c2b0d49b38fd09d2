"""What the project's command lines share (rrt_cli, validator, grading, benchmarks):
an argument parser whose errors are one usage line and one error line on stderr
with exit status 2 (never a traceback), with hints for the usual slips; the option
types (ASCII numbers only, ranges checked before any conversion); the course's
vehicle flags; writes to stdout and stderr that never raise (so never change an
exit status); the one bounded reader of the problem on stdin, and the reader of
either problem format (a ``.sw`` grid or a ``kinoplan 1`` problem).

Above planning_core, below every command line; a command line's own options stay in
its package. One module, as the planner imports it on every run.

argparse is imported only when a parser is made or an option value is bad
(:data:`OneLineErrorParser` is made on first use): the planner parses its common
command lines without it (argparse with gettext and locale is a large share of its
start-up: docs/setup-and-startup.md)."""

from __future__ import annotations

import math
import os
import sys
from types import SimpleNamespace

from planning_core.problem import Problem
from planning_core.problem_text import ProblemFormatError, parse_problem
from planning_core.vehicles import Vehicle

EXIT_USAGE = 2
MAX_COUNT = 2 ** 63 - 1
"""The largest integer option (an iteration limit)."""

_DECIMAL = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"

MAX_PROBLEM_BYTES = 64 * 1024 * 1024
"""The most bytes of problem read from stdin (the validator's cap on a planner's
output); a longer stdin is a bad problem, found after reading one byte past it."""
_READ_CHUNK = 1 << 20


# ----- writes that never raise ------------------------------------------------------


def _point_at_devnull(fd: int) -> None:
    """Make ``fd`` /dev/null (a closed or failing standard stream)."""
    try:
        null = os.open(os.devnull, os.O_RDWR)
        if null != fd:
            os.dup2(null, fd)
            os.close(null)
    except OSError:
        pass


def reserve_standard_fds() -> None:
    """Open /dev/null on any of fds 0-2 that is closed, so that no file or pipe the
    program opens later takes its number (a pipe on fd 2 would be inherited by a
    child as its stderr). ``sys.stdin``/``sys.stdout``/``sys.stderr`` stay None."""
    for fd in (0, 1, 2):
        try:
            os.fstat(fd)
        except OSError:
            _point_at_devnull(fd)


def say(line: str) -> None:
    """``line`` on stderr. Never raises, so never changes an exit status: a closed
    or full stderr is pointed at /dev/null, so the exit's flush cannot fail either."""
    stream = sys.stderr
    if stream is None:
        return
    try:
        stream.write(line + "\n")
        stream.flush()
    except (OSError, ValueError):
        _point_at_devnull(2)


def write_stdout(text: str) -> OSError | None:
    """Write ``text`` to stdout and flush: None when it is written, else the error
    (stdout closed, full, or its reader gone: a BrokenPipeError). A failed stdout is
    pointed at /dev/null, so the interpreter's exit flush cannot fail again."""
    stream = sys.stdout
    if stream is None:
        return OSError("stdout is closed")
    try:
        stream.write(text)
        stream.flush()
    except OSError as error:
        _point_at_devnull(1)
        return error
    except ValueError:  # the stream object was closed
        return OSError("stdout is closed")
    return None


def describe_os_error(error: OSError) -> str:
    return error.strerror or str(error) or type(error).__name__


# ----- the parser -------------------------------------------------------------------


def looks_like_problem_file(arg: str) -> bool:
    """An argument surely meant as the problem: a .sw name, or an existing file that
    is not executable (an executable is a planner: the validator's hint is then ``--``)."""
    return arg.endswith(".sw") or (os.path.isfile(arg) and not os.access(arg, os.X_OK))


def _terminal_columns() -> int:
    """shutil.get_terminal_size().columns without importing shutil."""
    columns = os.environ.get("COLUMNS", "")
    if columns.isascii() and columns.isdigit() and len(columns) <= 6 and int(columns) > 0:
        return int(columns)
    try:
        return os.get_terminal_size(sys.__stdout__.fileno()).columns or 80
    except (AttributeError, ValueError, OSError):
        return 80


def _make_parser_class():
    """:class:`OneLineErrorParser`, made on first use (see the module's doc)."""
    import argparse

    class _HelpFormatter(argparse.HelpFormatter):
        """argparse's layout and width, without argparse's import of shutil (and zlib,
        bz2, lzma with it): every add_argument makes a formatter, so every run paid it."""

        def __init__(self, prog, indent_increment=2, max_help_position=24, width=None, **more):
            width = _terminal_columns() - 2 if width is None else width
            super().__init__(prog, indent_increment, max_help_position, width, **more)


    class OneLineErrorParser(argparse.ArgumentParser):
        """``argparse`` with errors as ``usage: ...`` and ``NAME: error: ...``, exit 2; an
        unknown argument gets a hint (a near-miss option, a problem file given by name).
        ``name``: what the program's stderr lines start with (default: ``prog``, what
        the usage line says the user types)."""

        def __init__(self, *args, name: str | None = None, **kwargs):
            kwargs.setdefault("formatter_class", _HelpFormatter)
            super().__init__(*args, **kwargs)
            self.name = name or self.prog

        def error(self, message):
            say(self.format_usage().rstrip("\n"))
            say(f"{self.name}: error: {message}")
            raise SystemExit(EXIT_USAGE)

        def parse_args(self, args=None, namespace=None):
            parsed, extras = self.parse_known_args(args, namespace)
            if extras:
                self.reject_extras(extras)
            return parsed

        def reject_extras(self, extras: list[str], more_hints: tuple[str, ...] = ()) -> None:
            """argparse's "unrecognized arguments" error, with the hints in brackets."""
            hints = [*self.extras_hints(extras), *more_hints]
            suffix = f" ({'; '.join(hints)})" if hints else ""
            self.error(f"unrecognized arguments: {' '.join(extras)}{suffix}")

        def extras_hints(self, extras: list[str]) -> list[str]:
            hints = []
            for arg in extras:
                if arg.startswith("-") and len(arg) > 1:
                    near = self.near_miss(arg)
                    if near is not None:
                        hints.append(f"did you mean {near}?")
                elif looks_like_problem_file(arg):
                    hints.append(f"the problem is read from stdin: use < {arg}")
            return hints

        def near_miss(self, arg: str) -> str | None:
            """The option string closest to ``arg`` (difflib's default cutoff), or None."""
            import difflib  # only on this error path
            options = [s for action in self._actions for s in action.option_strings]
            close = difflib.get_close_matches(arg.split("=", 1)[0], options, n=1)
            return close[0] if close else None

    return OneLineErrorParser


def __getattr__(name: str):
    if name == "OneLineErrorParser":
        globals()[name] = parser_class = _make_parser_class()
        return parser_class
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ----- option types -----------------------------------------------------------------


def _show(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:37] + "...")


def _type_error(message: str) -> Exception:
    """argparse's ArgumentTypeError: its message is the whole error line's."""
    import argparse  # only for a bad value
    return argparse.ArgumentTypeError(message)


def positive_float(text: str) -> float:
    """An option value that must be a positive finite ASCII decimal (a time limit)."""
    import re  # only for a decimal option: a usual command line has none (re costs ms)
    if not re.fullmatch(_DECIMAL, text):
        raise _type_error(f"{_show(text)} is not a number")
    value = float(text)
    if not (value > 0 and math.isfinite(value)):
        raise _type_error(f"{_show(text)} must be a positive finite number")
    return value


def turning_radius(text: str) -> float:
    """The Dubins car's ``-radius``: a positive number within RADIUS_RANGE."""
    from planning_core.systems.dubins import RADIUS_RANGE  # only with -radius
    value = positive_float(text)
    low, high = RADIUS_RANGE
    if not low <= value <= high:
        raise _type_error(f"{_show(text)} is out of range: a turning radius is from {low:g} "
                          f"to {high:g} map units")
    return value


def bounded_integer(text: str, low: int, high: int, what: str) -> int:
    """An ASCII integer in [low, high]; its digits are counted before int() sees them."""
    unsigned = text[1:] if text[:1] in ("+", "-") else text
    if not (unsigned.isascii() and unsigned.isdigit()):  # [+-]?[0-9]+, without re
        raise _type_error(f"{_show(text)} is not an integer")
    digits = text.lstrip("+-").lstrip("0") or "0"
    if len(digits) <= len(str(high)):
        value = -int(digits) if text.startswith("-") else int(digits)
        if low <= value <= high:
            return value
    raise _type_error(f"{_show(text)} is out of range: {what}")


def positive_int(text: str) -> int:
    """A count (an iteration limit): an integer in [1, 2^63)."""
    return bounded_integer(text, 1, MAX_COUNT, "expected an integer in [1, 2^63)")


# ----- the usual command lines without argparse --------------------------------------


def quick_parse(argv: list[str], switches: tuple[str, ...], valued: dict,
                defaults: dict) -> SimpleNamespace | None:
    """What a parser with these options gives for ``argv`` when every word is an exact
    switch of ``switches``, or an exact option of ``valued`` (option: its type)
    followed by a valid value that does not start with ``-``; None for anything
    else (argparse decides, and words the errors). ``defaults``: every option's
    default, by its attribute name."""
    values = dict(defaults)
    words = iter(argv)
    for word in words:
        if word in switches:
            values[word[1:]] = True
        elif word in valued:
            text = next(words, None)
            if text is None or text.startswith("-"):
                return None
            try:
                values[word[1:]] = valued[word](text)
            except Exception:  # a bad value: argparse words the error
                return None
        else:
            return None
    return SimpleNamespace(**values)


class ParserOnError:
    """Stands in for the parser after :func:`quick_parse`: a usage error found later
    (e.g. -ugrad with -grad) makes the parser, with ``build``, for its usage line."""

    def __init__(self, build):
        self.build = build

    def error(self, message: str) -> None:
        self.build().error(message)


VEHICLE_SWITCHES = ("-ugrad", "-grad", "-left", "-dubins")
VEHICLE_DEFAULTS = {"ugrad": False, "grad": False, "left": False, "dubins": False,
                    "radius": None}
"""The vehicle flags for :func:`quick_parse` (``-radius`` takes :func:`turning_radius`)."""


# ----- vehicle flags ----------------------------------------------------------------


def add_switches(parser, switches: dict[str, str]) -> None:
    """On/off flags (false unless given), each with its help, in the order given."""
    for flag, help_text in switches.items():
        parser.add_argument(flag, action="store_true", help=help_text)


def add_vehicle_flags(parser: argparse.ArgumentParser, title: str) -> None:
    """The course's vehicle flags, spelled as the course spells them, and the Dubins car's."""
    group = parser.add_argument_group(title)
    add_switches(group, {
        "-ugrad": "point vehicle <x, y> moving straight (the default)",
        "-grad": "spaceship <x, y, dx, dy> with thrust <theta, s>",
        "-left": "spaceship that only thrusts ahead or left (implies -grad)",
        "-dubins": "Dubins car <x, y, heading>: forward only, turning radius -radius; "
                   "printed as its curves sampled at most 0.05 apart (point rows)"})
    group.add_argument("-radius", type=turning_radius, default=None, metavar="R",
                       help="with -dubins: the least turning radius in map units "
                            "(default: 0.5)")


def vehicle_from_flags(parser: OneLineErrorParser, args: argparse.Namespace) -> Vehicle:
    """The vehicle the -ugrad/-grad/-left/-dubins flags name; a contradiction, or
    -radius without -dubins, is a usage error."""
    if args.ugrad and (args.grad or args.left):
        parser.error("-ugrad cannot be combined with -grad or -left")
    if args.dubins and (args.ugrad or args.grad or args.left):
        parser.error("-dubins cannot be combined with -ugrad, -grad or -left")
    if args.radius is not None and not args.dubins:
        parser.error("-radius is the Dubins car's turning radius: it needs -dubins")
    if args.dubins:
        return Vehicle.DUBINS
    if args.left:
        return Vehicle.LEFT_SPACESHIP
    return Vehicle.SPACESHIP if args.grad else Vehicle.POINT


def vehicle_options(args: argparse.Namespace):
    """What ``planning_core.setups.grid_setup`` takes for the flags' vehicle: the
    Dubins car's radius; None for the others."""
    if not args.dubins:
        return None
    from planning_core.systems.dubins import DubinsOptions
    return DubinsOptions() if args.radius is None else DubinsOptions(args.radius)


def reject_vehicle_flags(parser: OneLineErrorParser, args: argparse.Namespace) -> None:
    """``-grad``, ``-ugrad``, ``-left``, ``-dubins``, ``-radius`` name a grid vehicle:
    with a kinoplan problem (its ``system`` line names the system) they are a usage
    error, exit 2."""
    given = [flag for flag in ("-ugrad", "-grad", "-left", "-dubins")
             if getattr(args, flag[1:])]
    given += ["-radius"] if args.radius is not None else []
    if given:
        parser.error(f"{' '.join(given)}: a kinoplan problem names its own system "
                     "(the vehicle flags are for .sw problems)")


# ----- the problem: on stdin, in either format -------------------------------------


def _read_capped(stream, cap: int) -> bytearray | None:
    """At most ``cap`` bytes of ``stream`` (None if there are more), in chunks, so
    memory stays within the cap whatever is on the other end."""
    data = bytearray()
    while True:
        chunk = stream.read(min(_READ_CHUNK, cap + 1 - len(data)))
        if not chunk:
            return data
        data += chunk
        if len(data) > cap:
            return None


def read_problem_text_from_stdin(prog: str, cap: int = MAX_PROBLEM_BYTES) -> str | None:
    """The text on stdin (UTF-8, undecodable bytes replaced); None after one
    ``PROG: ...`` line on stderr when it cannot be read or passes ``cap`` bytes (the
    caller exits 2). A terminal on stdin gets a one-line notice first."""
    stream = sys.stdin
    if stream is None:
        return ""  # stdin closed: an empty problem
    try:
        if stream.isatty():
            say(f"{prog}: reading the problem from stdin (end it with Ctrl-D)")
        raw = _read_capped(stream.buffer, cap)
    except OSError as error:
        say(f"{prog}: cannot read the problem from stdin: {describe_os_error(error)}")
        return None
    if raw is None:
        say(f"{prog}: bad problem: more than {cap} bytes on stdin (the cap is "
            f"{cap / 2 ** 20:g} MiB)")
        return None
    return raw.decode("utf-8", errors="replace")


def read_problem_from_stdin(prog: str, parse=None):
    """The problem on stdin, read by ``parse`` (default: the ``.sw`` reader;
    :func:`parse_any_problem` for either format); None after one ``PROG: ...`` line
    on stderr (a ``bad problem`` names the line and column; the caller exits 2)."""
    text = read_problem_text_from_stdin(prog)
    if text is None:
        return None
    try:
        return (parse or parse_problem)(text)
    except ProblemFormatError as error:
        say(f"{prog}: bad problem: {error}")
        return None


def parse_any_problem(text: str):
    """A ``.sw`` :class:`Problem` or, when the first word says ``kinoplan`` (SPEC 5),
    a :class:`~planning_core.kinoplan.KinoplanProblem`; ProblemFormatError if bad.
    The kinoplan reader is imported only for such a text (start-up of .sw runs)."""
    head = text.lstrip()[:1]
    if head and not (head.isdigit() or head in "+-"):
        from planning_core.kinoplan_text import looks_like_kinoplan, parse_kinoplan
        if looks_like_kinoplan(text):
            return parse_kinoplan(text)
    return parse_problem(text)


def is_kinoplan(problem) -> bool:
    """The problem is a ``kinoplan 1`` one (it carries its own system)."""
    return not isinstance(problem, Problem)
