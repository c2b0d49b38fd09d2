"""An interrupted grading run resumes: finished rows are kept, not recomputed."""

from __future__ import annotations

import os
import re
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from grading.cli import main
from grading_fixtures import OUR_RUN, ROOT, make_class, make_submission

MODES = "point,grad"


def _argv(submissions: Path, problems: Path, out: Path) -> list[str]:
    return ["--submissions", str(submissions), "--problems", str(problems), "--out", str(out),
            "--modes", MODES, "--jobs", "2"]


def _grade(submissions: Path, problems: Path, out: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "grading", *_argv(submissions, problems, out)],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        env=dict(os.environ, PYTHONPATH=str(ROOT)))


def _rows(out: Path) -> dict[tuple, float]:
    """(submission, problem, mode) -> wall time, of the stored runs."""
    try:
        db = sqlite3.connect(out / "grades.sqlite", timeout=5)
        try:
            return {tuple(row[:3]): row[3] for row in db.execute(
                "SELECT submission, problem, mode, wall_time FROM runs")}
        finally:
            db.close()
    except sqlite3.OperationalError:  # not created yet
        return {}


def _left_running(folder: Path) -> list[int]:
    """Processes whose working directory is in ``folder``."""
    found = []
    for name in filter(str.isdigit, os.listdir("/proc")):
        try:
            if os.readlink(f"/proc/{name}/cwd").startswith(str(folder)):
                found.append(int(name))
        except OSError:
            pass
    return found


def _interrupt(signum: int, tmp_path: Path, capsys):
    submissions, problems, _ = make_class(tmp_path, [], ["simple-0.sw"])
    for name in ("a", "b", "c"):
        make_submission(submissions, name, "", f'sleep 0.3; exec "{OUR_RUN}" "$@"',
                        tmp_path / "unused")
    out = tmp_path / "out"
    grading = _grade(submissions, problems, out)
    deadline = time.monotonic() + 30
    while not _rows(out) and time.monotonic() < deadline:
        time.sleep(0.05)
    grading.send_signal(signum)
    grading.communicate(timeout=60)
    kept = _rows(out)
    assert 0 < len(kept) < 6, "the kill came too late to test a resume"
    deadline = time.monotonic() + 5
    while _left_running(submissions) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _left_running(submissions) == []

    capsys.readouterr()
    status = main(_argv(submissions, problems, out))  # the rerun: in this process
    stderr = capsys.readouterr().err
    assert status == 0, stderr
    assert re.search(rf"{6 - len(kept)} runs now, {len(kept)} kept", stderr), stderr
    final = _rows(out)
    assert len(final) == 6
    assert {key: final[key] for key in kept} == kept  # the same wall times: not redone
    book = (out / "gradebook.csv").read_text()
    assert book == ("submission,valid,runs,valid_point,valid_grad,score\n"
                    "a,2,2,1,1,100.0\nb,2,2,1,1,100.0\nc,2,2,1,1,100.0\n")


def test_resume_after_sigkill(tmp_path, capsys):
    _interrupt(signal.SIGKILL, tmp_path, capsys)


@pytest.mark.slow
def test_resume_after_sigterm(tmp_path, capsys):
    _interrupt(signal.SIGTERM, tmp_path, capsys)


# A local worker on SIGTERM (its grader died: the parent-death signal): between tasks, where
# the pool's loop catches a SystemExit (while it sends a result back) and would wait on for
# work, holding the grader's pipes; and after a task whose SystemExit was lost (Python ignores
# one raised in an at-fork hook: run_planner forks). The old handler left both running.
_WORKER = """
import os, signal, sys, time
sys.path.insert(0, sys.argv[1])
from grading import grade
signal.signal(signal.SIGTERM, grade._exit_on_signal)

def signalled():
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(30)  # the handler runs here

def between_tasks():
    try:
        signalled()
    except BaseException:  # as the pool's loop does
        pass

def lost():
    try:
        signalled()
    except SystemExit:  # as an at-fork hook's caller does
        pass
    return "a row"

between_tasks() if sys.argv[2] == "between" else grade._in_local_worker(lost)
print("still running")
"""


@pytest.mark.parametrize("where", ["between", "lost"])
def test_a_local_worker_told_to_end_ends_at_once(where):
    done = subprocess.run([sys.executable, "-c", _WORKER, str(ROOT), where],
                          capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stdout) == (128 + signal.SIGTERM, ""), done.stderr
