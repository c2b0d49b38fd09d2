"""Blossom RRT (seed 004's planner for the first-order car, SPEC 5.2), for every
kinodynamic family system.

Each iteration draws a target (the goal with probability ``goal_bias``, else a
uniform state), finds the tree node nearest to it by the metric, and grows a
"blossom" there: ``b`` random controls, each held for up to KMAX slices and
stopped at the first invalid slice, the last valid state kept (so a control's K
is its number of valid slices; fewer than KMIN and it adds nothing). The end
nearest the target becomes the new node. Holding each control as long as it
stays valid makes long, cheap strides across open space; the search ends at the
first node in the goal region.

The grid's ships hold a control for one whole step (their space information has
no ``advance``), so blossom does not plan for them: RRT with
``controls_per_extension = b`` is the same idea there.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass

from planning_core.problem_definition import ProblemDefinition
from planning_core.space_information import ControlSpaceInformation
from rrt_cli.planners import rrt
from rrt_cli.planners.base import PlanResult, StopCondition, guarded


@dataclass(frozen=True)
class BlossomParams:
    """Blossom RRT's settings (``-planner blossom``)."""

    b: int = 5
    """Random controls tried from the nearest node per iteration (seed 004: 1, 3, 5)."""
    goal_bias: float = 0.05
    """Probability that the target is the goal (as RRT's, SPEC 2)."""
    kmax: int | None = None
    """Most slices a control is held; None: the problem's KMAX (car1: 250)."""

    def __post_init__(self):
        if self.b < 1:
            raise ValueError("b must be at least 1")
        if not 0.0 <= self.goal_bias <= 1.0:
            raise ValueError("goal_bias must be in [0, 1]")
        if self.kmax is not None and self.kmax < 1:
            raise ValueError("kmax must be at least 1")


Params = BlossomParams


@guarded
def solve(si: ControlSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: BlossomParams = BlossomParams()) -> PlanResult:
    system = si.system
    if getattr(si, "advance", None) is None:
        raise ValueError("blossom plans for systems whose controls are held K slices "
                         "(the kinodynamic family systems) only")
    began = time.perf_counter()
    grow = _blossom(si, params.b, system.kmin, params.kmax or system.kmax)
    return rrt.grow(si, pdef, stop, rng, grow, params.goal_bias, began)


def _blossom(si, b: int, kmin: int, kmax: int):
    """``grow(state, target, rng) -> (end, control) | None``: the best of ``b``
    controls held while valid, by ``si.closeness`` to the target."""
    advance, closeness = si.advance, si.closeness
    sample_values = si.system.sample_values

    def grow(state, target, rng):
        best, best_d = None, math.inf
        for _ in range(b):
            values = sample_values(rng)
            end, k = advance(state, values, kmax)
            if k < kmin:
                continue
            d = closeness(end, target)
            if d < best_d:
                best, best_d = (end, (*values, k)), d
        return best

    return grow
