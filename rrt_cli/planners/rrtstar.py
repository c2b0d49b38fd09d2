"""RRT* (Karaman & Frazzoli 2011, "Sampling-based algorithms for optimal motion
planning", IJRR) with k-nearest rewiring, as OMPL's RRTstar runs by default, for
the point vehicle and the geometric family (arm2, rigid2).

Each iteration draws a target (until a node is in the goal region: the goal with
probability ``goal_bias``, else mostly a point of the tree's frontier where the world
has one, ``frontier_targets``; after it, now and then one of the world's bend points,
``bend_targets``, or a point of the goal region's rim, ``rim_targets``; otherwise a
uniform state), takes the tree node nearest to it and steers toward it as RRT does.
Until a node is in the goal region, where the world measures the distance to the goal
along its free cells (the grid), a share of iterations (``guided_targets``) instead
takes the node nearest the goal by it, each node once, toward a state down the way
(:mod:`rrt_cli.planners.guide`; a departure from the paper). Steering is
:class:`StraightLineSteering`'s: straight, at most ``extent_fraction`` of the space's
extent, a blocked motion cut short ``wall_clearance`` before its first invalid state.
The new state's ``k = ceil(rewire_factor e (1 + 1/d) log(n + 1))`` nearest nodes then
- *choose its parent*: the one through which its cost-to-come is least and whose
  motion to it is free (tried in order of that cost until one is: OMPL's delayed
  collision checking); then, with ``ancestor_hops``, that parent's parent in its
  place, and so on up, while the motion from it is free and cheaper (Theta*'s
  any-angle parent; a departure from the paper: paths pull taut round the corners
  their nodes pass, and in open space every node hangs from the start);
- *are rewired*: each whose cost-to-come falls by going through the new state, and
  whose motion from it is free, takes it as parent; its subtree's costs fall too.
A cost is a path's length: ``si.distance`` of each motion, measured and checked in
the direction it is travelled.

Without an objective the search ends at the first node in the goal region. With
one (``-optimize``) it goes on until the objective is met or ``stop`` ends it, and
the answer is the goal-region node of least cost-to-come. The output's tree is the
final tree, after rewiring. Informed RRT* (:mod:`rrt_cli.planners.informed`) is
this loop with its own targets and pruning.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from typing import Any, Callable, Optional

from planning_core.goal import PLANNER_MARGIN
from planning_core.interrupt import Stop
from planning_core.samplers import randint, uniform
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition, guarded
from rrt_cli.planners.guide import Guide
from rrt_cli.planners.prmstar import star_neighbor_count
from rrt_cli.planners.steering import StraightLineSteering
from rrt_cli.planners.tree import MotionTree, start_in_goal

State = tuple[float, ...]

RIM_INSIDE = 1.0 - 4 * PLANNER_MARGIN
"""Rim targets lie this fraction of the tolerance from the goal's centre: inside the
planners' goal test (``goal.PLANNER_MARGIN``) whatever the rounding."""


@dataclass(frozen=True)
class RRTStarParams:
    """RRT*'s settings (``-planner rrtstar``)."""

    goal_bias: float = 0.05
    """Probability that the target is the goal, until a node is in the goal region
    (OMPL's: then a goal target would only add the same state again)."""
    extent_fraction: float = 0.2
    """Longest extension as a fraction of the space's maximum extent (OMPL's range:
    0.2 of it); 0: unlimited, as the course's RRT."""
    rewire_factor: float = 1.1
    """Scales k = e (1 + 1/d) log(n + 1), the neighbours tried as parents and rewired
    (OMPL's 1.1: strictly above Karaman & Frazzoli's bound)."""
    frontier_targets: float = 0.9
    """Until the first solution, the share of targets drawn from the tree's frontier
    where the world offers one (the grid: free cells without a node beside cells with
    one, as RRT-Connect's); after it, none (the optimization draws as the paper's)."""
    guided_targets: float = 0.5
    """Until the first solution, the share of iterations that extend the node nearest
    the goal along the free cells, each node once, toward a state down its cheapest
    chain of cells (:mod:`rrt_cli.planners.guide`). 0: none."""
    bend_targets: float = 0.05
    """After the first solution, the share of targets that are the world's bend
    points where it has any (``si.bend_points``: the grid's pinches, passable only
    by a node exactly there, and its convex corners, where shortest paths bend); the
    rest as the paper's."""
    rim_targets: float = 0.02
    """After the first solution, the share of targets on the goal region's rim where
    the region is a ball (``si.goal_center``), where a shortest path from outside it
    ends: a uniform state drawn in toward the centre to the tolerance. 0: none."""
    ancestor_hops: bool = True
    """A new node's parent passes to the parent's parent, and on up its chain, while
    that motion is free and cheaper (Theta*'s any-angle parent; a departure from the
    paper). False: the paper's choice among the neighbours alone."""
    partial_extension: bool = True
    """A blocked extension goes as far as it is free instead of adding nothing."""
    min_extension: float = 0.01
    """A partial extension shorter than this adds no node."""
    wall_clearance: Optional[float] = None
    """A partial extension stops this far short of the first invalid state, as in RRT
    (see ``RRTParams.wall_clearance``); None: the space information's."""


