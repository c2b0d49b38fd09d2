"""RRT (LaValle 1998, "Rapidly-exploring random trees: a new tool for path
planning"), as the course's reference planner runs it, for the point vehicle
and the spaceships.

Each iteration draws a target (the goal with probability ``goal_bias``, else a
uniform point of the map), finds the tree node nearest to it by position and
extends that node toward it with the vehicle's steering. The search ends at the
first node within ``goal_tolerance`` of the goal, like OMPL's RRT with its
default "stop at first solution".
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass

from planning_core.problem import Problem
from planning_core.vehicles import Vehicle, spaceship
from planning_core.world import GridWorld, connected_free_cells
from rrt_cli.nearest import QuadtreeNearest
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition
from rrt_cli.steering import PointSteering, SpaceshipSteering


@dataclass(frozen=True)
class RRTParams:
    goal_bias: float = 0.05
    """Probability that the random target is the goal (SPEC 2: 0.05)."""
    goal_tolerance: float = 0.1
    """A node within this distance of the goal point solves the problem."""
    controls_per_extension: int = 10
    """Spaceship: random controls tried per extension; the closest free one wins."""
    partial_extension: bool = True
    """Point vehicle: when the segment to the target is blocked, go as far as it is
    free instead of adding nothing (the reference adds nothing; this is what makes
    mazes tractable)."""
    min_extension: float = 0.01
    """Point vehicle: a partial extension shorter than this adds no node."""
    wall_clearance: float = 1.0
    """Point vehicle: a partial extension stops this far (map units) short of the
    first blocked cell. A node pressed against a wall is the nearest node to every
    target behind it and its extensions fail at once; one cell of clearance cut the
    iterations 3 to 9 times on random fields and mazes (0.01, 0.25, 0.5, 1, 1.5, 2
    and 3 were measured; README, "Decisions")."""


def make_steering(world: GridWorld, vehicle: Vehicle, params) -> PointSteering | SpaceshipSteering:
    if vehicle is Vehicle.POINT:
        return PointSteering(world, params.partial_extension, params.min_extension,
                             params.wall_clearance)
    return SpaceshipSteering(world, ship_theta_range(vehicle), params.controls_per_extension)


def ship_theta_range(vehicle: Vehicle) -> float:
    """Random thetas are drawn from ``[0, range)``: the left-only ship's is half a turn."""
    return (spaceship.LEFT_THETA_RANGE if vehicle is Vehicle.LEFT_SPACESHIP
            else spaceship.THETA_RANGE)


def goal_certainly_unreachable(problem: Problem, vehicle: Vehicle) -> bool:
    """Point vehicle only: no 8-connected chain of free cells joins start and goal.

    Spaceships are left to the limits: checked only at slice positions, a fast one
    may legally hop a thin wall.
    """
    if vehicle is not Vehicle.POINT:
        return False
    (sx, sy), (gx, gy) = problem.start, problem.goal
    reach = connected_free_cells(problem, (int(sx), int(sy)), diagonal=True)
    return not reach[int(gy) * problem.width + int(gx)]


def sample_target(rng: random.Random, width: int, height: int) -> tuple[float, float]:
    """Uniform in the open map ``(0, W) x (0, H)``, so targets print strictly inside."""
    while True:
        x, y = rng.random() * width, rng.random() * height
        if x > 0.0 and y > 0.0:
            return x, y


def start_state(problem: Problem, vehicle: Vehicle) -> tuple[float, ...]:
    x, y = problem.start
    return (x, y) if vehicle is Vehicle.POINT else (x, y, 0.0, 0.0)


def solve(problem: Problem, vehicle: Vehicle, stop: StopCondition, rng: random.Random,
          params: RRTParams = RRTParams()) -> PlanResult:
    began = time.perf_counter()
    world = GridWorld(problem)
    steering = make_steering(world, vehicle, params)
    gx, gy = problem.goal
    tolerance2 = params.goal_tolerance * params.goal_tolerance
    width, height = problem.width, problem.height

    states = [start_state(problem, vehicle)]
    parents = [-1]
    controls: list[tuple[float, float] | None] = [None]
    index = QuadtreeNearest(width, height)
    index.add(*problem.start)

    def result(status: PlanStatus, goal_node: int | None, iterations: int, message=""):
        return PlanResult(status, trajectory_rows(states, parents, controls, vehicle, goal_node),
                          tree_rows(states, parents, controls, vehicle), PlanStats(
                              iterations, len(states), time.perf_counter() - began), message)

    if (problem.start[0] - gx) ** 2 + (problem.start[1] - gy) ** 2 <= tolerance2:
        return result(PlanStatus.SOLVED, 0, 0)
    if goal_certainly_unreachable(problem, vehicle):
        return result(PlanStatus.UNREACHABLE, None, 0,
                      "no chain of free cells joins the start and the goal")

    iterations = 0
    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return result(limit, None, iterations)
        iterations += 1
        if rng.random() < params.goal_bias:
            target = (gx, gy)
        else:
            target = sample_target(rng, width, height)
        near = index.nearest(*target)
        step = steering.extend(states[near], target, rng)
        if step is None:
            continue
        new_state, control = step
        states.append(new_state)
        parents.append(near)
        controls.append(control)
        index.add(new_state[0], new_state[1])
        if (new_state[0] - gx) ** 2 + (new_state[1] - gy) ** 2 <= tolerance2 * (1 - 1e-9):
            return result(PlanStatus.SOLVED, len(states) - 1, iterations)


def _path_to(parents: list[int], node: int) -> list[int]:
    path = []
    while node != -1:
        path.append(node)
        node = parents[node]
    path.reverse()
    return path


def trajectory_rows(states, parents, controls, vehicle: Vehicle, goal_node: int | None):
    """The output's trajectory for a tree stored as parallel lists (SPEC 2 rows),
    from the root to ``goal_node``; empty when there is no goal node."""
    if goal_node is None:
        return ()
    path = _path_to(parents, goal_node)
    if vehicle is Vehicle.POINT:
        return tuple(states[k] for k in path)
    if len(path) == 1:
        # Start already at the goal: one line, zero thrust keeps the ship there.
        return (states[0] + (0.0, 0.0),)
    # Each line: a state and the control that leads to the next path node.
    return tuple(states[path[k]] + controls[path[k + 1]] for k in range(len(path) - 1))


def tree_rows(states, parents, controls, vehicle: Vehicle):
    """The output's tree section: one row per non-root node (parent state, then the
    child's state for the point vehicle or the edge's control for a spaceship)."""
    if vehicle is Vehicle.POINT:
        return tuple(states[parents[k]] + states[k] for k in range(1, len(states)))
    return tuple(states[parents[k]] + controls[k] for k in range(1, len(states)))

Params = RRTParams
