"""A world's bound segment tests (planning_core.worlds.segment_tests, compiled for the
arm) answer as the shapes do: ``free`` as ``first_obstacle(Segment(...)) is None``,
``gap`` as the closest of the box's sides and ``shapes.segment_gap`` per obstacle."""

from __future__ import annotations

import math
import random

import pytest

from planning_core.worlds.continuous import ContinuousWorld
from planning_core.worlds.segment_tests import nearer
from planning_core.worlds.shapes import (ConvexPolygon, Disc, Rect, Segment, point_distance,
                                         segment_gap)
from tests.conftest import unit_sample

OBSTACLES = (Rect(0.6, 0.6, 1.3, 1.3), Disc(1.6, -0.45, 0.2), Disc(-1.3, 0.5, 0.25),
             ConvexPolygon(((-1.0, -1.5), (0.0, -1.8), (0.2, -0.9))), Rect(-1.7, -1.7, -1.2, -1.2))


def reference_gap(world: ContinuousWorld, x0, y0, x1, y1, enough):
    box = world.box.bbox if world.box is not None else (-math.inf,) * 2 + (math.inf,) * 2
    lx, hx = (x0, x1) if x0 <= x1 else (x1, x0)
    ly, hy = (y0, y1) if y0 <= y1 else (y1, y0)
    best = min(lx - box[0], box[2] - hx, ly - box[1], box[3] - hy, enough)
    for obstacle in world.obstacles:
        ox0, oy0, ox1, oy1 = obstacle.bbox
        if max(ox0 - hx, lx - ox1, oy0 - hy, ly - oy1) < best:
            best = min(best, segment_gap(obstacle, x0, y0, x1, y1))
    return best


def random_segment(rng: random.Random):
    x0, y0 = rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5)
    if rng.random() < 0.1:
        return x0, y0, x0, y0  # a point
    length = rng.choice((0.05, 0.3, 1.0, 3.0))
    return x0, y0, x0 + rng.uniform(-length, length), y0 + rng.uniform(-length, length)


def reference_shape_gap(shape, x0, y0, x1, y1):
    """A rect's or polygon's gap as it was written before some hypots were skipped
    (``segment_tests.nearer``): every endpoint's and vertex's distance."""
    if isinstance(shape, Rect):
        rx0, ry0, rx1, ry1 = shape.bbox
        best = min(math.hypot(max(rx0 - x0, 0.0, x0 - rx1), max(ry0 - y0, 0.0, y0 - ry1)),
                   math.hypot(max(rx0 - x1, 0.0, x1 - rx1), max(ry0 - y1, 0.0, y1 - ry1)))
    else:
        best = min(point_distance(shape, x0, y0), point_distance(shape, x1, y1))
    for vx, vy in shape.corners if isinstance(shape, Rect) else shape.points:
        ex, ey, wx, wy = x1 - x0, y1 - y0, vx - x0, vy - y0
        l2 = ex * ex + ey * ey
        t = 0.0 if l2 == 0.0 else min(1.0, max(0.0, (ex * wx + ey * wy) / l2))
        d = math.hypot(wx - t * ex, wy - t * ey)
        if d < best:
            best = d
    return best


def check_segments(seed: int, count: int = 5000) -> None:
    """``free`` and ``gap`` against the shapes, and the rect and polygon gaps against
    their old form, bit for bit (also run with the compiled build: tests/test_compiled.py)."""
    rng = random.Random(seed)
    shapes = [o for o in OBSTACLES if not isinstance(o, Disc)]
    for box in (Rect(-2.2, -2.2, 2.2, 2.2), None):
        world = ContinuousWorld(box, OBSTACLES)
        free_count = 0
        for _ in range(count):
            x0, y0, x1, y1 = random_segment(rng)
            if rng.random() < 0.01:  # not a segment: the gaps' arithmetic alone
                x0 = rng.choice((math.nan, math.inf, -math.inf))
            for shape in shapes:
                assert (segment_gap(shape, x0, y0, x1, y1).hex()
                        == reference_shape_gap(shape, x0, y0, x1, y1).hex())
            if not math.isfinite(x0):
                continue
            free = world.first_obstacle(Segment(x0, y0, x1, y1)) is None
            assert world.segment_free(x0, y0, x1, y1) == free
            if free:
                free_count += 1
                enough = rng.choice((0.05, 1.0, math.inf))
                got = world.segment_clearance(x0, y0, x1, y1, enough)
                assert got.hex() == reference_gap(world, x0, y0, x1, y1, enough).hex()
        assert count / 10 < free_count < count * 9 / 10  # both answers were exercised


@pytest.mark.parametrize("count", unit_sample([2000, 5000]))
def test_free_and_gap_answer_as_the_shapes_do(count):
    check_segments(seed=5, count=count)


def test_nearer_is_the_min_with_the_hypot():
    rng = random.Random(3)
    values = (0.0, -0.0, 1e-310, 5e-324, 1.0, 3.0, 1e300, math.inf, -math.inf, math.nan)
    for _ in range(20000):
        best, px, py = (rng.choice(values) if rng.random() < 0.3 else rng.uniform(-3, 3)
                        for _ in range(3))
        assert nearer(best, px, py).hex() == min(best, math.hypot(px, py)).hex()


def test_a_nan_end_is_never_free():
    world = ContinuousWorld(None, OBSTACLES)
    assert not world.segment_free(math.nan, 0.0, 1.0, 1.0)
    assert not world.segment_free(0.0, 0.0, 1.0, math.nan)
