"""The course report's table: real runs checked by the validator, and the page's figures
(paired means over the runs both planners solved) from stored rows."""

import pytest

from benchmarks import course_report
from benchmarks.course_report import COURSE, VEHICLES, overall, page, run_once, settings, table
from planning_core.problem_text import parse_problem


def row(map_name, vehicle, setting, seed, length=None, first="0.01"):
    return {"map": map_name, "vehicle": vehicle, "setting": setting, "seed": str(seed),
            "solved": str(length is not None), "valid": str(length is not None),
            "length": "" if length is None else repr(length), "first_seconds": first,
            "planning_seconds": first}


@pytest.mark.parametrize("vehicle", VEHICLES[::2], ids=lambda v: v.name)  # point, R=0.5
def test_a_run_is_validated_and_measured_by_the_validator(vehicle):
    text = (COURSE / "space-1.sw").read_text()
    setup = course_report._setup(parse_problem(text), vehicle)
    found = run_once(text, setup, vehicle, settings(1.0)["rrtstar"], 1)
    assert found["solved"] and found["valid"]
    assert float(found["length"]) >= 3.9  # space-1's shortest path is about 3.9 long
    assert float(found["first_seconds"]) > 0


def test_the_overall_means_pair_the_runs_both_solved():
    rows = [row("a", "point", "rrt", 1, 8.0), row("a", "point", "rrtstar", 1, 4.0),
            row("a", "point", "rrt", 2, 10.0), row("a", "point", "rrtstar", 2, None),
            row("b", "point", "rrt", 1, None), row("b", "point", "rrtstar", 1, 30.0)]
    line = next(text for text in overall(rows, 1.0) if "| point | rrtstar |" in text)
    cells = [c.strip() for c in line.split("|")[1:-1]]
    # 2 of 3 valid (rrt: 2 of 3); one run pairs: 8 against 4.
    assert cells[2:7] == ["2/3 (2/3)", "1", "8.00", "4.00", "0.50"]


def test_the_per_map_table_and_the_page():
    rows = [row("a", "point", "rrt", s, 8.0 + s) for s in (1, 2)]
    rows += [row("a", "point", "rrtstar", s, 4.0 + s) for s in (1, 2)]
    lines = table(rows, 1.0)
    cells = [c.strip() for c in lines[2].split("|")[1:-1]]
    assert cells[:5] == ["a", "point", "2/2", "9.50 (9.500)", "0.0100"]
    assert cells[-2] == f"{5.5 / 9.5:.2f}"
    text = page(rows, {"date": "D", "commit": "C"}, 1.0)
    assert "| date | D |" in text and "| commit | C |" in text and "Seeds 1 to 2" in text


def test_a_rerun_keeps_the_stored_runs_only_of_the_same_code(tmp_path, capsys):
    """An interrupted run resumes; runs another code made are dropped, with one line."""
    runs = tmp_path / "runs.csv"
    runs.write_text("map,vehicle\n")
    (tmp_path / "code").write_text("another code\n")
    course_report.keep_runs_of_this_code(tmp_path)
    assert not runs.exists() and "made by other code" in capsys.readouterr().err
    runs.write_text("map,vehicle\n")
    course_report.keep_runs_of_this_code(tmp_path)  # the mark is this code's now
    assert runs.exists() and capsys.readouterr().err == ""
