"""Informed sampling (Gammell, Srinivasa & Barfoot 2014, "Informed RRT*: Optimal
sampling-based path planning focused via direct sampling of an admissible
ellipsoidal heuristic", IROS): once a path of cost ``c`` is known, only states
whose :class:`SolutionHeuristic` (a lower bound on the cost of any path through
them) is at most ``c`` can improve it, and :class:`InformedSampler` draws states
uniformly from that informed set.

For path length in R^n with a single goal state the informed set is the prolate
hyperspheroid ``{x : |x - start| + |x - goal| <= c}``, drawn directly
(:class:`ProlateHyperspheroid`). Our goals are regions and some spaces have
angles, so the sampler draws from a superset and keeps a draw only when its
heuristic is at most ``c``, which makes it exactly uniform over the informed set:

- the superset is the hyperspheroid over the space's first Euclidean metric group
  (the point's x, y; rigid2's x, y), foci the start and the goal region's centre,
  its diameter ``c + tolerance`` less the least the other groups must add, divided
  by the group's weight; the other variables (rigid2's heading) uniform;
- where that hyperspheroid is larger than the group's box, where the space has no
  Euclidean group (arm2's torus of two angles) or the region has no centre (a goal
  that leaves variables free), the superset is the whole space: draws from the
  space information's uniform targets (OMPL's rejection sampling).

Plain Python floats (``./run.sh`` needs only the standard library).
"""

from __future__ import annotations

import math
import random
from typing import Any, Callable, Optional, Sequence

State = tuple[float, ...]

SAMPLE_ATTEMPTS = 100
"""Draws an informed sample may take before giving up (OMPL's default)."""
_SLACK = 1e-9
"""Relative widening of the superset: rounding in its bound may not cut the set."""


def unit_ball_measure(n: int) -> float:
    """The volume of the unit ball in R^n."""
    return math.pi ** (n / 2.0) / math.gamma(n / 2.0 + 1.0)


def unit_ball_point(rng: random.Random, n: int) -> list[float]:
    """A uniform point of the unit ball in R^n: a normal direction, radius U^(1/n)."""
    while True:
        direction = [rng.gauss(0.0, 1.0) for _ in range(n)]
        norm = math.sqrt(math.fsum(v * v for v in direction))
        if norm > 0.0:
            break
    radius = rng.random() ** (1.0 / n)
    return [v * radius / norm for v in direction]


class ProlateHyperspheroid:
    """``{x in R^n : |x - a| + |x - b| <= diameter}``: the ellipsoid with foci ``a``
    and ``b``, transverse diameter ``diameter`` (at least ``|b - a|``) along the line
    of the foci and ``sqrt(diameter^2 - |b - a|^2)`` across it."""

    def __init__(self, a: Sequence[float], b: Sequence[float]) -> None:
        self.a, self.b = tuple(a), tuple(b)
        self.n = len(self.a)
        self.centre = [(p + q) / 2.0 for p, q in zip(self.a, self.b)]
        self.focal_distance = math.dist(self.a, self.b)
        # The Householder reflection taking the first axis to the foci's direction
        # (the ellipsoid is symmetric about every plane through that line).
        self.reflector: Optional[list[float]] = None
        if self.focal_distance > 0.0:
            axis = [(q - p) / self.focal_distance for p, q in zip(self.a, self.b)]
            v = [(1.0 if i == 0 else 0.0) - axis[i] for i in range(self.n)]
            if math.fsum(x * x for x in v) > 1e-24:
                self.reflector = v

    def radii(self, diameter: float) -> tuple[float, float]:
        """The semi-axis along the foci's line and the one across it."""
        return diameter / 2.0, math.sqrt(max(0.0, diameter ** 2 - self.focal_distance ** 2)) / 2.0

    def measure(self, diameter: float) -> float:
        """The ellipsoid's volume."""
        along, across = self.radii(diameter)
        return unit_ball_measure(self.n) * along * across ** (self.n - 1)

    def contains(self, x: Sequence[float], diameter: float) -> bool:
        return math.dist(x, self.a) + math.dist(x, self.b) <= diameter

    def sample(self, rng: random.Random, diameter: float) -> list[float]:
        """A uniform point of the ellipsoid: the unit ball scaled by the radii,
        reflected onto the foci's line, moved to the centre."""
        along, across = self.radii(diameter)
        y = unit_ball_point(rng, self.n)
        y = [y[0] * along] + [v * across for v in y[1:]]
        v = self.reflector
        if v is not None:
            scale = 2.0 * math.fsum(p * q for p, q in zip(v, y)) / math.fsum(p * p for p in v)
            y = [p - scale * q for p, q in zip(y, v)]
        return [c + p for c, p in zip(self.centre, y)]


