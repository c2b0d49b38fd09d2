"""Run planner x vehicle x problem x seed in parallel worker processes.

Each run starts the planner as its own process (``python -m rrt_cli`` or the
OMPL peer ``python -m benchmarks.ompl_planner``) with the problem on stdin, so
whole-process time is what a user waits. The planner is started through
``launch.py``, a small interpreter that times it and collects its peak memory
with ``os.wait4`` (see there why not straight from the worker). The planner's ``-stats`` line gives
planning time, tree size and iterations; every output of a run that exits 0 is
re-checked with ``validator.checks.validate_output``, and an invalid one counts
as a failure. A run that outlives its time limit by ``grace`` is killed.
"""

from __future__ import annotations

import multiprocessing
import os
import re
import signal
import sys
import tempfile
import threading
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable

from benchmarks.catalog import ROOT, PlannerChoice
from benchmarks.generator import family_of, problem_id
from benchmarks.rows import RunRow, RunStatus
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle

LAUNCHER = Path(__file__).resolve().parent / "launch.py"
_STATS_LINE = re.compile(r"^\S+ stats: (.*)$", re.MULTILINE)
_EXIT_STATUS = {0: RunStatus.SOLVED, 2: RunStatus.BAD_INPUT, 3: RunStatus.NO_SOLUTION}


@dataclass(frozen=True)
class RunSpec:
    planner: PlannerChoice
    vehicle: Vehicle
    problem: Path
    seed: int
    time_limit: float

    @property
    def key(self) -> tuple:
        return (problem_id(self.problem), self.vehicle.value, self.planner.id, self.seed)


@dataclass(frozen=True)
class HarnessOptions:
    workers: int = 2
    grace: float = 5.0
    """Seconds past the time limit (plus 10 % of it) before the harness kills a run."""
    strict: bool = False
    """Validate with -strict: a segment cutting a blocked corner is a failure."""


def parse_stats(stderr_text: str) -> dict[str, str]:
    """The key=value pairs of the last ``<name> stats: ...`` line on stderr."""
    found = _STATS_LINE.findall(stderr_text)
    if not found:
        return {}
    return dict(item.split("=", 1) for item in found[-1].split() if "=" in item)


def _number(fields: dict[str, str], key: str, kind):
    try:
        return kind(fields[key])
    except (KeyError, ValueError):
        return None


def _kill_group(pid: int, killed: list[bool]) -> None:
    killed.append(True)
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def _read_launch_report(path: str) -> tuple[int, float, float] | None:
    """(exit status, wall seconds, peak MB) from launch.py; None if it was killed."""
    try:
        with open(path) as handle:
            status, wall, max_rss_kb = handle.read().split()
        return int(status), float(wall), int(max_rss_kb) / 1024.0  # Linux: kilobytes
    except (OSError, ValueError):
        return None


def _last_line(text: str, limit: int = 200) -> str:
    lines = [line for line in text.splitlines() if line.strip() and " stats: " not in line]
    return lines[-1][:limit] if lines else ""


