"""``rrt-grade``: grade every submission on every rubric item (problem x mode), each
as many times as the rubric repeats it; ``rrt-grade gradescope`` grades the
one submission of Gradescope's autograder layout.

    rrt-grade --submissions DIR --problems DIR --out DIR [--rubric FILE] [--modes ...]
              [--jobs N] [--timeout S] [--repeats N] [--format gradescope] [...]
    rrt-grade gradescope [--root /autograder] [--rubric FILE] [...]

Exit status: 0 grading completed (whatever the verdicts), 2 usage error, bad rubric or
bad problem, 3 another rrt-grade is grading into the same --out, 4 a bug of ours or a
lost cluster, 128+N stopped by signal N (rerun to resume).
"""

from __future__ import annotations

import argparse
import dataclasses
import signal
import sys
from pathlib import Path
from typing import Sequence

from cli_common import OneLineErrorParser, positive_float, positive_int, say, write_stdout
from grading.config import KINOPLAN, MODE_FLAGS, GradeConfig
from grading.grade import Busy, Outcome, grade
from grading.gradescope import RESULTS, write_class, write_results
from grading.html_report import write_html_report
from grading.progress import Progress
from grading.report import gradebook_rows, summary_table, write_gradebook, write_report
from grading.rubric import MAX_REPEATS, Rubric, RubricError, check_modes, load_rubric
from grading.scores import results
from grading.similar import similar_pairs


PROG = "rrt-grade"
USAGE = (f"{PROG} --submissions DIR --problems DIR --out DIR [--rubric FILE] "
         "[--modes point,grad,left] [--jobs N] [--timeout S] [--repeats N] "
         "[--format gradescope] [more: -h]")
GRADESCOPE_USAGE = (f"{PROG} gradescope [--root DIR] [--submission DIR] [--results FILE] "
                    "[--problems DIR] [--rubric FILE] [--out DIR] [more: -h]")
EXIT_BAD = 2
EXIT_BUSY = 3
EXIT_OURS = 4


def _modes(text: str) -> tuple[str, ...]:
    try:
        return check_modes([mode.strip() for mode in text.split(",") if mode.strip()])
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _weights(text: str) -> tuple[tuple[str, float], ...]:
    """``grad=2,left=3``: each mode's weight in the score."""
    pairs = []
    for item in filter(None, text.split(",")):
        mode, _, weight = item.partition("=")
        if mode not in (*MODE_FLAGS, KINOPLAN):
            raise argparse.ArgumentTypeError(f"unknown mode {mode!r}")
        pairs.append((mode, positive_float(weight)))
    return tuple(pairs)


def _repeats(text: str) -> int:
    value = positive_int(text)
    if value > MAX_REPEATS:
        raise argparse.ArgumentTypeError(f"at most {MAX_REPEATS}")
    return value


def add_grading_flags(parser: OneLineErrorParser) -> None:
    """The flags both commands share: the rubric and its shortcuts, the workers."""
    add = parser.add_argument
    add("--rubric", type=Path, metavar="FILE",
        help="a TOML rubric (docs/grading.md); the flags below set its top-level keys")
    add("--modes", type=_modes, help="the .sw problems' modes: comma-separated among point "
        "(no flag), grad (-grad), left (-grad -left); default all three")
    add("--weights", type=_weights, metavar="MODE=W,...",
        help="each mode's weight in the score (default 1 each; kinoplan: the .kp problems)")
    add("--timeout", type=positive_float, help="seconds per run (60)")
    add("--repeats", type=_repeats, metavar="N",
        help="runs of each problem and mode (1); its part of the score: the share valid")
    add("--scale", type=positive_float, help="the full score (100)")
    add("--jobs", type=positive_int, default=2, help="runs at once (default 2)")
    add("--build-timeout", type=positive_float, default=600.0,
        help="seconds for make.sh (600)")
    add("--rerun", action="store_true", help="redo every build and run")
    add("--no-sandbox", action="store_true", help="no namespaces (resource limits still)")
    add("--no-calibration", action="store_true",
        help="do not time our own planner on each item first")
    add("--progress-every", type=positive_float, default=10.0, metavar="S",
        help="when stderr is not a terminal: a progress line at least every S seconds (10)")


def build_parser() -> OneLineErrorParser:
    parser = OneLineErrorParser(prog=PROG, usage=USAGE, description=(
        "Build each submission (a folder with make.sh and run.sh) once, run it on every "
        "problem (.sw in each mode, .kp) as the rubric says, validate each run, store each "
        "result in OUT/grades.sqlite as it finishes (a rerun resumes), and write "
        "OUT/gradebook.csv, OUT/report.md and OUT/report.html. 'rrt-grade gradescope -h': "
        "Gradescope's autograder."))
    add = parser.add_argument
    add("--submissions", required=True, type=Path, metavar="DIR")
    add("--problems", required=True, type=Path, metavar="DIR", help="its *.sw and *.kp files")
    add("--out", required=True, type=Path, metavar="DIR")
    add_grading_flags(parser)
    add("--scheduler", metavar="ADDRESS", help="run on this Dask scheduler (tcp://HOST:PORT)")
    add("--format", choices=("gradescope",), action="append", default=[],
        help="also write OUT/gradescope/SUBMISSION/results.json (Gradescope's format)")
    return parser


