"""The grid's SpaceInformation: a course vehicle (point, spaceship, left-only
spaceship) on a ``.sw`` map, its goal region around a point.

Compiled (mypyc, ``planning_core.compiled``): the grid planners ask it several
times per iteration, so its methods are native calls into the compiled world.
:mod:`planning_core.space_information` says what a SpaceInformation is and
holds the kinoplan family's.
"""

from __future__ import annotations

import random
from typing import TYPE_CHECKING, Any, Optional, Sequence

from planning_core.goal import GoalRegion
from planning_core.interrupt import Stop
from planning_core.nearest.index import NearestIndex
from planning_core.problem import Problem
from planning_core.systems import load as load_system
from planning_core.worlds.grid import GridWorld, SegmentHit

if TYPE_CHECKING:  # for the annotation only: the quadtree is imported when a planner asks
    from planning_core.nearest.quadtree import QuadtreeNearest


class SpaceInformation:
    """A system moving in a world from a start toward a goal region."""

    def __init__(self, system: Any, world: GridWorld, start: tuple[float, ...],
                 goal: GoalRegion):
        self.system = system
        self.world = world
        self.start = start
        self.goal = goal
        self.duration: Optional[tuple[int, int]] = None
        """A kinoplan system's (KMIN, KMAX): planners choose how long a control is
        held. None here: a grid vehicle holds each control for one whole step."""
        self.printable = world.point_strictly_inside
        self.sample_control: Any = getattr(system, "sample_control", None)  # kinodynamic only

    @property
    def space(self) -> Any:
        """The system's state space within this world's bounds (spaces.StateSpace)."""
        return self.system.state_space(self.world.width, self.world.height)

    # -- states and motions ------------------------------------------------------
    def is_valid(self, state: Sequence[float]) -> bool:
        """The state's position is free (SPEC 1: in the map, not in a blocked cell)."""
        return self.world.point_free(state[0], state[1])

    def propagate_valid(self, state: Sequence[float], control: Any) -> Any:
        """Kinodynamic: where ``control`` leads from ``state`` if every slice is
        valid and the end prints strictly inside the map; else None."""
        end: Optional[tuple[float, ...]] = self.system.propagate_while(state, control,
                                                                       self.world)
        if end is None or not (end[0] > 0.0 and end[1] > 0.0):
            return None
        return end

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> SegmentHit | None:
        """Geometric: where the straight motion a -> b first meets an invalid
        state, checked exactly; None when it is free."""
        return self.world.first_blocked_cell_on_segment(a[0], a[1], b[0], b[1])

    # -- sampling ----------------------------------------------------------------
    def sample_target(self, rng: random.Random) -> tuple[float, float]:
        """A uniform position of the open map (blocked cells included)."""
        return self.world.sample_open_position(rng)

    def goal_target(self, rng: random.Random) -> tuple[float, float]:
        """The goal-biased target: the goal point, nudged inside the map when it lies
        on the left or bottom edge (a node there could not be printed). No ``rng``."""
        return self.world.printable_point(self.goal.point)

    # -- nearest and closeness: by position on the grid --------------------------
    def new_nearest(self) -> "PositionNearest":
        """An empty nearest-node index (a quadtree over the map, by position)."""
        return PositionNearest(self.world.width, self.world.height)

    @staticmethod
    def closeness(end: tuple[float, ...], target: tuple[float, ...]) -> float:
        """How far a steering end is from a target: squared position distance
        (products, not ``** 2``: compiled, a power is a generic call)."""
        dx, dy = end[0] - target[0], end[1] - target[1]
        return dx * dx + dy * dy

    def start_in_goal_controls(self) -> Optional[tuple]:
        """For a start already in the goal region: the path's controls, here none
        (plan_rows prints the system's ``rest_control``, SPEC 2)."""
        return ()

    # -- capabilities of the world (None where it has none) ------------------------
    def goal_certainly_unreachable(self, stop: Stop = None) -> bool:
        """True only when it is proved: a geometric system whose start and goal no
        chain of free cells joins. Kinodynamic systems are checked only at slice
        positions and may legally hop a thin wall, so for them it is never proved."""
        if self.system.kinodynamic:
            return False
        return self.world.certainly_disconnected(self.start, self.goal.point, stop)

    def distance_along_free_space(self, stop: Stop = None):
        """Position -> distance to the goal along free space, or None."""
        return self.world.distance_along_cells(stop)


class PositionNearest(NearestIndex):
    """The grid's nearest-node index: a quadtree over states' (x, y)."""

    def __init__(self, width: float, height: float):
        from planning_core.nearest.quadtree import QuadtreeNearest  # planners only: start-up
        self.index: QuadtreeNearest = QuadtreeNearest(width, height)

    def add(self, state: tuple[float, ...]) -> int:
        return self.index.add(state[0], state[1])

    def nearest(self, target: tuple[float, ...]) -> int:
        return self.index.nearest(target[0], target[1])


def grid_space_information(problem: Problem, system_name) -> SpaceInformation:
    """A ``.sw`` problem for the named system (``point``, ``spaceship``, ``left``;
    a :class:`~planning_core.vehicles.Vehicle` names one too)."""
    system = load_system(getattr(system_name, "value", system_name))
    return SpaceInformation(system, GridWorld(problem), system.start_state(*problem.start),
                            GoalRegion(problem.goal))
