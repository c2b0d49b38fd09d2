"""A class of fake submissions graded end to end through ``rrt-grade``'s main: a grid
map in two modes and a kinoplan problem."""

from __future__ import annotations

import csv
import os
import re
import sqlite3

import pytest

from grading.cli import main
from grading.runs import sandbox_here
from grading.sandbox import FULL
from grading_fixtures import CLASS, make_class, nap
from tests.validator.browser import Chromium, find_chromium

MODES = ["point", "grad"]
PROBLEMS = ["simple-0.sw", "pendulum-t3.kp"]
ITEMS = [("simple-0.sw", mode) for mode in MODES] + [("pendulum-t3.kp", "kinoplan")]
EXPECTED = {  # submission -> (verdict, failed check) in every mode
    "good": ("valid", None), "garbage": ("invalid", "parse"),
    "asleep": ("planner failed", "planner"), "crash": ("invalid", "parse"),
    "flood": ("invalid", "parse"), "nobuild": ("build failed", "build"),
    "forks": ("valid", None), "escape": ("valid", None), "copy-a": ("valid", None),
    "copy-b": ("valid", None), "other": ("valid", None),
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    base = tmp_path_factory.mktemp("class")
    submissions, problems, outside = make_class(base, list(CLASS), PROBLEMS)
    out = base / "out"
    status = main(["--submissions", str(submissions), "--problems", str(problems),
                   "--out", str(out), "--modes", ",".join(MODES), "--jobs", "6",
                   "--timeout", "3"])  # a valid run takes 0.5 s at load 4; asleep's 3 runs
    # hold 3 of the 6 workers for the whole timeout while the other 3 grade the rest
    db = sqlite3.connect(out / "grades.sqlite")
    db.row_factory = sqlite3.Row
    rows = [dict(row) for row in db.execute("SELECT * FROM runs")]
    db.close()
    return status, rows, out, submissions, outside


def test_exit_status_is_zero_whatever_the_verdicts(graded):
    assert graded[0] == 0


def test_one_row_per_submission_problem_mode_with_the_expected_verdict(graded):
    rows = graded[1]
    assert sorted((r["submission"], r["problem"], r["mode"]) for r in rows) == sorted(
        (name, *item) for name in CLASS for item in ITEMS)
    for row in rows:
        if row["submission"] == "flood" and row["timed_out"]:
            continue  # a loaded machine may not read 64 MiB within the timeout
        assert (row["verdict"], row["failed_check"]) == EXPECTED[row["submission"]], row


def test_the_rows_say_what_happened(graded):
    by = {(r["submission"], r["mode"]): r for r in graded[1]}
    assert by["good", "kinoplan"]["valid"] == 1 and by["good", "kinoplan"]["tree_size"] > 0
    good = by["good", "grad"]
    assert good["valid"] == 1 and good["path_length"] > 0 and good["tree_size"] > 0
    assert good["exit_status"] == 0 and good["output_bytes"] > 0
    assert by["asleep", "point"]["timed_out"] == 1
    assert by["crash", "point"]["signal"] == 11
    flood = by["flood", "point"]
    assert flood["output_bytes"] == 64 << 20 or flood["timed_out"]
    assert "exited 3" in by["nobuild", "point"]["message"]
    assert all(r["sandbox"] for r in graded[1])


def test_gradebook_columns_and_counts(graded):
    with open(graded[2] / "gradebook.csv", newline="") as book:
        reader = csv.DictReader(book)
        assert reader.fieldnames == ["submission", "valid", "runs", "valid_point",
                                     "valid_grad", "valid_kinoplan", "score"]
        rows = {row["submission"]: row for row in reader}
    assert rows["good"] == {"submission": "good", "valid": "3", "runs": "3",
                            "valid_point": "1", "valid_grad": "1", "valid_kinoplan": "1",
                            "score": "100.0"}
    assert rows["garbage"]["score"] == "0.0" and rows["nobuild"]["runs"] == "3"


def test_report_links_the_failing_runs_pdfs(graded):
    out = graded[2]
    report = (out / "report.md").read_text()
    assert "(pdf/garbage/simple-0-point.pdf)" in report
    assert (out / "pdf" / "garbage" / "simple-0-point.pdf").read_bytes()[:5] == b"%PDF-"
    import pypdfium2 as pdfium  # the page says whose run it was
    document = pdfium.PdfDocument(str(out / "pdf" / "garbage" / "simple-0-point.pdf"))
    assert "garbage: simple-0-point" in document[0].get_textpage().get_text_range()
    assert "(pdf/garbage/pendulum-t3-kinoplan.pdf)" in report
    assert (out / "pdf" / "garbage" / "pendulum-t3-kinoplan.pdf").read_bytes()[:5] == b"%PDF-"
    assert not (out / "pdf" / "good").exists()
    assert "failed: make.sh exited 3" in report


def test_nothing_the_submissions_started_is_left_running(graded):
    sleeps = [f"sleep\0{nap(graded[3])}{digit}\0".encode() for digit in "123"]
    left = []
    for name in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{name}/cmdline", "rb") as cmdline:
                if cmdline.read() in sleeps:  # forks', asleep's (timed out)
                    left.append(int(name))
        except OSError:
            pass
    assert left == []


def test_nothing_is_written_outside_the_submission_folder(graded):
    if not sandbox_here(True).namespaces:
        pytest.skip(f"no sandbox here: {sandbox_here(True).note}")
    assert os.listdir(graded[4]) == []
    assert all(r["sandbox"].startswith(FULL) for r in graded[1])


def test_a_kinoplan_problem_gets_no_vehicle_flags(graded):
    logs = graded[2] / "logs" / "other"
    assert (logs / "simple-0-grad.stderr").read_text() == "kraken: flag -grad\n"
    assert not (logs / "pendulum-t3-kinoplan.stderr").exists()  # nothing said: no flags


def _section(report: str, title: str) -> str:
    """The text of ``report``'s section ``title`` (a heading's line), to the next heading
    of its level or above."""
    level = title.split(" ")[0]
    start = report.index(title + "\n")
    ends = [report.find("\n" + "#" * n + " ", start + len(title))
            for n in range(1, len(level) + 1)]
    return report[start:min([end for end in ends if end >= 0] or [len(report)])]


def test_report_md_summarizes_the_class(graded):
    report = (graded[2] / "report.md").read_text()
    summary = _section(report, "## Class summary")
    assert f"{len(CLASS)} submissions; scores out of 100: mean " in summary
    assert "| 90 to 100 | 6 | ###### |" in summary  # good, forks, escape, copies, other
    assert "| 0 to 10 | 5 | ##### |" in summary
    rates = _section(report, "### Pass rate per problem and mode")
    assert "| simple-0.sw | 6/11 (55%) | 6/11 (55%) | - |" in rates
    assert "| pendulum-t3.kp | - | - | 6/11 (55%) |" in rates
    slowest = _section(report, "### Slowest runs").splitlines()
    assert all(line.startswith("| asleep | ") and line.endswith("| timed out |")
               for line in slowest[4:7])
    assert re.search(r"\| \d+\.\d\d s \| x\d+\.\d\d \| timed out \|$", slowest[4])
    failing = _section(report, "### Failing runs")
    assert "| build failed: make.sh exited 3: oops | 3 | nobuild |" in failing
    for name in EXPECTED:
        assert f"## {name}\n\n- Score: **" in report


def test_two_copies_are_flagged_and_a_third_different_one_is_not(graded):
    similar = _section((graded[2] / "report.md").read_text(), "### Similar pairs to look at")
    rows = [line for line in similar.splitlines() if line.startswith("| ") and "---" not in
            line][1:]
    assert [row.split(" | ")[:2] for row in rows] == [
        ["| copy-a, copy-b", "identical answers"], ["| copy-a, copy-b", "near-identical sources"]]
    assert "on 3 of the 3 problem-modes both solved" in rows[0]
    assert "run.sh and run.sh" in rows[1]


def test_each_distinct_failure_is_listed_once_with_its_count(graded):
    garbage = _section((graded[2] / "report.md").read_text(), "## garbage")
    failures = [line for line in garbage.splitlines() if line.startswith("- ")][3:]
    assert len(failures) == 1 and failures[0].startswith("- invalid (parse): ")
    assert failures[0].endswith(": 3 runs (pendulum-t3.kp: kinoplan; simple-0.sw: point, "
                                "grad)"), failures


def test_a_failing_runs_view_is_written_beside_its_submissions_page(graded):
    rows, out = graded[1], graded[2]
    by = {(r["submission"], r["mode"]): r for r in rows}
    for mode, stem in (("point", "simple-0-point"), ("kinoplan", "pendulum-t3-kinoplan")):
        view = out / "html" / "garbage" / f"{stem}.html"
        assert by["garbage", mode]["view"] == str(view)
        assert view.read_text().startswith("<!DOCTYPE html>") and "garbage: " + stem in \
            view.read_text()
    assert by["good", "point"]["view"] is None and not (out / "html" / "good" / "simple-0-point"
                                                        ".html").exists()
    page = (out / "html" / "garbage" / "index.html").read_text()
    assert 'data-src="simple-0-point.html"' in page and 'href="simple-0-point.html"' in page
    assert 'href="../../pdf/garbage/simple-0-point.pdf"' in page
    assert 'href="html/garbage/index.html"' in (out / "report.html").read_text()


@pytest.mark.skipif(find_chromium() is None, reason="no Chromium: ./make.sh installs Debian's "
                    "chromium where it can (apt-get, as root)")
def test_a_submissions_page_shows_a_failing_runs_view_in_the_browser(graded):
    with Chromium(find_chromium()) as browser:
        browser.open((graded[2] / "report.html").as_uri())
        browser.wait_for(lambda: browser.evaluate("window.rrtReport && window.rrtReport.ready"))
        assert browser.console_errors() == []
        browser.open((graded[2] / "html" / "garbage" / "index.html").as_uri())
        browser.wait_for(lambda: browser.evaluate("window.rrtReport && window.rrtReport.ready"))
        assert browser.evaluate("document.querySelectorAll('details.view').length") == 3
        browser.evaluate("document.querySelector('details.view summary').click()")
        frame = next_frame(browser)
        browser.wait_for(lambda: in_frame(browser, frame, "window.rrtView && window.rrtView"
                                                          ".ready"))
        assert in_frame(browser, frame, "document.getElementById('failure').textContent"
                        ).startswith("First failure (check 1, line 1): Error parsing planner")
        assert browser.console_errors() == []


def next_frame(browser) -> str:
    """The id of the page's frame that has loaded a file (the view opened)."""
    found = []

    def loaded() -> bool:
        frames = browser.call("Page.getFrameTree")["frameTree"].get("childFrames", [])
        found[:] = [f["frame"]["id"] for f in frames if f["frame"]["url"].startswith("file:")]
        return bool(found)
    browser.wait_for(loaded)
    return found[0]


def in_frame(browser, frame: str, expression: str):
    """``expression``'s value in the frame's page (the newest script context of it)."""
    gone = {event["params"]["executionContextId"] for event in browser.events
            if event.get("method") == "Runtime.executionContextDestroyed"}
    contexts = [event["params"]["context"]["id"] for event in browser.events
                if event.get("method") == "Runtime.executionContextCreated"
                and event["params"]["context"]["auxData"].get("frameId") == frame
                and event["params"]["context"]["id"] not in gone]
    if not contexts:
        return None
    answer = browser.call("Runtime.evaluate", expression=expression, contextId=contexts[-1],
                          returnByValue=True)
    return answer.get("result", {}).get("value")
