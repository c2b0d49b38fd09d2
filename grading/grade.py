"""The grading loop: builds, then runs, as tasks on an executor (a local process
pool, or a Dask cluster's), at most ``jobs`` at once, each row stored as it comes
back; what the store already holds is not redone."""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import fcntl
import os
import shutil
import signal
from collections import deque
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable, Iterator

from grading.config import GradeConfig
from grading.executors import dask_executor, each_result
from grading.problems import read_problem
from grading.progress import Progress
from grading.rubric import Item
from grading.runs import (build_one, calibrate_one, failed_build_row, lost_build_row,
                          lost_calibration_row, lost_run_row, run_one)
from grading.store import Store
from planning_core.problem_text import ProblemFormatError


@dataclass(frozen=True)
class Outcome:
    """What a grading run did, and kept from an earlier one."""

    runs: list[dict]        # the rows of the rubric's runs, sorted
    builds: dict[str, dict]  # by submission
    items: list[Item]       # the rubric's items on these problems
    calibration: dict[tuple[str, str], dict]  # our planner's row per (problem, mode)
    builds_done: int        # built now
    builds_kept: int        # found finished in the store
    runs_done: int          # run now (or recorded as not built)
    runs_kept: int          # found finished in the store


class Busy(Exception):
    """Another grading run holds the same ``--out``."""


LOCK = ".rrt-grade.lock"


def grade(config: GradeConfig, progress: Progress | None = None) -> Outcome:
    """Grade every submission x item x repeat into ``config.out``; resumable; raises
    :class:`Busy` while another grading run uses the same folder, ValueError (one line)
    for a bad problem or rubric."""
    items = _check(config)
    progress = progress or Progress(None)
    config.out.mkdir(parents=True, exist_ok=True)
    with _only_grading(config.out), contextlib.closing(Store(config.out)) as store:
        if config.rerun:  # and what the earlier runs left: logs, pictures, built folders
            store.clear()
            for folder in ("logs", "pdf", "html", "built"):
                shutil.rmtree(config.out / folder, ignore_errors=True)
        with _Executor(config) as executor:
            tasks = _Tasks(executor, config.jobs, progress)
            builds_done, builds_kept = _build_all(config, store, tasks)
            if config.calibrate:
                _calibrate(config, store, tasks, items)
            runs_done, runs_kept = _run_all(config, store, tasks, items)
        return Outcome(_current(config, store.runs(), items), store.builds(), items,
                       store.calibration(), builds_done, builds_kept, runs_done, runs_kept)


