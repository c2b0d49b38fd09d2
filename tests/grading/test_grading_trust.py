"""What rrt-grade trusts less than it did: a second rrt-grade on the same --out, text
written by submissions in report.md and report.html, stderr and make.sh's output in the logs, a run
that outlives its timeout, a worker that dies under a run."""

from __future__ import annotations

import csv
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

from grading.cli import EXIT_BUSY, main
from grading.grade import LOCK
from grading_fixtures import COURSE, ROOT, make_submission


def _class(tmp_path: Path, scripts: dict[str, tuple[str, str]]) -> tuple[Path, Path]:
    """``(submissions, problems)``: the named (make.sh, run.sh) bodies, simple-0.sw."""
    for name, (make, run) in scripts.items():
        make_submission(tmp_path / "subs", name, make, run, tmp_path / "unused")
    problems = tmp_path / "problems"
    problems.mkdir()
    (problems / "simple-0.sw").write_bytes((COURSE / "simple-0.sw").read_bytes())
    return tmp_path / "subs", problems


def _argv(submissions: Path, problems: Path, out: Path, *more: str) -> list[str]:
    return ["--submissions", str(submissions), "--problems", str(problems), "--out", str(out),
            *more]


def _gradebook(out: Path) -> dict[str, dict]:
    with open(out / "gradebook.csv", newline="") as book:
        return {row["submission"]: row for row in csv.DictReader(book)}


def test_a_second_rrt_grade_on_the_same_out_refuses_with_one_line(tmp_path):
    submissions, problems = _class(tmp_path, {"hang": ("", "sleep 100")})
    argv = [sys.executable, "-m", "grading", *_argv(submissions, problems, tmp_path / "out",
                                                    "--modes", "point", "--timeout", "30")]
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    first = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while not (tmp_path / "out" / "logs").exists() and time.monotonic() < deadline:
            time.sleep(0.05)  # the first one holds the lock and is running
        second = subprocess.run(argv, cwd=ROOT, env=env, capture_output=True, text=True,
                                timeout=60)
    finally:
        first.send_signal(signal.SIGTERM)
        first.wait(timeout=60)
    assert second.returncode == EXIT_BUSY == 3
    assert second.stderr == (f"rrt-grade: error: {tmp_path / 'out'} is being graded by "
                             f"another rrt-grade (pid {first.pid})\n")
    assert (tmp_path / "out" / LOCK).exists()


def test_the_lock_goes_with_its_holder(tmp_path):
    submissions, problems = _class(tmp_path, {"garbage": ("", "echo hello")})
    argv = _argv(submissions, problems, tmp_path / "out", "--modes", "point")
    assert main(argv) == 0
    assert main([*argv, "--rerun"]) == 0  # the first run's lock was released


def _children(pid: int) -> list[int]:
    found = []
    for name in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{name}/stat") as stat:
                if int(stat.read().rsplit(")", 1)[1].split()[1]) == pid:
                    found.append(int(name))
        except (OSError, IndexError, ValueError):
            pass
    return found


def test_the_lock_goes_with_rrt_grade_killed_while_its_workers_still_unwind(tmp_path):
    submissions, problems = _class(tmp_path, {"hang": ("", "sleep 100")})
    out = tmp_path / "out"
    first = subprocess.Popen([sys.executable, "-m", "grading",
                              *_argv(submissions, problems, out, "--modes", "point")],
                             cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)),
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while not (out / "logs" / "hang").exists() and time.monotonic() < deadline:
        time.sleep(0.05)  # a run is in flight
    workers = _children(first.pid)
    for worker in workers:
        os.kill(worker, signal.SIGSTOP)  # they would unwind, then end: here they cannot
    first.kill()
    first.wait()
    try:  # a rerun at once: graded, not refused as busy
        assert main(_argv(submissions, problems, out, "--modes", "point", "--timeout", "0.5")) == 0
    finally:
        for worker in workers:
            os.kill(worker, signal.SIGKILL)
    assert workers


