"""RRT-Connect (Kuffner & LaValle 2000, "RRT-Connect: An efficient approach to
single-query path planning", ICRA) for the point vehicle and the geometric
family (arm2, rigid2).

Two trees grow, one from the start and one from the goal, and swap roles every
iteration. The active tree *extends* one step toward a random target; when
that adds a node, the other tree *connects* toward the new node: it
extends toward it again and again while each step advances (neither reaching
it nor being trapped). When the connect reaches the node exactly, the trees
meet and the path is start tree -> meeting point -> goal tree.

Steps are straight motions (:class:`StraightLineSteering`, as RRT uses:
checked exactly against the grid, at the check step for the family); with
``max_step`` a step stops after that distance, and with ``partial_extension`` a
blocked step goes as far as it is free. The goal tree's motions are checked in
the direction the path will travel them (toward the goal). The goal tree's root
is the goal itself (``goal_configuration``), so the path ends exactly there.

The paper draws targets uniformly; here, where the world offers a frontier (the
grid: free cells without a node beside cells with one,
:mod:`planning_core.worlds.grid_frontier`), 90% of them come from it by default,
which in a maze is what keeps the trees advancing: see
``RRTConnectParams.frontier_targets`` (0 restores the paper). The rest are
uniform, over free space or over the whole space (``free_space_targets``; by
default as the space information prefers: the grid's free cells, the family's
whole space).

Where the space information asks for it (``si.rrt_guided_targets``: the Dubins car),
a share of each tree's iterations is guided (:mod:`rrt_cli.planners.guide`): the
start tree's node nearest the goal along the free cells, or the goal tree's nearest
the start, extends toward a state down the way, and the other tree connects to it.

The tree section of the output lists both trees' edges, goal-tree edges
pointing toward the goal.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass
from enum import Enum

from typing import Any, Optional

from planning_core.goal import GoalRegion
from planning_core.problem_definition import ProblemDefinition
from planning_core.samplers import uniform
from planning_core.space_information import GeometricSpaceInformation
from planning_core.worlds.grid_frontier import FrontierCells
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition, guarded
from rrt_cli.planners.paths import NO_GOAL_CONFIGURATION
from rrt_cli.planners.steering import StraightLineSteering
from rrt_cli.planners.tree import MotionTree


@dataclass(frozen=True)
class RRTConnectParams:
    """RRT-Connect's settings (``-planner rrtconnect``)."""

    max_step: float = 0.0
    """Longest single extension (map units; the metric for the family); 0: unlimited (straight to the
    target when the segment is free, as the course's RRT steers). OMPL's "range"."""
    partial_extension: bool = True
    """Extend: a blocked step goes as far as it is free instead of adding nothing."""
    partial_connect: bool = True
    """Connect: the same, for the steps toward the other tree's new node."""
    min_extension: float = 0.01
    """A partial step shorter than this adds no node (counts as trapped)."""
    wall_clearance: Optional[float] = None
    """A partial step stops this far short of the first invalid state, as in RRT
    (see ``RRTParams.wall_clearance``); None: the space information's."""
    free_space_targets: Optional[bool] = None
    """Draw random targets from valid states only instead of the whole space; None:
    as the space information prefers (``si.free_targets``: the grid's free cells,
    where most whole-map targets of a maze lie in walls; the family's whole space,
    as OMPL's, faster in rigid2-scene3's slot: docs/planners-geometric-family.md)."""
    frontier_targets: float = 0.9
    """Share of the random targets drawn from the trees' frontier (free cells with
    no node beside covered ones, where the world offers it; not for a directed system,
    the Dubins car); 0 gives the published RRT-Connect."""
    guided_targets: Optional[float] = None
    """The share of each tree's iterations that extend its node nearest the other
    root along the free cells toward a state down the way (as ``RRTParams.
    guided_targets``); None: the space information's ``rrt_guided_targets``."""
    def __post_init__(self):
        if not 0.0 <= self.frontier_targets <= 1.0:
            raise ValueError("frontier_targets must be in [0, 1]")


Params = RRTConnectParams


class _Grow(Enum):
    TRAPPED = "trapped"    # nothing added
    ADVANCED = "advanced"  # a node added short of the target
    REACHED = "reached"    # a node added at the target


