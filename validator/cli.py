"""``rrt-validator``: run a planner on a problem and check its answer (SPEC 3).

    rrt-validator [-ugrad | -grad] [-left] [-strict] [-noviz] [-o FILE] [-timeout S]
                  [-json] -- PLANNER [ARGS...] < problem.sw

argv -> problem (stdin) -> run_planner -> checks -> verdict text or JSON on
stdout, the PDF with render_pdf. Exit status: 0 valid, 1 invalid, 2 usage error
or bad problem, 3 the planner could not be started or timed out (4: a bug of ours).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import stat
import sys
from typing import Sequence

from planning_core.cli_args import (OneLineErrorParser, add_vehicle_flags, positive_float,
                                    read_problem_from_stdin, vehicle_from_flags)
from planning_core.problem import Problem
from planning_core.problem_text import format_problem
from planning_core.vehicles import Vehicle
from validator.checks import (CHECK_NAMES, CHECK_TITLES, INVALID_VERDICT, CheckResult,
                              ValidationReport, validate_output)
from validator.run_planner import DEFAULT_OUTPUT_CAP, DEFAULT_TIMEOUT, PlannerRun, run_planner

EXIT_VALID = 0
EXIT_INVALID = 1
EXIT_USAGE = 2
EXIT_PLANNER_FAILED = 3
EXIT_INTERNAL_ERROR = 4  # a validator bug: no verdict could be given
DEFAULT_PDF = "tree-viz.pdf"
PROG = "rrt-validator"


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineErrorParser(
        prog=PROG,
        usage=f"{PROG} [-ugrad | -grad] [-left] [-strict] [-noviz] [-o FILE] [-timeout S] "
              "[-json] -- PLANNER [ARGS...] < problem.sw",
        description="Read a .sw problem on stdin, run PLANNER ARGS (everything after --) "
                    "with the problem on its stdin, check the trajectory it prints "
                    "(SPEC 3, checks 1-7), print the verdict and draw the tree in a PDF.",
        epilog="Exit status: 0 valid, 1 invalid, 2 usage error or bad problem, "
               "3 the planner could not be started or timed out.")
    add_vehicle_flags(parser, "vehicle (default: point vehicle)")
    parser.add_argument("-strict", action="store_true",
                        help="a point segment cutting a blocked cell's corner between the "
                             "0.05 samples is a failure, not a warning")
    parser.add_argument("-noviz", action="store_true", help="do not write the PDF")
    parser.add_argument("-o", metavar="FILE", default=DEFAULT_PDF,
                        help=f"the PDF to write (default: {DEFAULT_PDF})")
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
    status = ("not applicable" if not applicable else "not run" if result is None
              else "passed" if result.passed else "failed")
    return {"number": number, "name": CHECK_NAMES[number - 1], "title": CHECK_TITLES[number - 1],
            "status": status, "passed": bool(result and result.passed),
            "message": result.message if result else "",
            "detail": result.detail if result else "",
            "line": result.line if result else None}


def report_json(vehicle: Vehicle, strict: bool, report: ValidationReport | None,
                run: PlannerRun, exit_status: int, pdf: str | None) -> dict:
    by_number = {check.number: check for check in report.checks} if report else {}
    checks = [_check_json(n, by_number.get(n), n <= 6 or vehicle.is_spaceship)
              for n in range(1, 8)]
    failure = report.first_failure if report else None
    return {
        "verdict": ("planner failed" if report is None
                    else "valid" if report.valid else "invalid"),
        "verdict_line": report.verdict if report else INVALID_VERDICT,
        "valid": bool(report and report.valid),
        "exit_status": exit_status,
        "vehicle": vehicle.value,
        "strict": strict,
        "checks": checks,
        "first_failure": _check_json(failure.number, failure, True) if failure else None,
        "first_failing_line": failure.line if failure else None,
        "warnings": list(report.warnings) if report else [],
        "counts": {"trajectory": report.trajectory_count if report else None,
                   "tree": report.tree_count if report else None,
                   "corner_cuts": len(report.corner_cuts) if report else None},
        "path_length": report.path_length if report else None,
        "planner": {"command": list(run.command), "started": run.started,
                    "start_error": run.start_error or None, "exit_code": run.exit_code,
                    "signal": run.signal, "timed_out": run.timed_out,
                    "wall_time": round(run.wall_time, 6), "output_bytes": len(run.output),
                    "output_cap_exceeded": run.output_cap_exceeded},
        "solver_messages": solver_messages(run),
        "pdf": pdf,
    }


def _write_pdf(path: str, problem: Problem, vehicle: Vehicle, report: ValidationReport | None,
               verdict: str, notes: list[str], label: str) -> bool:
    # Imported here: reportlab costs a few hundred ms and -noviz runs never need it.
    from validator.render_pdf import render_pdf
    try:
        with open(path, "wb") as out:
            render_pdf(out, problem, vehicle, report, verdict, notes, label)
    except OSError as error:
        sys.stderr.write(f"{PROG}: cannot write the PDF {path}: {error.strerror or error}\n")
        return False
    except Exception as error:  # a drawing bug must not cost the grader the verdict
        sys.stderr.write(f"{PROG}: could not draw the PDF {path}: {error!r}\n")
        return False
    return True


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if "--" in argv:
        split = argv.index("--")
        own, command = argv[:split], argv[split + 1:]
    else:
        own, command = argv, []
    parser = build_parser()
    args = parser.parse_args(own)  # -h prints the help and exits 0
    vehicle = vehicle_from_flags(parser, args)
    if not command:
        parser.error("no planner: put the planner's command after --, e.g. "
                     f"{PROG} -grad -- ./run.sh -grad < problem.sw")
    if not args.noviz:
        folder = os.path.dirname(args.o) or "."
        if os.path.isdir(args.o) or not os.path.isdir(folder) or not os.access(folder, os.W_OK):
            parser.error(f"-o {args.o}: cannot write a file there")

    problem = read_problem_from_stdin(PROG)
    if problem is None:
        return EXIT_USAGE
    label = _stdin_label()

    run = run_planner(command, format_problem(problem).encode("ascii"), timeout=args.timeout,
                      output_cap=DEFAULT_OUTPUT_CAP)
    messages = solver_messages(run)
    report: ValidationReport | None = None
    if run.ran_to_completion:
        text = decode_output(run.output)
        report = validate_output(problem, vehicle, text, strict=args.strict,
                                 output_cap_exceeded=run.output_cap if run.output_cap_exceeded
                                 else None)
        del text
        status = EXIT_VALID if report.valid else EXIT_INVALID
        verdict = report.verdict
    else:
        status, verdict = EXIT_PLANNER_FAILED, INVALID_VERDICT

    pdf = None
    if not args.noviz:
        if _write_pdf(args.o, problem, vehicle, report, verdict, messages, label):
            pdf = args.o

    if args.json:
        sys.stdout.write(json.dumps(report_json(vehicle, args.strict, report, run, status, pdf),
                                    allow_nan=False) + "\n")
    else:
        out = "".join(f"{message}\n" for message in messages)
        out += report_text(report) if report is not None else f"{verdict}\n"
        sys.stdout.write(out)
    sys.stdout.flush()
    summary = [f"planner {run.wall_time:.3f} s"]
    if report is not None and report.plan is not None:
        summary.append(f"{report.trajectory_count} trajectory lines, {report.tree_count} "
                       "tree edges")
    if report is not None and report.path_length is not None:
        summary.append(f"path length {report.path_length:.6g}")
    if pdf:
        summary.append(f"wrote {pdf}")
    sys.stderr.write(f"{PROG}: " + "; ".join(summary) + "\n")
    return status


def _terminate(signum, frame):
    # Unwinds through run_planner, which kills the planner's process group.
    raise SystemExit(128 + signum)


def entry_point() -> None:
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _terminate)
    # Whatever a planner printed may be echoed in a message: never fail on encoding it.
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.reconfigure(errors="backslashreplace")
        except (AttributeError, ValueError):
            pass
    try:
        status = main()
    except KeyboardInterrupt:
        status = 130
    except BrokenPipeError:
        # The reader went away (e.g. `| head`); nothing left to say.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # no second error at the exit's flush
        status = EXIT_INVALID
    except Exception as error:  # a bug of ours: say so in one line, not the planner's fault
        sys.stderr.write(f"{PROG}: internal error, please report it: {error!r}\n")
        status = EXIT_INTERNAL_ERROR
    raise SystemExit(status)


if __name__ == "__main__":
    entry_point()
