"""What a planner is asked for (OMPL's ProblemDefinition): a start state and a goal
region, apart from the SpaceInformation, which says how the system moves and where
it may be.

A goal is :class:`~planning_core.goal.GoalRegion` on a grid (a point and the 0.1
around it) or :class:`~planning_core.kinoplan.FamilyGoal` in the family (named state
variables under the metric); planners ask only what
:class:`~planning_core.space_information.Goal` says, and the space information of
the goal's own substrate asks for the rest. Plain classes, not dataclasses, as every
record on the planner's start-up path (docs/setup-and-startup.md).
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Optional

    from planning_core.space_information import Goal

State = tuple[float, ...]


class Objective:
    """Keep improving the path's cost after the first solution (OMPL's optimization
    objective with its cost threshold): an optimizing planner stops when the cost is
    at most ``threshold`` or its time is up. The cost itself is the space
    information's (``motion_cost``, or ``distance`` for straight motions)."""

    threshold: float
    """A cost good enough to stop at (0: none is, run until the time limit)."""

    def __init__(self, threshold: float = 0.0) -> None:
        self.threshold = threshold

    def __repr__(self) -> str:
        return f"Objective({self.threshold!r})"

    def satisfied(self, cost: float) -> bool:
        return cost <= self.threshold


class ProblemDefinition:
    """The start state and the goal region a planner is asked to join."""

    start: State
    """The first state of every path (the grid's ship: at rest)."""
    goal: Goal
    """The region a path's last state must reach."""
    objective: Optional[Objective]
    """None: the first solution is the answer; else keep improving it."""

    def __init__(self, start: State, goal: Goal, objective: Optional[Objective] = None) -> None:
        self.start = start
        self.goal = goal
        self.objective = objective

    def __repr__(self) -> str:
        return f"ProblemDefinition({self.start!r}, {self.goal!r}, {self.objective!r})"

    def with_objective(self, objective: Optional[Objective]) -> ProblemDefinition:
        """The same start and goal, asked to optimize (or not)."""
        return ProblemDefinition(self.start, self.goal, objective)
