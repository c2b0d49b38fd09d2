"""Ctrl-C and SIGTERM stop a benchmark run at once and keep the runs that finished;
runs.csv grows row by row; the progress lines in a log."""

import io
import os
import signal
import subprocess
import sys
import time

import pytest

from benchmarks import catalog, harness
from benchmarks.progress import Progress
from benchmarks.rows import CsvAppender, read_csv
from test_bench_report import row

# A time limit no other process uses (this test process's id in its decimals, as
# xdist runs these tests side by side), to find our planners in /proc.
MARK = f"37.{os.getpid()}1"  # (ends in 1: it reads back as the same text)
# The left-only ship needs minutes on the 200x200 field (runs first: largest map first)
# and well under a second on each small course map.
RUN = ["--preset", "course", "--planners", "rrt", "--vehicles", "left", "--problems",
       "course-simple-0", "course-space-0", "course-space-1", "random-d20-200", "--seeds", "1",
       "--max-size", "200", "--time", MARK, "--no-generate", "--no-plots"]


def planners_left() -> list[int]:
    """Our planner processes still alive (zombies have an empty command line)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as handle:
                words = handle.read().split(b"\0")
        except OSError:
            continue
        if b"rrt_cli" in words and MARK.encode() in words and int(pid) != os.getpid():
            found.append(int(pid))
    return found


def _as_at_a_terminal() -> None:
    """Ctrl-C's default action, as a command typed at a terminal has it: a test run
    started in the background by a script inherits SIGINT ignored (POSIX), and so
    would every process it starts."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(out, *extra) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(catalog.ROOT))
    return subprocess.Popen([sys.executable, "-m", "benchmarks", *RUN, *extra, "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env, cwd=catalog.ROOT, start_new_session=True,
                            preexec_fn=_as_at_a_terminal)


def wait_for_rows(csv_path, count: int, timeout: float = 60) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if csv_path.exists() and len(csv_path.read_text().splitlines()) >= 1 + count:
            return
        time.sleep(0.02)
    pytest.fail(f"{csv_path} did not get {count} rows in {timeout} s")


def stop(process: subprocess.Popen, signum: int, group: bool) -> tuple[float, str, str]:
    """Send the signal (to the whole process group, as a terminal's Ctrl-C does, or to
    the main process alone); the seconds until it exited, its stdout and stderr."""
    began = time.monotonic()
    (os.killpg if group else os.kill)(process.pid, signum)
    try:
        out, err = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    return time.monotonic() - began, out, err


def no_planner_left() -> bool:
    deadline = time.monotonic() + 3
    while planners_left() and time.monotonic() < deadline:
        time.sleep(0.05)
    return not planners_left()


@pytest.mark.parametrize("signum, group", [(signal.SIGTERM, False), (signal.SIGINT, True)])
def test_a_signal_stops_at_once_and_keeps_the_finished_runs(tmp_path, signum, group):
    process = start(tmp_path)
    wait_for_rows(tmp_path / "runs.csv", 2)
    seconds, out, err = stop(process, signum, group)
    assert process.returncode == 128 + signum, err
    assert seconds < 3  # within ~1 s; the long run alone has 37 s to go
    assert no_planner_left()
    rows = read_csv(tmp_path / "runs.csv")
    assert 2 <= len(rows) <= 3 and all(r.solved for r in rows)
    assert {r.problem for r in rows} <= {"course-simple-0", "course-space-0", "course-space-1"}
    assert out.strip() == str(tmp_path / "report.md")  # the report of what finished
    report = (tmp_path / "report.md").read_text()
    assert f"after {len(rows)} of 4 runs" in report and "Traceback" not in err
    assert "## Left-only spaceship" in report


def test_sigterm_kills_the_planner_of_a_single_worker_run(tmp_path):
    process = start(tmp_path, "--workers", "1")
    wait_for_rows(tmp_path / "runs.csv", 0)
    deadline = time.monotonic() + 30
    while not planners_left() and time.monotonic() < deadline:
        time.sleep(0.02)
    seconds, out, err = stop(process, signal.SIGTERM, group=False)
    assert process.returncode == 143 and seconds < 3, err
    assert no_planner_left()
    assert read_csv(tmp_path / "runs.csv") == []
    assert "after 0 of 4 runs" in (tmp_path / "report.md").read_text()


def test_csv_rows_are_on_disk_as_they_are_appended(tmp_path):
    path = tmp_path / "runs.csv"
    first, second = row("rrt", "a", 1, 0.5), row("rrt", "b", 2, 0.7, solved=False)
    with CsvAppender(path) as appender:
        assert read_csv(path) == []
        appender.append(first)
        assert read_csv(path) == [first]
        appender.append(second)
        assert read_csv(path) == [first, second]


def test_progress_in_a_log_is_a_line_at_the_first_run_and_per_tenth_of_the_runs():
    stream = io.StringIO()
    progress = Progress(20, stream)
    for done in range(1, 21):
        progress(done, 20, row("rrt", "p", done, 0.1, solved=done % 4 != 0))
    progress.close()
    lines = stream.getvalue().splitlines()
    assert len(lines) == 11 and "\r" not in stream.getvalue()
    assert lines[0].startswith("benchmarks:   5%") and "1/20" in lines[0]
    assert lines[1].startswith("benchmarks:  10%") and "2/20" in lines[1]
    assert "20/20" in lines[-1] and "unsolved=5" in lines[-1]


class _Stopped(Exception):
    pass


def test_a_signal_while_a_planner_starts_takes_effect_once_it_is_registered():
    def stop(signum, frame):
        raise _Stopped(signum)
    previous = signal.signal(signal.SIGTERM, stop)
    steps = []
    try:
        with pytest.raises(_Stopped):
            with harness._signals_held():
                signal.raise_signal(signal.SIGTERM)
                steps.append("registered")
            steps.append("after the block")
        assert steps == ["registered"]
        assert signal.getsignal(signal.SIGTERM) is stop
    finally:
        signal.signal(signal.SIGTERM, previous)
