"""The two-link arm's validity test, motion reach and motion check, on plain floats.

:class:`LinkTests` binds the arm (base, link lengths), its bounds and a world's
:class:`~planning_core.worlds.segment_tests.SegmentTests` once, so that the arm's
hot path (is a configuration valid? how many samples of a straight motion are
surely valid? where does a motion first fail?) runs as native calls in the
compiled build (mypyc, ``rrt_startup.compiled``), the joints computed once per
sample. :func:`joints` is the single copy of the arm's forward kinematics
(``Arm2.joints`` calls it).
"""

from __future__ import annotations

import math
from typing import Any, Final, Sequence

from planning_core.angles import remainder
from planning_core.nearest.metric import SpaceMetric
from planning_core.worlds.body_tests import SNAP
from planning_core.worlds.segment_tests import SegmentTests

TAU: Final = 2.0 * math.pi
REACH_WORTH: Final = 3
"""A clearance that skips fewer samples than this is not worth its cost here..."""
REACH_PAUSE: Final = 4
"""...so the next this many samples are tested one by one before another is taken."""
MOST: Final = 1e9
"""The most samples one reach skips."""


def cos_sin(angle: float) -> tuple[float, float]:
    """``(cos, sin)`` of the angle, each 0 below ``SNAP`` in magnitude (quarter turns exact)."""
    c, s = math.cos(angle), math.sin(angle)
    return (0.0 if abs(c) < SNAP else c), (0.0 if abs(s) < SNAP else s)


def joints(base_x: float, base_y: float, l1: float, l2: float,
           theta1: float, theta2: float) -> tuple[float, float, float, float]:
    """The elbow's and the tip's positions ``(ex, ey, tx, ty)``: ``elbow = base +
    l1 (cos t1, sin t1)``, ``tip = elbow + l2 (cos(t1 + t2), sin(t1 + t2))``."""
    c1, s1 = cos_sin(theta1)
    c12, s12 = cos_sin(theta1 + theta2)
    ex, ey = base_x + l1 * c1, base_y + l1 * s1
    return ex, ey, ex + l2 * c12, ey + l2 * s12


