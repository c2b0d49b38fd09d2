"""PRM* (Karaman & Frazzoli 2011, "Sampling-based algorithms for optimal motion
planning", IJRR), the k-nearest variant, for the point vehicle.

The roadmap and the query are PRM's (:mod:`rrt_cli.planners.prm`); the
connection rule differs: a new vertex tries its ``k = ceil(e (1 + 1/d) log n)``
nearest vertices, where ``n`` is the roadmap's size and ``d = 2`` the dimension
of the plane. k grows with the roadmap just fast enough for the roadmap's
shortest paths to converge to optimal ones.

PRM* is an anytime planner (OMPL's runs until its time is up). This one stops
on its own: once the query first succeeds with ``n`` vertices, the roadmap grows
to ``growth_after_connection * n`` vertices and is queried again, which buys a
shorter path for a bounded, proportional cost. If the stop condition fires
first, the best path so far is the answer.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from rrt_cli.planners.base import PlanResult, StopCondition
from rrt_cli.planners.prm import plan_with_roadmap

DIMENSION = 2


@dataclass(frozen=True)
class PRMStarParams:
    growth_after_connection: float = 2.0
    """After the first answer with n vertices, grow to this many times n and
    answer again (1.0: answer at once)."""
    min_vertices: int = 0
    """The first query waits until the roadmap has this many vertices."""
    goal_tolerance: float = 0.1
    """A start within this distance of the goal is already a solution."""


Params = PRMStarParams


def star_neighbor_count(vertices: int, dimension: int = DIMENSION) -> int:
    """k = ceil(e (1 + 1/d) log n), at least 1."""
    if vertices < 2:
        return 1
    return max(1, math.ceil(math.e * (1.0 + 1.0 / dimension) * math.log(vertices)))


def solve(problem: Problem, vehicle: Vehicle, stop: StopCondition, rng: random.Random,
          params: PRMStarParams = PRMStarParams()) -> PlanResult:
    return plan_with_roadmap(problem, vehicle, stop, rng, star_neighbor_count,
                             params.min_vertices, params.growth_after_connection,
                             params.goal_tolerance, "prmstar")
