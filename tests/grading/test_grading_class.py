"""A class of fake submissions graded end to end through ``rrt-grade``'s main."""

from __future__ import annotations

import csv
import os
import sqlite3

import pytest

from grading.cli import main
from grading.runs import sandbox_here
from grading.sandbox import FULL
from grading_fixtures import CLASS, make_class, nap

MODES = ["point", "grad"]
EXPECTED = {  # submission -> (verdict, failed check) in every mode
    "good": ("valid", None), "garbage": ("invalid", "parse"),
    "hang": ("planner failed", "planner"), "crash": ("invalid", "parse"),
    "flood": ("invalid", "parse"), "nobuild": ("build failed", "build"),
    "forks": ("valid", None), "escape": ("valid", None),
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    base = tmp_path_factory.mktemp("class")
    submissions, problems, outside = make_class(base, list(CLASS), ["simple-0.sw"])
    out = base / "out"
    status = main(["--submissions", str(submissions), "--problems", str(problems),
                   "--out", str(out), "--modes", ",".join(MODES), "--jobs", "2",
                   "--timeout", "2"])
    db = sqlite3.connect(out / "grades.sqlite")
    db.row_factory = sqlite3.Row
    rows = [dict(row) for row in db.execute("SELECT * FROM runs")]
    db.close()
    return status, rows, out, submissions, outside


def test_exit_status_is_zero_whatever_the_verdicts(graded):
    assert graded[0] == 0


def test_one_row_per_submission_problem_mode_with_the_expected_verdict(graded):
    rows = graded[1]
    assert sorted((r["submission"], r["mode"]) for r in rows) == sorted(
        (name, mode) for name in CLASS for mode in MODES)
    for row in rows:
        if row["submission"] == "flood" and row["timed_out"]:
            continue  # a loaded machine may not read 64 MiB within the timeout
        assert (row["verdict"], row["failed_check"]) == EXPECTED[row["submission"]], row


def test_the_rows_say_what_happened(graded):
    by = {(r["submission"], r["mode"]): r for r in graded[1]}
    good = by["good", "grad"]
    assert good["valid"] == 1 and good["path_length"] > 0 and good["tree_size"] > 0
    assert good["exit_status"] == 0 and good["output_bytes"] > 0
    assert by["hang", "point"]["timed_out"] == 1
    assert by["crash", "point"]["signal"] == 11
    flood = by["flood", "point"]
    assert flood["output_bytes"] == 64 << 20 or flood["timed_out"]
    assert "exited 3" in by["nobuild", "point"]["message"]
    assert all(r["sandbox"] for r in graded[1])


def test_gradebook_columns_and_counts(graded):
    with open(graded[2] / "gradebook.csv", newline="") as book:
        reader = csv.DictReader(book)
        assert reader.fieldnames == ["submission", "valid", "runs", "valid_point",
                                     "valid_grad", "score"]
        rows = {row["submission"]: row for row in reader}
    assert rows["good"] == {"submission": "good", "valid": "2", "runs": "2",
                            "valid_point": "1", "valid_grad": "1", "score": "100.0"}
    assert rows["garbage"]["score"] == "0.0" and rows["nobuild"]["runs"] == "2"


def test_report_links_the_failing_runs_pdfs(graded):
    out = graded[2]
    report = (out / "report.md").read_text()
    assert "(pdf/garbage/simple-0-point.pdf)" in report
    assert (out / "pdf" / "garbage" / "simple-0-point.pdf").read_bytes()[:5] == b"%PDF-"
    assert not (out / "pdf" / "good").exists()
    assert "failed: make.sh exited 3" in report


def test_nothing_the_submissions_started_is_left_running(graded):
    sleeps = [f"sleep\0{nap(graded[3])}{digit}\0".encode() for digit in "123"]
    left = []
    for name in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{name}/cmdline", "rb") as cmdline:
                if cmdline.read() in sleeps:  # forks', hang's (timed out)
                    left.append(int(name))
        except OSError:
            pass
    assert left == []


def test_nothing_is_written_outside_the_submission_folder(graded):
    if not sandbox_here(True).namespaces:
        pytest.skip(f"no sandbox here: {sandbox_here(True).note}")
    assert os.listdir(graded[4]) == []
    assert all(r["sandbox"].startswith(FULL) for r in graded[1])