class SolutionHeuristic:
    """``h(x) = distance(start, x) + max(0, goal.distance(x) - goal.tolerance)``: no
    path from the start through ``x`` to the goal region costs less (each motion's
    cost is the distance, and a state of the region is within the tolerance of the
    goal's own measure, which the distance is never below)."""

    def __init__(self, si: Any, pdef: Any) -> None:
        self.distance: Callable[[Any, Any], float] = si.distance
        self.start = pdef.start
        self.goal_distance: Callable[[Any], float] = pdef.goal.distance
        self.tolerance: float = pdef.goal.tolerance

    def __call__(self, state: Sequence[float]) -> float:
        to_go = self.goal_distance(state) - self.tolerance
        return self.distance(self.start, state) + (to_go if to_go > 0.0 else 0.0)


class InformedSampler:
    """Uniform states of ``{x : h(x) <= cost}`` (module docstring); before any
    solution (``cost`` infinite), the space information's uniform targets."""

    def __init__(self, si: Any, pdef: Any, rng: random.Random,
                 attempts: int = SAMPLE_ATTEMPTS) -> None:
        self.heuristic = SolutionHeuristic(si, pdef)
        self.rng, self.attempts = rng, attempts
        self.uniform: Callable[[random.Random], State] = si.sample_target
        space, centre = si.space, si.goal_center(pdef.goal)
        group = euclidean_group(space)
        self.indices: tuple[int, ...] = ()
        if group is not None and centre is not None:
            indices, self.weight = group
            self.indices = indices
            start = pdef.start
            self.spheroid = ProlateHyperspheroid([start[i] for i in indices],
                                                 [centre[i] for i in indices])
            # The least the other groups add along any path: their part of the
            # start-to-centre distance (the triangle inequality, group by group).
            other = space.distance(start, centre) - self.weight * self.spheroid.focal_distance
            self.rest = max(0.0, other) * (1.0 - _SLACK)
            self.tolerance = pdef.goal.tolerance
            variables = space.variables
            self.box = [(variables[i].low, variables[i].high) for i in indices]
            self.box_measure = math.prod(high - low for low, high in self.box)

    def sample(self, cost: float) -> Optional[State]:
        """A uniform state with ``h <= cost``, or None after ``attempts`` draws."""
        if not math.isfinite(cost):
            return self.uniform(self.rng)
        draw = self.uniform
        if self.indices:
            diameter = (cost + self.tolerance - self.rest) / self.weight * (1.0 + _SLACK)
            if self.spheroid.measure(diameter) < self.box_measure:
                draw = self._spheroid_draw(diameter)
        heuristic, rng = self.heuristic, self.rng
        for _ in range(self.attempts):
            state = draw(rng)
            if state is not None and heuristic(state) <= cost:
                return state
        return None

    def _spheroid_draw(self, diameter: float) -> Callable[[random.Random], Optional[State]]:
        """``draw(rng)``: a uniform state with the Euclidean group's part drawn from
        the hyperspheroid of ``diameter`` (None when that part leaves the box)."""
        uniform, spheroid, indices, box = self.uniform, self.spheroid, self.indices, self.box

        def draw(rng: random.Random) -> Optional[State]:
            state = list(uniform(rng))
            point = spheroid.sample(rng, diameter)
            for i, value, (low, high) in zip(indices, point, box):
                if not low < value < high:
                    return None
                state[i] = value
            return tuple(state)
        return draw


def euclidean_group(space: Any) -> Optional[tuple[tuple[int, ...], float]]:
    """The first metric group of bounded non-angle variables with a positive weight:
    its indices and weight, or None."""
    variables = space.variables
    for indices, weight in space.groups:
        if weight > 0.0 and all(not variables[i].angle and math.isfinite(variables[i].low)
                                and math.isfinite(variables[i].high) for i in indices):
            return tuple(indices), weight
    return None
