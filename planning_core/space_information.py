"""One object joining a system, a world and a goal region (OMPL's SpaceInformation).

Planners and the validator take it and ask it what they need: is a state valid,
where does a control lead while every slice stays valid, what is free between
two states, where to sample. What only some worlds can answer (distance along a
grid's free cells, the frontier of a tree, a proof that the goal is cut off) is
a capability: a method that answers None when the world does not offer it, so a
planner never branches on which vehicle it is planning for. A capability that
may walk every cell of a big map takes an optional ``stop`` and raises
:class:`~planning_core.interrupt.Interrupted` when it says the time is up.
"""

from __future__ import annotations

import random
from typing import Sequence

from planning_core.goal import GoalRegion
from planning_core.interrupt import Stop
from planning_core.problem import Problem
from planning_core.systems import load as load_system
from planning_core.worlds.grid import GridWorld, SegmentHit


class SpaceInformation:
    """A system moving in a world from a start toward a goal region."""

    def __init__(self, system, world: GridWorld, start: tuple[float, ...], goal: GoalRegion):
        self.system = system
        self.world = world
        self.start = start
        self.goal = goal
        # Bound once: these run in the planners' inner loops.
        self.position_free = world.point_free
        self.printable = world.point_strictly_inside

    @property
    def space(self):
        """The system's state space within this world's bounds (spaces.StateSpace)."""
        return self.system.state_space(self.world.width, self.world.height)

    # -- states and motions ------------------------------------------------------
    def is_valid(self, state: Sequence[float]) -> bool:
        """The state's position is free (SPEC 1: in the map, not in a blocked cell)."""
        return self.position_free(state[0], state[1])

    def propagate_valid(self, state, control):
        """Kinodynamic: where ``control`` leads from ``state`` if every slice is
        valid and the end prints strictly inside the map; else None."""
        end = self.system.propagate_while(state, control, self.position_free)
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

    def sample_control(self, rng: random.Random):
        return self.system.sample_control(rng)

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


def grid_space_information(problem: Problem, system_name) -> SpaceInformation:
    """A ``.sw`` problem for the named system (``point``, ``spaceship``, ``left``;
    a :class:`~planning_core.vehicles.Vehicle` names one too)."""
    system = load_system(getattr(system_name, "value", system_name))
    return SpaceInformation(system, GridWorld(problem), system.start_state(*problem.start),
                            GoalRegion(problem.goal))
