"""KPIECE1 for the spaceships: every output passes the validator's checks.

The course acceptance runs in full everywhere: every course problem x 20 seeds
x both ships (the same tests on every machine; the whole suite stays within a
few minutes on 2 cores). Each run is bounded by an iteration limit far
above what the planner needed on these maps (the most seen in the 20-seed
sweep was 25 025), so a regression fails instead of hanging.
"""

from __future__ import annotations

import random

import pytest

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle, spaceship
from rrt_cli.planners import PLANNERS, kpiece
from rrt_cli.planners.base import PlanStatus, StopCondition
from tests.conftest import COURSE_PROBLEMS, run_planner
from tests.planners import ship_planner_testlib
from tests.planners.ship_planner_testlib import (
    GAP_WALL, MAZE_20, MAZE_50, SHIPS, WALLED_GOAL, ZIGZAG)
from validator.checks import validate_output

SEEDS = range(20)


def solve_and_validate(problem_text: str, vehicle: Vehicle, seed: int,
                       params: kpiece.KPIECEParams = kpiece.KPIECEParams()):
    return ship_planner_testlib.solve_and_validate(kpiece, problem_text, vehicle, seed, params)


@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
@pytest.mark.parametrize("path", COURSE_PROBLEMS, ids=lambda p: p.stem)
@pytest.mark.parametrize("seed", SEEDS)
def test_course_problem_solved_and_valid(path, vehicle, seed):
    solve_and_validate(path.read_text(), vehicle, seed)


@pytest.mark.parametrize("vehicle", SHIPS, ids=lambda v: v.value)
@pytest.mark.parametrize("text", [GAP_WALL, ZIGZAG], ids=["gap-wall", "zigzag"])
@pytest.mark.parametrize("seed", range(2))
def test_generated_maps_solved_and_valid(text, vehicle, seed):
    solve_and_validate(text, vehicle, seed)


def test_published_variant_without_goal_steering_is_valid():
    params = kpiece.KPIECEParams(goal_controls=1, goal_distance="euclidean")
    for seed in range(3):
        solve_and_validate(COURSE_PROBLEMS[1].read_text(), Vehicle.SPACESHIP, seed, params)


@pytest.mark.parametrize("seed", range(3))
def test_maze_solved_along_the_free_cells(seed):
    """The default measures the goal distance along the corridors; the paper's
    straight line is kept as an option and still gives valid answers."""
    solve_and_validate(MAZE_20, Vehicle.SPACESHIP, seed)
    solve_and_validate(ZIGZAG, Vehicle.SPACESHIP, seed,
                       kpiece.KPIECEParams(goal_distance="euclidean"))


def test_position_only_projection_and_set_cell_size_are_valid():
    params = kpiece.KPIECEParams(cell_size=1.0, velocity_cell_size=None)
    solve_and_validate(GAP_WALL, Vehicle.SPACESHIP, 0, params)
    solve_and_validate(MAZE_20, Vehicle.LEFT_SPACESHIP, 0, params)


def test_left_ship_through_the_50x50_maze():
    """The velocity in the projection is what gets the left-only ship round a
    maze's right turns (position-only: 106 s on seed 1, with it about 2 s)."""
    solve_and_validate(MAZE_50, Vehicle.LEFT_SPACESHIP, 1)


def test_left_ship_controls_stay_in_its_range():
    result, _ = solve_and_validate(ZIGZAG, Vehicle.LEFT_SPACESHIP, 1)
    for row in result.tree:
        theta, thrust = row[4], row[5]
        assert 0.0 <= theta < spaceship.LEFT_THETA_RANGE
        assert 0.0 <= thrust <= spaceship.MAX_THRUST


def test_same_seed_same_output_and_other_seed_differs():
    _, first = solve_and_validate(GAP_WALL, Vehicle.SPACESHIP, 7)
    _, again = solve_and_validate(GAP_WALL, Vehicle.SPACESHIP, 7)
    _, other = solve_and_validate(GAP_WALL, Vehicle.SPACESHIP, 8)
    assert first == again
    assert first != other


def test_walled_in_goal_ends_at_the_iteration_limit():
    problem = parse_problem(WALLED_GOAL)
    result = kpiece.solve(problem, Vehicle.SPACESHIP, StopCondition(max_iterations=2000),
                          random.Random(0))
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.trajectory == ()
    assert result.stats.iterations == 2000
    # Every edge of the tree it grew is one collision-free step.
    assert len(result.tree) == result.stats.tree_nodes - 1 > 0
    for row in result.tree:
        assert spaceship.integrate(row[:4], row[4:], problem.blocked, problem.width,
                                   problem.height) is not None


def test_start_within_tolerance_of_goal_is_one_line():
    text = "3\n3\n___\n___\n___\n1.5 1.5\n1.55 1.5\n"
    result, _ = solve_and_validate(text, Vehicle.SPACESHIP, 0)
    assert len(result.trajectory) == 1


def test_point_vehicle_is_refused():
    with pytest.raises(ValueError):
        kpiece.solve(parse_problem(GAP_WALL), Vehicle.POINT, StopCondition(), random.Random(0))


@pytest.mark.parametrize("bad", [dict(good_score_factor=0.0), dict(bad_score_factor=1.5),
                                 dict(min_steps=3, max_steps=2), dict(cell_size=-1.0),
                                 dict(velocity_cell_size=0.0),
                                 dict(goal_controls=0), dict(goal_distance="manhattan")])
def test_bad_params_are_rejected(bad):
    with pytest.raises(ValueError):
        kpiece.KPIECEParams(**bad)


def test_cell_grid_tells_interior_from_exterior():
    grid = kpiece._CellGrid(2)
    coords = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]
    cells = []
    for k, coord in enumerate(coords):
        cell = kpiece._Cell(coord, score=1.0, created=k + 1)
        cell.coverage = 1
        grid.add(cell)
        cells.append(cell)
    assert grid.is_interior(cells[0])
    assert not any(grid.is_interior(cell) for cell in cells[1:])
    assert grid.exterior_count == 4
    assert grid.top(exterior=False) is cells[0]
    # Among exterior cells, the highest importance wins.
    cells[3].score = 10.0
    grid.update(cells[3])
    assert grid.top(exterior=True) is cells[3]


def test_close_samples_keep_the_closest_and_inflate_the_chosen():
    close = kpiece._CloseSamples(3)
    for node, distance in enumerate([5.0, 1.0, 4.0, 2.0, 3.0]):
        close.consider(node, distance)
    assert [node for _, node in close.items] == [1, 3, 4]
    assert close.select() == 1
    # Node 1 goes back in with (1 + 3) / 2 * 1.1 = 2.2: after node 3 (2.0).
    assert [node for _, node in close.items] == [3, 1, 4]


def test_registered_for_the_ships_and_cli_runs_it():
    assert PLANNERS["kpiece"].vehicles == frozenset(SHIPS)
    text = COURSE_PROBLEMS[1].read_text()
    done = run_planner(["-grad", "-left", "-planner", "kpiece", "-seed", "3"], text)
    assert done.returncode == 0, done.stderr
    report = validate_output(parse_problem(text), Vehicle.LEFT_SPACESHIP, done.stdout.decode())
    assert report.valid, report.first_failure
    refused = run_planner(["-planner", "kpiece"], text)
    assert refused.returncode == 2
    assert refused.stdout == b""
    assert b"does not support" in refused.stderr
