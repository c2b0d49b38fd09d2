"""Run planner x vehicle x problem x seed in parallel worker processes.

Each run starts the planner as its own process (``python -m rrt_cli`` or the
OMPL peer ``python -m benchmarks.ompl_planner``) with the problem on stdin, so
whole-process time is what a user waits. The planner is started through
``launch.py``, a small interpreter that times it and collects its peak memory
with ``os.wait4`` (see there why not straight from the worker). The planner's ``-stats`` line gives
planning time, tree size and iterations; every output of a run that exits 0 is
re-checked with ``validator.checks.validate_output``, and an invalid one counts
as a failure. A run that outlives its time limit by ``grace`` is killed.

Ctrl-C or SIGTERM stops a run of many within a second: the planners running
are killed (each is its own process group), the runs not started are cancelled,
and :func:`run_all` raises :class:`Interrupted` with the rows that finished.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import re
import signal
import sys
import tempfile
import threading
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Callable, Iterable, Iterator

from benchmarks.catalog import ROOT, PlannerChoice
from benchmarks.generator import family_of, problem_id
from benchmarks.rows import RunRow, RunStatus
from cli_common import is_kinoplan, parse_any_problem
from planning_core.vehicles import Vehicle

LAUNCHER = Path(__file__).resolve().parent / "launch.py"
_STATS_LINE = re.compile(r"^\S+ stats: (.*)$", re.MULTILINE)
_PROGRESS_LINE = re.compile(r"^\S+ progress: (.*)$", re.MULTILINE)
_EXIT_STATUS = {0: RunStatus.SOLVED, 2: RunStatus.BAD_INPUT, 3: RunStatus.NO_SOLUTION}
_RUNNING: set[int] = set()
"""Process groups of the planners this process is running (the in-process path and a
worker: one at a time)."""


@dataclass(frozen=True)
class RunSpec:
    planner: PlannerChoice
    vehicle: Vehicle | None
    """The grid vehicle; None for a ``kinoplan`` problem (it names its system)."""
    problem: Path
    seed: int
    time_limit: float

    @property
    def key(self) -> tuple:
        vehicle = self.vehicle.value if self.vehicle is not None else ""
        return (problem_id(self.problem), vehicle, self.planner.id, self.seed)


@dataclass(frozen=True)
class HarnessOptions:
    workers: int = 2
    grace: float = 5.0
    """Seconds past the time limit (plus 10 % of it) before the harness kills a run."""
    strict: bool = False
    """Validate with -strict: a segment cutting a blocked corner is a failure."""
    scheduler: str | None = None
    """A Dask scheduler's address: the runs go to its cluster, ``workers`` at a time."""


def parse_stats(stderr_text: str) -> dict[str, str]:
    """The key=value pairs of the last ``<name> stats: ...`` line on stderr."""
    found = _STATS_LINE.findall(stderr_text)
    if not found:
        return {}
    return dict(item.split("=", 1) for item in found[-1].split() if "=" in item)


def parse_progress(stderr_text: str) -> tuple[tuple[float, float], ...]:
    """The (seconds, cost) pairs of the last ``<name> progress: SECONDS:COST ...`` line
    on stderr, in time order, each cost below the one before; malformed, non-finite or
    negative pairs, and pairs that improve nothing, are left out."""
    found = _PROGRESS_LINE.findall(stderr_text)
    pairs: list[tuple[float, float]] = []
    for item in (found[-1].split() if found else ()):
        try:
            seconds, cost = (float(part) for part in item.split(":"))
        except ValueError:
            continue
        if math.isfinite(seconds) and math.isfinite(cost) and seconds >= 0 and cost >= 0:
            pairs.append((seconds, cost))
    kept: list[tuple[float, float]] = []
    for seconds, cost in sorted(pairs):
        if not kept or cost < kept[-1][1]:
            kept.append((seconds, cost))
    return tuple(kept)


def progress_text(pairs) -> str:
    """``pairs`` as the progress line writes them (the RunRow's ``progress`` field)."""
    return " ".join(f"{seconds!r}:{cost!r}" for seconds, cost in pairs)


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


@dataclass(frozen=True)
class _Finished:
    """What a planner process left: how it ended, its time, memory and output."""

    exit_status: int          # negative: killed by that signal
    process_seconds: float
    peak_memory_mb: float | None
    stdout: str
    stderr: str
    killed: bool              # by the harness, past the hard limit


