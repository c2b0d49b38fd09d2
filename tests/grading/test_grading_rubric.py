"""The rubric: its TOML file, what it grades, repeats and flaky submissions, and how
report.md lists failures."""

from __future__ import annotations

import csv
import json
import re
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest

from grading.cli import main
from grading.rubric import Rubric, RubricError, load_rubric, rubric_from_table
from grading.store import Store
from grading_fixtures import FLAKY, ROOT, make_class, make_submission

PROBLEMS = ["simple-0.sw", "space-0.sw", "pendulum-t3.kp", "arm2-pair1.kp"]


def _labels(rubric: Rubric) -> list[tuple]:
    return [(i.problem, i.mode, i.weight, i.timeout, i.repeats)
            for i in rubric.items(sorted(PROBLEMS))]


def test_rules_apply_in_order_and_a_kp_problem_has_its_one_mode():
    rubric = rubric_from_table({
        "modes": ["point", "grad"], "timeout": 20, "mode_weights": {"grad": 2, "kinoplan": 3},
        "problems": [{"match": "*.sw", "weight": 2, "modes": ["left"]},
                     {"match": "space-*", "modes": ["point", "left"], "repeats": 3},
                     {"match": "arm2-*", "skip": True}]})
    assert _labels(rubric) == [
        ("pendulum-t3.kp", "kinoplan", 3.0, 20.0, 1), ("simple-0.sw", "left", 2.0, 20.0, 1),
        ("space-0.sw", "point", 2.0, 20.0, 3), ("space-0.sw", "left", 2.0, 20.0, 3)]
    assert rubric.scale is None  # a file without a scale scores in points
    assert rubric.full_score(rubric.items(sorted(PROBLEMS))) == 9.0


def test_the_default_rubric_is_the_old_command_line():
    items = Rubric().items(sorted(PROBLEMS))
    assert [(i.problem, i.mode) for i in items][:4] == [
        ("arm2-pair1.kp", "kinoplan"), ("pendulum-t3.kp", "kinoplan"),
        ("simple-0.sw", "point"), ("simple-0.sw", "grad")]
    assert {(i.weight, i.timeout, i.repeats) for i in items} == {(1.0, 60.0, 1)}
    assert Rubric().full_score(items) == 100.0


@pytest.mark.parametrize("text, expected", [
    ("weigth = 2", "unknown key 'weigth'"),
    ("modes = ['point', 'fly']", "modes: expected distinct modes among point,grad,left"),
    ("repeats = 0", "repeats: expected an integer from 1 to 100"),
    ("timeout = -1", "timeout: expected a number above 0"),
    ("[[problems]]\nweight = 1", "problems entry 1: match: expected a file name or a glob"),
    ("[[problems]]\nmatch = 'x'\nrepeats = true", "problems entry 1: repeats: expected an"),
    ("mode_weights = {fly = 2}", "mode_weights: unknown mode 'fly'"),
    ("visibility = 'later'", "visibility: expected one of hidden, after_due_date"),
    ("modes = [", "not TOML: "),
])
def test_a_bad_rubric_is_one_line_and_exit_2_before_anything_runs(tmp_path, capsys, text,
                                                                  expected):
    submissions, problems, _ = make_class(tmp_path, ["garbage"], ["simple-0.sw"])
    (tmp_path / "rubric.toml").write_text(text + "\n")
    status = main(["--submissions", str(submissions), "--problems", str(problems),
                   "--out", str(tmp_path / "out"), "--rubric", str(tmp_path / "rubric.toml")])
    err = capsys.readouterr().err
    assert status == 2 and not (tmp_path / "out").exists()
    assert err.startswith(f"rrt-grade: error: {tmp_path / 'rubric.toml'}: ")
    assert expected in err and err.count("\n") == 1, err


