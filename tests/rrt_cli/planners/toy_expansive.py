"""A planner new to both substrates, written against the protocols only: grow a
tree by random motions from random nodes (the nearest to a random target, by
``si.new_nearest``), as an expansive-space tree would. One file; a test adds its
registry line (tests/rrt_cli/planners/test_substrate.py)."""

from __future__ import annotations

import random
import time
from dataclasses import dataclass

from planning_core.problem_definition import ProblemDefinition
from planning_core.space_information import ControlSpaceInformation
from rrt_cli.planners.base import PlanResult, PlanStatus, StopCondition, guarded
from rrt_cli.planners.tree import MotionTree, start_in_goal


@dataclass(frozen=True)
class Params:
    goal_bias: float = 0.1
    """Probability that the target is the goal's."""


@guarded
def solve(si: ControlSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: Params = Params()) -> PlanResult:
    began, goal = time.perf_counter(), pdef.goal
    tree, index = MotionTree(pdef.start), si.new_nearest()
    index.add(pdef.start)
    solved = start_in_goal(si, pdef, tree, began)
    iterations = 0
    while solved is None:
        limit = stop.status(iterations)
        if limit is not None:
            return tree.result(si.system, limit, None, iterations, began)
        iterations += 1
        target = (si.goal_target(goal, rng) if rng.random() < params.goal_bias
                  else si.sample_target(rng))
        node = index.nearest(target)
        motion = si.random_motion(tree.states[node], rng)
        for state in [] if motion is None else motion[1]:
            node = tree.add(node, state, motion[0])
            index.add(state)
            if goal.reached(state):
                return tree.result(si.system, PlanStatus.SOLVED, node, iterations, began)
    return solved