@dataclass(frozen=True)
class _Outcome:
    """The harness's verdict on a finished run, and what validating it measured."""

    status: RunStatus
    failure: str = ""
    valid: bool | None = None
    path_length: float | None = None
    trajectory_lines: int | None = None
    corner_cuts: int = 0
    validation_seconds: float = 0.0
    path_duration: float | None = None
    cost: float | None = None


def run_one(spec: RunSpec, options: HarnessOptions = HarnessOptions()) -> RunRow:
    """Run one planner process to the end and validate what it printed."""
    problem = parse_any_problem(spec.problem.read_text())
    hard_limit = spec.time_limit * 1.1 + options.grace
    finished = _run_planner(spec, hard_limit)
    stats = parse_stats(finished.stderr)
    if finished.killed:
        outcome = _Outcome(RunStatus.KILLED, f"killed after {hard_limit:.1f} s")
    elif finished.exit_status == 0:
        outcome = _validate(problem, spec.vehicle, finished.stdout, options.strict)
    else:
        outcome = _unsolved(finished, stats)
    return _row(spec, problem, finished, stats, outcome)


def _planner_env() -> dict[str, str]:
    """The environment with the project root first on PYTHONPATH."""
    return dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + ([os.environ["PYTHONPATH"]] if os.environ.get("PYTHONPATH") else [])))


def _run_planner(spec: RunSpec, hard_limit: float) -> _Finished:
    """Start the planner through launch.py with the problem on stdin; kill its
    process group past ``hard_limit`` seconds."""
    import subprocess  # noqa: PLC0415 (the workers need it; the parent may not)

    command = spec.planner.command(spec.vehicle, spec.seed, spec.time_limit)
    killed: list[bool] = []
    with open(spec.problem, "rb") as stdin, tempfile.TemporaryFile() as out, \
            tempfile.TemporaryFile() as err, tempfile.TemporaryDirectory() as scratch:
        report_path = os.path.join(scratch, "launch.txt")
        began = time.perf_counter()
        process = timer = None
        try:
            with _signals_held():  # until the planner is known, so it can be killed
                process = subprocess.Popen(
                    [sys.executable, "-S", "-I", str(LAUNCHER), report_path, *command],
                    stdin=stdin, stdout=out, stderr=err, env=_planner_env(), cwd=ROOT,
                    start_new_session=True)
                _RUNNING.add(process.pid)
                # A daemon: a timer left running must never hold up the interpreter's exit.
                timer = threading.Timer(hard_limit, _kill_group, (process.pid, killed))
                timer.daemon = True
                timer.start()
            _, wait_status, _ = os.wait4(process.pid, 0)
        except BaseException:  # Ctrl-C or SIGTERM: the planner must not outlive us
            if process is not None:
                _kill_group(process.pid, killed)
            raise
        finally:
            if process is not None:
                _RUNNING.discard(process.pid)
            if timer is not None:
                timer.cancel()
        process_seconds = time.perf_counter() - began
        exit_status = os.waitstatus_to_exitcode(wait_status)
        process.returncode = exit_status  # reaped here; keep Popen from waiting again
        peak_memory_mb = None
        launched = _read_launch_report(report_path)
        if launched is not None:
            exit_status, process_seconds, peak_memory_mb = launched
        return _Finished(exit_status, process_seconds, peak_memory_mb, _read_text(out),
                         _read_text(err), bool(killed))


