"""``rrt-validator``: run a planner on a problem and check its answer (SPEC 3).

    rrt-validator [-ugrad | -grad] [-left] [-strict] [-noviz] [-o FILE] [-timeout S]
                  [-json] -- PLANNER [ARGS...] < problem.sw (or problem.kp)

A ``kinoplan 1`` problem (SPEC 5, first word ``kinoplan``) names its own system:
the vehicle flags are then a usage error, the checks are SPEC 5.5's, and the PDF
has the family's pages (render_kinodynamic, render_geometric).

argv -> problem (stdin) -> the planner started, then the checks imported and the
problem's set-up made while it runs -> checks -> verdict text or JSON on stdout,
the picture with render_output (-o's extension picks PDF, HTML view, SVG or PNG; a
writer is imported only to draw one). Exit status: 0 valid,
1 invalid, 2 usage error, bad problem or a PDF that could not be written, 3 the
planner could not be started or timed out, 4 no verdict could be given (stdout
closed or full, or a bug of ours), 130 interrupted (Ctrl-C, one line). Writes to
stderr never change the status.
"""

from __future__ import annotations

import os
import _signal as signal  # signal's C module: no enums to make before the planner starts
import stat
import sys
from collections.abc import Sequence

from cli_common import (EXIT_USAGE, VEHICLE_DEFAULTS, VEHICLE_SWITCHES, ParserOnError,
                        add_vehicle_flags, describe_os_error, is_kinoplan,
                        looks_like_problem_file, parse_any_problem, positive_float,
                        quick_parse, read_problem_text_from_stdin, reject_vehicle_flags,
                        reserve_standard_fds, say, turning_radius, vehicle_from_flags,
                        vehicle_options, write_stdout)
from planning_core.problem import Problem
from planning_core.problem_text import ProblemFormatError, format_problem
from planning_core.vehicles import Vehicle
from validator import launched
from validator.run_planner import (DEFAULT_OUTPUT_CAP, DEFAULT_TIMEOUT, PlannerRun,
                                   StartedPlanner, start_planner)

# What the verdict needs beyond reading the problem and starting the planner (the
# checks, the problem's set-up) is imported while the planner runs: see main().
EXIT_VALID = 0
EXIT_INVALID = 1
EXIT_PLANNER_FAILED = 3
EXIT_NO_VERDICT = 4  # no verdict could be given: stdout failed, or a validator bug
EXIT_INTERNAL_ERROR = EXIT_NO_VERDICT
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT), as shells report it
DEFAULT_PDF = "tree-viz.pdf"
PROG = "rrt-validator"


def build_parser():
    """The argparse parser: -h, and every command line :func:`quick_parse` leaves."""
    from cli_common import OneLineErrorParser
    parser = OneLineErrorParser(
        prog=PROG,
        usage=f"{PROG} [-ugrad | -grad | -dubins [-radius R]] [-left] [-strict] [-noviz] "
              "[-o FILE] [-timeout S] [-json] -- PLANNER [ARGS...] < problem.sw",
        description="Read a problem on stdin (a .sw grid map, or a kinoplan 1 problem), run "
                    "PLANNER ARGS (everything after --) with the problem on its stdin, check "
                    "the trajectory it prints (SPEC 3, checks 1-7; kinoplan: SPEC 5.5), print "
                    "the verdict and draw the tree in a picture (PDF, HTML view, SVG or PNG).",
        epilog="Exit status: 0 valid, 1 invalid, 2 usage error, bad problem or unwritable "
               "PDF, 3 the planner could not be started or timed out, 4 no verdict "
               "could be given, 130 interrupted (Ctrl-C).")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-strict", action="store_true",
                        help="a point segment cutting a blocked cell's corner between the "
                             "0.05 samples is a failure, not a warning")
    parser.add_argument("-noviz", action="store_true", help="do not write the picture")
    parser.add_argument("-o", metavar="FILE", default=DEFAULT_PDF,
                        help=f"the picture to write, its format by the extension: .pdf, .html "
                             f"(a view for the browser), .svg or .png (default: {DEFAULT_PDF})")
    parser.add_argument("-timeout", metavar="S", type=positive_float, default=DEFAULT_TIMEOUT,
                        help=f"kill the planner's process group after S seconds "
                             f"(default: {DEFAULT_TIMEOUT:g}); exit status 3")
    parser.add_argument("-json", action="store_true",
                        help="print one JSON object instead of the verdict text")
    return parser