@contextlib.contextmanager
def _only_grading(out: Path) -> Iterator[None]:
    """Hold the lock of ``out`` (the file says who holds it), or raise :class:`Busy`.
    A POSIX lock: the workers forked from us do not hold it, so it goes when we do."""
    fd = os.open(out / LOCK, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
    try:
        try:
            fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except (BlockingIOError, PermissionError):  # EAGAIN or EACCES: held
            holder = os.read(fd, 32).decode(errors="replace").strip() or "unknown"
            raise Busy(f"{out} is being graded by another rrt-grade (pid {holder})") from None
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        yield
    finally:
        os.close(fd)


def _check(config: GradeConfig) -> list[Item]:
    """The rubric's items; ValueError (one line) for what would fail every run: no
    problems, a bad problem, a rubric that does not fit them."""
    names = config.problem_names()
    if not names:
        raise ValueError(f"no *.sw or *.kp problems in {config.problems}")
    for name in names:
        try:
            read_problem(config.problems / name)
        except (OSError, ProblemFormatError, UnicodeEncodeError) as error:
            raise ValueError(f"{config.problems / name}: bad problem: {error}") from None
    items = config.items()
    if not items:
        raise ValueError("the rubric leaves no problem to grade")
    return items


class _Tasks:
    """Runs a phase's tasks on the executor, at most ``jobs`` at once, and tells the
    progress of each one done and of every wait."""

    def __init__(self, executor, jobs: int, progress: Progress):
        self.executor, self.jobs, self.progress = executor, jobs, progress

    def run(self, phase: str, tasks: list[tuple], store: Callable[[dict], None],
            kept: int = 0, kept_good: int = 0, done: Iterable[dict] = ()) -> None:
        """``tasks`` run, each row stored as it comes; ``done``: rows stored without a task."""
        done = list(done)
        self.progress.start(phase, kept + len(done) + len(tasks), kept, kept_good)
        for row in done:
            store(row)
            self.progress.done(row)
        for row in _each_result(self.executor, self.jobs, tasks, self.progress.idle,
                                self.progress.tick):
            store(row)
            self.progress.done(row)
        self.progress.finish()


def _build_all(config: GradeConfig, store: Store, tasks: _Tasks) -> tuple[int, int]:
    kept = store.builds()
    names = config.submission_names()
    todo = [name for name in names if name not in kept]
    tasks.run("builds", [(build_one, config, name) for name in todo], store.add_build,
              kept=len(names) - len(todo),
              kept_good=sum(kept[name]["ok"] for name in names if name in kept))
    return len(todo), len(names) - len(todo)


def _calibrate(config: GradeConfig, store: Store, tasks: _Tasks, items: list[Item]) -> None:
    """Our planner on each item not timed yet."""
    kept = store.calibration()
    todo = [(calibrate_one, config, item) for item in items
            if (item.problem, item.mode) not in kept]
    tasks.run("calibration", todo, store.add_calibration, kept=len(items) - len(todo))


def _keys(config: GradeConfig, items: list[Item]) -> list[tuple[str, Item, int]]:
    """Every run: (submission, item, repeat)."""
    return [(name, item, repeat) for name in config.submission_names() for item in items
            for repeat in range(item.repeats)]


def _run_all(config: GradeConfig, store: Store, tasks: _Tasks, items: list[Item]
             ) -> tuple[int, int]:
    builds = store.builds()
    finished = store.finished_runs()
    every = _keys(config, items)
    todo = [key for key in every
            if (key[0], key[1].problem, key[1].mode, key[2]) not in finished]
    kept = len(every) - len(todo)
    kept_good = sum(row["valid"] for row in _current(config, store.runs(), items))
    failed = [failed_build_row(*key, builds[key[0]]) for key in todo if not builds[key[0]]["ok"]]
    to_run = [(run_one, config, *key) for key in todo if builds[key[0]]["ok"]]
    tasks.run("runs", to_run, store.add_run, kept, kept_good, failed)
    return len(todo), kept


def _current(config: GradeConfig, rows: list[dict], items: list[Item]) -> list[dict]:
    """The stored runs the rubric asks for (a store may hold more: an earlier rubric's)."""
    repeats = {(item.problem, item.mode): item.repeats for item in items}
    names = set(config.submission_names())
    return [row for row in rows if row["submission"] in names
            and row["repeat"] < repeats.get((row["problem"], row["mode"]), 0)]


def _each_result(executor, jobs: int, tasks: Iterable[tuple], idle: Callable[[], None],
                 tick: float) -> Iterator[dict]:
    """Each task's result as it finishes, at most ``jobs`` at once, ``idle()`` after each
    ``tick`` seconds of waiting (on the local pool: :func:`_local_results`)."""
    if isinstance(executor, _LocalPool):
        return _local_results(executor, jobs, tasks, idle, tick)
    return each_result(executor, jobs, tasks, idle, tick)


# The row of a task whose worker died under it twice, the second time running alone.
_LOST: dict[Callable, Callable[..., dict]] = {build_one: lost_build_row, run_one: lost_run_row,
                                              calibrate_one: lost_calibration_row}


def _local_results(pool: _LocalPool, jobs: int, tasks: Iterable[tuple],
                   idle: Callable[[], None], tick: float) -> Iterator[dict]:
    """Like :func:`grading.executors.each_result`, but a worker that dies does not end
    the grading: the pool is renewed, the tasks it took down are run again one at a time,
    and one whose worker dies again gets a row that says so."""
    queue = _Queue(iter(tasks))
    pending: dict[cf.Future, tuple[tuple, bool]] = {}
    ready: list[dict] = []
    while True:
        try:
            queue.submit(pool, jobs, pending)
            broken = False
        except BrokenProcessPool:  # it broke since the last wait
            broken = True
        yield from ready  # stored while the freed workers already run the next tasks
        ready = []
        if not pending and not broken:
            return
        if not broken:
            done, _ = cf.wait(pending, timeout=tick, return_when=cf.FIRST_COMPLETED)
            if not done:
                idle()
                continue
            broken = any(isinstance(future.exception(), BrokenProcessPool) for future in done)
        if broken:
            cf.wait(pending)  # the others go down with it
            done = set(pending)
            pool.renew()
        for future in done:
            task, alone = pending.pop(future)
            if not isinstance(future.exception(), BrokenProcessPool):
                ready.append(future.result())
            elif alone:
                ready.append(_LOST[task[0]](*task[1:]))
            else:
                queue.suspects.append(task)


class _Queue:
    """The tasks not started yet, and those a dying worker took down (the suspects)."""

    def __init__(self, tasks: Iterator[tuple]):
        self.tasks = tasks
        self.unsent: deque[tuple] = deque()   # taken from ``tasks``, refused by a broken pool
        self.suspects: deque[tuple] = deque()

    def submit(self, pool: _LocalPool, jobs: int, pending: dict) -> None:
        """Submit what may run now: a suspect alone, else up to ``jobs`` others; raises
        BrokenProcessPool (nothing lost) when the pool is broken."""
        if self.suspects:
            if not pending:
                pending[pool.submit(self.suspects[0])] = (self.suspects[0], True)
                self.suspects.popleft()
            return
        while len(pending) < jobs:
            task = self.unsent.popleft() if self.unsent else next(self.tasks, ())
            if not task:
                return
            try:
                pending[pool.submit(task)] = (task, False)
            except BrokenProcessPool:
                self.unsent.appendleft(task)
                raise


class _LocalPool:
    """A local process pool whose workers die with us, renewed when one died."""

    def __init__(self, jobs: int):
        self.jobs = jobs
        self.executor = self._start()

    def _start(self) -> cf.ProcessPoolExecutor:
        return cf.ProcessPoolExecutor(self.jobs, initializer=_worker_start,
                                      initargs=(os.getpid(),))

    def submit(self, task: tuple) -> cf.Future:
        return self.executor.submit(_in_local_worker, *task)

    def renew(self) -> None:
        self.executor.shutdown(wait=True)
        self.executor = self._start()

    def close(self, interrupted: bool) -> None:
        """On an interruption, stop the runs in flight rather than wait for them."""
        if interrupted:
            stop = getattr(self.executor, "terminate_workers", None)  # Python 3.14
            for process in ([] if stop else list(getattr(self.executor, "_processes",
                                                         {}).values())):
                process.terminate()
            if stop:
                stop()
        self.executor.shutdown(wait=True, cancel_futures=interrupted)


class _Executor:
    """The executor: Dask's for a scheduler address, else a local pool; on the way out
    (also on SIGTERM or Ctrl-C) nothing runs on."""

    def __init__(self, config: GradeConfig):
        self.config = config
        self.dask = None

    def __enter__(self):
        if self.config.scheduler:
            self.dask = dask_executor(self.config.scheduler)
            self.executor = self.dask.__enter__()
        else:
            self.executor = _LocalPool(self.config.jobs)
        return self.executor

    def __exit__(self, kind, error, trace):
        if self.dask is not None:
            return self.dask.__exit__(kind, error, trace)
        self.executor.close(kind is not None)
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


_IN_TASK = False
"""In a local worker: a task is running (from just before its function to just after)."""
_STOP = 0
"""In a local worker: the signal that asked it to end (0: none yet)."""


def _exit_on_signal(signum, frame):
    """In a task, unwind it (run_planner kills the run's processes on the way); between
    tasks end at once: the pool's loop would catch the SystemExit (while it sends a
    result back, say) and wait on for work that never comes, holding our pipes."""
    global _STOP
    _STOP = signum
    if not _IN_TASK:
        os._exit(128 + signum)
    signal.signal(signal.SIGALRM, signal.SIG_DFL)
    signal.alarm(5)  # the clean-up gets 5 s; then the kernel ends the worker
    raise SystemExit(128 + signum)


def _in_local_worker(function, *args):
    """Run a task; on SIGTERM (unwound through run_planner's clean-up) end the worker,
    which the pool would otherwise keep waiting for work that will never come."""
    global _IN_TASK
    try:
        _IN_TASK = True
        try:
            return function(*args)
        finally:  # a signal before the flag is down raises here: caught below
            _IN_TASK = False
            if _STOP:  # its SystemExit was lost: raised in an at-fork hook, which
                os._exit(128 + _STOP)  # Python reports and ignores (fork in run_planner)
    except SystemExit as stop:
        os._exit(stop.code if isinstance(stop.code, int) else 1)