@contextmanager
def _signals_held() -> Iterator[None]:
    """Ctrl-C and SIGTERM arriving inside the block take effect at its end. Between a
    planner's start and its registration in ``_RUNNING`` they would leave it running
    (their handlers run only in the main thread; elsewhere this holds nothing)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []
    previous = {signum: signal.signal(signum, lambda signum, frame: held.append(signum))
                for signum in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, signal.SIG_DFL if handler is None else handler)
        for signum in held:
            signal.raise_signal(signum)  # its own handler runs (and may raise) here


def _read_text(handle: IO[bytes]) -> str:
    handle.seek(0)
    return handle.read().decode("utf-8", errors="replace")


def _validate(problem, vehicle: Vehicle | None, stdout_text: str, strict: bool) -> _Outcome:
    """A run that exited 0: solved if the validator accepts its output, else invalid."""
    from validator.checks import validate_output, validate_plan

    checked = time.perf_counter()
    if is_kinoplan(problem):
        from planning_core.setups import kinoplan_setup
        report = validate_plan(kinoplan_setup(problem), stdout_text, strict)
    else:
        report = validate_output(problem, vehicle, stdout_text, strict=strict)
    validation_seconds = time.perf_counter() - checked
    if report.valid:
        status, failure, path_length = RunStatus.SOLVED, "", report.path_length
    else:
        first = report.first_failure
        status, path_length = RunStatus.INVALID, None
        failure = f"{first.message} {first.detail}".strip() if first else "invalid"
    return _Outcome(status, failure, report.valid, path_length, report.trajectory_count,
                    len(report.corner_cuts), validation_seconds,
                    control_duration(problem, report) if report.valid else None, report.cost)


def control_duration(problem, report) -> float | None:
    """A valid kinodynamic family answer's total control duration in seconds (the sum of
    its K times DT: OMPL's ``PathControl::length()``); None for other answers."""
    if not is_kinoplan(problem) or not problem.system.kinodynamic:
        return None
    return sum(row[-1] for row in report.plan.trajectory_rows()) * problem.system.dt


def _unsolved(finished: _Finished, stats: dict[str, str]) -> _Outcome:
    """A run that exited non-zero: exit 3 with the planner's reason, or another status."""
    if finished.exit_status == 3:
        reason = stats.get("status", "")
        status = next((s for s in RunStatus if s.value == reason and s is not RunStatus.SOLVED),
                      RunStatus.NO_SOLUTION)
        return _Outcome(status, _last_line(finished.stderr))
    status = _EXIT_STATUS.get(finished.exit_status, RunStatus.CRASHED)
    if status is RunStatus.SOLVED:
        status = RunStatus.CRASHED
    return _Outcome(status,
                    _last_line(finished.stderr) or f"exit status {finished.exit_status}")


def _row(spec: RunSpec, problem, finished: _Finished, stats: dict[str, str],
         outcome: _Outcome) -> RunRow:
    family = is_kinoplan(problem)  # a kinoplan problem: its system is the row's vehicle
    return RunRow(
        problem=problem_id(spec.problem),
        family=problem.system_name if family else family_of(problem_id(spec.problem)),
        width=0 if family else problem.width, height=0 if family else problem.height,
        vehicle=problem.system_name if family else spec.vehicle.value,
        planner=spec.planner.id, implementation=spec.planner.implementation,
        seed=spec.seed, time_limit=float(spec.time_limit),
        solved=outcome.status is RunStatus.SOLVED, status=outcome.status.value,
        exit_status=finished.exit_status, valid=outcome.valid, failure=outcome.failure,
        planning_seconds=_number(stats, "planning_seconds", float),
        process_seconds=finished.process_seconds, path_length=outcome.path_length,
        tree_nodes=_number(stats, "tree_nodes", int),
        iterations=_number(stats, "iterations", int),
        trajectory_lines=outcome.trajectory_lines, peak_memory_mb=finished.peak_memory_mb,
        corner_cuts=outcome.corner_cuts, validation_seconds=outcome.validation_seconds,
        path_duration=outcome.path_duration,
        first_solution_seconds=_first_solution(stats, outcome),
        best_cost=outcome.cost,
        progress=progress_text(parse_progress(finished.stderr))
        if outcome.status is RunStatus.SOLVED else "")


def _first_solution(stats: dict[str, str], outcome: _Outcome) -> float | None:
    """A solved run's first solution time: the stats line's, else (a planner that
    stops at its first solution and does not say) its planning time."""
    if outcome.status is not RunStatus.SOLVED:
        return None
    first = _number(stats, "first_solution_seconds", float)
    return first if first is not None else _number(stats, "planning_seconds", float)


def order_for_balance(specs: Iterable[RunSpec]) -> list[RunSpec]:
    """Largest maps first (the long runs), planners interleaved on each problem so
    that ours and OMPL's share the same machine load."""
    def cost(spec: RunSpec):
        size = spec.problem.stat().st_size
        return (-size, *spec.key[:2], spec.seed, spec.planner.id)
    return sorted(specs, key=cost)