Params = RRTStarParams


class CostTree:
    """Nodes with their parent, children, cost-to-come and the cost of the motion from
    their parent; pruned nodes stay in the lists, marked dead."""

    def __init__(self, root: State) -> None:
        self.states: list[State] = [root]
        self.parents: list[int] = [-1]
        self.children: list[list[int]] = [[]]
        self.costs: list[float] = [0.0]
        self.steps: list[float] = [0.0]
        self.alive: list[bool] = [True]
        self.size = 1
        """Live nodes."""

    def add(self, parent: int, state: State, step: float) -> int:
        self.states.append(state)
        self.parents.append(parent)
        self.children.append([])
        self.costs.append(self.costs[parent] + step)
        self.steps.append(step)
        self.alive.append(True)
        self.children[parent].append(len(self.states) - 1)
        self.size += 1
        return len(self.states) - 1

    def reparent(self, node: int, parent: int, step: float) -> None:
        """``node`` hangs from ``parent`` by a motion of cost ``step``; the
        costs-to-come of its subtree follow."""
        self.children[self.parents[node]].remove(node)
        self.children[parent].append(node)
        self.parents[node] = parent
        self.steps[node] = step
        costs, steps, children = self.costs, self.steps, self.children
        costs[node] = costs[parent] + step
        stack = [node]
        while stack:
            above = stack.pop()
            for child in children[above]:
                costs[child] = costs[above] + steps[child]
                stack.append(child)

    def path_to(self, node: int) -> list[int]:
        """The nodes from the root to ``node``."""
        path = []
        while node != -1:
            path.append(node)
            node = self.parents[node]
        path.reverse()
        return path

    def edges(self) -> tuple:
        """``(parent state, None, state)`` per live node but the root, in node order."""
        states, parents = self.states, self.parents
        return tuple((states[parents[k]], None, states[k])
                     for k in range(1, len(states)) if self.alive[k])

    def prune(self, keep: Callable[[int], bool]) -> None:
        """Drop every node whose subtree holds no node ``keep`` accepts (the root stays)."""
        order, children = [0], self.children
        for node in order:  # breadth first: each parent before its children
            order.extend(children[node])
        kept = {0}
        for node in reversed(order):
            if node in kept or keep(node) or any(child in kept for child in children[node]):
                kept.add(node)
        for node in order:
            if node not in kept:
                self.alive[node] = False
                self.size -= 1
            children[node] = [child for child in children[node] if child in kept]


