"""benchmarks/bench_cpp.py: which cases it measures, and (with g++ and libompl-dev) a
tiny run per kind of case, our planner and OMPL's in C++ taking turns."""

from __future__ import annotations

import pytest

from benchmarks import bench_cpp
from benchmarks.ompl_cpp_programs import binary
from tests.conftest import unit_sample


def test_every_planner_pairs_with_its_cpp_counterpart_on_the_chosen_problems():
    chosen = bench_cpp.cases(["point", "family"], ["narrow-10", "pendulum-t3"], [])
    pairs = {(case.system, case.problem.stem, case.planner, case.mode) for case in chosen}
    assert ("point", "narrow-10", "rrt", "point") in pairs
    assert ("point", "narrow-10", "prmstar", "prmstar") in pairs
    assert ("pendulum", "pendulum-t3", "kpiece", "kpiece") in pairs
    assert not any(planner == "rrtconnect" for system, _, planner, _ in pairs
                   if system == "pendulum")  # no geometric planner for a kinodynamic system
    left = bench_cpp.cases(["left"], ["course-simple-0"], ["kpiece"])
    assert [(case.program, case.mode) for case in left] == [("grid_ompl", "kpiece-left")]


def test_the_summary_lists_the_rows_above_one():
    rows = [("| a |", 0.5), ("| b |", 1.0), ("| c |", 1.2)]
    lines = bench_cpp.summary(rows)
    assert lines[0].startswith("2 of 3 rows at most 1.0x") and lines[-1] == "| c |"


@pytest.mark.parametrize("system,problem,planner", unit_sample([
    ("point", "course-simple-0", "rrtconnect"), ("family", "pendulum-t3", "kpiece"),
    ("family", "arm2-pair1", "prm"), ("spaceship", "course-space-1", "rrt")]))
def test_a_tiny_run_writes_one_row_of_both_sides_into_its_page(system, problem, planner,
                                                               tmp_path, capsys):
    if binary("family_ompl" if system == "family" else "grid_ompl") is None:
        pytest.skip("no g++ or OMPL headers (apt-get install libompl-dev)")
    page = tmp_path / "cpp.md"
    argv = ["--seeds", "2", "--time", "20", "--systems", system, "--problems", problem,
            "--planners", planner, "--page", str(page)]
    assert bench_cpp.main(argv) == 0
    row = next(line for line in capsys.readouterr().out.splitlines() if f"| {problem} |" in line)
    cells = [cell.strip() for cell in row.strip("|").split("|")]
    assert cells[2] == planner and cells[8:10] == ["2/2", "2/2"]
    ours, theirs, ratio = (float(cell) for cell in cells[3:6])
    assert ours > 0 and theirs > 0 and ratio > 0  # (of unrounded medians: 0.1 ms cells)
    assert min(float(cells[6]), float(cells[7])) >= 1  # iterations, both sides
    text = page.read_text()
    assert row in text and "python -m benchmarks.bench_cpp " + " ".join(argv) in text