ProgressCallback = Callable[[int, int, RunRow], None]


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread by :func:`interrupt_on_sigterm`'s handler."""


class Interrupted(Exception):
    """Ctrl-C or SIGTERM stopped :func:`run_all`: the rows of the runs that had
    finished (in the order of the specs) and the signal's number."""

    def __init__(self, rows: list[RunRow], signum: int):
        super().__init__(f"interrupted by signal {signum} after {len(rows)} runs")
        self.rows = rows
        self.signum = signum


def interrupt_on_sigterm() -> None:
    """From now on SIGTERM raises :class:`Terminated` (a KeyboardInterrupt) in the
    main thread, so that it stops a run as Ctrl-C does."""
    def handler(signum, frame):
        raise Terminated()
    signal.signal(signal.SIGTERM, handler)


def _worker_started(pids) -> None:
    """In each worker process: Ctrl-C is the parent's to handle (a terminal sends it
    to the whole process group); SIGTERM kills the running planner, then the worker."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def terminate(signum, frame):
        for pid in list(_RUNNING):
            _kill_group(pid, [])
        os._exit(128 + signum)
    signal.signal(signal.SIGTERM, terminate)
    pids.put(os.getpid())


def _stop_workers(pool: ProcessPoolExecutor, pids) -> None:
    """Cancel the runs not started; SIGTERM every worker (each kills its planner)."""
    pool.shutdown(wait=False, cancel_futures=True)
    while not pids.empty():
        try:
            os.kill(pids.get(), signal.SIGTERM)
        except ProcessLookupError:
            pass


def run_all(specs: list[RunSpec], options: HarnessOptions = HarnessOptions(),
            progress: ProgressCallback | None = None) -> list[RunRow]:
    """Every spec once, ``options.workers`` at a time; rows in the order of ``specs``.
    ``progress`` is called with each row as its run finishes. Ctrl-C (or SIGTERM,
    after :func:`interrupt_on_sigterm`) raises :class:`Interrupted`."""
    ordered = order_for_balance(specs)
    rows: dict[tuple, RunRow] = {}

    def finished(spec: RunSpec, row: RunRow) -> None:
        rows[spec.key] = row
        if progress:
            progress(len(rows), len(ordered), row)
    try:
        if options.scheduler:
            _run_on_dask(ordered, options, finished)
        elif options.workers <= 1:
            for spec in ordered:
                finished(spec, run_one(spec, options))
        else:
            _run_in_workers(ordered, options, finished)
    except KeyboardInterrupt as stop:
        signum = signal.SIGTERM if isinstance(stop, Terminated) else signal.SIGINT
        raise Interrupted([rows[s.key] for s in specs if s.key in rows], signum) from None
    return [rows[spec.key] for spec in specs]


def _run_in_workers(ordered: list[RunSpec], options: HarnessOptions,
                    finished: Callable[[RunSpec, RunRow], None]) -> None:
    # spawn: workers start clean (no inherited threads or OMPL state).
    context = multiprocessing.get_context("spawn")
    pids = context.SimpleQueue()
    pool = ProcessPoolExecutor(max_workers=options.workers, mp_context=context,
                               initializer=_worker_started, initargs=(pids,))
    try:
        futures = {pool.submit(run_one, spec, options): spec for spec in ordered}
        for future in as_completed(futures):
            finished(futures[future], future.result())
    except BaseException:
        _stop_workers(pool, pids)
        raise
    pool.shutdown()


def _run_on_dask(ordered: list[RunSpec], options: HarnessOptions,
                 finished: Callable[[RunSpec, RunRow], None]) -> None:
    """The runs on the Dask cluster at ``options.scheduler``, ``options.workers`` in
    flight; Ctrl-C cancels those not started (a run started ends at its hard limit)."""
    from grading.executors import dask_executor, each_result  # optional: Dask

    with dask_executor(options.scheduler) as executor:
        for spec, row in each_result(executor, options.workers,
                                     ((_run_keyed, spec, options) for spec in ordered)):
            finished(spec, row)


def _run_keyed(spec: RunSpec, options: HarnessOptions) -> tuple[RunSpec, RunRow]:
    return spec, run_one(spec, options)
