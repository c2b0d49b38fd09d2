"""PRM* (Karaman & Frazzoli 2011, "Sampling-based algorithms for optimal motion
planning", IJRR), the k-nearest variant, for the point vehicle and the geometric
family (arm2, rigid2).

The roadmap and the query are PRM's (:mod:`rrt_cli.planners.prm`); the
connection rule differs: a new vertex tries its ``k = ceil(e (1 + 1/d) log n)``
nearest vertices, where ``n`` is the roadmap's size and ``d`` the dimension of
the space (2 for the plane and the arm's torus, 3 for SE(2)); seed 004's
``k = ceil(log n)`` is ``log_neighbors``. k grows with the roadmap just fast enough for the roadmap's
shortest paths to converge to optimal ones.

PRM* is an anytime planner (OMPL's runs until its time is up). This one stops
on its own, and the rule is ours: a first answer that is one edge, the straight
line, is final. Otherwise the roadmap doubles and is queried again, and keeps
doubling while it has under 256 vertices (cheap; a small roadmap's path improves
in jumps) or while a doubling shortens the path by at least 3%, as long as the
doubled roadmap stays within 5000 vertices (about 2 s on a 50x50 maze); that cap
binds the first doubling too. Small cluttered maps so end within a few percent of
the shortest path (``benchmarks/shortest_path.py`` measures it); a map whose first
answer needs over 2500 vertices answers at once, since doubling would cost as long
again as the search so far (on a 100x100 map, well past a 30 s limit). If the
stop condition fires first, the best path so far is the answer.
Every rule counts vertices, not seconds, so ``-seed`` reproduces the run.
"""

from __future__ import annotations

import functools
import math
import random
from dataclasses import dataclass

from planning_core.problem_definition import ProblemDefinition
from planning_core.space_information import GeometricSpaceInformation
from rrt_cli.planners.base import PlanResult, StopCondition, guarded
from rrt_cli.planners.prm import Refinement, plan_with_roadmap

DIMENSION = 2


@dataclass(frozen=True)
class PRMStarParams:
    """PRM*'s settings (``-planner prmstar``)."""

    growth_after_connection: float = 2.0
    """After an answer with n vertices, grow to this many times n and answer
    again (1.0: answer at once)."""
    min_improvement: float = 0.03
    """Grow again while the last growth shortened the path by at least this
    fraction (1.0: one growth only)..."""
    max_refined_vertices: int = 5000
    """... and only while the grown roadmap stays within this many vertices
    (about 2 s on a 50x50 maze); this binds the first growth too (0: answer at
    once)."""
    min_refined_vertices: int = 256
    """Below this many vertices grow again even when the last growth gained
    nothing (a small roadmap's path improves in jumps; about 0.05 s)."""
    min_vertices: int = 0
    """The first query waits until the roadmap has this many vertices."""
    log_neighbors: bool = False
    """Seed 004's rule k = ceil(log n) instead of k = ceil(e (1 + 1/d) log n)."""


Params = PRMStarParams


def star_neighbor_count(vertices: int, dimension: int = DIMENSION, factor: float = 1.0) -> int:
    """k = ceil(factor e (1 + 1/d) log n), at least 1 (RRT*'s too, with OMPL's rewire
    factor)."""
    if vertices < 2:
        return 1
    return max(1, math.ceil(factor * math.e * (1.0 + 1.0 / dimension) * math.log(vertices)))


def log_neighbor_count(vertices: int) -> int:
    """Seed 004's k = ceil(log n), at least 1."""
    return max(1, math.ceil(math.log(vertices))) if vertices >= 2 else 1


@guarded
def solve(si: GeometricSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: PRMStarParams = PRMStarParams()) -> PlanResult:
    refinement = Refinement(params.growth_after_connection, params.min_improvement,
                            params.max_refined_vertices, params.min_refined_vertices)
    if params.log_neighbors:
        neighbor_count = log_neighbor_count
    else:
        dimension = si.dimension
        neighbor_count = functools.partial(star_neighbor_count, dimension=dimension)
    return plan_with_roadmap(si, pdef, stop, rng, neighbor_count, params.min_vertices,
                             refinement, "prmstar")
