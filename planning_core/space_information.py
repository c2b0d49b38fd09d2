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

from planning_core.grid_space_information import (  # noqa: F401 - the grid's, re-exported
    PositionNearest,
    SpaceInformation,
    grid_space_information,
)
from planning_core.interrupt import Stop
from planning_core.samplers import MotionSampler

AnySpaceInformation = Any
"""What planners annotate ``si`` with: any SpaceInformation (grid, kinoplan, geometric),
not a class, so a compiled planner (planning_core.compiled) checks none at run time."""


class KinoplanSpaceInformation:
    """A ``kinoplan 1`` system (SPEC 5) in its continuous world: the same questions
    as :class:`SpaceInformation`, answered over full states and the problem's metric.

    Valid: the problem's state validator (bounds, body in the box, off every
    obstacle); no printability test (the bounds are part of validity). Targets
    are uniform states of the system's space; nearest and closeness are by the
    metric (an exact kd-tree)."""

    def __init__(self, problem):
        from planning_core.kinoplan import body_tester, state_validator
        from planning_core.nearest.kdtree import space_metric
        self.problem = problem
        self.system = system = problem.system
        self.world = problem.world
        self.start = problem.start
        self.goal = problem.goal
        self.space = system.space
        self.is_valid = state_validator(system, self.world)
        # The metric as the kd-tree measures (compiled: a native call, the same floats).
        self.closeness = space_metric(self.space).distance
        self._sample = self.space.sample_uniform
        self.duration = (system.kmin, system.kmax) if system.kinodynamic else None
        self.sample_target = self._sample  # the method below, bound (the hot path)
        if system.kinodynamic:
            # The validity test fused into the integration loop (the hot path; the
            # generated class's methods, native calls in the compiled build).
            fused = system.advancer(body_tester(system, self.world))
            self.advance = fused.advance
            self.propagate_valid = fused.propagate_valid
            self.sample_control = system.sample_control
            # KPIECE1's random motion (samplers.MotionSampler: the draws, then the slices).
            self.random_motion = MotionSampler(system.control_sampler, fused.advance).sample

    def propagate_valid(self, state, control):
        """Where ``control`` leads from ``state`` if every slice is valid; else None.
        (Each kinodynamic instance shadows this with the fused version.)"""
        return self.system.propagate_while(state, control, self.is_valid)

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
        of 24: RG-RRT's inserts cheapest, RRT's queries as fast as with 16,
        docs/planners-family.md)."""
        from planning_core.nearest.kdtree import KDTree
        return KDTree(self.space, leaf_capacity=24)

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
