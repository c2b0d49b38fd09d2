"""RRT (LaValle 1998, "Rapidly-exploring random trees: a new tool for path
planning"), as the course's reference planner runs it, for any system.

Each iteration draws a target (the goal with probability ``goal_bias``, else
``si.sample_target``: a uniform point of the map, or a uniform state of a
family system's space), finds the tree node nearest to it (``si.new_nearest``:
by position on the grid, by the metric in the family) and extends that node
toward it with the system's steering (straight lines for a geometric system, the
best of random controls for a kinodynamic one). The search ends at the first
node in the goal region, like OMPL's RRT with its default "stop at first
solution". Where the space information asks for it (the Dubins car, whose uniform
targets rarely lead it through a maze), a share of iterations is guided instead:
the node nearest the goal along the free cells extends toward a state down the way
(:mod:`rrt_cli.planners.guide`).
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass

from planning_core.nearest.index import NearestIndex
from planning_core.samplers import uniform
from rrt_cli.planners.base import PlanResult, PlanStatus, StopCondition, guarded
from rrt_cli.planners.steering import make_steering
from rrt_cli.planners.tree import MotionTree, start_in_goal

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Callable, Optional


@dataclass(frozen=True)
class RRTParams:
    """RRT's settings (``-planner rrt``)."""

    goal_bias: float = 0.05
    """Probability that the random target is the goal (SPEC 2: 0.05)."""
    controls_per_extension: Optional[int] = None
    """Kinodynamic systems: random controls tried per extension, the closest valid one
    wins; None: the space information's (the grid's ships 10, the family 1)."""
    partial_extension: bool = True
    """Geometric systems: when the segment to the target is blocked, go as far as it is
    free instead of adding nothing (the reference adds nothing; this is what makes
    mazes tractable)."""
    min_extension: float = 0.01
    """Geometric systems: a partial extension shorter than this adds no node."""
    wall_clearance: Optional[float] = None
    """Geometric systems: a partial extension stops this far short of the first
    invalid state (a node pressed against a wall fails every extension toward the
    targets behind it; docs/parameter-history.md); None: the space information's
    (the grid: a map unit; the family: one check step)."""
    guided_targets: Optional[float] = None
    """The share of iterations that extend the node nearest the goal along the free
    cells toward a state down the way (:mod:`rrt_cli.planners.guide`); None: the space
    information's ``rrt_guided_targets`` (the Dubins car's 0.5; 0 elsewhere: the point's
    RRT is the course's reference loop)."""


@guarded
def solve(si: Any, pdef: Any, stop: StopCondition, rng: random.Random,
          params: RRTParams = RRTParams()) -> PlanResult:
    guided = si.rrt_guided_targets if params.guided_targets is None else params.guided_targets
    if guided > 0.0:
        from rrt_cli.planners.guide import Guide  # only where guided: start-up
        Guide.prepare(si, guided)
    began = time.perf_counter()
    steering = make_steering(si, params)
    return grow(si, pdef, stop, rng, steering.extend, params.goal_bias, began, guided)


def grow(si: Any, pdef: Any, stop: StopCondition, rng: random.Random,
         extend: Callable, goal_bias: float, began: float,
         guided_targets: float = 0.0) -> PlanResult:
    """RRT's loop with ``extend(state, target, rng) -> (state, control) | None`` as
    its steering, until a node reaches the goal or ``stop`` says so (blossom RRT is
    this loop with its own steering); ``guided_targets`` of its iterations guided."""
    goal = pdef.goal
    tree = MotionTree(pdef.start)
    index: NearestIndex = si.new_nearest()  # typed: native calls (nearest/index.py)
    index.add(pdef.start)
    system = si.system

    solved = start_in_goal(si, pdef, tree, began)
    if solved is not None:
        return solved
    if si.certainly_unreachable(pdef.start, goal, stop.time_is_up):
        return tree.result(system, PlanStatus.UNREACHABLE, None, 0, began,
                           "no chain of free cells joins the start and the goal")

    goal_target, sample_target, states = si.goal_target, si.sample_target, tree.states
    guide: Any = None
    if guided_targets > 0.0:
        from rrt_cli.planners.guide import Guide  # only where guided: start-up
        guide = Guide.begin(si, goal, guided_targets, pdef.start, stop.time_is_up)
    iterations = 0
    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return tree.result(system, limit, None, iterations, began)
        iterations += 1
        guided = guide.draw(rng, states) if guide is not None else None
        if guided is not None:
            near, target = guided
        else:
            target = goal_target(goal, rng) if uniform(rng) < goal_bias else sample_target(rng)
            near = index.nearest(target)
        step = extend(states[near], target, rng)
        if step is None:
            continue
        new_state, control = step
        node = tree.add(near, new_state, control)
        index.add(new_state)
        if guide is not None:
            guide.add(node, new_state)
        if goal.reached(new_state):
            return tree.result(system, PlanStatus.SOLVED, node, iterations, began)

Params = RRTParams
