"""Half-open cells at their exact edges (SPEC 1: cell (i, j) covers
[i, i+1) x [j, j+1); a point collides when it is outside [0, W) x [0, H) or
its cell is blocked).

On the map below the only blocked cell is B = (2, 1) = [2, 3) x [1, 2). So its
left edge x = 2 and bottom edge y = 1 belong to B (a point there collides),
its right edge x = 3 and top edge y = 2 belong to the free neighbours (a point
there is free); of its corners only (2, 1) is in B. Hence:

* a segment that ENDS on x = 2 moving right (or on y = 1 moving up) hits B at
  its last point; one that ends on x = 3 moving left (or on y = 2 moving down)
  does not; one that STARTS on x = 3 moving right (or y = 2 moving up) does not;
* a segment that runs along B's bottom or left edge hits it, along its top or
  right edge it grazes it and is free;
* a diagonal through a corner hits B only where it passes into B's interior
  or through the corner (2, 1).

Each case is checked in every direction through all three segment tests of
the grid world (exact walk, the exact one-cell test, the course's 0.05-unit
sampling), through the point test, and, where it can be put as a planner's
answer, through the validator (``validate_output``, strict) and the
planner's problem reader (``rrt_cli.cli.main``: a start or goal on a blocked
cell's own edge is refused, on a free cell's edge accepted).

Internal names: ``GridWorld`` and ``segment_meets_cell``.
"""

from __future__ import annotations

import math

import pytest

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from planning_core.worlds.grid import GridWorld, segment_meets_cell
from tests.conftest import plan_in_process
from validator.checks import validate_output

W, H = 5, 4
ROWS = ["_____", "_____", "__#__", "_____"]  # top row first: B = (2, 1)
B = (2, 1)
BELOW_2 = math.nextafter(2.0, 0.0)  # 1.9999999999999998
BELOW_3 = math.nextafter(3.0, 0.0)


def problem_text(start=(0.5, 0.5), goal=(4.5, 3.5)) -> str:
    return "\n".join([str(W), str(H), *ROWS, repr(start[0]), repr(start[1]),
                      repr(goal[0]), repr(goal[1])]) + "\n"


@pytest.fixture(scope="module")
def world():
    return GridWorld(parse_problem(problem_text()))


# ---------------------------------------------------------------- points

@pytest.mark.parametrize("point, free", [
    ((2.0, 1.5), False),   # B's left edge is B's
    ((3.0, 1.5), True),    # B's right edge is cell (3, 1)'s
    ((2.5, 1.0), False),   # B's bottom edge is B's
    ((2.5, 2.0), True),    # B's top edge is cell (2, 2)'s
    ((2.0, 1.0), False),   # the one corner of B that is B's
    ((3.0, 1.0), True), ((2.0, 2.0), True), ((3.0, 2.0), True),
    ((BELOW_3, 1.5), False), ((2.5, BELOW_2), False),
    ((BELOW_2, 1.5), True), ((2.5, math.nextafter(1.0, 0.0)), True),
    ((0.0, 0.0), True),    # the map's left and bottom edges are inside it
    ((5.0, 1.5), False), ((1.5, 4.0), False),  # its right and top edges are not
    ((math.nextafter(5.0, 0.0), math.nextafter(4.0, 0.0)), True),
    ((-1e-300, 1.5), False), ((1.5, -1e-300), False),
])
def test_point_belongs_to_the_cell_whose_left_or_bottom_edge_it_is_on(world, point, free):
    assert world.point_free(*point) is free, point


