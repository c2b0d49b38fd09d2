"""RRT-Connect (Kuffner & LaValle 2000, "RRT-Connect: An efficient approach to
single-query path planning", ICRA) for the point vehicle.

Two trees grow, one from the start and one from the goal, and swap roles every
iteration. The active tree *extends* one step toward a random target; when
that adds a node, the other tree *connects* toward the new node: it
extends toward it again and again while each step advances (neither reaching
it nor being trapped). When the connect reaches the node exactly, the trees
meet and the path is start tree -> meeting point -> goal tree.

Steps are straight segments checked exactly against the grid
(:class:`PointSteering`, as RRT uses); with ``max_step`` a step stops after
that distance, and with ``partial_extension`` a blocked step goes as far as it
is free. The goal tree's segments are checked in the direction the path will
travel them (toward the goal). The goal tree's root is the goal point itself,
so the path ends exactly at the goal.

The paper draws targets uniformly; here, by default, 90% come from the trees'
frontier (free cells without a node beside cells with one,
:mod:`rrt_cli.planners.frontier`), which in a maze is what keeps the trees
advancing: see ``RRTConnectParams.frontier_targets`` (0 restores the paper).

The tree section of the output lists both trees' edges, goal-tree edges
pointing toward the goal.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from enum import Enum

from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from planning_core.world import GridWorld
from rrt_cli.nearest import QuadtreeNearest
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition
from rrt_cli.planners.frontier import FrontierCells
from rrt_cli.planners.point_common import free_cell_indices, goal_vertex, sample_free_point
from rrt_cli.planners.rrt import goal_certainly_unreachable, sample_target
from rrt_cli.steering import PointSteering


@dataclass(frozen=True)
class RRTConnectParams:
    max_step: float = 0.0
    """Longest single extension, in map units; 0 means unlimited (straight to the
    target when the segment is free, as the course's RRT steers). OMPL's "range"."""
    partial_extension: bool = True
    """Extend: a blocked step goes as far as it is free instead of adding nothing."""
    partial_connect: bool = True
    """Connect: the same, for the steps toward the other tree's new node."""
    min_extension: float = 0.01
    """A partial step shorter than this adds no node (counts as trapped)."""
    wall_clearance: float = 1.0
    """A partial step stops this far (map units) short of the first blocked cell,
    as in RRT (see ``RRTParams.wall_clearance``)."""
    free_space_targets: bool = True
    """Draw random targets from the free cells only (uniform over free space)
    instead of the whole map: on crowded maps and mazes most whole-map targets
    lie inside walls and only feed extensions that stop at the wall."""
    frontier_targets: float = 0.9
    """Share of the random targets drawn from the trees' frontier: free cells
    no node lies in yet next to a cell one does (:mod:`rrt_cli.planners.frontier`);
    the rest are drawn as ``free_space_targets`` says. 0 gives the published
    RRT-Connect. In a 100x100 maze this takes the median time from about 80 s
    to under 1 s; the uniform share keeps every free point a possible target."""
    goal_tolerance: float = 0.1
    """A start within this distance of the goal is already a solution."""

    def __post_init__(self):
        if not 0.0 <= self.frontier_targets <= 1.0:
            raise ValueError("frontier_targets must be in [0, 1]")


Params = RRTConnectParams


class _Grow(Enum):
    TRAPPED = "trapped"    # nothing added
    ADVANCED = "advanced"  # a node added short of the target
    REACHED = "reached"    # a node added at the target


class _Tree:
    """One tree: positions, parents (-1 for the root) and a nearest index."""

    def __init__(self, root: tuple[float, float], width: int, height: int, toward_root: bool):
        self.states = [root]
        self.parents = [-1]
        self.index = QuadtreeNearest(width, height)
        self.index.add(*root)
        # The goal tree's edges are travelled child -> parent by the final path.
        self.toward_root = toward_root

    def path_to_root(self, node: int) -> list[tuple[float, float]]:
        path = []
        while node != -1:
            path.append(self.states[node])
            node = self.parents[node]
        return path

    def edges(self) -> list[tuple[float, ...]]:
        states, parents = self.states, self.parents
        if self.toward_root:
            return [states[k] + states[parents[k]] for k in range(1, len(states))]
        return [states[parents[k]] + states[k] for k in range(1, len(states))]


class _Grower:
    """Extends a tree one step toward a target (OMPL's growTree)."""

    def __init__(self, world: GridWorld, params: RRTConnectParams, rng: random.Random,
                 frontier: FrontierCells | None):
        self.world = world
        self.frontier = frontier
        self.max_step = params.max_step
        self.extend_steering = PointSteering(world, params.partial_extension,
                                             params.min_extension, params.wall_clearance)
        self.connect_steering = PointSteering(world, params.partial_connect,
                                              params.min_extension, params.wall_clearance)
        self.rng = rng

    def grow(self, tree: _Tree, target: tuple[float, float],
             connecting: bool = False) -> tuple[_Grow, int]:
        """The outcome and the index of the node added (-1 when trapped)."""
        near = tree.index.nearest(*target)
        nx, ny = tree.states[near]
        tx, ty = target
        clipped = False
        if self.max_step > 0.0:
            distance = math.hypot(tx - nx, ty - ny)
            if distance > self.max_step:
                t = self.max_step / distance
                tx, ty = nx + (tx - nx) * t, ny + (ty - ny) * t
                clipped = True
        steering = self.connect_steering if connecting else self.extend_steering
        step = steering.extend((nx, ny), (tx, ty), self.rng)
        if step is None:
            return _Grow.TRAPPED, -1
        new = step[0]
        if tree.toward_root and self.world.first_blocked_cell_on_segment(
                new[0], new[1], nx, ny) is not None:
            return _Grow.TRAPPED, -1  # free one way only: a rounding tie at a cell edge
        tree.states.append(new)
        tree.parents.append(near)
        added = tree.index.add(*new)
        if self.frontier is not None:
            self.frontier.cover(new)
        reached = not clipped and new == target
        return (_Grow.REACHED if reached else _Grow.ADVANCED), added


def solve(problem: Problem, vehicle: Vehicle, stop: StopCondition, rng: random.Random,
          params: RRTConnectParams = RRTConnectParams()) -> PlanResult:
    if vehicle is not Vehicle.POINT:
        raise ValueError("rrtconnect plans for the point vehicle only")
    began = time.perf_counter()
    world = GridWorld(problem)
    width, height = problem.width, problem.height
    start = problem.start
    goal = goal_vertex(world, problem.goal)
    start_tree = _Tree(start, width, height, toward_root=False)
    goal_tree = _Tree(goal, width, height, toward_root=True)
    frontier = FrontierCells(problem) if params.frontier_targets > 0.0 else None
    grower = _Grower(world, params, rng, frontier)

    def result(status: PlanStatus, trajectory, iterations: int, message: str = ""):
        tree = start_tree.edges() + goal_tree.edges()
        nodes = len(start_tree.states) + len(goal_tree.states)
        return PlanResult(status, tuple(trajectory), tuple(tree),
                          PlanStats(iterations, nodes, time.perf_counter() - began), message)

    gx, gy = problem.goal
    if math.hypot(start[0] - gx, start[1] - gy) <= params.goal_tolerance * (1 - 1e-9):
        return result(PlanStatus.SOLVED, [start], 0)
    if goal_certainly_unreachable(problem, vehicle):
        return result(PlanStatus.UNREACHABLE, (), 0,
                      "no chain of free cells joins the start and the goal")

    if params.free_space_targets:
        free_cells = free_cell_indices(problem)

        def draw_uniform_target():
            return sample_free_point(rng, free_cells, width)
    else:
        def draw_uniform_target():
            return sample_target(rng, width, height)

    if frontier is None:
        draw_target = draw_uniform_target
    else:
        frontier.cover(start)
        frontier.cover(goal)
        frontier_share = params.frontier_targets

        def draw_target():
            if frontier and rng.random() < frontier_share:
                return frontier.sample(rng)
            return draw_uniform_target()

    active, other = start_tree, goal_tree
    iterations = 0
    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return result(limit, (), iterations)
        iterations += 1
        outcome, added = grower.grow(active, draw_target())
        if outcome is not _Grow.TRAPPED:
            meeting = active.states[added]
            # Connect: keep stepping the other tree toward the new node.
            connect = _Grow.ADVANCED
            while connect is _Grow.ADVANCED:
                connect, reached = grower.grow(other, meeting, connecting=True)
            if connect is _Grow.REACHED:
                if active is start_tree:
                    start_node, goal_node = added, reached
                else:
                    start_node, goal_node = reached, added
                head = start_tree.path_to_root(start_node)
                head.reverse()
                # Both trees hold the meeting point: print it once.
                tail = goal_tree.path_to_root(goal_node)[1:]
                return result(PlanStatus.SOLVED, head + tail, iterations)
        active, other = other, active