def _stdin_label() -> str:
    """The problem file's name when stdin is redirected from one (for the PDF title)."""
    try:
        if stat.S_ISREG(os.fstat(0).st_mode):
            return os.path.basename(os.readlink("/proc/self/fd/0"))
    except OSError:
        pass
    return "stdin"


def decode_output(data: bytes) -> str:
    """UTF-8 when it is; otherwise Latin-1, which decodes any bytes at one char each."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def solver_messages(run: PlannerRun) -> list[str]:
    """What happened to the planner, in the course tool's words where it had them."""
    if not run.started:
        return [f"Could not start solver: {run.start_error}."]
    if run.timed_out:
        return [f"Solver timed out after {run.timeout:g} s; its process group was killed."]
    messages = []
    if run.exit_code:
        messages.append(f"Solver returned non-zero exit code {run.exit_code}.")
    if run.signal:
        messages.append(f"Solver killed by signal {run.signal}.")
    if run.output_cap_exceeded:
        messages.append(f"Solver output passed the cap of {run.output_cap} bytes; the solver "
                        "was stopped.")
    return messages


def report_text(report: ValidationReport) -> str:
    lines = [f"Warning: {warning}" for warning in report.warnings]
    failure = report.first_failure
    if failure is not None:
        lines.append(failure.message)
        if failure.detail:
            lines.append(f"  {failure.detail}")
    lines.append(report.verdict)
    return "\n".join(lines) + "\n"


def _check_json(number: int, result: CheckResult | None, applicable: bool) -> dict:
    from validator.checks import CHECKS
    status = ("not applicable" if not applicable else "not run" if result is None
              else "passed" if result.passed else "failed")
    check = CHECKS[number - 1]
    return {"number": number, "name": check.name, "title": check.title,
            "status": status, "passed": bool(result and result.passed),
            "message": result.message if result else "",
            "detail": result.detail if result else "",
            "line": result.line if result else None}


def report_json(vehicle: Vehicle | str, strict: bool, report: ValidationReport | None,
                run: PlannerRun, exit_status: int, pdf: str | None,
                kinodynamic: bool | None = None) -> dict:
    """The JSON object; ``vehicle`` is a Vehicle, or a kinoplan system's name with
    ``kinodynamic`` saying whether check 7 applies."""
    from validator.checks import CHECKS, INVALID_VERDICT
    directed = False
    if isinstance(vehicle, Vehicle):
        kinodynamic = vehicle.is_spaceship
        directed = getattr(vehicle.system, "directed", False)
    by_number = {check.number: check for check in report.checks} if report else {}
    checks = [_check_json(n, by_number.get(n), check.applies(bool(kinodynamic), directed))
              for n, check in enumerate(CHECKS, 1)]
    failure = report.first_failure if report else None
    return {
        "verdict": ("planner failed" if report is None
                    else "valid" if report.valid else "invalid"),
        "verdict_line": report.verdict if report else INVALID_VERDICT,
        "valid": bool(report and report.valid),
        "exit_status": exit_status,
        "vehicle": getattr(vehicle, "value", vehicle),
        "strict": strict,
        "checks": checks,
        "first_failure": _check_json(failure.number, failure, True) if failure else None,
        "first_failing_line": failure.line if failure else None,
        "warnings": list(report.warnings) if report else [],
        "counts": {"trajectory": report.trajectory_count if report else None,
                   "tree": report.tree_count if report else None,
                   "corner_cuts": len(report.corner_cuts) if report else None},
        "path_length": report.path_length if report else None,
        "cost": report.cost if report else None,
        "cost_kind": report.cost_kind if report and report.cost is not None else None,
        "planner": {"command": list(run.command), "started": run.started,
                    "start_error": run.start_error or None, "exit_code": run.exit_code,
                    "signal": run.signal, "timed_out": run.timed_out,
                    "wall_time": round(run.wall_time, 6), "output_bytes": len(run.output),
                    "output_cap_exceeded": run.output_cap_exceeded,
                    "started_by": "launcher" if run.launched else "validator"},
        "solver_messages": solver_messages(run),
        "pdf": pdf,
    }


