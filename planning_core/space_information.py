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
from typing import Any, Optional, Sequence

from planning_core.goal import GoalRegion
from planning_core.interrupt import Stop
from planning_core.problem import Problem
from planning_core.systems import load as load_system
from planning_core.worlds.grid import GridWorld, SegmentHit

AnySpaceInformation = Any
"""What planners annotate ``si`` with: any SpaceInformation (grid, kinoplan, geometric),
not a class, so a compiled planner (planning_core.compiled) checks none at run time."""


class SpaceInformation:
    """A system moving in a world from a start toward a goal region."""

    duration = None
    """A kinoplan system's (KMIN, KMAX): planners choose how long a control is held.
    None here: a grid vehicle holds each control for one whole step."""

    def __init__(self, system, world: GridWorld, start: tuple[float, ...], goal: GoalRegion):
        self.system = system
        self.world = world
        self.start = start
        self.goal = goal
        # Bound once: these run in the planners' inner loops.
        self.position_free = world.point_free
        self.printable = world.point_strictly_inside
        self.sample_control = getattr(system, "sample_control", None)  # kinodynamic only

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
        end = self.system.propagate_while(state, control, self.world)
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
    def closeness(end: Sequence[float], target: Sequence[float]) -> float:
        """How far a steering end is from a target: squared position distance."""
        return (end[0] - target[0]) ** 2 + (end[1] - target[1]) ** 2

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


class PositionNearest:
    """The grid's nearest-node index: a quadtree over states' (x, y)."""

    def __init__(self, width: float, height: float):
        from planning_core.nearest.quadtree import QuadtreeNearest
        self.index = QuadtreeNearest(width, height)
        self._add, self._nearest = self.index.add, self.index.nearest

    def add(self, state: Sequence[float]) -> int:
        return self._add(state[0], state[1])

    def nearest(self, target: Sequence[float]) -> int:
        return self._nearest(target[0], target[1])


def grid_space_information(problem: Problem, system_name) -> SpaceInformation:
    """A ``.sw`` problem for the named system (``point``, ``spaceship``, ``left``;
    a :class:`~planning_core.vehicles.Vehicle` names one too)."""
    system = load_system(getattr(system_name, "value", system_name))
    return SpaceInformation(system, GridWorld(problem), system.start_state(*problem.start),
                            GoalRegion(problem.goal))


class KinoplanSpaceInformation:
    """A ``kinoplan 1`` system (SPEC 5) in its continuous world: the same questions
    as :class:`SpaceInformation`, answered over full states and the problem's metric.

    Valid: the problem's state validator (bounds, body in the box, off every
    obstacle); no printability test (the bounds are part of validity). Targets
    are uniform states of the system's space; nearest and closeness are by the
    metric (an exact kd-tree)."""

    def __init__(self, problem):
        from planning_core.kinoplan import body_test, state_validator
        self.problem = problem
        self.system = system = problem.system
        self.world = problem.world
        self.start = problem.start
        self.goal = problem.goal
        self.space = system.space
        self.is_valid = state_validator(system, self.world)
        self.closeness = self.space.distance
        self._sample = self.space.sample_uniform
        self.duration = (system.kmin, system.kmax) if system.kinodynamic else None
        if system.kinodynamic:
            # The validity test fused into the integration loop (the hot path).
            self.advance = system.advancer(body_test(system, self.world))
            self.propagate_valid = self._propagate_valid_by(self.advance)

    def propagate_valid(self, state, control):
        """Where ``control`` leads from ``state`` if every slice is valid; else None.
        (Each kinodynamic instance shadows this with the fused version.)"""
        return self.system.propagate_while(state, control, self.is_valid)

    @staticmethod
    def _propagate_valid_by(advance):
        def propagate_valid(state, control):
            k = control[-1]
            end, done = advance(state, control, k)
            return end if done == k else None
        return propagate_valid

    def random_motion(self, state, rng: random.Random):
        """``(end, control)``: random held values for a random K in [KMIN, KMAX]
        (``rng``: the values, then K), cut at the first invalid slice, K then the
        slices done (OMPL's propagateWhileValid); None when fewer than KMIN were valid."""
        system = self.system
        values = system.sample_values(rng)
        kmin, kmax = self.duration
        end, k = self.advance(state, values, rng.randint(kmin, kmax))
        return (end, (*values, k)) if k >= kmin else None

    def advance(self, state, control, kmax: int):
        """``(state, k)``: ``control``'s held values applied for up to ``kmax``
        slices, stopped before the first invalid one; the last valid state and
        how many slices led to it (each kinodynamic instance shadows this)."""
        raise ValueError(f"{self.system.name} is not kinodynamic")

    def sample_target(self, rng: random.Random) -> tuple[float, ...]:
        """A uniform state of the system's space (valid or not)."""
        return self._sample(rng)

    def sample_control(self, rng: random.Random):
        return self.system.sample_control(rng)

    def goal_target(self, rng: random.Random) -> tuple[float, ...]:
        """The goal's values; the variables it does not name from a uniform sample
        (one draw per variable; none when the goal names every variable)."""
        if self.goal.full:
            return self.goal.target
        return self.goal.complete(self._sample(rng))

    def new_nearest(self):
        """An empty nearest-node index over full states (kd-tree, the metric; leaves
        of 16 answered the family's queries fastest, docs/planners-family.md)."""
        from planning_core.nearest.kdtree import KDTree
        return KDTree(self.space, leaf_capacity=16)

    def start_in_goal_controls(self) -> Optional[tuple]:
        """For a start already in the goal region: one held control, each value 0
        clamped into its bounds, for KMIN slices, when every slice is valid and the
        end is still in the goal region; else None (then plan as usual)."""
        system = self.system
        if not system.kinodynamic:
            return ()
        control = tuple(min(max(0.0, lo), hi) for lo, hi in system.controls) + (system.kmin,)
        end = self.propagate_valid(self.start, control)
        return (control,) if end is not None and self.goal.reached(end) else None

    def invalid_reason(self, state: Sequence[float]) -> Optional[str]:
        """Why ``state`` is not valid (a bound, the box, which obstacle), or None."""
        from planning_core.kinoplan import invalid_reason
        return invalid_reason(self.system, self.world, state, self.problem.obstacle_lines)

    def goal_certainly_unreachable(self, stop: Stop = None) -> bool:
        return False

    def distance_along_free_space(self, stop: Stop = None):
        return None


def kinoplan_space_information(problem) -> KinoplanSpaceInformation:
    """The SpaceInformation of a :class:`~planning_core.kinoplan.KinoplanProblem`
    (a geometric system's: :mod:`planning_core.geometric_space_information`)."""
    if not problem.system.kinodynamic:
        from planning_core.geometric_space_information import GeometricSpaceInformation
        return GeometricSpaceInformation(problem)
    return KinoplanSpaceInformation(problem)
