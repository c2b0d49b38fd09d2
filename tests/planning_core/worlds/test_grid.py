"""Exact segment-against-grid test vs dense sampling, and the course sampling rule."""

import random

import pytest

from planning_core.problem import Problem
from planning_core.problem_text import parse_problem
from planning_core.worlds.grid import GridWorld, connected_free_cells, segment_meets_cell
from tests.conftest import unit_sample

SPACE0 = "4\n3\n____\n__#_\n___#\n0.1\n1.54\n3.8\n1.1\n"


def random_world(rng: random.Random, width=8, height=6, density=0.3) -> GridWorld:
    blocked = bytes(1 if rng.random() < density else 0 for _ in range(width * height))
    return GridWorld(Problem(width, height, blocked, (0.5, 0.5), (1.5, 1.5)))


def densely_sampled_hit(world: GridWorld, x0, y0, x1, y1, samples=4000):
    for k in range(samples + 1):
        t = k / samples
        if not world.point_free(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t):
            return t
    return None


@pytest.mark.parametrize("worlds", unit_sample([15, 40]))
def test_exact_walk_finds_every_collision_dense_sampling_finds(worlds):
    rng = random.Random(11)
    checked = 0
    for _ in range(worlds):
        world = random_world(rng)
        for _ in range(40):
            pts = [rng.uniform(-0.5, 8.5), rng.uniform(-0.5, 6.5), rng.uniform(-0.5, 8.5),
                   rng.uniform(-0.5, 6.5)]
            exact = world.first_blocked_cell_on_segment(*pts)
            sampled = densely_sampled_hit(world, *pts)
            if sampled is not None:
                assert exact is not None, pts
                # The exact entry is never after the first colliding sample.
                assert exact.fraction <= sampled + 1e-12
            if exact is None:
                assert sampled is None
            checked += 1
    assert checked == worlds * 40


def test_corner_cut_missed_by_sampling_is_caught_exactly():
    world = GridWorld(parse_problem(SPACE0))
    # Clips the bottom-left corner of blocked cell (2, 1): in at (2, 1.005), out at
    # (2.005, 1), far shorter than the 0.05 sampling step; both ends are free.
    segment = (1.5, 1.505, 2.5, 0.505)
    assert world.first_sampled_collision(*segment) is None
    hit = world.first_blocked_cell_on_segment(*segment)
    assert hit is not None and (hit.column, hit.row) == (2, 1)


def test_half_open_edges_touching_is_not_entering():
    world = GridWorld(parse_problem(SPACE0))
    # Running along x = 3.0, the left edge of free column 3, beside blocked (2, 1).
    assert world.first_blocked_cell_on_segment(3.0, 1.2, 3.0, 1.9) is None
    # The right edge of blocked (2, 1) is x = 3.0, which belongs to the free neighbour;
    # x = 2.0 belongs to the blocked cell itself.
    assert world.first_blocked_cell_on_segment(1.5, 1.5, 2.0, 1.5) is not None
    assert segment_meets_cell(3.5, 1.5, 3.0, 1.5, 2, 1) is None


@pytest.mark.parametrize("segment,expected", [
    ((0.1, 0.5, 3.5, 0.5), (3, 0)),
    ((2.5, 0.5, 2.5, 2.5), (2, 1)),
    ((0.5, 2.5, 3.9, 2.9), None),
    ((3.5, 2.5, 4.5, 2.5), (4, 2)),   # leaves the map
])
def test_first_blocked_cell(segment, expected):
    hit = GridWorld(parse_problem(SPACE0)).first_blocked_cell_on_segment(*segment)
    assert (None if hit is None else (hit.column, hit.row)) == expected


def test_sampling_includes_both_endpoints():
    world = GridWorld(parse_problem(SPACE0))
    assert world.first_sampled_collision(0.5, 0.5, 3.5, 0.5) is not None
    assert world.first_sampled_collision(3.5, 0.5, 0.5, 0.5) == (3.5, 0.5)


def test_flood_fill_connectivity_with_and_without_diagonals():
    # Free cells (0,0) and (1,1) touch only at a corner.
    problem = Problem(2, 2, bytes([0, 1, 1, 0]), (0.5, 0.5), (1.5, 1.5))
    assert not connected_free_cells(problem, (0, 0), diagonal=False)[3]
    assert connected_free_cells(problem, (0, 0), diagonal=True)[3]


def test_pinch_points_are_the_corners_passable_only_exactly():
    # Rows from the top. Pinches at (2, 3), (4, 3) and (1, 4); at (3, 3) the other
    # diagonal is blocked, and its corner point lies in a blocked cell: no passage.
    text = "6\n5\n#_____\n_#_#__\n__#_#_\n______\n_____#\n0.5\n0.5\n5.5\n3.5\n"
    world = GridWorld(parse_problem(text))
    pinches = world.pinch_points()
    assert pinches == [(2.0, 3.0), (4.0, 3.0), (1.0, 4.0)]  # row by row from the bottom
    for x, y in pinches:
        assert world.first_blocked_cell_on_segment(x - 0.5, y - 0.5, x + 0.5, y + 0.5) is None
        for dx, dy in ((1e-9, -1e-9), (-1e-9, 1e-9)):  # beside the corner: blocked
            assert world.first_blocked_cell_on_segment(
                x - 0.5 + dx, y - 0.5 + dy, x + 0.5 + dx, y + 0.5 + dy) is not None
    corners = [(x, y) for x in range(1, world.width) for y in range(1, world.height)]
    for x, y in corners:  # every other interior corner: no such passage
        if (x, y) in pinches:
            continue
        through = world.first_blocked_cell_on_segment(x - 0.5, y - 0.5, x + 0.5, y + 0.5)
        nudged = [world.first_blocked_cell_on_segment(x - 0.5 + d, y - 0.5 - d,
                                                       x + 0.5 + d, y + 0.5 - d)
                  for d in (1e-9, -1e-9)]
        assert through is not None or None in nudged, (x, y)
    assert GridWorld(parse_problem(SPACE0)).pinch_points() == [(3.0, 1.0)]


def test_convex_corners_are_the_free_points_on_corners_of_one_blocked_cell():
    # Rows from the top: one blocked cell (1, 1) alone, and a pinch at (4, 2) (blocked
    # (3, 2) and (4, 1)), whose corner has two blocked cells round it.
    text = "6\n4\n______\n___#__\n_#__#_\n______\n0.5\n0.5\n5.5\n3.5\n"
    world = GridWorld(parse_problem(text))
    corners = world.convex_corners()
    nudge = 1 - 1e-9
    assert corners == [(nudge, nudge), (2.0, 1.0), (4.0 - 1e-9, 1.0 - 1e-9), (5.0, 1.0),
                       (1.0, 2.0), (2.0, 2.0), (3.0 - 1e-9, 2.0 - 1e-9), (5.0, 2.0),
                       (3.0, 3.0), (4.0, 3.0)]  # row by row from the bottom
    assert (4.0, 2.0) not in corners and world.pinch_points() == [(4.0, 2.0)]
    for x, y in corners:
        assert world.point_free(x, y)
        assert max(abs(x - round(x)), abs(y - round(y))) < 2e-9
