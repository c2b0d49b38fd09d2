"""A preset's results page: the date, the 40-hex commit and the machine of the run, and
the tables of its report.md, from a results folder the command wrote."""

import platform
import re
import subprocess

import pytest

from benchmarks import catalog
from benchmarks.cli import _cpu_model, main
from benchmarks.results_page import main as page_main

TINY = ["--preset", "smoke", "--planners", "rrt", "--problems", "course-simple-0",
        "--vehicles", "point", "--seeds", "1", "--no-generate", "--no-plots", "--no-ompl",
        "--workers", "1"]


def head_commit() -> str:
    try:
        done = subprocess.run(["git", "rev-parse", "HEAD"], cwd=catalog.ROOT,
                              capture_output=True, text=True, timeout=10)
    except OSError:
        done = None
    if done is None or done.returncode != 0:
        pytest.skip("not a git checkout")
    return done.stdout.strip()


def test_the_page_holds_date_commit_machine_and_the_reports_tables(tmp_path, capsys):
    folder = tmp_path / "smoke"
    assert main([*TINY, "--out", str(folder)]) == 0
    capsys.readouterr()
    assert page_main([str(folder)]) == 0
    page = capsys.readouterr().out
    assert page.startswith("# Results: the `smoke` preset\n")
    assert "> docs/results/smoke.md`" in page
    narrowed = tmp_path / "smoke-rrt"  # a narrowed run in its own folder: its own page
    folder.rename(narrowed)
    assert page_main([str(narrowed)]) == 0
    other = capsys.readouterr().out
    assert other.startswith("# Results: `smoke-rrt`, a run of the `smoke` preset\n")
    assert "> docs/results/smoke-rrt.md`" in other and "smoke.md" not in other
    facts = dict(re.findall(r"^\| ([^|]+?) \| (.*) \|$", page, re.MULTILINE))
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d[+-]\d\d:\d\d", facts["date"])
    commit = re.match(r"[0-9a-f]{40}\b", facts["commit"])
    assert commit and commit.group() == head_commit()
    assert _cpu_model() in facts["machine"] and facts["machine"].startswith(
        f"{__import__('os').cpu_count()} x ")
    assert facts["Python, OMPL"] == f"{platform.python_version()}, left out (--no-ompl)"
    assert re.fullmatch(r"[\d.]+ [\d.]+ [\d.]+ before, [\d.]+ [\d.]+ [\d.]+ after",
                        facts["load average (1, 5, 15 min)"])
    report = (narrowed / "report.md").read_text()
    tables = [line for line in report.splitlines() if line.startswith("|")]
    assert tables and all(line in page.splitlines() for line in tables)
    assert "## Targets" in page and "No target has runs to judge in this run" in page
    assert "- host:" not in page  # the run's facts are in the table, not repeated


def test_a_folder_without_a_run_is_one_error_and_status_2(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        page_main([str(tmp_path)])
    err = capsys.readouterr()
    assert stop.value.code == 2 and err.out == ""
    assert "report.md does not exist (run the preset first)" in err.err
    assert "Traceback" not in err.err
    (tmp_path / "report.md").write_text("# r\n")
    (tmp_path / "meta.json").write_text("[1]")
    with pytest.raises(SystemExit) as stop:
        page_main([str(tmp_path)])
    assert stop.value.code == 2 and "does not hold an object" in capsys.readouterr().err