def _output_path_problem(path: str) -> str | None:
    """Why ``-o path`` cannot be written, found before the planner runs, or None. An
    existing file is opened for writing (not truncated); for a missing one, a file of
    our own unique name is made in its folder and removed, as the PDF is written
    there and renamed: the target's name itself is never created nor removed (two
    validators checking the same -o at once do not race)."""
    if not path:
        return "the file name is empty"
    if os.path.isdir(path):
        return "it is a folder"
    try:
        if os.path.exists(path):
            # Non-blocking: a FIFO without a reader fails (ENXIO) instead of hanging.
            os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
        else:  # missing, or a symlink to a missing file: its target's folder
            probe = os.path.join(os.path.dirname(os.path.realpath(path)),
                                 f".rrt-validator-probe.{os.getpid()}.{os.urandom(8).hex()}")
            os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
            os.unlink(probe)
    except OSError as error:
        return describe_os_error(error)
    return None


def _write_picture(path: str, problem: Problem, vehicle: Vehicle,
                   report: ValidationReport | None, verdict: str, notes: list[str],
                   label: str) -> bool:
    """Draw the picture into ``path`` in the format its extension names: True when
    written. A drawing bug is one line on stderr and False (it must not cost the
    grader the verdict); a file that cannot be written raises OSError (exit status 2)."""
    # Imported here: reportlab costs a few hundred ms and -noviz runs never need it.
    from validator.render_output import FORMATS, picture_format, write_picture
    extension = picture_format(path)
    try:
        # Each writer writes a temporary file beside the path and renames it.
        write_picture(path, extension, problem, vehicle, report, verdict, notes, label)
    except OSError:
        raise
    except Exception as error:
        say(f"{PROG}: could not draw the {FORMATS[extension]} {path}: {error!r}")
        return False
    return True


def planner_stderr_note(run: PlannerRun) -> list[str]:
    """For the picture of a planner that failed: the last lines it wrote on stderr
    (its reason), control characters shown escaped, each cut to 240 characters."""
    if not (run.exit_code or run.signal or run.timed_out) or not run.stderr_tail:
        return []
    lines = [line.strip() for line in decode_output(run.stderr_tail).splitlines()]
    shown = [line.encode("ascii", "backslashreplace").decode() for line in lines if line][-2:]
    return [f"Its stderr ends: {line[:240]}" for line in shown]


def _separator_hint(argv: list[str], extras: list[str]) -> tuple[str, ...]:
    """Without ``--``, an argument we do not know that is no problem file is most
    likely the planner: show the command with ``--`` put before it."""
    planner = next((arg for arg in extras
                    if not arg.startswith("-") and not looks_like_problem_file(arg)), None)
    if planner is None:
        return ()
    import shlex  # only on this error path
    at = argv.index(planner)
    suggestion = shlex.join([PROG, *argv[:at], "--", *argv[at:]])
    return (f"the planner's command goes after --: {suggestion} < problem.sw",)


_SWITCHES = (*VEHICLE_SWITCHES, "-strict", "-noviz", "-json")
_VALUED = {"-radius": turning_radius, "-o": str, "-timeout": positive_float}
_DEFAULTS = {**VEHICLE_DEFAULTS, "strict": False, "noviz": False, "json": False,
             "o": DEFAULT_PDF, "timeout": DEFAULT_TIMEOUT}