class StarSearch:
    """RRT*'s tree, its nearest index and its best goal node between iterations.
    ``draw_target(best_cost)`` is the non-goal target (RRT*: uniform; Informed
    RRT*: informed once a solution exists), None to skip the iteration."""

    def __init__(self, si: Any, pdef: Any, rng: random.Random, params: RRTStarParams,
                 draw_target: Callable[[float], Optional[State]], stop: Stop = None) -> None:
        self.si, self.goal, self.rng, self.stop = si, pdef.goal, rng, stop
        self.guided_share = params.guided_targets
        Guide.prepare(si, self.guided_share)
        self.guide: Optional[Guide] = None
        """The nodes not yet guided from (:meth:`begin_guide`; until the first solution)."""
        self.goal_bias, self.rewire_factor = params.goal_bias, params.rewire_factor
        self.hops = params.ancestor_hops
        self.frontier_share = params.frontier_targets
        self.frontier = si.frontier() if self.frontier_share > 0.0 else None
        if self.frontier is not None:
            self.frontier.cover(pdef.start)
        self.draw_target = draw_target
        self.bend_share = params.bend_targets
        self.bends: Optional[list[State]] = None
        """The world's bend points, found when first drawn (after a solution)."""
        self.rim_share = params.rim_targets
        self.centre = si.goal_center(pdef.goal) if self.rim_share > 0.0 else None
        self.rim_radius = pdef.goal.tolerance * RIM_INSIDE
        self.distance, self.first_hit = si.distance, si.first_hit
        self.steering = StraightLineSteering(si, params.partial_extension,
                                             params.min_extension, params.wall_clearance)
        self.max_step = params.extent_fraction * si.space.maximum_extent() or math.inf
        self.tree = CostTree(pdef.start)
        self.index_nodes: list[int] = []
        self._rebuild_index()
        self.goal_nodes: list[int] = []
        self.best, self.best_cost = -1, math.inf
        self.improvements: list[tuple[float, float]] = []

    def iterate(self) -> bool:
        """One iteration; True when the best solution became cheaper."""
        guide = self.guide if not self.goal_nodes else None
        guided = guide.draw(self.rng, self.tree.states) if guide is not None else None
        if guided is not None:
            steered = self._steer(guided[1], guided[0])
        else:
            target = self._target()
            if target is None:
                return False
            steered = self._steer(target)
        if steered is None:
            return False
        near, new = steered
        k = star_neighbor_count(self.tree.size + 1, self.si.dimension, self.rewire_factor)
        neighbours = [self.index_nodes[i] for i in self.index.k_nearest(new, k)]
        parent, step = self._choose_parent(near, new, neighbours)
        node = self.tree.add(parent, new, step)
        self.index.add(new)
        self.index_nodes.append(node)
        if self.frontier is not None and not self.goal_nodes:
            self.frontier.cover(new)
        if guide is not None:
            guide.add(node, new)
        changed = self._rewire(node, neighbours)
        if self.goal.reached(new):
            self.goal_nodes.append(node)
            changed = True
        return changed and self._update_best()

    def _target(self) -> Optional[State]:
        """Until a node is in the goal region: the goal (``goal_bias``), else a frontier
        cell's point (``frontier_targets``); after, a bend point (``bend_targets``) or
        a point of the goal's rim (``rim_targets``); then ``draw_target``'s."""
        rng = self.rng
        if not self.goal_nodes:
            if uniform(rng) < self.goal_bias:
                return self.si.goal_target(self.goal, rng)
            frontier = self.frontier
            if frontier and uniform(rng) < self.frontier_share:
                return frontier.sample(rng)
        else:
            if self.bend_share > 0.0:
                if self.bends is None:
                    self.bends = list(self.si.bend_points())
                bends = self.bends
                if bends and uniform(rng) < self.bend_share:
                    return bends[randint(rng, 0, len(bends) - 1)]
            if self.centre is not None and uniform(rng) < self.rim_share:
                return self._rim_target()
        return self.draw_target(self.best_cost)

    def _rim_target(self) -> Optional[State]:
        """A uniform state drawn in along the way from the goal's centre to the goal's
        rim (``interpolate`` covers distance evenly), None when it is the centre."""
        centre, si = self.centre, self.si
        state = si.sample_target(self.rng)
        length = si.distance(centre, state)
        if length <= self.rim_radius:
            return state if length > 0.0 else None
        return si.interpolate(centre, state, self.rim_radius / length)

    def begin_guide(self) -> None:
        """Measure the distance down the free cells where the world does (with
        ``guided_targets``; the grid's Dijkstra, so on the planning clock)."""
        self.guide = Guide.begin(self.si, self.goal, self.guided_share, self.tree.states[0],
                                 self.stop)

    def _steer(self, target: State, near: int = -1) -> Optional[tuple[int, State]]:
        """``near`` (by default the node nearest ``target``) and the new state steered
        from it, or None."""
        if near < 0:
            near = self.index_nodes[self.index.nearest(target)]
        start = self.tree.states[near]
        length = self.distance(start, target)
        if length > self.max_step:
            target = self.si.interpolate(start, target, self.max_step / length)
        step = self.steering.extend(start, target, self.rng)
        if step is None or step[0] == start:
            return None
        return near, step[0]

    def _choose_parent(self, near: int, new: State, neighbours: list[int]) -> tuple[int, float]:
        """The neighbour through which ``new`` is cheapest to reach by a free motion
        (``near``'s motion is known free), or with ancestor hops the ancestor of it
        that :meth:`_hop` climbs to, and that motion's cost."""
        states, costs, distance = self.tree.states, self.tree.costs, self.distance
        near_step = distance(states[near], new)
        through_near = costs[near] + near_step
        offers = sorted((costs[n] + distance(states[n], new), n) for n in neighbours)
        parent, step = near, near_step
        for cost, candidate in offers:
            if cost >= through_near or candidate == near:
                break
            if self.first_hit(states[candidate], new) is None:
                parent, step = candidate, distance(states[candidate], new)
                break
        return self._hop(parent, step, new) if self.hops else (parent, step)

    def _hop(self, parent: int, step: float, new: State) -> tuple[int, float]:
        """Up ``parent``'s chain while the motion from the next ancestor to ``new`` is
        free and makes ``new`` cheaper (Nash et al. 2007, "Theta*: Any-angle path
        planning on grids", AAAI, with every ancestor and not only the grandparent)."""
        tree, distance = self.tree, self.distance
        parents, states, costs = tree.parents, tree.states, tree.costs
        up = parents[parent]
        while up >= 0:
            up_step = distance(states[up], new)
            if costs[up] + up_step >= costs[parent] + step \
                    or self.first_hit(states[up], new) is not None:
                break
            parent, step, up = up, up_step, parents[up]
        return parent, step

    def _rewire(self, node: int, neighbours: list[int]) -> bool:
        """Hang each neighbour from ``node`` when that is cheaper and free; whether any."""
        tree, distance, first_hit = self.tree, self.distance, self.first_hit
        new, cost = tree.states[node], tree.costs[node]
        changed = False
        for other in neighbours:
            state = tree.states[other]
            step = distance(new, state)
            if other != tree.parents[node] and cost + step < tree.costs[other] \
                    and first_hit(new, state) is None:
                tree.reparent(other, node, step)
                changed = True
        return changed

    def _update_best(self) -> bool:
        """The goal node of least cost-to-come; True when it is cheaper than before."""
        costs, best, best_cost = self.tree.costs, self.best, self.best_cost
        improved = False
        for node in self.goal_nodes:
            if costs[node] < best_cost:
                best, best_cost, improved = node, costs[node], True
        self.best, self.best_cost = best, best_cost
        return improved

    def prune(self, keep: Callable[[int], bool]) -> None:
        """Drop the subtrees without a node ``keep`` accepts (the best goal node is
        always kept) and index the rest anew."""
        best = self.best
        self.tree.prune(lambda node: node == best or keep(node))
        alive = self.tree.alive
        self.goal_nodes = [node for node in self.goal_nodes if alive[node]]
        self._rebuild_index()

    def _rebuild_index(self) -> None:
        self.index = self.si.new_nearest()
        self.index_nodes = [node for node, live in enumerate(self.tree.alive) if live]
        for node in self.index_nodes:
            self.index.add(self.tree.states[node])

    def result(self, status: PlanStatus, iterations: int, began: float) -> PlanResult:
        """The best path (when solved) and the final tree."""
        tree = self.tree
        path = tuple(tree.states[k] for k in tree.path_to(self.best)) if self.best >= 0 else ()
        first = self.improvements[0][0] if self.improvements else None
        stats = PlanStats(iterations, tree.size, time.perf_counter() - began, first,
                          tuple(self.improvements))
        return PlanResult(status, self.si.system, path, (), tree.edges(), stats)


