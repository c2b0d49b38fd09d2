"""The same class graded on a Dask cluster (two local workers) and on the local
pool gives the same gradebook."""

from __future__ import annotations

from pathlib import Path

import pytest

from grading.cli import main
from grading_fixtures import ROOT, make_class

distributed = pytest.importorskip("distributed")

NAMES = ["good", "garbage", "crash", "nobuild"]


def _gradebook(submissions, problems, out, *more) -> str:
    status = main(["--submissions", str(submissions), "--problems", str(problems),
                   "--out", str(out), "--modes", "point,grad", "--jobs", "2", *more])
    assert status == 0
    return (out / "gradebook.csv").read_text()


@pytest.mark.slow
def test_a_dask_cluster_gives_the_local_pools_gradebook(tmp_path):
    submissions, problems, _ = make_class(tmp_path, NAMES, ["simple-0.sw", "space-0.sw"])
    local = _gradebook(submissions, problems, tmp_path / "local")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        remote = _gradebook(submissions, problems, tmp_path / "dask", "--scheduler",
                            cluster.scheduler_address)
    assert remote == local
    assert local.splitlines()[1:] == ["crash,0,4,0,0,0.0", "garbage,0,4,0,0,0.0",
                                      "good,4,4,2,2,100.0", "nobuild,0,4,0,0,0.0"]


def _wait_for(path, seconds: float = 60.0) -> None:
    import time
    deadline = time.monotonic() + seconds
    while not path.exists() and time.monotonic() < deadline:
        time.sleep(0.1)


@pytest.mark.slow
def test_a_scheduler_and_two_workers_on_loopback(tmp_path):
    import json
    import os
    import subprocess
    import sys
    submissions, problems, _ = make_class(tmp_path, NAMES, ["simple-0.sw"])
    local = _gradebook(submissions, problems, tmp_path / "local")
    file = tmp_path / "scheduler.json"
    dask = [str(Path(sys.executable).parent / "dask")]
    env = dict(os.environ, PYTHONPATH=str(ROOT))  # the workers import grading
    started = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", "0",
                                 "--no-dashboard", "--scheduler-file", str(file)], env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        _wait_for(file)
        address = json.loads(file.read_text())["address"]
        started += [subprocess.Popen([*dask, "worker", address, "--nthreads", "1",
                                      "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL) for _ in range(2)]
        with distributed.Client(address) as client:
            client.wait_for_workers(2, timeout=60)
        remote = _gradebook(submissions, problems, tmp_path / "dask", "--scheduler", address)
    finally:
        for process in reversed(started):
            process.terminate()
            process.wait(timeout=30)
    assert remote == local