def test_the_reports_show_what_submissions_and_planners_wrote_as_text(tmp_path):
    submissions, problems = _class(tmp_path, {
        "x<img src=1 onerror=alert(1)>": ("", "echo '1'; echo '<script>alert(2)</script> 3'"),
        "mk": ("echo '[click](http://evil) <img src=x onerror=alert(3)>'; exit 1", "")})
    out = tmp_path / "out"
    assert main(_argv(submissions, problems, out, "--modes", "point")) == 0
    report = (out / "report.md").read_text()
    for raw in ("<img", "<script", "[click](http://evil)"):
        assert raw not in report
    for shown in ("## x&lt;img src=1 onerror=alert(1)&gt;", "&lt;script&gt;",
                  "\\[click\\](http://evil) &lt;img src=x onerror=alert(3)&gt;"):
        assert shown in report
    assert "(pdf/x%3Cimg%20src%3D1%20onerror%3Dalert%281%29%3E/simple-0-point.pdf)" in report
    pages = [out / "report.html", *(out / "html").glob("*/index.html"),
             *(out / "html").glob("*/simple-0-point.html")]
    assert len(pages) == 4  # the class, two submissions, the view of the one that built
    for page in pages:
        text = page.read_text()
        for raw in ("<img", "<script>alert", "onerror=alert(1)>"):
            assert raw not in text, page
    assert "x&lt;img src=1 onerror=alert(1)&gt;" in (out / "report.html").read_text()
    assert "&lt;script&gt;alert(2)&lt;/script&gt;" in (
        out / "html" / "x<img src=1 onerror=alert(1)>" / "index.html").read_text()
    assert "[click](http://evil) &lt;img src=x onerror=alert(3)&gt;" in (
        out / "html" / "mk" / "index.html").read_text()


def test_a_runs_stderr_and_make_sh_output_are_kept_up_to_1_mib(tmp_path):
    noise = "head -c 3000000 /dev/zero | tr '\\0' x"
    submissions, problems = _class(tmp_path, {"noisy": (noise, noise + ' >&2\nexec "{run}" "$@"')})
    out = tmp_path / "out"
    assert main(_argv(submissions, problems, out, "--modes", "point")) == 0
    for log in ("make.log", "simple-0-point.stderr"):
        data = (out / "logs" / "noisy" / log).read_bytes()
        assert data.startswith(b"x" * (1 << 20) + b"\n")
        assert data[(1 << 20) + 1:] == (b"rrt-validator: the planner wrote 3000000 bytes on "
                                        b"stderr; only the first 1048576 were passed on\n")
    assert _gradebook(out)["noisy"]["score"] == "100.0"


def test_a_run_that_answers_then_outlives_its_timeout_is_not_valid(tmp_path):
    submissions, problems = _class(tmp_path, {"good": ("", 'exec "{run}" "$@"'),
                                              "late": ("", '"{run}" "$@"\nsleep 100')})
    out = tmp_path / "out"
    # its planner answers in 0.5 s at load 4 (3x within the timeout), then it sleeps past it
    assert main(_argv(submissions, problems, out, "--modes", "point,grad", "--timeout", "1.5")) == 0
    db = sqlite3.connect(out / "grades.sqlite")
    rows = db.execute("SELECT verdict, valid, timed_out, output_bytes FROM runs "
                      "WHERE submission = 'late'").fetchall()
    assert len(rows) == 2
    for verdict, valid, timed_out, output_bytes in rows:  # it did print a valid answer
        assert (verdict, valid, timed_out) == ("planner failed", 0, 1) and output_bytes > 0
    book = _gradebook(out)
    assert (book["late"]["valid"], book["late"]["score"]) == ("0", "0.0")
    assert (book["good"]["valid"], book["good"]["score"]) == ("2", "100.0")
    assert "| [timed out](pdf/late/simple-0-point.pdf) |" in (out / "report.md").read_text()


def test_a_worker_that_dies_costs_only_the_run_it_was_running(tmp_path, capsys):
    submissions, problems = _class(tmp_path, {"good": ("", 'exec "{run}" "$@"'),
                                              "killer": ("", "kill -9 $PPID; sleep 5")})
    out = tmp_path / "out"
    assert main(_argv(submissions, problems, out, "--modes", "point,grad", "--jobs", "2",
                      "--no-sandbox")) == 0
    db = sqlite3.connect(out / "grades.sqlite")
    rows = db.execute("SELECT verdict, message FROM runs WHERE submission = 'killer'").fetchall()
    assert rows == [("planner failed", "rrt-grade's worker died during this run, twice (the "
                     "second time running alone)")] * 2
    good = db.execute("SELECT * FROM runs WHERE submission = 'good' AND NOT valid").fetchall()
    assert _gradebook(out)["good"]["score"] == "100.0", (good, capsys.readouterr())


def test_submission_names_stay_text_in_the_gradebook_and_the_terminal(tmp_path):
    from grading.report import summary_table, write_gradebook
    rows = [{"submission": name, "valid": 1, "runs": 1, "valid_point": 1, "score": 100.0}
            for name in ("=HYPERLINK(\"http://x\")", "+1", "\x1b[2Jwiped", "alice")]
    with open(write_gradebook(tmp_path, rows), newline="") as saved:
        cells = [row["submission"] for row in csv.DictReader(saved)]
    assert cells == ["'=HYPERLINK(\"http://x\")", "'+1", "\x1b[2Jwiped", "alice"]
    table = summary_table(rows)
    assert "\x1b" not in table and "\\x1b[2Jwiped" in table