# ---------------------------------------------------------------- segments
# (x0, y0, x1, y1), expected first hit (column, row, fraction) or None.
SEGMENTS = {
    # moving right
    "right, ends on B's left edge": ((0.5, 1.5, 2.0, 1.5), (2, 1, 1.0)),
    "right, ends just short of B": ((0.5, 1.5, BELOW_2, 1.5), None),
    "right, leaves (1,1) by its right edge into B": ((1.5, 1.5, 3.5, 1.5), (2, 1, 0.25)),
    "right, starts on B's right edge": ((3.0, 1.5, 4.5, 1.5), None),
    "right, leaves (3,1) by its right edge, free": ((3.5, 1.5, 4.0, 1.5), None),
    "right, ends on the map's right edge": ((4.5, 1.5, 5.0, 1.5), (5, 1, 1.0)),
    "right, starts inside B": ((2.5, 1.5, 4.5, 1.5), (2, 1, 0.0)),
    # moving left
    "left, ends on B's right edge": ((4.5, 1.5, 3.0, 1.5), None),
    "left, ends just inside B": ((4.5, 1.5, BELOW_3, 1.5), (2, 1, 1.0)),
    "left, leaves (3,1) by its left edge into B": ((4.5, 1.5, 0.5, 1.5), (2, 1, 0.375)),
    "left, starts on B's left edge": ((2.0, 1.5, 0.5, 1.5), (2, 1, 0.0)),
    "left, ends on the map's left edge": ((1.5, 1.5, 0.0, 1.5), None),
    # moving up
    "up, ends on B's bottom edge": ((2.5, 0.5, 2.5, 1.0), (2, 1, 1.0)),
    "up, ends just short of B": ((2.5, 0.5, 2.5, math.nextafter(1.0, 0.0)), None),
    "up, leaves (2,0) by its top edge into B": ((2.5, 0.5, 2.5, 3.5), (2, 1, 1 / 6)),
    "up, starts on B's top edge": ((2.5, 2.0, 2.5, 3.5), None),
    "up, ends on the map's top edge": ((1.5, 3.5, 1.5, 4.0), (1, 4, 1.0)),
    # moving down
    "down, ends on B's top edge": ((2.5, 3.5, 2.5, 2.0), None),
    "down, ends just inside B": ((2.5, 3.5, 2.5, BELOW_2), (2, 1, 1.0)),
    "down, leaves (2,2) by its bottom edge into B": ((2.5, 3.5, 2.5, 0.5), (2, 1, 0.5)),
    "down, starts on B's bottom edge": ((2.5, 1.0, 2.5, 0.5), (2, 1, 0.0)),
    "down, ends on the map's bottom edge": ((1.5, 0.5, 1.5, 0.0), None),
    # grazing B's edges, both ways
    "along B's top edge, rightward": ((1.5, 2.0, 3.5, 2.0), None),
    "along B's top edge, leftward": ((3.5, 2.0, 1.5, 2.0), None),
    "along B's right edge, upward": ((3.0, 0.5, 3.0, 2.5), None),
    "along B's right edge, downward": ((3.0, 2.5, 3.0, 0.5), None),
    "along B's bottom edge, rightward": ((1.5, 1.0, 3.5, 1.0), (2, 1, 0.25)),
    "along B's bottom edge, leftward": ((3.5, 1.0, 1.5, 1.0), (2, 1, 0.25)),
    "along B's left edge, upward": ((2.0, 0.5, 2.0, 2.5), (2, 1, 0.25)),
    "along B's left edge, downward": ((2.0, 2.5, 2.0, 0.5), (2, 1, 0.25)),
    # diagonals through B's corners
    "through top-right corner (3,2), down-right": ((2.5, 2.5, 3.5, 1.5), None),
    "through top-right corner (3,2), up-left": ((3.5, 1.5, 2.5, 2.5), None),
    "through top-left corner (2,2), up-right": ((1.5, 1.5, 2.5, 2.5), None),
    "through top-left corner (2,2), down-left": ((2.5, 2.5, 1.5, 1.5), None),
    "through bottom-right corner (3,1), up-right": ((2.5, 0.5, 3.5, 1.5), None),
    "through bottom-right corner (3,1), down-left": ((3.5, 1.5, 2.5, 0.5), None),
    "through bottom-left corner (2,1), down-right": ((1.5, 1.5, 2.5, 0.5), (2, 1, 0.5)),
    "through bottom-left corner (2,1), up-left": ((2.5, 0.5, 1.5, 1.5), (2, 1, 0.5)),
    "into B past corner (3,1), up-left": ((3.5, 0.5, 2.5, 1.5), (2, 1, 0.5)),
    "into B past corner (2,2), down-right": ((1.5, 2.5, 2.5, 1.5), (2, 1, 0.5)),
    # steep and shallow crossings of several columns and rows
    "steep, across B": ((2.25, 0.25, 2.75, 3.75), (2, 1, 0.75 / 3.5)),
    "shallow, across B": ((0.5, 0.5, 4.5, 2.5), (2, 1, 0.375)),
    "steep, beside B": ((1.25, 0.25, BELOW_2, 3.75), None),
}
EXACT = 1e-12
# These touch B at its corner (2, 1) only: a single point, which 0.05-unit
# samples step over (the corner cuts the validator warns about).
CORNER_ONLY = {"through bottom-left corner (2,1), down-right",
               "through bottom-left corner (2,1), up-left"}


def ids(cases):
    return list(cases)


@pytest.mark.parametrize("name", ids(SEGMENTS))
def test_exact_walk_first_blocked_cell(world, name):
    segment, expected = SEGMENTS[name]
    hit = world.first_blocked_cell_on_segment(*segment)
    if expected is None:
        assert hit is None, f"{name}: {segment} reported hitting {hit}"
    else:
        assert hit is not None, f"{name}: {segment} reported free"
        column, row, fraction = expected
        assert (hit.column, hit.row) == (column, row), (name, hit)
        assert hit.fraction == pytest.approx(fraction, abs=EXACT), (name, hit)