class LinkTests:
    """The arm's two links in a world: :meth:`valid` is the state validator,
    :meth:`reach` the motion reach (``planning_core.kinoplan``), :meth:`first_invalid`
    the arm's motion check (``GeometricSpaceInformation.first_hit``)."""

    def __init__(self, segments: SegmentTests, base_x: float, base_y: float, l1: float,
                 l2: float, lows: Sequence[float], highs: Sequence[float], margin: float):
        self.segments = segments
        self.base_x, self.base_y = base_x, base_y
        self.l1, self.l2 = l1, l2
        self.lo0, self.lo1 = float(lows[0]), float(lows[1])
        self.hi0, self.hi1 = float(highs[0]), float(highs[1])
        """Closed bounds per state variable (an angle's: infinite)."""
        self.margin = margin
        """Kept off every link's clearance: far above rounding."""

    def valid(self, state: Sequence[float]) -> bool:
        """Two finite values within their bounds, and both links in the box and off
        every obstacle."""
        if len(state) != 2:
            return False
        theta1, theta2 = state[0], state[1]
        if not self.in_bounds(theta1, theta2):
            return False
        ex, ey, tx, ty = joints(self.base_x, self.base_y, self.l1, self.l2, theta1, theta2)
        return self.links_free(ex, ey, tx, ty)

    def in_bounds(self, theta1: float, theta2: float) -> bool:
        """Finite and within the closed bounds."""
        return (theta1 - theta1 == 0.0 and self.lo0 <= theta1 <= self.hi0
                and theta2 - theta2 == 0.0 and self.lo1 <= theta2 <= self.hi1)

    def links_free(self, ex: float, ey: float, tx: float, ty: float) -> bool:
        """Base -> elbow, then elbow -> tip, in the box and off every obstacle."""
        segments = self.segments
        return (segments.free(self.base_x, self.base_y, ex, ey)
                and segments.free(ex, ey, tx, ty))

    def reach(self, state: Sequence[float], step: Sequence[float]) -> int:
        """Given a valid ``state``, how many of the next samples of a straight
        motion, each ``step`` (per angle, unwrapped) further on, are surely valid.

        Link 1 moves at most ``l1 |d theta1|`` per step, link 2 at most that plus
        ``l2 |d theta1 + d theta2|`` (a chord is no longer than its arc): samples
        that stay within each link's clearance (less the margin) pass the exact test."""
        ex, ey, tx, ty = joints(self.base_x, self.base_y, self.l1, self.l2, state[0], state[1])
        move1 = self.l1 * abs(step[0])
        return self.reach_at(ex, ey, tx, ty, move1, move1 + self.l2 * abs(step[0] + step[1]))

    def reach_at(self, ex: float, ey: float, tx: float, ty: float, move1: float,
                 move2: float) -> int:
        """:meth:`reach` from the joints and each link's move per step."""
        margin, segments = self.margin, self.segments
        most = MOST
        if move2 > 0.0:  # link 2 first: it moves more, and caps link 1's search
            most = (segments.gap(ex, ey, tx, ty, margin + most * move2) - margin) / move2
        if move1 > 0.0:
            gap = segments.gap(self.base_x, self.base_y, ex, ey, margin + most * move1)
            most = min(most, (gap - margin) / move1)
        return int(max(0.0, min(most, MOST)))

    def first_invalid(self, a: Sequence[float], b: Sequence[float], n: int) -> int:
        """The first invalid one of the samples ``i / n``, ``i`` in 1..n, of the
        straight motion a -> b (angles the shorter way; the floats of
        ``StateSpace.interpolate``), or 0 when all are valid. After a valid sample,
        those its :meth:`reach` proves valid are skipped (the same answer as
        testing each); near an obstacle, where a reach skips little, the next
        ``REACH_PAUSE`` are tested plainly before another is taken."""
        a0, a1, b0, b1 = a[0], a[1], b[0], b[1]
        d0, d1 = remainder(b0 - a0, TAU), remainder(b1 - a1, TAU)
        step0, step1 = d0 / n, d1 / n
        move1 = self.l1 * abs(step0)
        move2 = move1 + self.l2 * abs(step0 + step1)
        i, wait = 1, 0
        while i <= n:
            t = i / n
            if t < 0.5:
                q0, q1 = remainder(a0 + t * d0, TAU), remainder(a1 + t * d1, TAU)
            else:
                q0, q1 = remainder(b0 - (1.0 - t) * d0, TAU), remainder(b1 - (1.0 - t) * d1, TAU)
            if not self.in_bounds(q0, q1):
                return i
            ex, ey, tx, ty = joints(self.base_x, self.base_y, self.l1, self.l2, q0, q1)
            if not self.links_free(ex, ey, tx, ty):
                return i
            if wait > 0 or i == n:
                i, wait = i + 1, wait - 1
                continue
            skip = self.reach_at(ex, ey, tx, ty, move1, move2)
            i, wait = i + 1 + skip, (REACH_PAUSE if skip < REACH_WORTH else 0)
        return 0


def sample_count(distance: float, check: float) -> int:
    """``n``: a motion this long is checked at ``n + 1`` samples, ends included
    (SPEC 5.2's ``max(1, ceil(d / check))``)."""
    return max(1, math.ceil(distance / check))


class MotionCheck:
    """The arm's ``first_hit`` in one native call: the motion's sample count by the
    space's metric (the kd-tree's), then :meth:`LinkTests.first_invalid`."""

    def __init__(self, links: LinkTests, metric: SpaceMetric, check: float, hit: Any):
        self.links = links
        self.metric = metric
        self.check = check
        self.hit = hit
        """Called with the fraction of the first invalid sample (``MotionHit``)."""

    def first_hit(self, a: tuple[float, ...], b: tuple[float, ...]) -> Any:
        """``hit(i / n)`` for the first invalid sample ``i`` of a -> b, or None."""
        n = sample_count(self.metric.distance(a, b), self.check)
        i = self.links.first_invalid(a, b, n)
        return self.hit(i / n) if i != 0 else None
