"""A world's body test (planning_core.worlds.body_tests, compiled for the cars)
answers as the shapes do: ``free(x, y, theta)`` as
``polygon_free(place(body, x, y, theta))`` along walks of poses (so that its free
disc is used), touching, far out, NaN and infinite ones included; the clearance
bit for bit as the obstacles' own point distances."""

from __future__ import annotations

import math
import random

from hypothesis import strategies as st

from planning_core.worlds.continuous import ContinuousWorld
from planning_core.worlds.shapes import (ConvexPolygon, Disc, Rect, body_polygon, place,
                                         point_in)
from tests.conftest import property_pair
from tests.planning_core.worlds.test_continuous_world import BOX, GRID, convex, obstacles

OBSTACLES = (Rect(4, 0, 5, 3), Disc(8, 8, 1), ConvexPolygon([(2, 6), (4, 6), (3, 8)]),
             Rect(4.5, 2, 6, 4), Disc(1.5, 1.5, 0.5))
SPECIAL = (math.nan, math.inf, -math.inf)
QUARTERS = (0.0, math.pi / 2, math.pi, -math.pi / 2, 3 * math.pi / 2)


def reference_clearance(world: ContinuousWorld, x: float, y: float) -> float:
    """ContinuousWorld.clearance as it was written over the shapes (before body_tests)."""
    box = world.box
    gap = math.inf if box is None else max(0.0, min(x - box.x0, box.x1 - x,
                                                    y - box.y0, box.y1 - y))
    for obstacle in world.obstacles:
        ox0, oy0, ox1, oy1 = obstacle.bbox
        if max(ox0 - x, x - ox1) < gap and max(oy0 - y, y - oy1) < gap:
            gap = min(gap, reference_distance(obstacle, x, y))
    return gap


def reference_distance(shape, x: float, y: float) -> float:
    if isinstance(shape, Disc):
        return max(0.0, math.hypot(x - shape.cx, y - shape.cy) - shape.r)
    if isinstance(shape, Rect):
        return math.hypot(max(shape.x0 - x, 0.0, x - shape.x1),
                          max(shape.y0 - y, 0.0, y - shape.y1))
    if point_in(shape, x, y):
        return 0.0
    best, (ax, ay) = math.inf, shape.points[-1]
    for bx, by in shape.points:
        ex, ey, wx, wy = bx - ax, by - ay, x - ax, y - ay
        l2 = ex * ex + ey * ey
        t = 0.0 if l2 == 0.0 else min(1.0, max(0.0, (ex * wx + ey * wy) / l2))
        best = min(best, math.hypot(wx - t * ex, wy - t * ey))
        ax, ay = bx, by
    return best


def walk(world: ContinuousWorld, body: ConvexPolygon, poses) -> set:
    """Every pose answered as the placed polygon is; the answers seen."""
    free, seen = world.body_test(body), set()
    for x, y, theta in poses:
        expected = world.polygon_free(place(body, x, y, theta))
        assert free(x, y, theta) == expected, (x, y, theta)
        seen.add(expected)
    return seen


def random_poses(rng: random.Random, count: int, step: float):
    """A walk in [-1, 11]^2 by small steps, now and then a jump, a dyadic pose (exact
    contacts), a quarter turn, a NaN or an infinite coordinate."""
    x, y = 5.0, 5.0
    for _ in range(count):
        roll = rng.random()
        if roll < 0.03:
            x, y = rng.uniform(-1.0, 11.0), rng.uniform(-1.0, 11.0)
        elif roll < 0.06:
            x, y = rng.randint(-4, 44) / 4, rng.randint(-4, 44) / 4
        x, y = x + step * (rng.random() - 0.5), y + step * (rng.random() - 0.5)
        theta = rng.choice(QUARTERS) if rng.random() < 0.1 else rng.uniform(-4.0, 4.0)
        if rng.random() < 0.02:
            yield rng.choice([(rng.choice(SPECIAL), y, theta), (x, rng.choice(SPECIAL), theta),
                              (x, y, rng.choice(SPECIAL))])
        else:
            yield x, y, theta


def check_random_walks(seed: int = 5, count: int = 3000) -> None:
    """Seeded walks in three worlds with two bodies (also run compiled: tests/test_compiled)."""
    rng = random.Random(seed)
    bodies = (body_polygon("rect", [2, 1]), ConvexPolygon([(-0.4, -0.3), (0.5, 0.0), (-0.1, 0.4)]))
    for world in (ContinuousWorld(BOX, OBSTACLES), ContinuousWorld(None, OBSTACLES),
                  ContinuousWorld(BOX, ())):
        for body in bodies:
            seen = walk(world, body, random_poses(rng, count, 0.05))
            assert seen == {True, False}
        for _ in range(count):
            x, y = rng.uniform(-1.0, 11.0), rng.uniform(-1.0, 11.0)
            assert world.clearance(x, y).hex() == reference_clearance(world, x, y).hex()


def test_body_test_and_clearance_answer_as_the_shapes_do():
    check_random_walks()


def test_a_free_pose_far_out_leaves_no_free_disc_behind():
    """Without a box a pose at an infinite x is free (no obstacle near it); the poses
    after it are still tested."""
    world, body = ContinuousWorld(None, (Disc(0, 0, 1),)), body_polygon("rect", [2, 1])
    assert walk(world, body, [(math.inf, 0.0, 0.0), (0.0, 0.0, 0.0), (5.0, 0.0, 0.0),
                              (0.5, math.inf, 0.0), (0.5, 0.0, 0.0)]) == {True, False}


STEP = st.floats(-0.25, 0.25)
THETA = st.one_of(st.floats(-4, 4), st.sampled_from(QUARTERS))
POSE = st.one_of(st.tuples(STEP, STEP, THETA),  # a step from the last pose
                 st.tuples(GRID, GRID, THETA).map(lambda p: ("at", *p)),  # a jump, exact
                 st.tuples(st.sampled_from(SPECIAL + (0.0,)), st.sampled_from(SPECIAL + (0.0,)),
                           st.sampled_from(SPECIAL + QUARTERS)).map(lambda p: ("special", *p)))


def poses_of(moves):
    x, y = 5.0, 5.0
    for move in moves:
        if move[0] == "at":
            _, x, y, theta = move
        elif move[0] == "special":  # NaN / infinities around the walk's last pose
            _, sx, sy, theta = move
            yield x + sx, y + sy, theta
            continue
        else:
            dx, dy, theta = move
            x, y = x + dx, y + dy
        yield x, y, theta


WALKS = (obstacles, st.one_of(st.just(body_polygon("rect", [2, 1])), convex()), st.booleans(),
         st.lists(POSE, min_size=1, max_size=60))
"""Obstacles, a body, boxed or not, and a walk's moves: the walk properties' cases."""


def check_walk(obs, body, boxed, moves):
    """Free answers as the placed polygon along the walk."""
    walk(ContinuousWorld(BOX if boxed else None, obs), body, poses_of(moves))


test_free_answers_as_the_placed_polygon_along_any_walk, \
    test_free_answers_as_the_placed_polygon_along_any_walk_full = property_pair(
        check_walk, *WALKS, unit=50, full=150)
