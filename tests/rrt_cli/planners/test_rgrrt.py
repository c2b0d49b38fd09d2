"""RG-RRT for the spaceships: its own behaviour and parameters, every solution
checked by the validator. What every ship planner must do (course problems x 20
seeds x both ships, reproducibility, limits, the CLI) is in
test_ship_planner_contract.py.
"""

from __future__ import annotations

import math
import random

import pytest

from planning_core.problem_text import parse_problem
from planning_core.grid_space_information import GridControlOptions
from planning_core.setups import grid_setup
from planning_core.systems import spaceship
from planning_core.vehicles import Vehicle
from rrt_cli.planners import rgrrt
from tests.rrt_cli.planners import ship_planner_testlib
from tests.rrt_cli.planners.ship_planner_testlib import GAP_WALL, MAZE_20, MAZE_50, SHIPS, ZIGZAG


def solve_and_validate(problem_text: str, vehicle: Vehicle, seed: int,
                       params: rgrrt.RGRRTParams = rgrrt.RGRRTParams(), options=None):
    return ship_planner_testlib.solve_and_validate(rgrrt, problem_text, vehicle, seed, params,
                                                   options)


@pytest.mark.parametrize("bad", [dict(random_controls=-1), dict(goal_bias=1.5),
                                 dict(guided_share=-0.1), dict(goal_controls=-1),
                                 dict(goal_distance="manhattan")])
def test_bad_params_are_rejected(bad):
    with pytest.raises(ValueError):
        rgrrt.RGRRTParams(**bad)


def test_a_thrust_beyond_the_ships_is_rejected():
    with pytest.raises(ValueError):
        spaceship.SYSTEM.reachable_controls(8, (0.6,))


@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
def test_every_edge_takes_a_control_of_the_reachable_set(vehicle):
    theta_range = vehicle.system.theta_range
    options = GridControlOptions()
    fixed = set(grid_setup(parse_problem(GAP_WALL), vehicle).si.reachable_controls())
    assert len(fixed) == 1 + options.reach_angles * len(options.reach_thrusts)
    # A full turn is half-open; the left-only ship's half turn is closed, so
    # its set holds full braking (theta = pi), which the validator accepts.
    assert all(0.0 <= theta < spaceship.FULL_TURN for theta, _ in fixed)
    assert max(theta for theta, _ in fixed) == (
        math.pi if vehicle is Vehicle.LEFT_SPACESHIP
        else theta_range * (options.reach_angles - 1) / options.reach_angles)
    result, _ = solve_and_validate(GAP_WALL, vehicle, 2, rgrrt.RGRRTParams(goal_controls=0))
    assert {tuple(row[4:]) for row in result.tree} <= fixed
    # The goal bias and the random targets together use more than one control.
    assert len({tuple(row[4:]) for row in result.tree}) > 2


def test_random_goal_controls_only_where_the_goal_is_within_a_step():
    params = rgrrt.RGRRTParams()
    fixed = set(grid_setup(parse_problem(ZIGZAG), Vehicle.SPACESHIP).si.reachable_controls())
    problem = parse_problem(ZIGZAG)
    gx, gy = problem.goal
    random_edges = 0
    for seed in range(5):
        result, _ = solve_and_validate(ZIGZAG, Vehicle.SPACESHIP, seed, params)
        for x, y, dx, dy, theta, thrust in result.tree:
            if (theta, thrust) not in fixed:
                random_edges += 1
                assert math.hypot(x - gx, y - gy) <= math.hypot(dx, dy) + spaceship.MAX_THRUST
    assert random_edges > 0  # some runs land on the goal with one of them

def test_no_node_is_added_twice():
    result, _ = solve_and_validate(ZIGZAG, Vehicle.SPACESHIP, 4)
    edges = [tuple(row) for row in result.tree]
    assert len(edges) == len(set(edges))


@pytest.mark.parametrize("seed", range(3))
def test_maze_solved_along_the_free_cells(seed):
    """The default's guided steps go best-first along the corridors; ranking
    by position instead of the braking point, and the paper's goal-as-target,
    are kept as options and still give valid answers."""
    solve_and_validate(MAZE_20, Vehicle.SPACESHIP, seed)
    solve_and_validate(MAZE_20, Vehicle.LEFT_SPACESHIP, seed,
                       rgrrt.RGRRTParams(guide_by_stopping_point=False))
    solve_and_validate(ZIGZAG, Vehicle.SPACESHIP, seed,
                       rgrrt.RGRRTParams(goal_distance="euclidean"))


@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
def test_50x50_maze_both_ships(vehicle):
    """Ranking by the braking point is what gets both ships round a maze's
    corners in about a second (by position: up to tens of seconds, or not at all)."""
    solve_and_validate(MAZE_50, vehicle, 1)


def test_stopping_point_key_ranks_a_braking_line_into_a_wall_last():
    problem = parse_problem(GAP_WALL)   # wall at column 3, gap in row 2; goal (6.5, 3.5)
    setup = grid_setup(problem, "spaceship")
    key = setup.si.stopping_point_key(setup.si.distance_along_free_space(setup.pdef.goal))
    at_rest = key((2.5, 2.5, 0.0, 0.0))
    through_gap = key((2.5, 2.5, 1.0, 0.0))     # stops at (3.5, 2.5), in the gap
    into_wall = key((2.5, 0.5, 1.0, 0.0))       # stops inside the wall
    assert through_gap < at_rest < into_wall
    assert into_wall > 1e5


def test_extra_random_controls_are_valid():
    params = rgrrt.RGRRTParams(random_controls=3)
    options = GridControlOptions(reach_thrusts=(0.25, 0.5), reach_angles=6)
    for vehicle in SHIPS:
        solve_and_validate(GAP_WALL, vehicle, 5, params, options)