def _parse_command_line(argv: list[str]):
    """Our flags, the vehicle, the planner's command and the parser (or its stand-in:
    the usual command lines are read without argparse, a start-up saving); a usage
    error exits 2."""
    has_separator = "--" in argv
    split = argv.index("--") if has_separator else len(argv)
    own, command = argv[:split], argv[split + 1:]
    args = quick_parse(own, _SWITCHES, _VALUED, _DEFAULTS) if has_separator else None
    if args is None:
        parser = build_parser()
        args, extras = parser.parse_known_args(own)  # -h prints the help and exits 0
        if extras:
            parser.reject_extras(extras,
                                 () if has_separator else _separator_hint(argv, extras))
    else:
        parser = ParserOnError(build_parser)
    vehicle = vehicle_from_flags(parser, args)
    if not command:
        parser.error("no planner: put the planner's command after --, e.g. "
                     f"{PROG} -grad -- ./run.sh -grad < problem.sw")
    if not args.noviz:
        _check_picture_path(parser, args.o)
    return args, vehicle, command, parser


def _check_picture_path(parser, path: str) -> None:
    """A usage error (exit 2) unless ``path`` names a format we write, this machine
    can draw it and the file can be written; found before the planner runs."""
    from validator.render_output import FORMATS, known_formats, missing_tool, picture_format
    extension = picture_format(path)
    if extension is None:
        parser.error(f"-o {path!r}: unknown picture format {os.path.splitext(path)[1]!r}: "
                     f"use one of {known_formats()}")
    missing = missing_tool(extension)
    if missing is not None:
        say(f"{PROG}: {missing}")
        raise SystemExit(EXIT_USAGE)
    why = _output_path_problem(path)
    if why is not None:
        parser.error(f"-o {path!r}: cannot write the {FORMATS[extension]} there ({why})")


def _validate(run: PlannerRun, setup, strict: bool, drawn: bool
              ) -> tuple[ValidationReport | None, int, str]:
    """The report (None when the planner did not run to the end), status, verdict.
    Not ``drawn`` (-noviz), the tree's rows are checked and counted, not kept."""
    from validator.checks import INVALID_VERDICT, Limits, validate_plan
    if not run.ran_to_completion:
        return None, EXIT_PLANNER_FAILED, INVALID_VERDICT
    limits = Limits() if drawn else Limits(max_tree_rows_kept=0)
    report = validate_plan(setup, decode_output(run.output), strict=strict, limits=limits,
                           output_cap_exceeded=run.output_cap if run.output_cap_exceeded
                           else None)
    return report, EXIT_VALID if report.valid else EXIT_INVALID, report.verdict


def _summary(run: PlannerRun, report: ValidationReport | None, pdf: str | None) -> str:
    summary = [f"planner {run.wall_time:.3f} s"]
    if report is not None and report.plan is not None:
        summary.append(f"{report.trajectory_count} trajectory lines, {report.tree_count} "
                       "tree edges")
    if report is not None and report.path_length is not None:
        summary.append(f"path length {report.path_length:.6g}")
    if pdf:
        summary.append(f"wrote {pdf}")
    return f"{PROG}: " + "; ".join(summary)


def _read_problem(parser, args):
    """``(problem, its text for the planner)``, or None after one line on stderr (a
    bad problem: exit 2); vehicle flags with a kinoplan problem are a usage error."""
    given = launched.problem()  # the launcher's sealed copy of stdin, if it read it
    text = read_problem_text_from_stdin(PROG) if given is None else given.decode(
        "utf-8", errors="replace")
    if text is None:
        return None
    try:
        problem = parse_any_problem(text)
    except ProblemFormatError as error:
        say(f"{PROG}: bad problem: {error}")
        return None
    if is_kinoplan(problem):
        reject_vehicle_flags(parser, args)
        # The reader accepts ASCII only: the text goes to the planner as it came.
        return problem, text.encode("ascii")
    return problem, format_problem(problem).encode("ascii")


def _setup(problem, vehicle: Vehicle, args):
    """The problem's Setup (what the checks take), with the checks imported and
    prepared (:func:`validator.checks.prepare`): the validator's own heavy part,
    done while the planner runs."""
    from planning_core.setups import grid_setup, kinoplan_setup
    from validator.checks import prepare
    if is_kinoplan(problem):
        setup = kinoplan_setup(problem)
    else:
        setup = grid_setup(problem, vehicle, vehicle_options(args))
    prepare(setup)
    return setup


