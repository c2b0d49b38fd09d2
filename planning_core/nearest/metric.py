"""A space's metric as the planners' inner loops ask for it: the distance, the
kd-tree's box bound, interpolation and wrapping, over tuples of floats.

:class:`SpaceMetric` is the reference: the space's own methods (its readable
definitions) and the box bound written out as a loop over the metric's groups.
The registered systems' spaces have a generated subclass each
(``planning_core/generated_kernels.py``) whose unrolled methods do the same float
operations in the same order; ``planning_core.kernels.space_metric`` picks one.
Compiled (mypyc), a caller typed with this class makes direct calls.
"""

from __future__ import annotations

import math
from typing import Any, Final

TAU: Final = 2.0 * math.pi


class SpaceMetric:
    """The metric of ``space`` (a ``spaces.StateSpace``): :meth:`distance`,
    :meth:`interpolate` and :meth:`wrap` are the space's own; :meth:`bound` is a lower
    bound of the distance from a query to any point of a box."""

    def __init__(self, space: Any) -> None:
        self.space = space
        self.order: list[int] = []
        """The grouped axes, group after group."""
        self.ends: list[int] = []
        """Where each group's axes end in ``order``."""
        self.weights: list[float] = []
        self.single: list[bool] = []
        """One axis: the group's term is ``W * abs(gap)``, else ``W * sqrt(sum of squares)``."""
        for indices, weight in space.groups:
            self.order.extend(indices)
            self.ends.append(len(self.order))
            self.weights.append(float(weight))
            self.single.append(len(indices) == 1)
        self.angle: list[bool] = [v.angle for v in space.variables]

    def distance(self, a: tuple[float, ...], b: tuple[float, ...]) -> float:
        """The metric distance (``StateSpace.distance``)."""
        result: float = self.space.distance(a, b)
        return result

    def interpolate(self, a: tuple[float, ...], b: tuple[float, ...],
                    t: float) -> tuple[float, ...]:
        """The state a fraction ``t`` of the way (``StateSpace.interpolate``)."""
        result: tuple[float, ...] = self.space.interpolate(a, b, t)
        return result

    def wrap(self, state: tuple[float, ...]) -> tuple[float, ...]:
        """Angles wrapped to [-pi, pi] (``StateSpace.wrap``)."""
        result: tuple[float, ...] = self.space.wrap(state)
        return result

    def bound(self, q: tuple[float, ...], lo: list[float], hi: list[float],
              slack: float) -> float:
        """A lower bound of the distance from ``q`` (angles wrapped) to any point of the
        box ``[lo, hi]``: the distance's terms over the per-axis gaps to the box, an
        angle's the shorter way round less ``slack``, so rounding keeps it at most the
        distance of any point inside (``kdtree``'s module docstring)."""
        total = 0.0
        start = 0
        for g in range(len(self.ends)):
            end = self.ends[g]
            squares = 0.0
            gap = 0.0
            for j in range(start, end):
                i = self.order[j]
                gap = angle_gap(q[i], lo[i], hi[i], slack) if self.angle[i] else \
                    real_gap(q[i], lo[i], hi[i])
                squares += gap * gap
            if self.single[g]:
                total += self.weights[g] * abs(gap)
            else:
                total += self.weights[g] * math.sqrt(squares)
            start = end
        return total


def real_gap(v: float, lo: float, hi: float) -> float:
    """How far ``v`` lies outside ``[lo, hi]``."""
    if v < lo:
        return lo - v
    if v > hi:
        return v - hi
    return 0.0


def angle_gap(v: float, lo: float, hi: float, slack: float) -> float:
    """The shorter way round the circle from ``v`` to the arc ``[lo, hi]``, less ``slack``
    (0 inside it, and never below 0)."""
    if v < lo:
        gap = min(lo - v, v + TAU - hi)
    elif v > hi:
        gap = min(v - hi, lo + TAU - v)
    else:
        return 0.0
    return gap - slack if gap > slack else 0.0
