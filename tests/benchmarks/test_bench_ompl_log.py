"""The OMPL benchmark log writer, on a tiny real run, read back with OMPL's own reader."""

import sqlite3
from pathlib import Path

import pytest

from benchmarks import catalog
from benchmarks.harness import RunSpec, run_all
from benchmarks.ompl_log import PROPERTIES, LogHeader, format_log, write_logs
from planning_core.vehicles import Vehicle

PROBLEMS = Path(catalog.ROOT) / "benchmarks" / "problems"
HEADER = LogHeader(hostname="test-host", date="2025-01-02T03:04:05", cpu_info="2 x test cpu",
                   total_seconds=1.5)


@pytest.fixture(scope="module")
def tiny_run():
    rrt = next(p for p in catalog.our_planners() if p.id == "rrt")
    specs = [RunSpec(rrt, vehicle, PROBLEMS / "course" / name, seed, 5.0)
             for vehicle, name in ((Vehicle.POINT, "space-0.sw"),
                                   (Vehicle.SPACESHIP, "simple-0.sw"))
             for seed in (1, 2, 3)]
    return run_all(specs)


def test_log_layout(tiny_run):
    rows = [r for r in tiny_run if r.vehicle == "point"]
    lines = format_log(rows, HEADER).splitlines()
    assert lines[0].split()[1] == "version"
    assert lines[1] == "Experiment course-space-0_point"
    assert lines[2] == "Running on test-host"
    assert "1 planners" in lines
    start = lines.index("rrt (ours)")
    assert lines[start + 4] == f"{len(PROPERTIES)} properties for each run"
    runs_at = start + 5 + len(PROPERTIES)
    assert lines[runs_at] == "3 runs"
    for k, run in enumerate(sorted(rows, key=lambda r: r.seed)):
        values = lines[runs_at + 1 + k].split("; ")
        assert values[-1] == ""  # every value is followed by "; "
        assert float(values[0]) == run.planning_seconds
        assert values[2] == "1" and values[4] == "6"  # solved, "Exact solution"
    assert lines[runs_at + 4] == "."
    with pytest.raises(ValueError):
        format_log(tiny_run, HEADER)  # two experiments in one log


def test_ompl_statistics_script_reads_the_logs(tiny_run, tmp_path):
    tools = pytest.importorskip("ompl.tools")
    paths = write_logs(tiny_run, tmp_path / "logs", HEADER)
    assert sorted(p.name for p in paths) == ["course-simple-0_spaceship.log",
                                             "course-space-0_point.log"]
    database = tmp_path / "bench.db"
    tools.readBenchmarkLog(str(database), [str(p) for p in paths], False)
    tools.computeViews(str(database), False)
    with sqlite3.connect(database) as db:
        experiments = db.execute("SELECT name, timelimit, hostname FROM experiments "
                                 "ORDER BY name").fetchall()
        assert experiments == [("course-simple-0_spaceship", 5.0, "test-host"),
                               ("course-space-0_point", 5.0, "test-host")]
        runs = db.execute("SELECT time, solved, graph_states, seed, solution_length "
                          "FROM runs ORDER BY experimentid, seed").fetchall()
    expected = sorted(tiny_run, key=lambda r: (r.vehicle != "spaceship", r.seed))
    assert len(runs) == len(expected)
    for (time, solved, nodes, seed, length), row in zip(runs, expected):
        assert (time, bool(solved), nodes, seed) == (row.planning_seconds, row.solved,
                                                     row.tree_nodes, row.seed)
        assert length == pytest.approx(row.path_length)