@pytest.mark.parametrize("name", ids(SEGMENTS))
def test_segment_meets_cell_b(name):
    segment, expected = SEGMENTS[name]
    t = segment_meets_cell(*segment, *B)
    if expected is None or expected[:2] != B:
        assert t is None, f"{name}: {segment} meets B at t={t}"
    else:
        assert t is not None and t == pytest.approx(expected[2], abs=EXACT), (name, t)


@pytest.mark.parametrize("segment, column, row", [
    # Every cell that touches B along an edge it does not own, approached or left
    # through that edge: the segment lies in the neighbour, never in B.
    ((3.5, 1.5, 3.0, 1.5), 2, 1), ((3.0, 1.5, 3.8, 1.5), 2, 1),
    ((2.5, 2.5, 2.5, 2.0), 2, 1), ((2.5, 2.0, 2.5, 2.8), 2, 1),
    # and the neighbours themselves do own those points
    ((3.5, 1.5, 3.0, 1.5), 3, 1), ((3.0, 1.5, 3.8, 1.5), 3, 1),
    ((2.5, 2.5, 2.5, 2.0), 2, 2), ((2.5, 2.0, 2.5, 2.8), 2, 2),
])
def test_segment_meets_cell_at_owned_and_foreign_edges(segment, column, row):
    t = segment_meets_cell(*segment, column, row)
    if (column, row) == B:
        assert t is None, (segment, t)
    else:
        assert t is not None, segment


def spec_point_in_b(x: float, y: float) -> bool:
    """SPEC 1, written out: the point's cell is B."""
    return (math.floor(x), math.floor(y)) == B


ANCHORS = [(2.0, 1.0), (3.0, 1.0), (2.0, 2.0), (3.0, 2.0),     # B's corners
           (2.0, 1.5), (3.0, 1.5), (2.5, 1.0), (2.5, 2.0)]     # its edges' middles
STEPS = [(dx, dy) for dx in (-0.25, 0.0, 0.25) for dy in (-0.25, 0.0, 0.25) if dx or dy]


@pytest.mark.parametrize("anchor", ANCHORS, ids=str)
def test_short_segments_from_and_to_every_corner_and_edge_of_b(world, anchor):
    # A segment of at most 0.25 per axis from a corner or edge of B (quarter
    # coordinates, exact in binary): all its points but the anchor lie in one cell,
    # so it meets B exactly when the anchor or its middle is in B (SPEC 1).
    ax, ay = anchor
    for dx, dy in STEPS:
        far = (ax + dx, ay + dy)
        middle_in_b = spec_point_in_b(ax + dx / 2, ay + dy / 2)
        anchor_in_b = spec_point_in_b(ax, ay)
        for segment, anchor_first in (((ax, ay, *far), True), ((*far, ax, ay), False)):
            if middle_in_b or (anchor_in_b and anchor_first):
                fraction = 0.0
            elif anchor_in_b:
                fraction = 1.0
            else:
                fraction = None
            t = segment_meets_cell(*segment, *B)
            hit = world.first_blocked_cell_on_segment(*segment)
            sample = world.first_sampled_collision(*segment)
            if fraction is None:
                assert t is None, f"segment_meets_cell: {segment} meets B at t={t}"
                assert hit is None, f"exact walk: {segment} hits {hit}"
                assert sample is None, f"sampling: {segment} collides at {sample}"
            else:
                assert t == fraction, f"segment_meets_cell: {segment} meets B at t={t}"
                assert hit is not None and (hit.column, hit.row, hit.fraction) == (
                    *B, fraction), f"exact walk: {segment} hits {hit}"
                assert sample is not None and spec_point_in_b(*sample), (
                    f"sampling: {segment} collides at {sample}")


@pytest.mark.parametrize("point, inside", [
    ((2.0, 1.0), True), ((2.0, 1.5), True), ((2.5, 1.0), True), ((2.5, 1.5), True),
    ((3.0, 1.5), False), ((2.5, 2.0), False), ((3.0, 2.0), False), ((2.0, 2.0), False),
    ((3.0, 1.0), False),
])
def test_segment_meets_cell_of_a_single_point(point, inside):
    t = segment_meets_cell(*point, *point, *B)
    assert (t == 0.0) if inside else (t is None), (point, t)


