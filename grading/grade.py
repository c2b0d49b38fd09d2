"""The grading loop: builds, then runs, as tasks on an executor (a local process
pool, or a Dask cluster's), at most ``jobs`` at once, each row stored as it comes
back; what the store already holds is not redone."""

from __future__ import annotations

import concurrent.futures as cf
import os
import shutil
import signal
from dataclasses import dataclass
from typing import Callable, Iterable, Iterator

from grading.config import MODE_FLAGS, GradeConfig
from grading.executors import dask_executor, each_result
from grading.runs import build_one, failed_build_row, run_one
from grading.store import Store
from planning_core.problem_text import ProblemFormatError, parse_problem

Progress = Callable[[int, int, dict], None]  # (finished, total, the row just stored)


@dataclass(frozen=True)
class Outcome:
    """What a grading run did, and kept from an earlier one."""

    runs: list[dict]        # every row of the store, sorted
    builds: dict[str, dict]  # by submission
    builds_done: int        # built now
    builds_kept: int        # found finished in the store
    runs_done: int          # run now (or recorded as not built)
    runs_kept: int          # found finished in the store


def grade(config: GradeConfig, progress: Progress | None = None) -> Outcome:
    """Grade every submission x problem x mode into ``config.out``; resumable."""
    _check(config)
    config.out.mkdir(parents=True, exist_ok=True)
    store = Store(config.out)
    try:
        if config.rerun:  # and what the earlier runs left: their logs and PDFs
            store.clear()
            for folder in ("logs", "pdf"):
                shutil.rmtree(config.out / folder, ignore_errors=True)
        with _Executor(config) as executor:
            builds_done, builds_kept = _build_all(config, store, executor)
            runs_done, runs_kept = _run_all(config, store, executor, progress)
        return Outcome(store.runs(), store.builds(), builds_done, builds_kept, runs_done,
                       runs_kept)
    finally:
        store.close()


def _check(config: GradeConfig) -> None:
    """ValueError (one line) for what would fail every run: modes, problems."""
    unknown = [mode for mode in config.modes if mode not in MODE_FLAGS]
    if unknown:
        raise ValueError(f"unknown mode {unknown[0]!r} (known: {', '.join(MODE_FLAGS)})")
    names = config.problem_names()
    if not names:
        raise ValueError(f"no *.sw problems in {config.problems}")
    for name in names:
        try:
            parse_problem((config.problems / name).read_text(errors="replace"))
        except (OSError, ProblemFormatError) as error:
            raise ValueError(f"{config.problems / name}: bad problem: {error}") from None


def _build_all(config: GradeConfig, store: Store, executor) -> tuple[int, int]:
    kept = store.builds()
    todo = [name for name in config.submission_names() if name not in kept]
    for row in _each_result(executor, config.jobs,
                            ((build_one, config, name) for name in todo)):
        store.add_build(row)
    return len(todo), len(kept)


def _run_all(config: GradeConfig, store: Store, executor, progress: Progress | None
             ) -> tuple[int, int]:
    builds = store.builds()
    finished = store.finished_runs()
    every = [(name, problem, mode) for name in config.submission_names()
             for problem in config.problem_names() for mode in config.modes]
    todo = [key for key in every if key not in finished]
    count = len(every) - len(todo)

    def record(row: dict) -> None:
        nonlocal count
        store.add_run(row)
        count += 1
        if progress:
            progress(count, len(every), row)

    to_run = []
    for key in todo:
        build = builds[key[0]]
        if build["ok"]:
            to_run.append((run_one, config, *key))
        else:
            record(failed_build_row(*key, build))
    for row in _each_result(executor, config.jobs, to_run):
        record(row)
    return len(todo), len(every) - len(todo)


def _each_result(executor, jobs: int, tasks: Iterable[tuple]) -> Iterator[dict]:
    """Each task's result as it finishes, at most ``jobs`` at once; a local worker runs
    it through :func:`_in_local_worker`."""
    if isinstance(executor, cf.ProcessPoolExecutor):
        tasks = ((_in_local_worker, *task) for task in tasks)
    return each_result(executor, jobs, tasks)


class _Executor:
    """The executor: Dask's for a scheduler address, else a local process pool whose
    workers die with us; on the way out (also on SIGTERM or Ctrl-C) nothing runs on."""

    def __init__(self, config: GradeConfig):
        self.config = config
        self.dask = None

    def __enter__(self):
        if self.config.scheduler:
            self.dask = dask_executor(self.config.scheduler)
            self.executor = self.dask.__enter__()
        else:
            self.executor = cf.ProcessPoolExecutor(self.config.jobs,
                                                   initializer=_worker_start,
                                                   initargs=(os.getpid(),))
        return self.executor

    def __exit__(self, kind, error, trace):
        if self.dask is not None:
            return self.dask.__exit__(kind, error, trace)
        if kind is not None:  # interrupted: stop the runs in flight, do not wait for them
            stop = getattr(self.executor, "terminate_workers", None)  # Python 3.14
            for process in ([] if stop else list(getattr(self.executor, "_processes",
                                                         {}).values())):
                process.terminate()
            if stop:
                stop()
        self.executor.shutdown(wait=True, cancel_futures=kind is not None)
        return False


def _worker_start(parent: int) -> None:
    """A local worker: SIGTERM when the grading process dies (even by SIGKILL), and
    SIGTERM unwinds through run_planner, which kills the run's process group."""
    signal.signal(signal.SIGTERM, _exit_on_signal)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the grading process handles Ctrl-C
    try:
        import ctypes
        ctypes.CDLL(None).prctl(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:  # it died before the prctl took effect
        os._exit(1)


def _exit_on_signal(signum, frame):
    signal.signal(signal.SIGALRM, signal.SIG_DFL)
    signal.alarm(5)  # the clean-up gets 5 s; then the kernel ends the worker
    raise SystemExit(128 + signum)


def _in_local_worker(function, *args):
    """Run a task; on SIGTERM (unwound through run_planner's clean-up) end the worker,
    which the pool would otherwise keep waiting for work that will never come."""
    try:
        return function(*args)
    except SystemExit as stop:
        os._exit(stop.code if isinstance(stop.code, int) else 1)
