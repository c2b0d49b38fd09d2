"""What every planner takes and returns."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from enum import Enum


class PlanStatus(Enum):
    SOLVED = "solved"
    TIME_LIMIT = "time limit reached"
    ITERATION_LIMIT = "iteration limit reached"
    UNREACHABLE = "goal unreachable"


@dataclass
class StopCondition:
    """Ends a search after ``time_limit`` seconds or ``max_iterations`` iterations.

    The clock starts when the condition is made.
    """

    time_limit: float = 30.0
    max_iterations: int = 10_000_000
    started: float = field(default_factory=time.perf_counter)

    @property
    def deadline(self) -> float:
        return self.started + self.time_limit

    def status(self, iterations: int) -> PlanStatus | None:
        """The limit that is reached, if any."""
        if iterations >= self.max_iterations:
            return PlanStatus.ITERATION_LIMIT
        if time.perf_counter() >= self.deadline:
            return PlanStatus.TIME_LIMIT
        return None


@dataclass(frozen=True)
class PlanStats:
    iterations: int
    tree_nodes: int
    planning_seconds: float


Edge = tuple  # (from_state, control or None, to_state)


@dataclass(frozen=True)
class PlanResult:
    """What a planner found, as states and controls; the output's rows are made
    from it in one place (:func:`planning_core.plan_rows.plan_rows`).

    ``path``: the states from the start to the state that reached the goal (empty
    when unsolved). ``path_controls``: for a kinodynamic system, the control that
    leads from ``path[i]`` to ``path[i + 1]``. ``edges``: the tree (or roadmap),
    ``(from_state, control, to_state)``, control None for geometric systems.
    """

    status: PlanStatus
    system: object
    path: tuple[tuple[float, ...], ...]
    path_controls: tuple[tuple[float, ...], ...]
    edges: tuple[Edge, ...]
    stats: PlanStats
    message: str = ""

    @property
    def solved(self) -> bool:
        return self.status is PlanStatus.SOLVED

    @property
    def trajectory(self) -> tuple[tuple[float, ...], ...]:
        """The output's trajectory rows (SPEC 2)."""
        from planning_core.plan_rows import trajectory_rows
        return trajectory_rows(self.system, self.path, self.path_controls)

    @property
    def tree(self) -> tuple[tuple[float, ...], ...]:
        """The output's tree rows (SPEC 2)."""
        from planning_core.plan_rows import tree_rows
        return tree_rows(self.system, self.edges)
