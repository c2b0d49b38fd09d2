"""A rigid body's straight-motion check (rigid2, SPEC 5.2) in one native call.

The interpreted way tests each sample through three calls (the space's
interpolation, the state validator, the body test); compiled (mypyc,
``rrt_startup.compiled``), :meth:`BodyMotionCheck.first_invalid` runs the
whole loop on plain floats with the same float operations as
``StateSpace.interpolate``, ``FamilySystem.in_bounds`` and
:meth:`~planning_core.worlds.body_tests.BodyTest.free`, so the same samples come
out valid. Inside the body test's free disc a sample costs a few multiplications.
"""

from __future__ import annotations

import math
from typing import Any, Final, Sequence

from planning_core.angles import remainder
from planning_core.nearest.metric import SpaceMetric
from planning_core.worlds.body_tests import BodyTest
from planning_core.worlds.link_tests import sample_count

TAU: Final = 2.0 * math.pi


class BodyMotionCheck:
    """``first_hit`` of a body placed at the state (x, y, theta): x and y bounded,
    theta an angle; the sample count by the space's metric (the kd-tree's)."""

    def __init__(self, body: BodyTest, lows: Sequence[float], highs: Sequence[float],
                 metric: SpaceMetric, check: float, hit: Any):
        self.body = body
        self.x_low, self.y_low = float(lows[0]), float(lows[1])
        self.x_high, self.y_high = float(highs[0]), float(highs[1])
        """Closed bounds of x and y (infinite where the problem sets none)."""
        self.metric = metric
        self.check = check
        self.hit = hit
        """Called with the fraction of the first invalid sample (``MotionHit``)."""

    def in_bounds(self, x: float, y: float, theta: float) -> bool:
        """Finite, and x and y within their closed bounds (``FamilySystem.in_bounds``)."""
        return (x - x == 0.0 and self.x_low <= x <= self.x_high
                and y - y == 0.0 and self.y_low <= y <= self.y_high and theta - theta == 0.0)

    def first_invalid(self, a: Sequence[float], b: Sequence[float], n: int) -> int:
        """The first invalid one of the samples ``i / n``, ``i`` in 1..n, of the
        straight motion a -> b (theta the shorter way; the floats of
        ``StateSpace.interpolate``), or 0 when all are valid."""
        ax, ay, at, bx, by, bt = a[0], a[1], a[2], b[0], b[1], b[2]
        dx, dy, dt = bx - ax, by - ay, remainder(bt - at, TAU)
        body = self.body
        for i in range(1, n + 1):
            t = i / n
            if t < 0.5:
                x, y, theta = ax + t * dx, ay + t * dy, remainder(at + t * dt, TAU)
            else:
                u = 1.0 - t
                x, y, theta = bx - u * dx, by - u * dy, remainder(bt - u * dt, TAU)
            if not (self.in_bounds(x, y, theta) and body.free(x, y, theta)):
                return i
        return 0

    def first_hit(self, a: tuple[float, ...], b: tuple[float, ...]) -> Any:
        """``hit(i / n)`` for the first invalid sample ``i`` of a -> b, or None."""
        n = sample_count(self.metric.distance(a, b), self.check)
        i = self.first_invalid(a, b, n)
        return self.hit(i / n) if i != 0 else None
