"""KPIECE1 for the spaceships: its own behaviour and parameters, every solution
checked by the validator. What every ship planner must do (course problems x 20
seeds x both ships, reproducibility, limits, the CLI) is in
test_ship_planner_contract.py.
"""

from __future__ import annotations

import pytest

from planning_core.grid_space_information import GridControlOptions
from planning_core.vehicles import Vehicle
from rrt_cli.planners import kpiece
from tests.conftest import COURSE_PROBLEMS, unit_sample
from tests.rrt_cli.planners import ship_planner_testlib
from tests.rrt_cli.planners.ship_planner_testlib import GAP_WALL, MAZE_20, MAZE_50, ZIGZAG


def solve_and_validate(problem_text: str, vehicle: Vehicle, seed: int,
                       params: kpiece.KPIECEParams = kpiece.KPIECEParams(), options=None):
    return ship_planner_testlib.solve_and_validate(kpiece, problem_text, vehicle, seed, params,
                                                   options)


def test_published_variant_without_goal_steering_is_valid():
    params = kpiece.KPIECEParams(goal_controls=1, goal_distance="euclidean")
    for seed in range(3):
        solve_and_validate(COURSE_PROBLEMS[1].read_text(), Vehicle.SPACESHIP, seed, params)


@pytest.mark.parametrize("seed", unit_sample(range(3)))  # seeds 1-2 in CI
def test_maze_solved_along_the_free_cells(seed):
    """The default measures the goal distance along the corridors; the paper's
    straight line is kept as an option and still gives valid answers."""
    solve_and_validate(MAZE_20, Vehicle.SPACESHIP, seed)
    solve_and_validate(ZIGZAG, Vehicle.SPACESHIP, seed,
                       kpiece.KPIECEParams(goal_distance="euclidean"))


# The left ship in the 20 x 20 maze (1.6 s) runs in CI; the zigzag also makes it turn.
@pytest.mark.parametrize("problem, vehicle", unit_sample([
    pytest.param(GAP_WALL, Vehicle.SPACESHIP, id="gap-wall-spaceship"),
    pytest.param(ZIGZAG, Vehicle.LEFT_SPACESHIP, id="zigzag-left"),
    pytest.param(MAZE_20, Vehicle.LEFT_SPACESHIP, id="maze-20-left")], keep=2))
def test_position_only_projection_and_set_cell_size_are_valid(problem, vehicle):
    options = GridControlOptions(cell_size=1.0, velocity_cell_size=None)
    solve_and_validate(problem, vehicle, 0, options=options)


def test_longer_random_motions_are_valid():
    options = GridControlOptions(min_steps=2, max_steps=4)
    solve_and_validate(GAP_WALL, Vehicle.SPACESHIP, 1, options=options)


@pytest.mark.slow  # a long run (seconds)
def test_left_ship_through_the_50x50_maze():
    """The velocity in the projection is what gets the left-only ship round a
    maze's right turns (position-only: 106 s on seed 1, with it about 2 s)."""
    solve_and_validate(MAZE_50, Vehicle.LEFT_SPACESHIP, 1)


@pytest.mark.parametrize("bad", [dict(good_score_factor=0.0), dict(bad_score_factor=1.5),
                                 dict(goal_controls=0), dict(goal_distance="manhattan")])
def test_bad_params_are_rejected(bad):
    with pytest.raises(ValueError):
        kpiece.KPIECEParams(**bad)


@pytest.mark.parametrize("bad", [dict(min_steps=3, max_steps=2), dict(cell_size=-1.0),
                                 dict(velocity_cell_size=0.0), dict(controls_per_extension=0),
                                 dict(reach_angles=0), dict(reach_thrusts=(0.0,))])
def test_bad_ship_options_are_rejected(bad):
    with pytest.raises(ValueError):
        GridControlOptions(**bad)


def test_cell_grid_tells_interior_from_exterior():
    grid = kpiece._CellGrid(2)
    coords = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]
    cells = []
    for k, coord in enumerate(coords):
        cell = kpiece._Cell(kpiece._cell_key(coord), score=1.0, created=k + 1)
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


def test_cell_keys_are_one_per_cell_and_neighbours_match():
    """A key per coordinate tuple, distinct for distinct cells (packed or not, at
    the packing's limit too), and a key's neighbour is the neighbour's key."""
    limit = kpiece._KEY_LIMIT
    coords = [(3,), (0, -2), (1, 2, 3), (5, -6, 7, -8), (1, 2, 3, 4, 5), (limit, -limit),
              (limit + 1, 0), (-limit - 1, 0), (0, 0, 0, limit), (10 ** 6, 2), (0, 0)]
    keys = {}
    for coord in coords:
        grid = kpiece._CellGrid(len(coord))
        key = kpiece._cell_key(coord)
        assert keys.setdefault(key, coord) == coord
        for axis in range(len(coord)):
            for sign in (1, -1):
                near = list(coord)
                near[axis] += sign
                assert grid.neighbour_key(key, axis, sign) == kpiece._cell_key(tuple(near))
    assert isinstance(kpiece._cell_key((limit, -limit)), int)
    assert kpiece._cell_key((limit + 1, 0)) == (limit + 1, 0)


def test_close_samples_keep_the_closest_and_inflate_the_chosen():
    close = kpiece._CloseSamples(3)
    for node, distance in enumerate([5.0, 1.0, 4.0, 2.0, 3.0]):
        close.consider(node, distance)
    assert [node for _, node in close.items] == [1, 3, 4]
    assert close.select() == 1
    # Node 1 goes back in with (1 + 3) / 2 * 1.1 = 2.2: after node 3 (2.0).
    assert [node for _, node in close.items] == [3, 1, 4]