class _Tree(MotionTree):
    """One tree with a nearest index over its states."""

    def __init__(self, root: tuple[float, ...], index, toward_root: bool, reverse=None):
        self.reverse = reverse
        """None, or the space's ``reverse_state``: then the tree (grown from the goal)
        holds reversed states and grows forward in them (a directed system)."""
        super().__init__(self.flip(root))
        self.index = index
        self.index.add(self.states[0])
        # The goal tree's edges are travelled child -> parent by the final path.
        self.toward_root = toward_root
        self.guide: Any = None
        """Its nodes not yet guided from (:class:`~rrt_cli.planners.guide.Guide`), or None."""

    def flip(self, state: tuple[float, ...]) -> tuple[float, ...]:
        """A path's state as this tree holds it, and back (reversing is its own
        inverse): reversed, or as it is."""
        return state if self.reverse is None else self.reverse(state)

    def path_to_root(self, node: int) -> list[tuple[float, ...]]:
        return [self.flip(self.states[k]) for k in reversed(self.path_to(node))]

    def travelled_edges(self) -> list[tuple]:
        """The edges as the path would travel them (a goal tree's: toward the root)."""
        if not self.toward_root:
            return self.edges()
        real = self.flip
        return [(real(child), control, real(parent))
                for child, control, parent in self.edges(toward_root=True)]


class _Grower:
    """Extends a tree one step toward a target (OMPL's growTree)."""

    def __init__(self, si: GeometricSpaceInformation, params: RRTConnectParams,
                 rng: random.Random, frontier: FrontierCells | None):
        self.si = si
        self.frontier = frontier
        self.max_step = params.max_step
        self.extend_steering = StraightLineSteering(si, params.partial_extension,
                                                    params.min_extension, params.wall_clearance)
        self.connect_steering = StraightLineSteering(si, params.partial_connect,
                                                     params.min_extension, params.wall_clearance)
        self.rng = rng

    def grow(self, tree: _Tree, target: tuple[float, ...],
             connecting: bool = False, near: int = -1) -> tuple[_Grow, int]:
        """The outcome and the index of the node added (-1 when trapped): from the
        node nearest ``target``, a path's state; or from ``near`` toward ``target``
        held as the tree holds its states (a guided iteration)."""
        if near < 0:
            target = tree.flip(target)
            near = tree.index.nearest(target)
        near_state = tree.states[near]
        clipped = False
        if self.max_step > 0.0:
            distance = self.si.distance(near_state, target)
            if distance > self.max_step:
                target = self.si.interpolate(near_state, target, self.max_step / distance)
                clipped = True
        steering = self.connect_steering if connecting else self.extend_steering
        step = steering.extend(near_state, target, self.rng)
        if step is None:
            return _Grow.TRAPPED, -1
        new = step[0]
        if tree.toward_root and self.si.first_hit(tree.flip(new),
                                                  tree.flip(near_state)) is not None:
            # Free one way only (a rounding tie, other samples; for a reversed tree, the
            # curve travelled forward): a path through it would fail its check every time.
            return _Grow.TRAPPED, -1
        added = tree.add(near, new)
        tree.index.add(new)
        if tree.guide is not None:
            tree.guide.add(added, new)
        if self.frontier is not None:
            self.frontier.cover(new)
        reached = not clipped and new == target
        return (_Grow.REACHED if reached else _Grow.ADVANCED), added


def _target_sampler(si: GeometricSpaceInformation, params: RRTConnectParams,
                    rng: random.Random, frontier: FrontierCells | None, stop: StopCondition):
    """Draws targets: the frontier's share, the rest uniform (over free space or the map)."""
    free = si.free_targets if params.free_space_targets is None else params.free_space_targets
    if free:
        draw_uniform_target = si.free_sampler(rng, stop.time_is_up)
    else:
        def draw_uniform_target():
            return si.sample_target(rng)

    if frontier is None:
        return draw_uniform_target
    frontier_share = params.frontier_targets

    def draw_target():
        if frontier and uniform(rng) < frontier_share:
            return frontier.sample(rng)
        return draw_uniform_target()

    return draw_target


