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


@dataclass(frozen=True)
class PlanResult:
    """``trajectory`` and ``tree`` hold the rows of the output format (SPEC 2):
    point vehicle ``(x, y)`` and ``(x1, y1, x2, y2)``; spaceships six numbers."""

    status: PlanStatus
    trajectory: tuple[tuple[float, ...], ...]
    tree: tuple[tuple[float, ...], ...]
    stats: PlanStats
    message: str = ""

    @property
    def solved(self) -> bool:
        return self.status is PlanStatus.SOLVED