def plan(si: Any, pdef: Any, stop: StopCondition, rng: random.Random, params: RRTStarParams,
         draw_target: Callable[[float], Optional[State]],
         on_better: Optional[Callable[[StarSearch], None]] = None) -> PlanResult:
    """RRT*'s loop (module docstring); ``on_better(search)`` after each cheaper solution
    that does not end the search (Informed RRT*'s pruning)."""
    if si.system.kinodynamic:
        raise ValueError("RRT* plans for geometric systems only")
    # Set up before the clock starts, as OMPL's setup() precedes solve(): the empty tree,
    # nearest index and frontier (microseconds) load the modules behind them.
    search = StarSearch(si, pdef, rng, params, draw_target, stop.time_is_up)
    began = time.perf_counter()
    solved = start_in_goal(si, pdef, MotionTree(pdef.start), began)
    if solved is not None:
        return solved
    if si.certainly_unreachable(pdef.start, pdef.goal, stop.time_is_up):
        return PlanResult(PlanStatus.UNREACHABLE, si.system, (), (), (),
                          PlanStats(0, 1, time.perf_counter() - began),
                          "no chain of free cells joins the start and the goal")
    search.begin_guide()
    objective, iterations = pdef.objective, 0
    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return search.result(PlanStatus.SOLVED if search.best >= 0 else limit,
                                 iterations, began)
        iterations += 1
        if not search.iterate():
            continue
        search.improvements.append((time.perf_counter() - began, search.best_cost))
        if objective is None or objective.satisfied(search.best_cost):
            return search.result(PlanStatus.SOLVED, iterations, began)
        if on_better is not None:
            on_better(search)


@guarded
def solve(si: Any, pdef: Any, stop: StopCondition, rng: random.Random,
          params: RRTStarParams = RRTStarParams()) -> PlanResult:
    sample_target = si.sample_target
    return plan(si, pdef, stop, rng, params, lambda best_cost: sample_target(rng))
