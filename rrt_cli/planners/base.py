"""What every planner takes and returns."""

from __future__ import annotations

import functools
import time
from enum import Enum

from planning_core.interrupt import Interrupted

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Optional


class PlanStatus(Enum):
    SOLVED = "solved"
    TIME_LIMIT = "time limit reached"
    ITERATION_LIMIT = "iteration limit reached"
    UNREACHABLE = "goal unreachable"
    OUT_OF_MEMORY = "out of memory"


class StopCondition:
    """Ends a search after ``time_limit`` seconds or ``max_iterations`` iterations.

    The clock starts when the condition is made (``started``), and covers the
    planner's set-up too: long set-up loops ask :meth:`time_is_up` (the iteration
    limit counts search iterations only, so ``-iterations N`` stays reproducible).
    """

    def __init__(self, time_limit: float = 30.0, max_iterations: int = 10_000_000) -> None:
        self.time_limit = time_limit
        self.max_iterations = max_iterations
        self.started = time.perf_counter()

    def __repr__(self) -> str:
        return (f"StopCondition(time_limit={self.time_limit!r}, "
                f"max_iterations={self.max_iterations!r})")

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

    def time_is_up(self) -> bool:
        """The ``stop`` a world's long computation takes (planning_core.interrupt)."""
        return time.perf_counter() >= self.deadline


class PlanStats:
    """What a planning run did: iterations, tree size, time (for -stats). A plain
    class, not a dataclass, as every record on the planner's start-up path."""

    iterations: int
    tree_nodes: int
    planning_seconds: float
    first_solution_seconds: Optional[float]
    """When the first solution was found (None: none, or the planner stops at its first:
    then it is ``planning_seconds``)."""
    improvements: tuple[tuple[float, float], ...]
    """An optimizing planner's ``(seconds, cost)`` at each better solution (the
    benchmarks' cost against time)."""

    def __init__(self, iterations: int, tree_nodes: int, planning_seconds: float,
                 first_solution_seconds: Optional[float] = None,
                 improvements: tuple[tuple[float, float], ...] = ()) -> None:
        self.iterations = iterations
        self.tree_nodes = tree_nodes
        self.planning_seconds = planning_seconds
        self.first_solution_seconds = first_solution_seconds
        self.improvements = improvements

    def __repr__(self) -> str:
        return (f"PlanStats({self.iterations!r}, {self.tree_nodes!r}, "
                f"{self.planning_seconds!r}, {self.first_solution_seconds!r}, "
                f"{self.improvements!r})")


Edge = tuple  # (from_state, control or None, to_state)


class PlanResult:
    """What a planner found, as states and controls; the output's rows are made
    from it in one place (:func:`planning_core.plan_rows.plan_rows`).

    ``path``: the states from the start to the state that reached the goal (empty
    when unsolved). ``path_controls``: for a kinodynamic system, the control that
    leads from ``path[i]`` to ``path[i + 1]``. ``edges``: the tree (or roadmap),
    ``(from_state, control, to_state)``, control None for geometric systems.
    """

    def __init__(self, status: PlanStatus, system: Any, path: tuple[tuple[float, ...], ...],
                 path_controls: tuple[tuple[float, ...], ...], edges: tuple[Edge, ...],
                 stats: PlanStats, message: str = "") -> None:
        self.status = status
        self.system = system
        self.path = path
        self.path_controls = path_controls
        self.edges = edges
        self.stats = stats
        self.message = message

    def with_path(self, path: tuple[tuple[float, ...], ...],
                  path_controls: tuple[tuple[float, ...], ...] = ()) -> PlanResult:
        """The same result with another path (a smoothed one; the start's own)."""
        return PlanResult(self.status, self.system, path, path_controls, self.edges,
                          self.stats, self.message)

    def __repr__(self) -> str:
        return (f"PlanResult({self.status!r}, {self.system!r}, path of {len(self.path)}, "
                f"{len(self.edges)} edges, {self.stats!r}, {self.message!r})")

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


SETUP_CUT_SHORT = "during set-up"
OUT_OF_MEMORY_MESSAGE = "the run needs more memory than it may have"


def guarded(solve):
    """A planner's ``solve`` that ends as a result, never as a traceback, when a
    world's set-up is cut short by the time limit (:class:`Interrupted`:
    TIME_LIMIT) or memory runs out (OUT_OF_MEMORY). Either result has no path
    and no edges, 0 iterations and nodes, and the seconds since ``stop`` began."""

    @functools.wraps(solve)
    def run(si, pdef, stop: StopCondition, rng, *params, **named) -> PlanResult:
        try:
            return solve(si, pdef, stop, rng, *params, **named)
        except Interrupted:
            status, message = PlanStatus.TIME_LIMIT, SETUP_CUT_SHORT
        except MemoryError:
            # What failed to fit was the call's: it is gone now, and this is small.
            status, message = PlanStatus.OUT_OF_MEMORY, OUT_OF_MEMORY_MESSAGE
        stats = PlanStats(0, 0, time.perf_counter() - stop.started)
        return PlanResult(status, si.system, (), (), (), stats, message)

    return run