@guarded
def solve(si: GeometricSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: RRTConnectParams = RRTConnectParams()) -> PlanResult:
    if si.system.kinodynamic:
        raise ValueError("rrtconnect plans for geometric systems only")
    share = si.rrt_guided_targets if params.guided_targets is None else params.guided_targets
    if share > 0.0:
        from rrt_cli.planners.guide import Guide  # only where guided: start-up
        Guide.prepare(si, share)
    began = time.perf_counter()
    start, goal = pdef.start, si.goal_configuration(pdef.goal, rng)
    if goal is None:
        return PlanResult(PlanStatus.UNREACHABLE, si.system, (), (), (),
                          PlanStats(0, 0, time.perf_counter() - began), NO_GOAL_CONFIGURATION)
    start_tree = _Tree(start, si.new_nearest(), toward_root=False)
    goal_tree = _Tree(goal, si.new_nearest(), toward_root=True,
                      reverse=getattr(si, "reverse_state", None))

    def result(status: PlanStatus, path, iterations: int, message: str = ""):
        edges = start_tree.travelled_edges() + goal_tree.travelled_edges()
        stats = PlanStats(iterations, len(start_tree) + len(goal_tree),
                          time.perf_counter() - began)
        return PlanResult(status, si.system, tuple(path), (), tuple(edges), stats, message)

    if pdef.goal.reached(start):
        return result(PlanStatus.SOLVED, [start], 0)
    if si.certainly_unreachable(start, pdef.goal, stop.time_is_up):
        return result(PlanStatus.UNREACHABLE, (), 0,
                      "no chain of free cells joins the start and the goal")
    # A directed system's trees (the Dubins car's) meet only at a pose both reach:
    # frontier targets, beside each tree's own nodes, do not draw them together
    # (measured: docs/dubins.md, "Targets").
    frontier = (si.frontier() if params.frontier_targets > 0.0 and goal_tree.reverse is None
                else None)
    if frontier is not None:
        frontier.cover(start)
        frontier.cover(goal)
    grower = _Grower(si, params, rng, frontier)
    draw_target = _target_sampler(si, params, rng, frontier, stop)
    _begin_guides(si, share, pdef, start_tree, goal_tree, stop)
    active, other = start_tree, goal_tree
    iterations = 0
    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return result(limit, (), iterations)
        iterations += 1
        guided = active.guide.draw(rng, active.states) if active.guide is not None else None
        target, near = (draw_target(), -1) if guided is None else (guided[1], guided[0])
        path = _extend_and_connect(grower, active, other, start_tree, target, near, si, stop)
        if path is not None:
            return result(PlanStatus.SOLVED, path, iterations)
        active, other = other, active


def _begin_guides(si: GeometricSpaceInformation, share: float,
                  pdef: ProblemDefinition, start_tree: _Tree, goal_tree: _Tree,
                  stop: StopCondition) -> None:
    """Guide each tree toward the other's root with ``share`` of its iterations (the
    grid's Dijkstra from each root: on the planning clock)."""
    if share > 0.0:
        from rrt_cli.planners.guide import Guide  # only where guided: start-up
        start = pdef.start
        start_tree.guide = Guide.begin(si, pdef.goal, share, start, stop.time_is_up)
        goal_tree.guide = Guide.begin(si, GoalRegion((start[0], start[1])), share,
                                      goal_tree.states[0], stop.time_is_up)


def _extend_and_connect(grower: _Grower, active: _Tree, other: _Tree, start_tree: _Tree,
                        target, near: int, si: GeometricSpaceInformation,
                        stop: StopCondition) -> list | None:
    """Extend ``active`` toward ``target`` (from ``near``, a guided iteration, or from
    the nearest node), then connect ``other`` to the new node (until the time is up: a
    directed system's steps need not get nearer); the path from start to goal when
    they meet."""
    outcome, added = grower.grow(active, target, near=near)
    if outcome is _Grow.TRAPPED:
        return None
    meeting = active.flip(active.states[added])
    connect = _Grow.ADVANCED
    while connect is _Grow.ADVANCED and not stop.time_is_up():
        connect, reached = grower.grow(other, meeting, connecting=True)
    if connect is not _Grow.REACHED:
        return None
    start_node, goal_node = (added, reached) if active is start_tree else (reached, added)
    goal_tree = other if active is start_tree else active
    head = [start_tree.states[k] for k in start_tree.path_to(start_node)]
    # Both trees hold the meeting point: print it once.
    tail = goal_tree.path_to_root(goal_node)[1:]
    if goal_tree.reverse is not None and not _free_forward(si, [head[-1]] + tail):
        return None  # a reversed motion is checked again as travelled: rounding ties
    return head + tail


def _free_forward(si: GeometricSpaceInformation, states: list) -> bool:
    """Every motion between consecutive states is free, as travelled."""
    return all(si.first_hit(a, b) is None for a, b in zip(states, states[1:]))
