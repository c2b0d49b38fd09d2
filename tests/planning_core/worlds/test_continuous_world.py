"""The continuous world (planning_core.worlds.continuous): a closed box, closed obstacles.

Hand cases for the box border and obstacle contact, the first obstacle hit, arm
links and points; a property check against a brute-force loop over the shapes.
"""

from __future__ import annotations

import dataclasses
import math

import pytest
from hypothesis import assume
from hypothesis import strategies as st

from planning_core.worlds.continuous import OUTSIDE_BOX, ContinuousWorld
from planning_core.worlds.shapes import (
    ConvexPolygon,
    Disc,
    Rect,
    Segment,
    body_polygon,
    inside_box,
    intersects,
    place,
    point_in,
)
from tests.conftest import property_pair

BOX = Rect(0, 0, 10, 10)
BODY = body_polygon("rect", [2, 1])          # x in [-1, 1], y in [-0.5, 0.5] in its own frame
SQUARE = ConvexPolygon([(0, 0), (1, 0), (1, 1), (0, 1)])

WORLD = ContinuousWorld(BOX, (
    Rect(4, 0, 5, 3),                                   # 0: a wall from the floor
    Disc(8, 8, 1),                                      # 1
    ConvexPolygon([(2, 6), (4, 6), (3, 8)]),            # 2: triangle
    Rect(4.5, 2, 6, 4),                                 # 3: overlaps obstacle 0
))


def test_border_is_closed():
    assert WORLD.polygon_free(place(BODY, 1, 5, 0))                    # touches x = 0
    assert WORLD.first_obstacle(place(BODY, math.nextafter(1.0, 0.0), 5, 0)) == OUTSIDE_BOX
    assert WORLD.polygon_free(place(BODY, 5, 9.5, 0))                  # touches y = 10
    assert WORLD.polygon_free(place(BODY, 0.5, 1, math.pi / 2))        # upright in the corner
    assert WORLD.first_obstacle(place(BODY, 0.5, 0.999, math.pi / 2)) == -1
    assert WORLD.first_obstacle(place(BODY, 50, 50, 0)) == -1


def test_touching_an_obstacle_is_a_collision():
    assert WORLD.first_obstacle(place(BODY, 3, 1, 0)) == 0               # right end on x = 4
    assert WORLD.first_obstacle(place(BODY, math.nextafter(3.0, 0.0), 1, 0)) is None
    assert WORLD.first_obstacle(place(BODY, 5, 3.5, 0)) == 0             # hits 0 and 3: the first
    assert WORLD.first_obstacle(place(BODY, 5.5, 4.5, 0)) == 3           # bottom on y = 4
    assert WORLD.first_obstacle(place(BODY, 8, 6.5, 0)) == 1             # top y = 7: disc tangent
    assert WORLD.polygon_free(place(BODY, 8, 6.5 - 1e-9, 0))
    assert WORLD.first_obstacle(place(BODY, 3, 5.5, 0)) == 2             # on the triangle's base
    assert WORLD.polygon_free(place(BODY, 3, 5.4, 0))


def test_rotated_body_between_obstacles():
    # upright (theta = pi/2) the body is 1 wide: it fits the 1-wide slot x in [6, 7] of a
    # world with walls at x <= 6 and x >= 7, touching both; lying flat it does not fit
    world = ContinuousWorld(BOX, (Rect(5, 0, 6, 10), Rect(7, 0, 8, 10)))
    assert world.first_obstacle(place(BODY, 6.5, 5, math.pi / 2)) == 0   # touches both walls
    thin = body_polygon("rect", [2, 0.5])
    assert world.polygon_free(place(thin, 6.5, 5, math.pi / 2))
    assert world.first_obstacle(place(thin, 6.5, 5, 0)) == 0


def test_arm_links():
    assert WORLD.segment_free(0, 0, 3.5, 2)                            # from the box corner
    assert not WORLD.segment_free(0, 0, 4, 2)                          # tip on obstacle 0's side
    assert not WORLD.segment_free(-1e-9, 0, 3, 2)                      # base outside the box
    assert WORLD.segment_free(0, 10, 10, 10)                           # along the top border
    assert not WORLD.segment_free(7, 5, 7, 8)                          # ends on the disc (7, 8)
    assert WORLD.first_obstacle(Segment(1, 7, 6, 7)) == 2              # through the triangle
    # "first" is the lowest index, not the first along the link: the disc (1) is
    # touched at (8, 7) after the triangle (2) is crossed
    assert WORLD.first_obstacle(Segment(1, 7, 9, 7)) == 1


def test_points():
    assert WORLD.point_free(0, 0) and WORLD.point_free(10, 3.5)
    assert not WORLD.point_free(10 + 1e-9, 3.5)
    assert not WORLD.point_free(4, 1) and not WORLD.point_free(7, 8)    # on obstacle boundaries
    assert WORLD.point_free(3.9, 1) and not WORLD.point_free(3, 7)


