"""Progress on any stream: a line at least every 10 s (``--progress-every``) when stderr
is not a terminal, also while a run hangs; a bar on a terminal; and the local pool on a
bare python3, through ./rrt-grade on PATH."""

from __future__ import annotations

import fcntl
import io
import os
from collections import Counter
import pty
import re
import struct
import subprocess
import sys
import termios
from pathlib import Path

import pytest

from grading.progress import TICK, Progress, duration
from grading_fixtures import ROOT, make_class, make_submission

LINE = re.compile(r"^rrt-grade: (builds|calibration|runs) (\d+)/(\d+) done(?: \(\d+ kept\))?, "
                  r"(\d+) (?:built|valid), (\S+) elapsed(?:, about (\S+) left)?$")


def _seconds(text: str) -> int:
    hours, minutes, seconds = re.fullmatch(r"(?:(\d+)h)?(?:(\d+)m)?(?:(\d+)s)?", text).groups()
    return int(hours or 0) * 3600 + int(minutes or 0) * 60 + int(seconds or 0)


class Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_not_on_a_terminal_a_line_at_least_every_10_s_also_while_nothing_finishes():
    clock, stream = Clock(), io.StringIO()
    progress = Progress(stream, clock=clock)
    progress.start("runs", 3)
    times = [0.0]
    while clock.now < 60:  # the loop's ticks while one run hangs
        clock.now += TICK
        before = stream.getvalue().count("\n")
        progress.idle()
        if stream.getvalue().count("\n") > before:
            times.append(clock.now)
    gaps = [b - a for a, b in zip(times, times[1:])]
    assert len(times) >= 6 and all(10 - TICK <= gap <= 10 for gap in gaps), gaps
    progress.done({"valid": 1})
    clock.now += 1
    progress.done({"valid": 0})
    progress.finish()
    lines = stream.getvalue().splitlines()
    assert lines[0] == "rrt-grade: runs 0/3 done, 0 valid, 0s elapsed"
    assert lines[-1] == "rrt-grade: runs 2/3 done, 1 valid, 1m01s elapsed, about 30s left"
    assert all(LINE.match(line) for line in lines)


def test_durations_read_as_a_person_would():
    assert [duration(s) for s in (0, 59.4, 61, 3599, 3600, 7380)] == [
        "0s", "59s", "1m01s", "59m59s", "1h00m", "2h03m"]


def test_a_closed_stderr_does_not_stop_the_grading():
    stream = io.StringIO()
    stream.close()
    progress = Progress(stream)
    progress.start("runs", 1)
    progress.done({"valid": 1})
    progress.finish()


def _class(tmp_path: Path) -> list[str]:
    submissions, problems, _ = make_class(tmp_path, ["good", "garbage"], ["simple-0.sw"])
    make_submission(submissions, "hang", "", "sleep 30", tmp_path / "unused")
    return ["--submissions", str(submissions), "--problems", str(problems),
            "--out", str(tmp_path / "out"), "--modes", "point,grad"]


# A long end-to-end run (a grading held by two hanging runs): CI only; the line's cadence
# is the first test's, on a clock.
@pytest.mark.slow
def test_progress_lines_with_stdout_and_stderr_redirected_to_files(tmp_path):
    argv = _class(tmp_path) + ["--timeout", "3", "--progress-every", "0.5"]
    with open(tmp_path / "stdout", "wb") as out, open(tmp_path / "stderr", "wb") as err:
        done = subprocess.run(["rrt-grade", *argv], stdout=out, stderr=err, timeout=300,
                              env=dict(os.environ, PATH=f"{ROOT}:{os.environ['PATH']}"))
    assert done.returncode == 0
    lines = (tmp_path / "stderr").read_text().splitlines()
    progress = [LINE.match(line) for line in lines[:-1]]
    assert all(progress), lines
    runs = [match for match in progress if match[1] == "runs"]
    elapsed = [_seconds(match[5]) for match in runs]
    assert len(runs) >= 5 and max(b - a for a, b in zip(elapsed, elapsed[1:])) <= 2, lines
    stuck = Counter(match[2] for match in runs).most_common(1)[0][1]
    assert stuck >= 3  # lines while the hanging runs held both workers
    assert runs[-1][2] == runs[-1][3] == "6" and runs[-1][4] == "2"
    assert any(match[6] for match in runs)  # an estimate of the rest
    assert lines[-1].startswith("rrt-grade: 6 runs now, 0 kept; 3 builds now")
    assert (tmp_path / "stdout").read_text().splitlines()[0].split() == [
        "submission", "valid", "runs", "valid_point", "valid_grad", "score"]


