"""The harness on tiny runs: real planner processes, validation, kills, parallel workers."""

import dataclasses
import sys
from pathlib import Path

from benchmarks import catalog
from benchmarks.harness import HarnessOptions, RunSpec, parse_stats, run_all, run_one
from benchmarks.rows import RunStatus
from planning_core.vehicles import Vehicle
from validator.checks import validate_output

PROBLEMS = Path(catalog.ROOT) / "benchmarks" / "problems"
SIMPLE = PROBLEMS / "course" / "simple-0.sw"
SPACE = PROBLEMS / "course" / "space-1.sw"


def ours(name="rrt") -> catalog.PlannerChoice:
    return next(p for p in catalog.our_planners() if p.id == name)


@dataclasses.dataclass(frozen=True)
class ScriptPlanner(catalog.PlannerChoice):
    """A stand-in planner: a Python snippet in place of the planner's command."""

    script: str = ""

    def command(self, vehicle, seed, time_limit):
        return [sys.executable, "-c", self.script]


def script_planner(script: str) -> ScriptPlanner:
    return ScriptPlanner("fake", "ours", "fake", frozenset(Vehicle), script=script)


def test_stats_line_is_parsed():
    text = ("warning: something\nrrt_cli stats: status=solved planner=rrt vehicle=point "
            "seed=1 iterations=4 tree_nodes=5 planning_seconds=0.000227\n")
    assert parse_stats(text) == {"status": "solved", "planner": "rrt", "vehicle": "point",
                                 "seed": "1", "iterations": "4", "tree_nodes": "5",
                                 "planning_seconds": "0.000227"}
    assert parse_stats("no stats here\n") == {}


def test_a_real_run_is_measured_and_validated():
    for vehicle, problem in ((Vehicle.POINT, SIMPLE), (Vehicle.SPACESHIP, SPACE)):
        row = run_one(RunSpec(ours(), vehicle, problem, 3, 10.0))
        assert row.solved and row.valid and row.status == "solved", row
        assert row.exit_status == 0
        assert row.problem == "course-" + problem.stem and row.family == "course"
        assert row.vehicle == vehicle.value and row.planner == "rrt"
        assert 0 < row.planning_seconds < row.process_seconds
        assert row.tree_nodes >= 2 and row.iterations >= 1
        assert row.path_length > 0 and row.trajectory_lines >= 2
        assert 5 < row.peak_memory_mb < 2000


def test_an_invalid_solution_counts_as_a_failure():
    # Exits 0 with a trajectory that starts away from the start (check 4).
    bad = script_planner("print('2\\n2.5 2.5\\n3.8 1.1\\n0')")
    row = run_one(RunSpec(bad, Vehicle.POINT, SIMPLE, 1, 5.0))
    assert row.exit_status == 0
    assert row.valid is False and not row.solved
    assert row.status == RunStatus.INVALID.value
    assert "doesn't start at start" in row.failure
    # The same text is what the validator rejects on its own.
    problem_text = SIMPLE.read_text()
    from planning_core.problem_text import parse_problem
    assert not validate_output(parse_problem(problem_text), Vehicle.POINT,
                               "2\n2.5 2.5\n3.8 1.1\n0\n").valid


def test_exit_statuses_and_limits_are_classified():
    gave_up = script_planner(
        "import sys; sys.stderr.write('x stats: status=time_limit iterations=7 tree_nodes=3 "
        "planning_seconds=0.5\\nx: no solution\\n'); sys.exit(3)")
    row = run_one(RunSpec(gave_up, Vehicle.POINT, SIMPLE, 1, 5.0))
    assert (row.status, row.solved, row.valid) == ("time_limit", False, None)
    assert (row.iterations, row.tree_nodes, row.planning_seconds) == (7, 3, 0.5)
    assert row.failure == "x: no solution"
    crashed = script_planner("raise RuntimeError('boom')")
    row = run_one(RunSpec(crashed, Vehicle.POINT, SIMPLE, 1, 5.0))
    assert row.status == "crashed" and row.exit_status == 1 and "boom" in row.failure


def test_a_run_past_its_limit_is_killed():
    sleeper = script_planner("import time; time.sleep(30)")
    row = run_one(RunSpec(sleeper, Vehicle.POINT, SIMPLE, 1, 0.1),
                  HarnessOptions(grace=0.1))
    assert row.status == "killed" and not row.solved
    assert row.exit_status < 0  # by a signal
    assert row.process_seconds < 5


def test_parallel_workers_return_rows_in_spec_order():
    specs = [RunSpec(ours(), Vehicle.POINT, problem, seed, 5.0)
             for problem in (SIMPLE, SPACE) for seed in (1, 2)]
    rows = run_all(specs, HarnessOptions(workers=2))
    assert [(r.problem, r.seed) for r in rows] == [("course-" + s.problem.stem, s.seed)
                                                   for s in specs]
    assert all(r.solved for r in rows)


def test_planners_come_from_the_registry():
    from rrt_cli.planners import PLANNERS
    listed = {p.id: p for p in catalog.all_planners(include_ompl=False)}
    assert set(listed) == set(PLANNERS)
    for name, entry in PLANNERS.items():
        assert listed[name].vehicles == {v for v in Vehicle if entry.plans_for(v.system)}


def test_peak_memory_is_the_planner_own_not_the_harness_worker():
    ballast = bytearray(150 * 1024 * 1024)  # the harness process is large ...
    ballast[::4096] = b"x" * len(ballast[::4096])  # ... and resident
    small = run_one(RunSpec(script_planner("pass"), Vehicle.POINT, SIMPLE, 1, 5.0))
    big = run_one(RunSpec(script_planner("b = bytearray(80 * 2**20); b[::4096] = "
                                         "b'x' * len(b[::4096])"), Vehicle.POINT, SIMPLE, 1,
                          5.0))
    del ballast
    assert small.peak_memory_mb < 50
    assert 80 < big.peak_memory_mb < 150
