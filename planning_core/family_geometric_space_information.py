"""The SpaceInformation of a geometric ``kinoplan 1`` system (arm2, rigid2; SPEC 5.2).

Straight motions in configuration space, checked at the system's ``check``
resolution exactly as the validator checks them (``motion_samples``: ``n + 1``
equally spaced samples, in the direction travelled), nearest neighbours by the
metric in a kd-tree (angles wrapping), and the goal as a configuration. It
answers the questions the straight-line planners (RRT, RRT-Connect, PRM, PRM*,
the smoother) ask of a geometric SpaceInformation
(:class:`~planning_core.space_information.GeometricSpaceInformation`); what only a
grid has (a free-cell list, a frontier, a proof of disconnection) it answers its
own way or with None.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

from planning_core.family_space_information import FamilySpaceInformation
from planning_core.interrupt import Stop
from planning_core.kinoplan import body_tester, link_tests
from planning_core.kernels import mode as _mode
from planning_core.worlds.body_motion import BodyMotionCheck
from planning_core.worlds.link_tests import MotionCheck, sample_count

State = tuple[float, ...]

VALID_SAMPLE_ATTEMPTS = 10_000
"""Rejection sampling of a valid configuration gives up after this many draws."""
BRIDGE_SHARE = 0.5
"""Share of a roadmap's samples drawn by the bridge test (the rest uniform valid)."""
BRIDGE_ATTEMPTS = 100
"""A bridge-test draw falls back to a uniform valid one after this many tries (OMPL's default)."""
BRIDGE_STEPS = 10
"""The bridge's second end lies a Gaussian of this many check steps from the first, per variable."""


@dataclass(frozen=True)
class MotionHit:
    """Where a straight motion first meets an invalid sample."""

    fraction: float
    """Of the motion's length, in (0, 1]: the first invalid sample is ``i / n``."""


class FamilyGeometricSpaceInformation(FamilySpaceInformation):
    """A geometric family system in its continuous world, for straight-line planners."""

    rechecks_prefix = True
    """A motion cut short is sampled anew (its samples are not the longer one's)."""
    lazy_edges = True
    """A roadmap checks an edge only when a path takes it (Bohlin & Kavraki 2000;
    why: docs/planners-geometric-family.md)."""
    free_targets = False
    """Uniform targets valid or not, as OMPL's (faster in rigid2-scene3's slot:
    docs/planners-geometric-family.md)."""

    def __init__(self, problem):
        super().__init__(problem)
        system = self.system
        self.wall_clearance = system.check
        """A motion cut short stops one check step before its first invalid sample."""
        self.rrt_guided_targets = 0.0
        metric = self.kernels["metric"]
        # The metric's own methods (native calls in the compiled build), no wrapper.
        self.distance, self.interpolate = metric.distance, metric.interpolate
        self.check = system.check
        self.dimension = self.space.dimension
        self.can_end_at = self.is_valid
        links, body = link_tests(system, problem.world), body_tester(system, problem.world)
        variables = self.space.variables
        if links is not None:  # the arm: its first_hit in one native call
            self.first_hit = MotionCheck(links, metric, self.check, MotionHit).first_hit
            self.kernels["motion check"] = "the links' (LinkTests), " + _mode(MotionCheck)
        elif body is not None and [v.angle for v in variables] == [False, False, True]:
            # a body at (x, y, theta): the same, by BodyMotionCheck
            self.first_hit = BodyMotionCheck(
                body, [v.low for v in variables[:2]], [v.high for v in variables[:2]],
                metric, self.check, MotionHit).first_hit
            self.kernels["motion check"] = "the body's (BodyMotionCheck), " + _mode(BodyMotionCheck)
            self.kernels["body test"] = body

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> Optional[MotionHit]:
        """The first invalid sample of the motion a -> b (``a`` itself not tested),
        at SPEC 5.2's ``n = max(1, ceil(d / check))``; None when every one is valid.
        The arm shadows this with ``link_tests.MotionCheck.first_hit``, which skips
        samples that a valid one's clearance proves valid, and the rigid body with
        ``body_motion.BodyMotionCheck.first_hit``: the same answer as testing each."""
        n = self.samples_between(a, b)
        valid, interpolate = self.is_valid, self.interpolate
        for i in range(1, n + 1):
            if not valid(interpolate(a, b, i / n)):
                return MotionHit(i / n)
        return None

    def samples_between(self, a: Sequence[float], b: Sequence[float]) -> int:
        """``n``: the motion a -> b is checked at ``n + 1`` samples, ends included."""
        return sample_count(self.distance(a, b), self.check)

    def can_end_at(self, state: Sequence[float]) -> bool:
        """A path may end or turn at any valid configuration."""
        return self.is_valid(state)

    def goal_configuration(self, goal, rng: random.Random) -> Optional[State]:
        """A valid configuration in the goal region where a path may end: the goal
        itself when it names every variable, else the goal's values completed
        from uniform samples (None if no valid one turns up)."""
        if goal.full:
            return goal.target
        for _ in range(VALID_SAMPLE_ATTEMPTS):
            state = goal.complete(self._sample(rng))
            if self.is_valid(state) and goal.reached(state):
                return state
        return None

    def goal_center(self, goal) -> Optional[State]:
        """The goal itself when it names every variable (its metric is then the
        space's), else None."""
        return goal.target if goal.full else None

    def free_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], State]:
        """``draw()``: a uniform valid configuration (rejection sampling; after
        ``VALID_SAMPLE_ATTEMPTS`` draws, the last one, valid or not)."""
        sample, valid = self._sample, self.is_valid

        def draw() -> State:
            for _ in range(VALID_SAMPLE_ATTEMPTS):
                state = sample(rng)
                if valid(state):
                    return state
            return state
        return draw

    def roadmap_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], State]:
        """``draw()`` for a roadmap's vertices: with probability ``BRIDGE_SHARE`` the
        bridge test (Hsu et al. 2003: the valid midpoint of two invalid
        configurations close together, which lies in a narrow passage), else
        uniform valid (why: docs/planners-geometric-family.md)."""
        uniform, sample, valid = self.free_sampler(rng, stop), self._sample, self.is_valid
        sigma, wrap, interpolate = BRIDGE_STEPS * self.check, self.space.wrap, self.interpolate
        gauss = rng.gauss

        def draw() -> State:
            if rng.random() < BRIDGE_SHARE:
                for _ in range(BRIDGE_ATTEMPTS):
                    a = sample(rng)
                    if valid(a):
                        continue
                    b = wrap(tuple(v + gauss(0.0, sigma) for v in a))
                    if valid(b):
                        continue
                    middle = interpolate(a, b, 0.5)
                    if valid(middle):
                        return middle
            return uniform()
        return draw