def _run(command: list[str], problem_bytes: bytes, timeout: float, prepare):
    """The planner's run and ``prepare()``'s value: the planner is started first,
    ``prepare`` runs while it does (the timeout counts both), and on any exception
    the planner and everything it started are killed."""
    started = (launched.take_over(command, problem_bytes, timeout, DEFAULT_OUTPUT_CAP)
               or start_planner(command, problem_bytes, timeout=timeout,
                                output_cap=DEFAULT_OUTPUT_CAP))
    if not isinstance(started, StartedPlanner):  # it could not be started
        return started, prepare()
    try:
        prepared = _ctrl_c_after(prepare)
    except BaseException:
        started.stop()
        raise
    return started.finish(), prepared


def _ctrl_c_after(work):
    """``work()``, a Ctrl-C meanwhile taken when it returns: CPython remembers a
    KeyboardInterrupt raised inside ``exec`` of a string (how dataclasses and
    namedtuple make their methods, at import) and ends the process by SIGINT at exit,
    not with our status 130."""
    if not hasattr(signal, "pthread_sigmask"):
        return work()
    held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        return work()
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    args, vehicle, command, parser = _parse_command_line(argv)
    found = _read_problem(parser, args)
    if found is None:
        return EXIT_USAGE
    problem, problem_bytes = found
    kinoplan = is_kinoplan(problem)
    label = _stdin_label()

    run, setup = _run(command, problem_bytes, args.timeout,
                      lambda: _setup(problem, vehicle, args))
    messages = solver_messages(run)
    report, status, verdict = _validate(run, setup, args.strict, not args.noviz)

    pdf = None
    if not args.noviz:
        try:
            if _write_picture(args.o, problem, vehicle, report, verdict,
                              messages + planner_stderr_note(run), label):
                pdf = args.o
        except OSError as error:
            from validator.render_output import FORMATS, picture_format
            say(f"{PROG}: cannot write the {FORMATS[picture_format(args.o)]} {args.o}: "
                f"{describe_os_error(error)}")
            status = EXIT_USAGE

    if args.json:
        import json  # only for -json
        shown = problem.system_name if kinoplan else vehicle
        out = json.dumps(report_json(shown, args.strict, report, run, status, pdf,
                                     setup.system.kinodynamic), allow_nan=False) + "\n"
    else:
        out = "".join(f"{message}\n" for message in messages)
        out += report_text(report) if report is not None else f"{verdict}\n"
    failure = write_stdout(out)
    if failure is not None:
        if not isinstance(failure, BrokenPipeError):  # a reader that left wants no note
            say(f"{PROG}: cannot write the verdict to stdout: {describe_os_error(failure)}")
        return EXIT_NO_VERDICT
    say(_summary(run, report, pdf))
    return status


def _terminate(signum, frame):
    # Unwinds through _run, which kills the planner's process group.
    raise SystemExit(128 + signum)


def entry_point() -> None:
    reserve_standard_fds()
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _terminate)
    # Whatever a planner printed may be echoed in a message: never fail on encoding it.
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.reconfigure(errors="backslashreplace")
        except (AttributeError, ValueError):
            pass
    try:
        try:
            status = main()
        finally:
            launched.discard()  # the launcher's planner, when the validator did not run it
    except KeyboardInterrupt:  # Ctrl-C: _run has killed the planner's group
        say(f"{PROG}: interrupted")
        status = EXIT_INTERRUPTED
    except SystemExit as done:  # -h, a usage error, or a signal (_terminate)
        status = done.code
    except Exception as error:  # a bug of ours: say so in one line, not the planner's fault
        say(f"{PROG}: internal error, please report it: {error!r}")
        status = EXIT_NO_VERDICT
    if status == EXIT_VALID and write_stdout("") is not None:  # e.g. -h into a full stdout
        status = EXIT_NO_VERDICT
    raise SystemExit(status)


if __name__ == "__main__":
    entry_point()