def test_world_without_a_box():
    free = ContinuousWorld(None)
    assert free.polygon_free(place(BODY, 1e6, -1e6, 1.0))
    assert free.segment_free(-5, -5, 5, 5) and free.point_free(-1e9, 1e9)
    assert free.contains(SQUARE) and WORLD.contains(SQUARE)
    assert not WORLD.contains(place(SQUARE, -1, 0, 0))
    walls = ContinuousWorld(None, [Disc(0, 0, 1)])
    assert walls.first_obstacle(place(BODY, 2, 0, 0)) == 0
    assert walls.first_obstacle(place(BODY, 100, 0, 0)) is None


def test_scene_from_the_shared_problems_has_a_free_start_and_goal():
    """rigid2-scene1 (problems/family): body rect 0.3 0.15 in world 0 0 2 2."""
    scene = ContinuousWorld(Rect(0, 0, 2, 2), [
        ConvexPolygon([(0.7, 0.0), (0.9, 0.0), (0.9, 1.2), (0.7, 1.3)]),
        ConvexPolygon([(1.2, 0.7), (1.4, 0.7), (1.4, 2.0), (1.2, 2.0)]),
        ConvexPolygon([(0.2, 1.5), (0.6, 1.5), (0.4, 1.8)]),
    ])
    body = body_polygon("rect", [0.3, 0.15])
    assert scene.polygon_free(place(body, 0.5, 0.25, 0))
    assert scene.polygon_free(place(body, 1.75, 1.5, 0))
    assert scene.first_obstacle(place(body, 0.8, 0.25, 0)) == 0
    assert scene.first_obstacle(place(body, 1.3, 1.5, math.pi / 2)) == 1


def test_nan_is_never_free():
    nan = math.nan
    for world in (WORLD, ContinuousWorld(None, [Disc(0, 0, 1)]), ContinuousWorld(None)):
        assert world.first_obstacle(place(BODY, nan, 1, 0)) == OUTSIDE_BOX
        assert not world.polygon_free(place(BODY, 1, 1, nan))
        assert not world.polygon_free(place(BODY, 1, 1, math.inf))
        assert not world.polygon_free(place(BODY, 1, nan, 0))
        assert not world.segment_free(nan, 0, 1, 1)
        assert not world.segment_free(0, 0, nan, 1)
        assert not world.point_free(nan, 1)


def test_validation_and_value_semantics():
    with pytest.raises(TypeError, match="obstacle 1"):
        ContinuousWorld(BOX, (Rect(0, 0, 1, 1), (0, 0, 1, 1)))
    with pytest.raises(TypeError, match="box"):
        ContinuousWorld((0, 0, 1, 1), ())
    with pytest.raises(dataclasses.FrozenInstanceError):
        WORLD.box = None
    again = ContinuousWorld(BOX, list(WORLD.obstacles))
    assert again == WORLD and hash(again) == hash(WORLD) and isinstance(again.obstacles, tuple)


# --- Property: the world agrees with a brute-force loop over the shapes -----------------

GRID = st.integers(-8, 48).map(lambda k: k / 4)        # around the box [0, 10]^2, dyadic
SIZE = st.integers(1, 12).map(lambda k: k / 4)


@st.composite
def convex(draw):
    cx, cy, r = draw(GRID), draw(GRID), draw(SIZE)
    angles = sorted(set(draw(st.lists(st.integers(0, 15), min_size=3, max_size=7))))
    assume(len(angles) >= 3)
    try:
        return ConvexPolygon([(cx + r * math.cos(k * math.pi / 8),
                               cy + r * math.sin(k * math.pi / 8)) for k in angles])
    except ValueError:  # three vertices within a half circle can be nearly collinear
        assume(False)


rects = st.builds(lambda x, y, w, h: Rect(x, y, x + w, y + h), GRID, GRID, SIZE, SIZE)
obstacles = st.lists(st.one_of(rects, st.builds(Disc, GRID, GRID, SIZE), convex()), max_size=10)
queries = st.one_of(convex(), st.builds(Segment, GRID, GRID, GRID, GRID),
                    st.builds(lambda x, y, t: place(BODY, x, y, t), GRID, GRID, st.floats(-4, 4)))


def brute_first(world, shape):
    if world.box is not None and not inside_box(shape, world.box):
        return -1
    return next((i for i, o in enumerate(world.obstacles) if intersects(shape, o)), None)


def check_first_obstacle(obs, shape, boxed, px, py):
    world = ContinuousWorld(BOX if boxed else None, obs)
    expected = brute_first(world, shape)
    assert world.first_obstacle(shape) == expected
    if isinstance(shape, ConvexPolygon):
        assert world.polygon_free(shape) is (expected is None)
    else:
        assert world.segment_free(shape.x0, shape.y0, shape.x1, shape.y1) is (expected is None)
    in_box = not boxed or BOX.x0 <= px <= BOX.x1 and BOX.y0 <= py <= BOX.y1
    assert world.point_free(px, py) is (in_box and not any(point_in(o, px, py) for o in obs))


WORLD_CASES = (obstacles, queries, st.booleans(), GRID, GRID)
test_first_obstacle_equals_brute_force, test_first_obstacle_equals_brute_force_deep = \
    property_pair(check_first_obstacle, *WORLD_CASES, unit=80, full=3000)