@pytest.mark.parametrize("name", ids(SEGMENTS))
def test_sampled_check_agrees_at_the_edges(world, name):
    # The course's rule samples the segment (both ends included); every case
    # above but the corner touches either stays out of B or runs in it for a
    # stretch or ends in it, so sampling and the exact walk agree on hit or free.
    segment, expected = SEGMENTS[name]
    sample = world.first_sampled_collision(*segment)
    if name in CORNER_ONLY:
        assert sample is None or (math.floor(sample[0]), math.floor(sample[1])) == B, sample
    elif expected is None:
        assert sample is None, f"{name}: sample {sample} reported in collision"
    else:
        assert sample is not None, f"{name}: no sample reported in collision"
        column, row, _ = expected
        x, y = sample
        assert (math.floor(x), math.floor(y)) == (column, row), (name, sample)
        assert not world.point_free(x, y)


def test_sampled_check_includes_the_endpoint_on_the_edge(world):
    assert world.first_sampled_collision(0.5, 1.5, 2.0, 1.5) == (2.0, 1.5)
    assert world.first_sampled_collision(2.5, 0.5, 2.5, 1.0) == (2.5, 1.0)
    assert world.first_sampled_collision(2.0, 1.5, 0.5, 1.5) == (2.0, 1.5)


# ------------------------------------------------ the same through the validator

CORNER = "corner"  # a corner touch: valid with a warning, invalid with -strict


@pytest.mark.parametrize("path, valid", [
    ([(0.5, 2.0), (4.5, 2.0)], True),               # along B's top edge
    ([(0.5, 1.0), (4.5, 1.0)], False),              # along B's bottom edge
    ([(3.0, 0.5), (3.0, 3.5)], True),               # along B's right edge
    ([(2.0, 0.5), (2.0, 3.5)], False),              # along B's left edge
    ([(4.5, 1.5), (3.0, 1.5), (3.0, 3.5)], True),   # to B's right edge moving left, then up
    ([(0.5, 1.5), (2.0, 1.5), (2.0, 3.5)], False),  # to B's left edge moving right
    ([(2.5, 0.5), (2.5, 1.0), (4.5, 1.0)], False),  # up to B's bottom edge
    ([(2.5, 3.5), (2.5, 2.0), (4.5, 2.0)], True),   # down to B's top edge
    ([(2.5, 2.5), (3.5, 1.5), (3.5, 0.5)], True),   # through corner (3, 2)
    ([(1.5, 1.5), (2.0, 1.0), (4.5, 1.0)], False),  # to corner (2, 1), then along y = 1
    ([(1.5, 1.5), (2.5, 0.5), (4.5, 0.5)], CORNER),  # through corner (2, 1) only
])
def test_validator_collision_check_at_cell_edges(path, valid):
    problem = parse_problem(problem_text(start=path[0], goal=path[-1]))
    text = "\n".join([str(len(path)), *(f"{x!r} {y!r}" for x, y in path), "0"]) + "\n"
    for strict in (False, True):
        report = validate_output(problem, Vehicle.POINT, text, strict=strict)
        expect_valid = valid is True or (valid == CORNER and not strict)
        assert report.valid is expect_valid, (path, strict, report.first_failure)
        if not expect_valid:
            assert report.first_failure.number == 6, (path, report.first_failure)
        elif valid == CORNER:
            assert report.warnings and "cell (2, 1)" in report.warnings[0], report.warnings
        else:
            assert not report.warnings, (path, report.warnings)


# ------------------------------------------------ the planner's problem reader



@pytest.mark.parametrize("start, goal, refusal", [
    ((3.0, 1.5), (3.05, 1.5), None),                   # start on B's right edge
    ((2.5, 2.0), (2.5, 2.05), None),                   # start on B's top edge
    ((3.0, 2.0), (4.5, 3.5), None),                    # start on B's top-right corner
    ((2.0, 1.5), (0.5, 0.5), "blocked cell (2, 1)"),   # start on B's left edge
    ((2.5, 1.0), (0.5, 0.5), "blocked cell (2, 1)"),   # start on B's bottom edge
    ((0.5, 0.5), (2.0, 1.0), "blocked cell (2, 1)"),   # goal on B's bottom-left corner
    ((0.5, 0.5), (3.0, 1.0), None),                    # goal on B's bottom-right corner
    ((0.5, 0.5), (2.0, 2.0), None),                    # goal on B's top-left corner
    ((0.5, 0.5), (5.0, 1.5), "outside"),               # goal on the map's right edge
    ((0.5, 4.0), (0.5, 0.5), "outside"),               # start on the map's top edge
])
def test_planner_reads_start_and_goal_on_cell_edges(monkeypatch, start, goal, refusal):
    text = problem_text(start, goal)
    status, out, err = plan_in_process(monkeypatch, ["-seed", "1", "-iterations", "20000"], text)
    if refusal is not None:
        assert status == 2 and refusal in err, (start, goal, status, err)
        return
    assert status == 0, (start, goal, status, err)
    report = validate_output(parse_problem(text), Vehicle.POINT, out, strict=True)
    assert report.valid, (start, goal, report.first_failure)
