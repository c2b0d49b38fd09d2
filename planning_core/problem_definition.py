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
from typing import Protocol, Sequence

State = tuple[float, ...]


class Goal(Protocol):
    """A goal region."""

    def distance(self, state: Sequence[float]) -> float:
        """How far ``state`` is from the goal (the grid: by position; the family: the
        goal's metric)."""

    def accepts(self, state: Sequence[float]) -> bool:
        """The validator's test: within the tolerance."""

    def reached(self, state: Sequence[float]) -> bool:
        """The planners' test: a hair inside the tolerance (``goal.PLANNER_MARGIN``)."""


@dataclass(frozen=True)
class ProblemDefinition:
    """The start state and the goal region a planner is asked to join."""

    start: State
    """The first state of every path (the grid's ship: at rest)."""
    goal: Goal
    """The region a path's last state must reach."""