# The code each grading on a terminal runs: the grading, then which optional modules it loaded.
_GRADE = ("import sys; sys.path.insert(0, sys.argv[1]); from grading.cli import main\n"
          "status = main(sys.argv[2:])\n"
          "loaded = sorted(m for m in ('distributed', 'dask', 'tqdm', 'reportlab', 'numpy') "
          "if m in sys.modules)\nprint('loaded:', loaded, file=sys.stderr)\nsys.exit(status)")


def _graded_on_a_terminal(tmp_path: Path, flags: list[str]) -> tuple[int, str]:
    """``_class`` graded by ``python FLAGS -I -B`` with stderr on a terminal (a pty of 100
    columns): the exit status and what the terminal was sent."""
    argv = _class(tmp_path) + ["--timeout", "1", "--modes", "point"]
    primary, secondary = pty.openpty()
    fcntl.ioctl(secondary, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    with open(tmp_path / "stdout", "wb") as out:
        grading = subprocess.Popen([sys.executable, *flags, "-I", "-B", "-c", _GRADE,
                                    str(ROOT), *argv],
                                   stdout=out, stderr=secondary, stdin=subprocess.DEVNULL)
    os.close(secondary)
    shown = b""
    while True:
        try:
            chunk = os.read(primary, 65536)
        except OSError:  # the grading ended: the terminal is gone
            break
        if not chunk:
            break
        shown += chunk
    status = grading.wait(timeout=120)
    os.close(primary)
    return status, shown.decode(errors="replace")


@pytest.fixture(scope="module")
def bare(tmp_path_factory) -> tuple[int, str, Path]:
    """The class graded on a bare python3 (-S: no site-packages, so no Dask, tqdm or
    reportlab) on a terminal: the exit status, the terminal's text, the --out folder.
    Both tests below read it: the plain bar, and the local pool without site-packages."""
    tmp_path = tmp_path_factory.mktemp("bare")
    return (*_graded_on_a_terminal(tmp_path, ["-S"]), tmp_path / "out")


@pytest.mark.parametrize("site", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_on_a_terminal_a_bar(request, tmp_path, site):
    """``site``: the interpreter's site-packages (tqdm's bar); without: the plain line."""
    if site:
        pytest.importorskip("tqdm")
        status, text = _graded_on_a_terminal(tmp_path, [])
    else:
        status, text, _ = request.getfixturevalue("bare")
    assert status == 0
    assert "\r" in text and "rrt-grade" in text and "runs" in text
    assert ("it/s" in text or "task/s" in text or "s/task" in text) if site else \
        "\r\x1b[2Krrt-grade: runs 3/3 done, 1 valid, " in text


def test_the_local_pool_runs_on_a_bare_python3(bare):
    """No site-packages (-S): no Dask, tqdm or reportlab; the grading is whole, the failing
    runs have no PDF."""
    status, text, out = bare
    assert status == 0, text
    assert text.splitlines()[-1] == "loaded: []"
    book = (out / "gradebook.csv").read_text().splitlines()
    assert book[1:] == ["garbage,0,1,0,0.0", "good,1,1,1,100.0", "hang,0,1,0,0.0"]
    assert not (out / "pdf" / "garbage" / "simple-0-point.pdf").exists()