def test_a_rule_that_matches_no_problem_is_one_line_and_exit_2(tmp_path, capsys):
    submissions, problems, _ = make_class(tmp_path, ["garbage"], ["simple-0.sw"])
    (tmp_path / "rubric.toml").write_text('[[problems]]\nmatch = "spcae-*.sw"\n')
    status = main(["--submissions", str(submissions), "--problems", str(problems),
                   "--out", str(tmp_path / "out"), "--rubric", str(tmp_path / "rubric.toml")])
    assert status == 2
    assert capsys.readouterr().err == ("rrt-grade: error: problems entry 1 (match "
                                       "'spcae-*.sw') matches no problem\n")


def test_without_tomllib_or_tomli_a_rubric_is_one_line(tmp_path):
    (tmp_path / "rubric.toml").write_text("repeats = 2\n")
    code = ("import sys; sys.modules['tomllib'] = sys.modules['tomli'] = None\n"
            "from grading.rubric import load_rubric, RubricError\n"
            f"try:\n    load_rubric(__import__('pathlib').Path({str(tmp_path / 'rubric.toml')!r}))\n"
            "except RubricError as error:\n    print(error)\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          text=True, timeout=60)
    assert done.stdout == ("reading a rubric needs Python 3.11 or newer, or the tomli "
                           "package (pip install tomli)\n"), done.stderr
    if sys.version_info >= (3, 11):
        assert load_rubric(tmp_path / "rubric.toml").repeats == 2


def test_a_rubric_larger_than_its_cap_is_refused(tmp_path):
    (tmp_path / "big.toml").write_text("# " + "x" * (1 << 20) + "\n")
    with pytest.raises(RubricError, match="more than 1048576 bytes"):
        load_rubric(tmp_path / "big.toml")


def test_the_flags_set_the_rubrics_top_level_keys(tmp_path):
    (tmp_path / "rubric.toml").write_text('timeout = 30\nrepeats = 3\nmodes = ["grad"]\n'
                                          '[[problems]]\nmatch = "space-*"\ntimeout = 9\n')
    from grading.cli import _rubric, build_parser
    args = build_parser().parse_args(["--submissions", ".", "--problems", ".", "--out", "o",
                                      "--rubric", str(tmp_path / "rubric.toml"),
                                      "--timeout", "5", "--modes", "point"])
    assert _labels(_rubric(args)) == [
        ("arm2-pair1.kp", "kinoplan", 1.0, 5.0, 3), ("pendulum-t3.kp", "kinoplan", 1.0, 5.0, 3),
        ("simple-0.sw", "point", 1.0, 5.0, 3), ("space-0.sw", "point", 1.0, 9.0, 3)]


@pytest.fixture(scope="module")
def repeated(tmp_path_factory):
    """A flaky submission (valid on alternate runs) and a good one, 2 repeats of a .sw
    and a .kp problem worth 3 and 5 points; without the sandbox (the flaky one counts its
    runs in its own folder)."""
    base = tmp_path_factory.mktemp("repeats")
    submissions, problems, _ = make_class(base, ["good"], ["simple-0.sw", "pendulum-t3.kp"])
    make_submission(submissions, "flaky", *FLAKY, base / "unused")
    (base / "rubric.toml").write_text('modes = ["point"]\n'
                                      '[[problems]]\nmatch = "simple-0.sw"\nweight = 3\n'
                                      '[[problems]]\nmatch = "*.kp"\nweight = 5\n')
    out = base / "out"
    status = main(["--submissions", str(submissions), "--problems", str(problems), "--out",
                   str(out), "--rubric", str(base / "rubric.toml"), "--repeats", "2",
                   "--no-sandbox", "--format", "gradescope"])
    return status, out


def test_a_flaky_submission_gets_the_share_of_its_repeats_that_were_valid(repeated):
    status, out = repeated
    assert status == 0
    with open(out / "gradebook.csv", newline="") as book:
        rows = {row["submission"]: row for row in csv.DictReader(book)}
    assert (rows["flaky"]["score"], rows["flaky"]["runs"], rows["flaky"]["valid"]) == (
        "4.0", "4", "2")  # half of 3 + half of 5
    assert rows["good"]["score"] == "8.0"
    tests = json.loads((out / "gradescope" / "flaky" / "results.json").read_text())["tests"]
    assert [(t["name"], t["score"], t["max_score"]) for t in tests[1:]] == [
        ("pendulum-t3.kp kinoplan", 2.5, 5.0), ("simple-0.sw point", 1.5, 3.0)]
    db = sqlite3.connect(out / "grades.sqlite")
    valid = db.execute("SELECT problem, group_concat(valid, '') FROM (SELECT * FROM runs "
                       "WHERE submission = 'flaky' ORDER BY repeat) GROUP BY problem").fetchall()
    assert len(valid) == 2 and all(sorted(flags) == list("01") for _, flags in valid)


def test_the_report_shows_flaky_runs_as_such(repeated):
    report = (repeated[1] / "report.md").read_text()
    assert "| flaky | simple-0.sw | point | 1 of 2 |" in report
    assert "| flaky | pendulum-t3.kp | kinoplan | 1 of 2 |" in report
    assert re.search(r"\| \[flaky: 1/2 valid\]\(pdf/flaky/simple-0-point(-2)?\.pdf\) \|",
                     report)
    assert "- Score: **4.0** out of 8 (2 of 4 runs valid; 2 flaky)" in report
    assert "- invalid (parse): " in report and ": 2 runs (pendulum-t3.kp: kinoplan (1 of 2); " \
        "simple-0.sw: point (1 of 2))" in report


def test_failures_are_listed_in_the_tables_order(tmp_path):
    submissions, problems, _ = make_class(tmp_path, [], ["simple-0.sw"])
    make_submission(submissions, "mixed", "", 'case "$*" in *-grad*) echo "1 2";; '
                    '*) echo hello;; esac', tmp_path / "unused")
    out = tmp_path / "out"
    assert main(["--submissions", str(submissions), "--problems", str(problems), "--out",
                 str(out), "--no-calibration"]) == 0
    report = (out / "report.md").read_text()
    assert "| simple-0.sw | [invalid (parse)](pdf/mixed/simple-0-point.pdf) | " in report
    failures = [line for line in report.splitlines() if line.startswith("- invalid")]
    assert len(failures) == 2
    assert failures[0].endswith("got 'hello'): 1 run (simple-0.sw: point)")
    assert failures[1].endswith(": 2 runs (simple-0.sw: grad, left)")


def test_a_store_from_before_repeats_keeps_its_rows_as_repeat_0(tmp_path):
    db = sqlite3.connect(tmp_path / "grades.sqlite")
    db.executescript("""
        CREATE TABLE runs (submission TEXT NOT NULL, problem TEXT NOT NULL, mode TEXT NOT NULL,
            verdict TEXT NOT NULL, valid INTEGER NOT NULL, failed_check TEXT, message TEXT,
            detail TEXT, exit_status INTEGER, signal INTEGER, timed_out INTEGER, wall_time REAL,
            path_length REAL, trajectory_size INTEGER, tree_size INTEGER, output_bytes INTEGER,
            sandbox TEXT, pdf TEXT, log TEXT, finished TEXT NOT NULL DEFAULT (datetime('now')),
            PRIMARY KEY (submission, problem, mode));
        INSERT INTO runs (submission, problem, mode, verdict, valid, wall_time, finished)
            VALUES ('alice', 'simple-0.sw', 'point', 'valid', 1, 0.25, '2026-12-01 10:00:00');
        """)
    db.commit()
    db.close()
    store = Store(Path(tmp_path))
    try:
        rows = store.runs()
        assert store.finished_runs() == {("alice", "simple-0.sw", "point", 0)}
    finally:
        store.close()
    assert [(r["submission"], r["repeat"], r["valid"], r["wall_time"], r["finished"])
            for r in rows] == [("alice", 0, 1, 0.25, "2026-12-01 10:00:00")]
