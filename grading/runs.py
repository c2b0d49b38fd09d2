"""The kinds of task, run in a worker (a local process or a Dask worker): build a
submission; run one submission on one problem in one mode (one repeat) and validate
the answer with the validator's own functions; time our own planner on a problem
and mode (the calibration). Each returns its row for the store."""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import os
import shutil
import tempfile
import threading
from pathlib import Path
from typing import Iterator

from grading.config import GradeConfig, Limits
from grading.problems import GradedProblem, read_problem
from grading.rubric import Item
from grading.sandbox import Place, Sandbox, probe
from validator.checks import ValidationReport, validate_plan
from validator.cli import decode_output, solver_messages
from validator.run_planner import PlannerRun, run_planner

# run_planner's sweep assumes no other thread of the process starts processes
# meanwhile: a Dask worker with several threads runs its tasks one at a time.
_ONE_AT_A_TIME = threading.Lock()


def sandbox_here(wanted: bool) -> Sandbox:
    """This worker's sandbox, probed once per process (a cluster's machines may differ)."""
    with _ONE_AT_A_TIME:
        return _probe_once(wanted)


_probe_once = functools.lru_cache(maxsize=2)(probe)


def _place(config: GradeConfig, sandbox: Sandbox, submission: str, build: bool) -> Place:
    """A build works on a copy of the submission, kept as ``config.built`` when it
    succeeds; a run sees that through an overlay. Without namespaces both work in the
    submission's own folder."""
    folder = config.submissions.resolve() / submission  # a link there is refused, not followed
    built = config.built(submission)
    if not sandbox.namespaces:
        return Place(folder, folder)
    return Place(folder, folder if build else built.resolve(),
                 built.parent.resolve() if build else None,
                 hide=(config.out.resolve(), config.submissions.resolve()))


@contextlib.contextmanager
def _private_tmp(config: GradeConfig, sandbox: Sandbox) -> Iterator[Path | None]:
    """TMPDIR without namespaces: a folder of its own under OUT/tmp, removed after."""
    if sandbox.namespaces:
        yield None
        return
    scratch = config.out / "tmp"
    scratch.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=scratch) as tmp:
        yield Path(tmp)


def _contained(config: GradeConfig, sandbox: Sandbox, place: Place, program: list[str],
               log: Path, stdin: bytes, limits: Limits, timeout: float) -> PlannerRun:
    """``program`` run in its place through the validator's machinery, its stderr (up to
    the cap) into ``log``."""
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "wb") as sink, _private_tmp(config, sandbox) as tmp, \
            sandbox.identity() as identity, _ONE_AT_A_TIME:
        command = sandbox.command(dataclasses.replace(place, tmp=tmp), program, limits,
                                  timeout, identity)
        return run_planner(command, stdin, timeout=timeout, output_cap=limits.output_bytes,
                           stderr_cap=limits.stderr_bytes, stderr_fd=sink.fileno())


def _drop_if_empty(log: Path) -> str | None:
    """The log's path, or None (and no file) when nothing was written."""
    if log.exists() and log.stat().st_size == 0:
        log.unlink()
    return str(log) if log.exists() else None


def build_one(config: GradeConfig, submission: str) -> dict:
    """Run the submission's make.sh once in its folder; the ``builds`` row."""
    sandbox = sandbox_here(config.sandbox)
    log = config.out / "logs" / submission / "make.log"
    row = {"submission": submission, "log": str(log), "sandbox": sandbox.note}
    if not (config.submissions / submission / "make.sh").is_file():
        return {**row, "ok": 0, "reason": "no make.sh", "log": None}
    if sandbox.namespaces:  # what an earlier build left (grading/jail.py: _keep)
        built = config.built(submission)
        for stale in (built, built.with_name(f".{submission}.partial")):
            shutil.rmtree(stale, ignore_errors=True)
        built.parent.mkdir(parents=True, exist_ok=True)
    run = _contained(config, sandbox, _place(config, sandbox, submission, build=True),
                     ["sh", "-c", "exec ./make.sh >&2"], log, b"", config.build_limits,
                     config.build_timeout)
    reason = _build_failure(run, log)
    return {**row, "ok": int(not reason), "reason": reason, "exit_status": run.exit_code,
            "wall_time": round(run.wall_time, 6), "log": _drop_if_empty(log)}


def _build_failure(run: PlannerRun, log: Path) -> str:
    """Why the build failed, with the log's last line; '' when it did not."""
    if not run.started:
        return f"make.sh could not be started: {run.start_error}"
    if run.timed_out:
        why = f"make.sh timed out after {run.timeout:g} s"
    elif run.signal is not None:
        why = f"make.sh killed by signal {run.signal}"
    elif run.exit_code:
        why = f"make.sh exited {run.exit_code}"
    else:
        return ""
    lines = log.read_text(errors="replace").split("\n") if log.exists() else []
    last = next((line.strip() for line in reversed(lines) if line.strip()), "")
    return f"{why}: {last[:200]}" if last else why


def failed_build_row(submission: str, item: Item, repeat: int, build: dict) -> dict:
    """The row of a run that was not attempted: its submission did not build."""
    return {"submission": submission, "problem": item.problem, "mode": item.mode,
            "repeat": repeat, "verdict": "build failed", "valid": 0, "failed_check": "build",
            "message": build.get("reason") or "the build failed", "sandbox": build.get("sandbox"),
            "log": build.get("log")}


LOST = "rrt-grade's worker died during this {}, twice (the second time running alone)"


def lost_build_row(config: GradeConfig, submission: str) -> dict:
    """The ``builds`` row of a build whose worker died under it."""
    return {"submission": submission, "ok": 0, "reason": LOST.format("build")}


