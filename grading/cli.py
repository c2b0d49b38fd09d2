"""``rrt-grade``: grade every submission on every problem in every mode (issue 18).

    rrt-grade --submissions DIR --problems DIR --out DIR [--modes point,grad,left]
              [--jobs N] [--timeout S] [--scheduler ADDRESS] [--rerun]

Exit status: 0 grading completed (whatever the verdicts), 2 usage error, 3 another
rrt-grade is grading into the same --out, 4 a bug of ours or a lost cluster, 128+N
stopped by signal N (rerun to resume).
"""

from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path
from typing import Sequence

from cli_common import OneLineErrorParser, positive_float, positive_int, say, write_stdout
from grading.config import MODE_FLAGS, GradeConfig, ScoreRule
from grading.grade import Busy, Outcome, grade
from grading.report import gradebook_rows, summary_table, write_gradebook, write_report

PROG = "rrt-grade"
USAGE = (f"{PROG} --submissions DIR --problems DIR --out DIR [--modes point,grad,left] "
         "[--jobs N] [--timeout S] [--scheduler ADDRESS] [--rerun] [more: -h]")
EXIT_BUSY = 3
EXIT_OURS = 4


def _modes(text: str) -> tuple[str, ...]:
    modes = tuple(mode.strip() for mode in text.split(",") if mode.strip())
    bad = [mode for mode in modes if mode not in MODE_FLAGS]
    if bad or not modes or len(set(modes)) != len(modes):
        raise argparse.ArgumentTypeError(f"expected distinct modes among {','.join(MODE_FLAGS)}")
    return modes


def _weights(text: str) -> tuple[tuple[str, float], ...]:
    """``grad=2,left=3``: each mode's weight in the score."""
    pairs = []
    for item in filter(None, text.split(",")):
        mode, _, weight = item.partition("=")
        if mode not in MODE_FLAGS:
            raise argparse.ArgumentTypeError(f"unknown mode {mode!r}")
        pairs.append((mode, positive_float(weight)))
    return tuple(pairs)


def build_parser() -> OneLineErrorParser:
    parser = OneLineErrorParser(prog=PROG, usage=USAGE, description=(
        "Build each submission (a folder with make.sh and run.sh) once, run it on every "
        "problem in every mode through the validator, store each result in "
        "OUT/grades.sqlite as it finishes (a rerun resumes), and write "
        "OUT/gradebook.csv and OUT/report.md."))
    add = parser.add_argument
    add("--submissions", required=True, type=Path, metavar="DIR")
    add("--problems", required=True, type=Path, metavar="DIR", help="its *.sw files")
    add("--out", required=True, type=Path, metavar="DIR")
    add("--modes", type=_modes, default=("point", "grad", "left"),
        help="comma-separated among point (no flag), grad (-grad), left (-grad -left)")
    add("--jobs", type=positive_int, default=2, help="runs at once (default 2)")
    add("--timeout", type=positive_float, default=60.0, help="seconds per run (60)")
    add("--build-timeout", type=positive_float, default=600.0,
        help="seconds for make.sh (600)")
    add("--scheduler", metavar="ADDRESS", help="run on this Dask scheduler (tcp://HOST:PORT)")
    add("--rerun", action="store_true", help="redo every build and run")
    add("--no-sandbox", action="store_true", help="no namespaces (resource limits still)")
    add("--weights", type=_weights, default=(), metavar="MODE=W,...",
        help="each mode's weight in the score (default 1 each)")
    add("--scale", type=positive_float, default=100.0, help="the full score (100)")
    return parser


def _check_folders(parser: OneLineErrorParser, args) -> None:
    for flag in ("submissions", "problems"):
        if not getattr(args, flag).is_dir():
            parser.error(f"--{flag} {getattr(args, flag)}: not a folder")
    if args.out.exists() and not args.out.is_dir():
        parser.error(f"--out {args.out}: not a folder")
    if args.scheduler:
        try:
            import distributed  # noqa: F401  (optional: the grade extra)
        except ImportError:
            parser.error("--scheduler needs Dask's distributed: pip install -e '.[grade]'")


class _Bar:
    """A progress bar on stderr when it is a terminal."""

    def __init__(self) -> None:
        self.shown = sys.stderr is not None and sys.stderr.isatty()

    def __call__(self, done: int, total: int, row: dict) -> None:
        if self.shown:
            filled = 30 * done // max(total, 1)
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {done}/{total} "
                             f"{row['submission'][:20]:20}")
            sys.stderr.write("\n" if done == total else "")
            sys.stderr.flush()


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(list(sys.argv[1:] if argv is None else argv))
    _check_folders(parser, args)
    config = GradeConfig(args.submissions.resolve(), args.problems.resolve(),
                         args.out.resolve(), modes=args.modes, jobs=args.jobs,
                         timeout=args.timeout, build_timeout=args.build_timeout,
                         scheduler=args.scheduler, rerun=args.rerun,
                         sandbox=not args.no_sandbox,
                         score=ScoreRule(weights=args.weights, scale=args.scale))
    try:
        outcome = grade(config, _Bar())
    except ValueError as error:  # a bad problem: nothing was run
        say(f"{PROG}: error: {error}")
        return 2
    except Busy as error:
        say(f"{PROG}: error: {error}")
        return EXIT_BUSY
    return _finish(config, outcome)


def _finish(config: GradeConfig, outcome: Outcome) -> int:
    rows = gradebook_rows(config, outcome.runs)
    write_gradebook(config, rows)
    write_report(config, outcome.runs, outcome.builds)
    notes = {row["sandbox"] for row in outcome.runs if row.get("sandbox")}
    say(f"{PROG}: {outcome.runs_done} runs now, {outcome.runs_kept} kept; "
        f"{outcome.builds_done} builds now, {outcome.builds_kept} kept; "
        f"sandbox: {'; '.join(sorted(notes)) or 'none'}; wrote {config.out}")
    failure = write_stdout(summary_table(rows))
    return 0 if failure is None else EXIT_OURS


def _terminate(signum, frame):
    raise SystemExit(128 + signum)


def entry_point() -> None:
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _terminate)
    try:
        status = main()
    except KeyboardInterrupt:
        say(f"{PROG}: interrupted; rerun the same command to resume")
        status = 130
    except SystemExit as done:
        status = done.code
        if isinstance(status, int) and status > 128:
            say(f"{PROG}: stopped by signal {status - 128}; rerun the same command to resume")
    except Exception as error:
        say(f"{PROG}: error: {error!r}")
        status = EXIT_OURS
    raise SystemExit(status)


if __name__ == "__main__":
    entry_point()