def run_one(spec: RunSpec, options: HarnessOptions = HarnessOptions()) -> RunRow:
    """Run one planner process to the end and validate what it printed."""
    import subprocess  # noqa: PLC0415 (the workers need it; the parent may not)

    from validator.checks import validate_output

    problem_text = spec.problem.read_text()
    problem = parse_problem(problem_text)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + ([os.environ["PYTHONPATH"]] if os.environ.get("PYTHONPATH") else [])))
    command = spec.planner.command(spec.vehicle, spec.seed, spec.time_limit)
    hard_limit = spec.time_limit * 1.1 + options.grace
    killed: list[bool] = []
    with open(spec.problem, "rb") as stdin, tempfile.TemporaryFile() as out, \
            tempfile.TemporaryFile() as err, tempfile.TemporaryDirectory() as scratch:
        report_path = os.path.join(scratch, "launch.txt")
        began = time.perf_counter()
        process = subprocess.Popen([sys.executable, "-S", "-I", str(LAUNCHER), report_path,
                                    *command], stdin=stdin, stdout=out, stderr=err, env=env,
                                   cwd=ROOT, start_new_session=True)
        timer = threading.Timer(hard_limit, _kill_group, (process.pid, killed))
        timer.start()
        try:
            _, wait_status, _ = os.wait4(process.pid, 0)
        finally:
            timer.cancel()
        process_seconds = time.perf_counter() - began
        exit_status = os.waitstatus_to_exitcode(wait_status)
        process.returncode = exit_status  # reaped here; keep Popen from waiting again
        peak_memory_mb = None
        launched = _read_launch_report(report_path)
        if launched is not None:
            exit_status, process_seconds, peak_memory_mb = launched
        out.seek(0)
        stdout_text = out.read().decode("utf-8", errors="replace")
        err.seek(0)
        stderr_text = err.read().decode("utf-8", errors="replace")

    stats = parse_stats(stderr_text)
    planning = _number(stats, "planning_seconds", float)
    valid = None
    failure = ""
    path_length = trajectory_lines = None
    corner_cuts = 0
    validation_seconds = 0.0
    if killed:
        status = RunStatus.KILLED
        failure = f"killed after {hard_limit:.1f} s"
    elif exit_status == 0:
        checked = time.perf_counter()
        report = validate_output(problem, spec.vehicle, stdout_text, strict=options.strict)
        validation_seconds = time.perf_counter() - checked
        valid = report.valid
        corner_cuts = len(report.corner_cuts)
        trajectory_lines = report.trajectory_count
        if valid:
            status = RunStatus.SOLVED
            path_length = report.path_length
        else:
            status = RunStatus.INVALID
            first = report.first_failure
            failure = f"{first.message} {first.detail}".strip() if first else "invalid"
    elif exit_status == 3:
        reason = stats.get("status", "")
        status = next((s for s in RunStatus if s.value == reason and s is not RunStatus.SOLVED),
                      RunStatus.NO_SOLUTION)
        failure = _last_line(stderr_text)
    else:
        status = _EXIT_STATUS.get(exit_status, RunStatus.CRASHED)
        if status is RunStatus.SOLVED:
            status = RunStatus.CRASHED
        failure = _last_line(stderr_text) or f"exit status {exit_status}"
    return RunRow(
        problem=problem_id(spec.problem), family=family_of(problem_id(spec.problem)),
        width=problem.width, height=problem.height, vehicle=spec.vehicle.value,
        planner=spec.planner.id, implementation=spec.planner.implementation,
        seed=spec.seed, time_limit=float(spec.time_limit),
        solved=status is RunStatus.SOLVED, status=status.value, exit_status=exit_status,
        valid=valid, failure=failure, planning_seconds=planning,
        process_seconds=process_seconds, path_length=path_length,
        tree_nodes=_number(stats, "tree_nodes", int),
        iterations=_number(stats, "iterations", int), trajectory_lines=trajectory_lines,
        peak_memory_mb=peak_memory_mb,
        corner_cuts=corner_cuts, validation_seconds=validation_seconds)


def order_for_balance(specs: Iterable[RunSpec]) -> list[RunSpec]:
    """Largest maps first (the long runs), planners interleaved on each problem so
    that ours and OMPL's share the same machine load."""
    def cost(spec: RunSpec):
        size = spec.problem.stat().st_size
        return (-size, problem_id(spec.problem), spec.vehicle.value, spec.seed, spec.planner.id)
    return sorted(specs, key=cost)


ProgressCallback = Callable[[int, int, RunRow], None]


def run_all(specs: list[RunSpec], options: HarnessOptions = HarnessOptions(),
            progress: ProgressCallback | None = None) -> list[RunRow]:
    """Every spec once, ``options.workers`` at a time; rows in the order of ``specs``."""
    ordered = order_for_balance(specs)
    rows: dict[tuple, RunRow] = {}
    if options.workers <= 1:
        for spec in ordered:
            rows[spec.key] = run_one(spec, options)
            if progress:
                progress(len(rows), len(ordered), rows[spec.key])
    else:
        # spawn: workers start clean (no inherited threads or OMPL state).
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=options.workers, mp_context=context) as pool:
            futures = {pool.submit(run_one, spec, options): spec for spec in ordered}
            for future in as_completed(futures):
                spec = futures[future]
                rows[spec.key] = future.result()
                if progress:
                    progress(len(rows), len(ordered), rows[spec.key])
    return [rows[spec.key] for spec in specs]


class ProgressBar:
    """A one-line progress bar on stderr (a line per 5 % when stderr is not a terminal)."""

    def __init__(self, stream=None, width: int = 30):
        self.stream = stream or sys.stderr
        self.width = width
        self.began = time.perf_counter()
        self.failures = 0
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.last_step = -1

    def __call__(self, done: int, total: int, row: RunRow) -> None:
        if not row.solved:
            self.failures += 1
        elapsed = time.perf_counter() - self.began
        eta = elapsed / done * (total - done) if done else 0.0
        filled = int(self.width * done / total) if total else self.width
        text = (f"[{'#' * filled}{'.' * (self.width - filled)}] {done}/{total} runs, "
                f"{self.failures} unsolved, {_clock(elapsed)} elapsed, ~{_clock(eta)} left")
        if self.tty:
            self.stream.write("\r" + text + ("\n" if done == total else ""))
            self.stream.flush()
        else:
            step = done * 20 // total if total else 20
            if step != self.last_step or done == total:
                self.last_step = step
                self.stream.write(text + "\n")
                self.stream.flush()


def _clock(seconds: float) -> str:
    seconds = int(seconds)
    return f"{seconds // 60}:{seconds % 60:02d}"
