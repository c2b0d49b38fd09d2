"""Informed RRT* (Gammell, Srinivasa & Barfoot 2014, "Informed RRT*: Optimal
sampling-based path planning focused via direct sampling of an admissible
ellipsoidal heuristic", IROS), as OMPL's InformedRRTstar, for the point vehicle
and the geometric family (arm2, rigid2).

RRT*'s loop (:func:`rrt_cli.planners.rrtstar.plan`) with two changes once a
solution of cost ``c`` exists:
- targets are drawn uniformly from the informed set, the states whose admissible
  heuristic (distance from the start plus the least distance to the goal region) is
  at most ``c`` (:class:`~planning_core.informed_sampling.InformedSampler`: the
  prolate hyperspheroid of start and goal over the Euclidean variables, drawn
  directly; for arm2's angles, rejection from uniform states); a draw that finds no
  such state in ``sample_attempts`` tries skips the iteration;
- the tree is pruned whenever the best cost has fallen by more than
  ``prune_threshold`` since the last pruning: a node goes when neither it nor any
  node of its subtree has a heuristic of at most ``c`` (the best path stays).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Any

from planning_core.informed_sampling import SAMPLE_ATTEMPTS, InformedSampler
from rrt_cli.planners.base import PlanResult, StopCondition, guarded
from rrt_cli.planners.rrtstar import RRTStarParams, StarSearch, plan


@dataclass(frozen=True)
class InformedRRTStarParams(RRTStarParams):
    """Informed RRT*'s settings (``-planner informed``): RRT*'s and these."""

    prune_threshold: float = 0.05
    """Prune when the best cost has fallen by more than this fraction since the last
    pruning (OMPL's 0.05)."""
    sample_attempts: int = SAMPLE_ATTEMPTS
    """Draws an informed target may take before the iteration is skipped (OMPL's 100)."""


Params = InformedRRTStarParams


class Pruning:
    """Drops the nodes that cannot lead to a cheaper solution (module docstring)."""

    def __init__(self, heuristic: Any, threshold: float) -> None:
        self.heuristic, self.threshold = heuristic, threshold
        self.pruned_at = math.inf
        """The best cost at the last pruning."""

    def __call__(self, search: StarSearch) -> None:
        best = search.best_cost
        if math.isfinite(self.pruned_at) and \
                (self.pruned_at - best) <= self.threshold * self.pruned_at:
            return
        heuristic, states = self.heuristic, search.tree.states
        search.prune(lambda node: heuristic(states[node]) <= best)
        self.pruned_at = best


@guarded
def solve(si: Any, pdef: Any, stop: StopCondition, rng: random.Random,
          params: InformedRRTStarParams = InformedRRTStarParams()) -> PlanResult:
    sampler = InformedSampler(si, pdef, rng, params.sample_attempts)
    return plan(si, pdef, stop, rng, params, sampler.sample,
                Pruning(sampler.heuristic, params.prune_threshold))