def build_gradescope_parser() -> OneLineErrorParser:
    parser = OneLineErrorParser(prog=f"{PROG} gradescope", usage=GRADESCOPE_USAGE, description=(
        "Grade the one submission of Gradescope's autograder layout: ROOT/submission, "
        "problems in ROOT/source/problems, the rubric ROOT/source/rubric.toml when there is "
        "one; write ROOT/results/results.json."))
    add = parser.add_argument
    add("--root", type=Path, default=Path("/autograder"), metavar="DIR",
        help="the autograder's folder (/autograder)")
    add("--submission", type=Path, metavar="DIR", help="(ROOT/submission)")
    add("--results", type=Path, metavar="FILE", help="(ROOT/results/results.json)")
    add("--problems", type=Path, metavar="DIR", help="(ROOT/source/problems)")
    add("--out", type=Path, metavar="DIR", help="the grading's own files (ROOT/rrt-grade)")
    add_grading_flags(parser)
    return parser


def _check_folders(parser: OneLineErrorParser, args, folders: tuple[str, ...]) -> None:
    for flag in folders:
        path = getattr(args, flag)
        if not path.is_dir():
            parser.error(f"--{flag} {path}: not a folder")
    if args.out.exists() and not args.out.is_dir():
        parser.error(f"--out {args.out}: not a folder")
    if getattr(args, "scheduler", None):
        try:
            import distributed  # noqa: F401  (optional: the grade extra)
        except ImportError:
            parser.error("--scheduler needs Dask's distributed: pip install -e '.[grade]'")


def _rubric(args) -> Rubric:
    """The rubric file's (or the default), with the flags given setting its top-level keys;
    RubricError for a file that cannot be used."""
    rubric = load_rubric(args.rubric) if args.rubric else Rubric()
    shortcuts = {"modes": args.modes, "mode_weights": args.weights, "timeout": args.timeout,
                 "repeats": args.repeats, "scale": args.scale}
    return dataclasses.replace(rubric, **{name: value for name, value in shortcuts.items()
                                          if value is not None})


def _config(args, rubric: Rubric, submissions: Path, **more) -> GradeConfig:
    return GradeConfig(submissions.resolve(), args.problems.resolve(), args.out.resolve(),
                       rubric=rubric, jobs=args.jobs, build_timeout=args.build_timeout,
                       rerun=args.rerun, sandbox=not args.no_sandbox,
                       calibrate=not args.no_calibration, **more)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["gradescope"]:
        return gradescope_main(argv[1:])
    parser = build_parser()
    args = parser.parse_args(argv)
    _check_folders(parser, args, ("submissions", "problems"))
    try:
        rubric = _rubric(args)
    except RubricError as error:
        say(f"{PROG}: error: {error}")
        return EXIT_BAD
    config = _config(args, rubric, args.submissions, scheduler=args.scheduler,
                     formats=tuple(args.format))
    outcome = _grade(config, args)
    if isinstance(outcome, int):
        return outcome
    return _finish(config, outcome)


def _grade(config: GradeConfig, args) -> Outcome | int:
    """The outcome, or the exit status after one line (bad problem or rubric, busy)."""
    try:
        return grade(config, Progress(sys.stderr, every=args.progress_every))
    except ValueError as error:  # a bad problem or rubric: nothing was run
        say(f"{PROG}: error: {error}")
        return EXIT_BAD
    except Busy as error:
        say(f"{PROG}: error: {error}")
        return EXIT_BUSY


def _finish(config: GradeConfig, outcome: Outcome) -> int:
    graded = results(config, outcome)
    rows = gradebook_rows(graded)
    write_gradebook(config.out, rows)
    pairs = similar_pairs(config.submissions, graded.graded) if len(graded.graded) > 1 else []
    write_report(graded, pairs)
    write_html_report(graded, pairs)
    if "gradescope" in config.formats:
        write_class(graded)
    notes = {row["sandbox"] for row in outcome.runs if row.get("sandbox")}
    say(f"{PROG}: {outcome.runs_done} runs now, {outcome.runs_kept} kept; "
        f"{outcome.builds_done} builds now, {outcome.builds_kept} kept; "
        f"{len(pairs)} similar pairs to look at; "
        f"sandbox: {'; '.join(sorted(notes)) or 'none'}; wrote {config.out}")
    failure = write_stdout(summary_table(rows))
    return 0 if failure is None else EXIT_OURS


def gradescope_main(argv: list[str]) -> int:
    """``rrt-grade gradescope``: the submission of Gradescope's layout to results.json."""
    parser = build_gradescope_parser()
    args = parser.parse_args(argv)
    root = args.root
    args.submission = args.submission or root / "submission"
    args.problems = args.problems or root / "source" / "problems"
    args.out = args.out or root / "rrt-grade"
    args.results = args.results or root / "results" / RESULTS
    if args.rubric is None and (root / "source" / "rubric.toml").is_file():
        args.rubric = root / "source" / "rubric.toml"
    _check_folders(parser, args, ("submission", "problems"))
    if args.submission.is_symlink():  # as each submission of a class: not followed
        parser.error(f"--submission {args.submission}: a symbolic link, not a folder")
    try:
        rubric = _rubric(args)
    except RubricError as error:
        say(f"{PROG}: error: {error}")
        return EXIT_BAD
    submission = args.submission.resolve()
    config = _config(args, rubric, submission.parent, names=(submission.name,))
    outcome = _grade(config, args)
    if isinstance(outcome, int):
        return outcome
    graded = results(config, outcome)
    write_results(args.results, graded, graded.graded[0])
    write_report(graded, [])
    write_html_report(graded, [])
    say(f"{PROG}: wrote {args.results}")
    return 0 if write_stdout(summary_table(gradebook_rows(graded))) is None else EXIT_OURS


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
