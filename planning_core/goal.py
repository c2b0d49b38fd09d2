"""The goal region: a point and the tolerance around it, defined once.

SPEC 2: a state reaches the goal when its position is within 0.1 of the goal
point. The validator accepts ``distance <= 0.1`` (:meth:`GoalRegion.accepts`);
planners stop only at ``0.1 * (1 - 1e-9)`` (:meth:`GoalRegion.reached`), so that
no checker's rounding puts one of their answers at 0.1000000001.
"""

from __future__ import annotations

import math

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only (no run imports typing); the metric where a family goal is made
    from collections.abc import Sequence
    from typing import Final

    from planning_core.nearest.metric import SpaceMetric

GOAL_TOLERANCE: Final = 0.1
PLANNER_MARGIN: Final = 1e-9


class GoalRegion:
    """The goal point and the tolerance around it (a plain class, not a dataclass,
    as every record on the planner's start-up path)."""

    point: tuple[float, float]
    """The goal position (x, y)."""
    tolerance: float
    """Largest accepted distance of a state's position from ``point``."""

    def __init__(self, point: tuple[float, float], tolerance: float = GOAL_TOLERANCE) -> None:
        self.point = point
        self.tolerance = tolerance

    def __repr__(self) -> str:
        return f"GoalRegion({self.point!r}, {self.tolerance!r})"

    def distance(self, state: Sequence[float]) -> float:
        return math.hypot(state[0] - self.point[0], state[1] - self.point[1])

    def accepts(self, state: Sequence[float]) -> bool:
        """The validator's test: within the tolerance."""
        return self.distance(state) <= self.tolerance

    def reached(self, state: Sequence[float]) -> bool:
        """The planners' test, a hair inside the tolerance (squared, no sqrt)."""
        dx, dy = state[0] - self.point[0], state[1] - self.point[1]
        tolerance = self.tolerance
        return dx * dx + dy * dy <= tolerance * tolerance * (1 - PLANNER_MARGIN)


class MetricGoalTest:
    """A family goal's planner-side questions, native calls in the compiled build:
    the distance from a state to the goal's ``target`` under the goal's metric (a
    kd-tree metric, the same floats as the space's distance) and :meth:`reached`, a
    hair inside ``tolerance`` as :meth:`GoalRegion.reached` (``kinoplan.FamilyGoal``
    binds these two to itself)."""

    def __init__(self, metric: SpaceMetric, target: tuple[float, ...], tolerance: float) -> None:
        self.metric = metric
        self.target = target
        self.within = tolerance * (1 - PLANNER_MARGIN)

    def distance(self, state: Sequence[float]) -> float:
        return self.metric.distance(tuple(state), self.target)

    def reached(self, state: Sequence[float]) -> bool:
        return self.metric.distance(tuple(state), self.target) <= self.within