def lost_run_row(config: GradeConfig, submission: str, item: Item, repeat: int) -> dict:
    """The ``runs`` row of a run whose worker died under it."""
    return {"submission": submission, "problem": item.problem, "mode": item.mode,
            "repeat": repeat, "verdict": "planner failed", "valid": 0,
            "failed_check": "planner", "message": LOST.format("run")}


def lost_calibration_row(config: GradeConfig, item: Item) -> dict:
    """The ``calibration`` row of our planner's run whose worker died under it."""
    return {"problem": item.problem, "mode": item.mode, "verdict": "planner failed",
            "valid": 0}


def run_stem(item: Item, repeat: int) -> str:
    """The name of a run's log and PDF: ``PROBLEM-MODE``, and ``-N`` for repeat N > 1."""
    stem = f"{Path(item.problem).stem}-{item.mode}"
    return f"{stem}-{repeat + 1}" if repeat else stem


def run_one(config: GradeConfig, submission: str, item: Item, repeat: int) -> dict:
    """Run ``./run.sh`` with the mode's flags on the problem, validate; the ``runs`` row."""
    sandbox = sandbox_here(config.sandbox)
    problem = read_problem(config.problems / item.problem)
    stem = run_stem(item, repeat)
    log = config.out / "logs" / submission / f"{stem}.stderr"
    run = _contained(config, sandbox, _place(config, sandbox, submission, build=False),
                     ["./run.sh", *problem.flags(item.mode)], log, problem.stdin,
                     config.limits, item.timeout)
    report = _validated(run, problem, item.mode)
    row = {"submission": submission, "problem": item.problem, "mode": item.mode,
           "repeat": repeat, "exit_status": run.exit_code, "signal": run.signal,
           "timed_out": int(run.timed_out), "wall_time": round(run.wall_time, 6),
           "output_bytes": len(run.output), "output_sha256": _digest(run.output),
           "sandbox": sandbox.note, "log": _drop_if_empty(log), **_verdict(run, report)}
    if not row["valid"]:
        row.update(_draw(config.out, submission, stem, problem, item.mode, report,
                         solver_messages(run)))
    return row


def _validated(run: PlannerRun, problem: GradedProblem, mode: str) -> ValidationReport | None:
    """The validator's report on what the run printed; None when it did not run to its end."""
    if not run.ran_to_completion:
        return None
    return validate_plan(problem.setup(mode), decode_output(run.output), output_cap_exceeded=(
        run.output_cap if run.output_cap_exceeded else None))


def _digest(output: bytes) -> str | None:
    """The SHA-256 of a run's stdout (which runs printed the very same bytes)."""
    return hashlib.sha256(output).hexdigest() if output else None


OUR_PLANNER = Path(__file__).resolve().parents[1] / "run.sh"
CALIBRATION_SEED = "1"


def calibrate_one(config: GradeConfig, item: Item) -> dict:
    """Our own planner (this checkout's ``run.sh``, a fixed seed) on the item, outside the
    sandbox, under the item's time limit; the ``calibration`` row: its wall time is what
    each submission's time on the item is compared with."""
    problem = read_problem(config.problems / item.problem)
    command = [str(OUR_PLANNER), "-seed", CALIBRATION_SEED, *problem.flags(item.mode)]
    with open(os.devnull, "wb") as sink, _ONE_AT_A_TIME:
        run = run_planner(command, problem.stdin, timeout=item.timeout,
                          output_cap=config.limits.output_bytes, stderr_fd=sink.fileno())
    verdict = _verdict(run, _validated(run, problem, item.mode))
    return {"problem": item.problem, "mode": item.mode, "verdict": verdict["verdict"],
            "valid": verdict["valid"], "wall_time": round(run.wall_time, 6),
            "command": " ".join(command[1:])}


def _verdict(run: PlannerRun, report: ValidationReport | None) -> dict:
    """The verdict columns of a run's row."""
    if report is None:
        return {"verdict": "planner failed", "valid": 0, "failed_check": "planner",
                "message": " ".join(solver_messages(run))}
    failure = report.first_failure
    plan = report.plan
    return {"verdict": "valid" if report.valid else "invalid", "valid": int(report.valid),
            "failed_check": failure.name if failure else None,
            "message": failure.message if failure else None,
            "detail": failure.detail if failure else None,
            "path_length": report.path_length,
            "trajectory_size": report.trajectory_count if plan is not None else None,
            "tree_size": report.tree_count if plan is not None else None}


PICTURES = (("pdf", "pdf", ".pdf"), ("view", "html", ".html"))
"""A failing run's pictures: its row's column, its folder in ``--out`` (then
``SUBMISSION/STEM``), its format (validator.render_output's extension)."""


def _draw(out: Path, submission: str, stem: str, problem: GradedProblem, mode: str,
          report: ValidationReport | None, notes: list[str]) -> dict:
    """A failing run's PDF and browser view (the validator's drawings), by column; a
    picture that could not be drawn (reportlab missing among them) is None."""
    from validator.checks import INVALID_VERDICT
    from validator.render_output import write_picture  # each format's module: only now
    drawn = {}
    for column, folder, extension in PICTURES:
        path = out / folder / submission / f"{stem}{extension}"
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            write_picture(str(path), extension, problem.problem, problem.vehicle(mode), report,
                          INVALID_VERDICT, notes, f"{submission}: {stem}")
        except Exception:  # a drawing problem must not cost the run its row
            drawn[column] = None
        else:
            drawn[column] = str(path)
    return drawn
