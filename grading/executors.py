"""Running tasks on an executor, shared by rrt-grade and the benchmark harness: a Dask
cluster's executor for a scheduler address, and a loop that keeps at most ``jobs``
tasks in flight and yields each result as it finishes."""

from __future__ import annotations

import concurrent.futures as cf
from contextlib import contextmanager
from typing import Callable, Iterable, Iterator


@contextmanager
def dask_executor(address: str):
    """The executor of the Dask cluster at ``address`` (``tcp://HOST:PORT``); on the
    way out the tasks not started are cancelled and the client closed."""
    from distributed import Client  # optional: only for --scheduler
    client = Client(address)
    executor = client.get_executor(pure=False)
    try:
        yield executor
    except BaseException:
        executor.shutdown(wait=False)
        raise
    else:
        executor.shutdown(wait=True)
    finally:
        client.close()


def each_result(executor, jobs: int, tasks: Iterable[tuple],
                idle: Callable[[], None] | None = None, tick: float = 1.0) -> Iterator:
    """Each task's result (a task: ``(function, *args)``) as it finishes, with at most
    ``jobs`` submitted at once (the next ones before a result is handed on); ``idle()``
    after each ``tick`` seconds of waiting for one."""
    tasks = iter(tasks)
    pending: set[cf.Future] = set()
    done: set[cf.Future] = set()
    while True:
        while len(pending) < jobs:
            task = next(tasks, None)
            if task is None:
                break
            pending.add(executor.submit(*task))
        for future in done:  # handed on while the freed slots already run the next tasks
            yield future.result()
        if not pending:
            return
        done, pending = cf.wait(pending, timeout=tick if idle else None,
                                return_when=cf.FIRST_COMPLETED)
        if not done and idle:
            idle()
