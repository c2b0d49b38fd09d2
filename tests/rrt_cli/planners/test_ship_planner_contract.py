"""What every spaceship planner (kpiece, rgrrt) must do, tested once for each.

The course acceptance: every course problem x 20 seeds x both ships; seed 0 is
in the unit run (-m "not slow"), seeds 1-19 are marked slow and run with the
whole suite (./test.sh, CI). Each run is bounded by an iteration limit far above
what the planners needed on these maps (ship_planner_testlib.ITERATION_CAP), so
a regression fails instead of hanging. Each planner's own behaviour is tested
in test_kpiece.py and test_rgrrt.py.
"""

from __future__ import annotations

import random

import pytest

from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup
from planning_core.systems import left_spaceship, spaceship
from planning_core.vehicles import Vehicle
from planning_core.worlds.grid import GridWorld
from rrt_cli.planners import PLANNERS, kpiece, rgrrt
from rrt_cli.planners.base import PlanStatus, StopCondition
from tests.conftest import COURSE_PROBLEMS, run_planner, seed_sweep, solve_on
from tests.rrt_cli.planners.ship_planner_testlib import (
    GAP_WALL, SHIPS, WALLED_GOAL, ZIGZAG, solve_and_validate)
from validator.checks import validate_output

SEEDS = range(20)
PLANNER_MODULES = [kpiece, rgrrt]


def by_name(module) -> str:
    return module.__name__.rsplit(".", 1)[-1]


def solve(planner, problem_text: str, vehicle: Vehicle, seed: int):
    return solve_and_validate(planner, problem_text, vehicle, seed, planner.Params())


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
@pytest.mark.parametrize("path", COURSE_PROBLEMS, ids=lambda p: p.stem)
@pytest.mark.parametrize("seed", seed_sweep(SEEDS))  # seeds 1-19: slow
def test_course_problem_solved_and_valid(planner, path, vehicle, seed):
    solve(planner, path.read_text(), vehicle, seed)


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
@pytest.mark.parametrize("text", [GAP_WALL, ZIGZAG], ids=["gap-wall", "zigzag"])
@pytest.mark.parametrize("seed", range(2))
def test_generated_maps_solved_and_valid(planner, text, vehicle, seed):
    solve(planner, text, vehicle, seed)


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_left_ship_controls_stay_in_its_range(planner):
    result, _ = solve(planner, ZIGZAG, Vehicle.LEFT_SPACESHIP, 1)
    for row in result.tree:
        theta, thrust = row[4], row[5]
        # SPEC 3's check: theta in [0, pi] (RG-RRT's fixed set holds pi itself).
        assert 0.0 <= theta <= left_spaceship.SYSTEM.theta_range
        assert 0.0 <= thrust <= spaceship.MAX_THRUST


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_same_seed_same_output_and_other_seed_differs(planner):
    _, first = solve(planner, GAP_WALL, Vehicle.SPACESHIP, 7)
    _, again = solve(planner, GAP_WALL, Vehicle.SPACESHIP, 7)
    _, other = solve(planner, GAP_WALL, Vehicle.SPACESHIP, 8)
    assert first == again
    assert first != other


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_walled_in_goal_ends_at_the_iteration_limit(planner):
    problem = parse_problem(WALLED_GOAL)
    result = solve_on(planner, grid_setup(problem, Vehicle.SPACESHIP), StopCondition(max_iterations=2000),
                           random.Random(0))
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.trajectory == ()
    assert result.stats.iterations == 2000
    # Every edge of the tree it grew is one collision-free step.
    assert len(result.tree) == result.stats.tree_nodes - 1 > 0
    grid = GridWorld(problem)
    for row in result.tree:
        assert spaceship.SYSTEM.propagate_while(row[:4], row[4:], grid) is not None


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_start_within_tolerance_of_goal_is_one_line(planner):
    text = "3\n3\n___\n___\n___\n1.5 1.5\n1.55 1.5\n"
    result, _ = solve(planner, text, Vehicle.SPACESHIP, 0)
    assert len(result.trajectory) == 1


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_point_vehicle_is_refused(planner):
    with pytest.raises(ValueError):
        solve_on(planner, grid_setup(parse_problem(GAP_WALL), Vehicle.POINT),
                      StopCondition(), random.Random(0))


@pytest.mark.parametrize("planner", PLANNER_MODULES, ids=by_name)
def test_registered_for_the_ships_and_cli_runs_it(planner):
    name = by_name(planner)
    assert {v for v in Vehicle if PLANNERS[name].plans_for(v.system)} == set(SHIPS)
    text = COURSE_PROBLEMS[1].read_text()
    done = run_planner(["-grad", "-left", "-planner", name, "-seed", "3"], text)
    assert done.returncode == 0, done.stderr
    report = validate_output(parse_problem(text), Vehicle.LEFT_SPACESHIP, done.stdout.decode())
    assert report.valid, report.first_failure
    refused = run_planner(["-planner", name], text)
    assert refused.returncode == 2
    assert refused.stdout == b""
    assert b"does not support" in refused.stderr
