"""Issue 30's acceptance sweeps: ``grid-sweep`` (the new planners on every grid vehicle
they plan for), ``grid-optimize`` and ``family-optimize`` (the optimizing planners with
``-optimize``), run end to end through the harness, every answer validated."""

import pytest

from benchmarks import presets
from benchmarks.cli import main
from benchmarks.rows import read_csv
from planning_core.vehicles import Vehicle
from rrt_cli.planners import PLANNERS
from validator.checks import validate_output

FAST = ["--no-ompl", "--no-plots", "--no-generate", "--workers", "1"]


def _rows(tmp_path, *argv: str, workers: int = 1):
    out = tmp_path / "out"
    assert main([*argv, *FAST[:-1], str(workers), "--out", str(out)]) == 0
    return read_csv(out / "runs.csv"), (out / "report.md").read_text()


def test_the_grid_sweep_runs_every_new_planner_on_each_vehicle_and_validates(tmp_path):
    rows, report = _rows(tmp_path, "--preset", "grid-sweep", "--problems", "course-simple-0",
                         "--seeds", "1", "--time", "10")
    ran = {(row.vehicle, row.planner) for row in rows}
    assert ran == {(vehicle.value, planner)
                   for vehicle, planners in presets.NEW_PLANNERS.items() for planner in planners}
    assert all(row.solved and row.valid for row in rows), [r.failure for r in rows]
    assert "## Solved and validated" in report and "| dubins " in report


def test_grid_sweep_planners_are_the_registrys_for_their_vehicle():
    for vehicle, planners in presets.NEW_PLANNERS.items():
        for planner in planners:
            assert PLANNERS[planner].plans_for(vehicle.system), (vehicle, planner)


def test_grid_optimize_runs_only_optimizing_planners_with_optimize(tmp_path):
    rows, report = _rows(tmp_path, "--preset", "grid-optimize", "--problems",
                         "course-simple-0", "--seeds", "1", "--time", "0.4", workers=2)
    assert {row.planner for row in rows} == {"sst", "rrtstar", "informed"}
    assert {row.vehicle for row in rows} == {v.value for v in presets.NEW_PLANNERS}
    assert all(row.solved and row.valid for row in rows), [r.failure for r in rows]
    # -optimize runs to the limit: the planning clock is past the first solution's.
    # (Each finds its first in 0.05 s on simple-0.)
    assert all(row.planning_seconds >= 0.36 for row in rows)


def test_family_optimize_runs_the_optimizing_planners_on_what_they_plan_for(tmp_path):
    rows, _ = _rows(tmp_path, "--preset", "family-optimize", "--problems", "arm2-pair1",
                    "pendulum-t10", "--seeds", "1", "--time", "0.4", workers=2)  # first in 0.1 s
    assert {(row.problem, row.planner) for row in rows} == {
        ("arm2-pair1", "rrtstar"), ("arm2-pair1", "informed"), ("pendulum-t10", "sst")}
    assert all(row.solved and row.valid for row in rows), [r.failure for r in rows]


def test_the_harness_rejects_a_dubins_answer_that_turns_too_tightly():
    """The grid sweep's Dubins rows are judged with the turning check: a right-angle
    corner, fine for the point, fails for the car."""
    from planning_core.problem_text import parse_problem
    problem = parse_problem("4\n4\n____\n____\n____\n____\n0.5\n0.5\n2.5\n2.5\n")
    corner = [(0.5 + 0.05 * k, 0.5) for k in range(41)] + [
        (2.5, 0.5 + 0.05 * k) for k in range(1, 41)]
    text = f"{len(corner)}\n" + "".join(f"{x!r} {y!r}\n" for x, y in corner) + "0\n"
    assert validate_output(problem, Vehicle.POINT, text).valid
    assert not validate_output(problem, Vehicle.DUBINS, text).valid


@pytest.mark.slow
@pytest.mark.parametrize("preset", ["grid-sweep", "grid-optimize"])
def test_the_acceptance_sweep_on_the_course_maps(tmp_path, preset):
    """Issue 30's acceptance presets on the course maps, 2 seeds (the 20-seed runs are
    the commands of docs/optimal-planning.md#acceptance-sweeps: 800 and 600 runs, past
    this suite's budget): no answer invalid and every run solved, but the left-only
    ship's SST, whose first solution on space-3 takes seconds: at least half. The limit
    is the acceptance's: 5 s with -optimize (the spaceship's SST on space-3 takes 1-1.5 s
    quiet, more in CI beside other tests), 30 s without."""
    out = tmp_path / "out"
    limit = ["--time", "5"] if preset == "grid-optimize" else []  # -optimize runs it all
    assert main(["--preset", preset, "--problems", "course-*", "--seeds", "2", *limit,
                 *FAST[:-2], "--workers", "2", "--out", str(out)]) == 0
    rows = read_csv(out / "runs.csv")
    assert len(rows) == 5 * 2 * sum(
        len([p for p in planners if preset == "grid-sweep" or p in presets.OPTIMIZING])
        for planners in presets.NEW_PLANNERS.values())
    assert not [r for r in rows if r.status in ("invalid", "crashed", "killed")]
    left = [r for r in rows if (r.vehicle, r.planner) == ("left", "sst")]
    assert sum(r.solved for r in left) >= 0.5 * len(left)
    assert all(row.solved for row in rows if row not in left), sorted(
        (r.problem, r.vehicle, r.planner, r.seed, r.status) for r in rows
        if not r.solved and r not in left)
