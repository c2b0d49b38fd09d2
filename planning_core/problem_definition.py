"""What a planner is asked for (OMPL's ProblemDefinition): a start state and a goal
region, apart from the SpaceInformation, which says how the system moves and where
it may be.

A goal is :class:`~planning_core.goal.GoalRegion` on a grid (a point and the 0.1
around it) or :class:`~planning_core.kinoplan.FamilyGoal` in the family (named state
variables under the metric); planners ask only what :class:`Goal` says, and the
space information of the goal's own substrate asks for the rest.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Protocol, Sequence

State = tuple[float, ...]


class Goal(Protocol):
    """A goal region."""

    tolerance: float
    """The largest :meth:`distance` of a state in the region (so ``distance - tolerance``
    is a lower bound on the distance to the region: informed sampling's cost-to-go)."""

    def distance(self, state: Sequence[float]) -> float:
        """How far ``state`` is from the goal (the grid: by position; the family: the
        goal's metric)."""

    def accepts(self, state: Sequence[float]) -> bool:
        """The validator's test: within the tolerance."""

    def reached(self, state: Sequence[float]) -> bool:
        """The planners' test: a hair inside the tolerance (``goal.PLANNER_MARGIN``)."""


@dataclass(frozen=True)
class Objective:
    """Keep improving the path's cost after the first solution (OMPL's optimization
    objective with its cost threshold): an optimizing planner stops when the cost is
    at most ``threshold`` or its time is up. The cost itself is the space
    information's (``motion_cost``, or ``distance`` for straight motions)."""

    threshold: float = 0.0
    """A cost good enough to stop at (0: none is, run until the time limit)."""

    def satisfied(self, cost: float) -> bool:
        return cost <= self.threshold


@dataclass(frozen=True)
class ProblemDefinition:
    """The start state and the goal region a planner is asked to join."""

    start: State
    """The first state of every path (the grid's ship: at rest)."""
    goal: Goal
    """The region a path's last state must reach."""
    objective: Optional[Objective] = None
    """None: the first solution is the answer; else keep improving it."""
