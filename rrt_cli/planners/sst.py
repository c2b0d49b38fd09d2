"""SST, Stable Sparse RRT (Y. Li, Z. Littlefield and K. E. Bekris, "Asymptotically
optimal sampling-based kinodynamic planning", IJRR 35(5), 2016), for kinodynamic
systems: asymptotically near-optimal without a steering function.

Each iteration draws a target (the goal with probability ``goal_bias``, else
``si.sample_target``), a whole state (``si.state_target``: the ships' positions get a
random velocity), and selects the *best near* node: of the active nodes within
``selection_radius`` of the target by ``si.state_distance``, the cheapest (the path's
cost from the start, ``si.motion_cost`` summed); none there, the nearest active node.
After the first solution the target stays a point and nearness is ``si.distance``
(``SSTParams.refine_by_distance``; the ships: the position, the family: the same metric).
From it, a random control held for a random duration (``si.random_motion``: Monte Carlo
propagation, no steering). A new state joins the tree only if it is the cheapest so far
in its *witness*'s region: the witnesses are states at least ``pruning_radius`` apart,
the nearest one within ``pruning_radius`` (else the new state becomes one), each with at
most one active node, its representative. The representative it replaces turns inactive:
no longer selected nor found by nearest queries (it leaves the index); an inactive node
without children is pruned from the tree, and its parent too once that is inactive and
childless, and so on up.

Departures from OMPL's ``control::SST`` (read for the algorithm, not copied):
- until the first solution, where the world measures the distance to the goal along
  its free cells (the grid's ships), a share of iterations (``guided_share``) extends
  the active node nearest the goal by it instead of the best-near node, each node
  once, by every control of RG-RRT's reachable set held one step (``guided_reach``;
  RG-RRT's guide: without steering, targets pull the tree toward the goal only in a
  straight line, which in a maze is the wrong corridor, and a random control seldom
  brakes, which the left-only ship needs to turn right in a corridor);
- on the grid's ships, whose output holds one control per step, a motion of ``k``
  steps is ``k`` chained nodes, each judged against its witness in turn (the chain
  ends at the first that is not the cheapest there);
- the nodes of the best solution are never pruned (they may turn inactive), so the
  printed tree (the nodes still in the tree at the end) holds the printed path, where
  OMPL keeps a copy of the path instead.

Without an objective the search ends at the first node in the goal region; with
``pdef.objective`` it keeps going, each cheaper goal node the new answer, until
the objective is satisfied or ``stop`` says so. docs/optimal-planning.md has the
defaults' reasons and the measurements.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass
from typing import Any, Callable, Optional

from planning_core.heap import HeapEntry, heap_pop, heap_push
from planning_core.interrupt import Stop
from planning_core.nearest.index import NearestIndex
from planning_core.problem_definition import ProblemDefinition
from planning_core.samplers import uniform
from planning_core.space_information import ControlSpaceInformation
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition, guarded
from rrt_cli.planners.tree import MotionTree, start_in_goal


@dataclass(frozen=True)
class SSTParams:
    """SST's settings (``-planner sst``); the radii in ``si.distance``'s units."""

    goal_bias: float = 0.05
    """Probability that the target is the goal (OMPL's default, 0.05)."""
    selection_radius: Optional[float] = None
    """Best-near selection: the cheapest active node this close to the target; None:
    the space information's (the ships: 0.25 map units; the family: 1 % of the
    metric's largest distance)."""
    pruning_radius: Optional[float] = None
    """A witness's region (at most one active node in it); None: the space
    information's (the ships: 0.25 map units; the family: 0.5 %)."""
    frontier_targets: float = 0.9
    """Until the first solution, the share of targets drawn from the tree's frontier
    where the world offers one (the grid: free cells without a node beside cells with
    one, as RRT*'s); after it none (the paper's draws). 0: OMPL's draws throughout."""
    guided_share: float = 0.8
    """Until the first solution, the share of iterations that extend, instead of the
    best-near node, the active node nearest the goal along the free cells where the
    world measures that (the grid's ships; judged where braking would stop it, as
    RG-RRT's), each node once; after it none. 0: OMPL's selection throughout."""
    guided_reach: bool = True
    """A guided node is extended by every control of the reachable set held one step
    (RG-RRT's: coasting and full thrust at evenly spaced angles, braking included), not
    by one random motion: a best-first search among the guided nodes."""
    whole_motions: bool = True
    """A random motion is kept only when every slice of its drawn duration is valid,
    as OMPL's SST keeps it. False: kept up to its last valid slice (KPIECE1's rule;
    docs/optimal-planning.md compares them)."""
    refine_by_distance: bool = True
    """After the first solution, select by ``si.distance`` (the ships: the position; the
    cost is the path's length, so the cheapest node near a place is the one to extend)
    rather than the whole state. False: the paper's whole-state selection throughout."""

    def __post_init__(self) -> None:
        for name in ("goal_bias", "frontier_targets", "guided_share"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise ValueError(f"{name} must be in [0, 1]")
        for name in ("selection_radius", "pruning_radius"):
            value = getattr(self, name)
            if value is not None and not value >= 0.0:
                raise ValueError(f"{name} must be >= 0")


Params = SSTParams


class _Search:
    """One SST run: the tree with each node's cost, the active nodes' index, the
    witnesses and their representatives, the best goal node."""

    def __init__(self, si: ControlSpaceInformation, pdef: ProblemDefinition,
                 rng: random.Random, params: SSTParams, stop: Stop = None):
        self.si, self.rng, self.goal, self.goal_bias = si, rng, pdef.goal, params.goal_bias
        self.refine_by_distance = params.refine_by_distance
        self.whole_motions = params.whole_motions
        self.by_distance = False
        """:attr:`nodes` is ordered by ``si.distance`` (from the first iteration after
        the first solution, with ``refine_by_distance``)."""
        self.selection_radius = (si.selection_radius if params.selection_radius is None
                                 else params.selection_radius)
        self.pruning_radius = (si.pruning_radius if params.pruning_radius is None
                               else params.pruning_radius)
        start = pdef.start
        self.tree = MotionTree(start)
        self.costs = [0.0]
        self.children = [0]
        self.active = [True]
        """Selectable and in :attr:`nodes` (a witness's representative)."""
        self.in_tree = [True]
        """Not pruned."""
        self.pinned = [False]
        """On the best solution's path: never pruned."""
        self.nodes: NearestIndex = si.new_state_nearest()
        """The active nodes, by ``si.state_distance`` (or ``si.distance``:
        :attr:`by_distance`)."""
        self.nodes.add(start)
        self.witnesses: NearestIndex = si.new_state_nearest()
        self.witnesses.add(start)
        self.reps = [0]
        """Each witness's representative (-1: none yet)."""
        self.best: Optional[int] = None
        self.iterations = 0
        self.frontier_share = params.frontier_targets
        self.frontier = si.frontier() if self.frontier_share > 0.0 else None
        if self.frontier is not None:
            self.frontier.cover(start)
        self.guided_share = params.guided_share
        along = (si.distance_along_free_space(pdef.goal, stop) if self.guided_share > 0.0
                 else None)
        self.guide_key: Optional[Callable[[Any], float]] = (
            None if along is None else si.stopping_point_key(along))
        self.guide: list[HeapEntry] = []
        """Active nodes not yet guided, by :attr:`guide_key` (until the first solution)."""
        self.guide_controls: tuple = ()
        """A guided node's extensions (``guided_reach``): the reachable set's controls."""
        if self.guide_key is not None:
            heap_push(self.guide, HeapEntry(self.guide_key(start), 0))
            if params.guided_reach:
                self.guide_controls = tuple(si.reachable_controls())

    def select(self, target: Any) -> int:
        """The cheapest active node within the selection radius (ties: the nearer),
        else the nearest active node."""
        return self.nodes.cheapest_within(target, self.selection_radius, self.costs)

    def witness(self, state: Any) -> int:
        """The nearest witness if within the pruning radius, else ``state`` as a new
        one, without a representative."""
        closest = self.witnesses.nearest_within(state, self.pruning_radius)
        if closest >= 0:
            return closest
        self.reps.append(-1)
        return self.witnesses.add(state)

    def iterate(self) -> Optional[int]:
        """One iteration; a goal node cheaper than the best so far, or None."""
        self.iterations += 1
        si, rng = self.si, self.rng
        node = -1
        if self.guide_key is not None and self.best is None \
                and uniform(rng) < self.guided_share:
            node = self.guided()
            if node >= 0 and self.guide_controls:
                return self.expand(node)
        if node < 0:
            node = self.select(self.target())
        return self.extend(node, si.random_motion(self.tree.states[node], rng,
                                                  self.whole_motions))

    def expand(self, node: int) -> Optional[int]:
        """Every control of the reachable set held one step from ``node``; the first
        goal node made, or None."""
        state, propagate = self.tree.states[node], self.si.propagate_valid
        for control in self.guide_controls:
            end = propagate(state, control)
            if end is not None:
                goal_node = self.extend(node, (control, (end,)))
                if goal_node is not None:
                    return goal_node
        return None

    def extend(self, node: int, motion: Optional[tuple[Any, Any]]) -> Optional[int]:
        """``motion`` (a control and its steps' states) from ``node``, each step a node
        while it is the cheapest at its witness; a goal node cheaper than the best so
        far, or None."""
        if motion is None:
            return None
        control, steps = motion
        si = self.si
        for state in steps:
            cost = self.costs[node] + si.motion_cost(self.tree.states[node], control, state)
            witness = self.witness(state)
            old = self.reps[witness]
            if old >= 0 and not cost < self.costs[old]:
                return None
            node = self.add(node, state, control, cost)
            self.reps[witness] = node
            if old >= 0:
                self.deactivate(old)
            if self.goal.reached(state):
                best = self.best
                return node if best is None or cost < self.costs[best] else None
        return None

    def guided(self) -> int:
        """The active node nearest the goal (:attr:`guide_key`) not guided before, or -1."""
        guide, active = self.guide, self.active
        while guide:
            node = heap_pop(guide).order
            if active[node]:
                return node
        return -1

    def target(self) -> Any:
        """:meth:`point_target` as a whole state (``si.state_target``); after the first
        solution, with ``refine_by_distance``, the point itself, the nodes re-indexed by
        ``si.distance`` once (here, not at the solution: a run that stops there pays
        nothing)."""
        point = self.point_target()
        if self.best is None or not self.refine_by_distance:
            return self.si.state_target(point, self.rng)
        if not self.by_distance:
            self.nodes = self.active_nodes(self.si.new_nearest())
            self.by_distance = True
        return point

    def point_target(self) -> Any:
        """The goal (``goal_bias``); until the first solution, else mostly a frontier
        point (``frontier_targets``); else a uniform target."""
        si, rng = self.si, self.rng
        if uniform(rng) < self.goal_bias:
            return si.goal_target(self.goal, rng)
        frontier = self.frontier
        if frontier and self.best is None and uniform(rng) < self.frontier_share:
            return frontier.sample(rng)
        return si.sample_target(rng)

    def add(self, parent: int, state: Any, control: Any, cost: float) -> int:
        if self.frontier is not None and self.best is None:
            self.frontier.cover(state)
        node = self.tree.add(parent, state, control)
        self.children[parent] += 1
        self.costs.append(cost)
        self.children.append(0)
        self.active.append(True)
        self.in_tree.append(True)
        self.pinned.append(False)
        self.nodes.add(state)
        if self.guide_key is not None and self.best is None:
            heap_push(self.guide, HeapEntry(self.guide_key(state), node))
        return node

    def deactivate(self, node: int) -> None:
        """A representative replaced: out of the index, and pruned if childless."""
        self.active[node] = False
        self.nodes.remove(node)
        self.prune(node)

    def prune(self, node: int) -> None:
        """Remove ``node`` and then its ancestors while each is inactive, childless
        and not on the best path (the start is always active: nothing costs less)."""
        active, children, pinned, parents = (self.active, self.children, self.pinned,
                                             self.tree.parents)
        while not active[node] and children[node] == 0 and not pinned[node]:
            self.in_tree[node] = False
            node = parents[node]
            children[node] -= 1

    def accept(self, goal_node: int) -> None:
        """``goal_node`` is the new answer: its path is pinned, the old one's not."""
        old = self.best
        self.best = goal_node
        self.guide = []  # guided iterations end with the first solution
        if old is not None:
            self.pin(old, False)
        self.pin(goal_node, True)
        if old is not None:
            self.prune(old)

    def active_nodes(self, index: NearestIndex) -> NearestIndex:
        """``index`` (empty) holding the active nodes under the tree's numbers."""
        for state in self.tree.states:
            index.add(state)
        for node, is_active in enumerate(self.active):
            if not is_active:
                index.remove(node)
        return index

    def pin(self, node: int, pinned: bool) -> None:
        for k in self.tree.path_to(node):
            self.pinned[k] = pinned

    def result(self, status: PlanStatus, began: float,
               improvements: list[tuple[float, float]]) -> PlanResult:
        """The best path (none without a solution) and the tree's remaining edges."""
        tree = self.tree
        path, path_controls = tree.path(self.best)
        states, parents, controls = tree.states, tree.parents, tree.controls
        edges = tuple((states[parents[k]], controls[k], states[k])
                      for k in range(1, len(states)) if self.in_tree[k])
        stats = PlanStats(self.iterations, len(edges) + 1, time.perf_counter() - began,
                          improvements[0][0] if improvements else None, tuple(improvements))
        return PlanResult(status, self.si.system, path, path_controls, edges, stats)


@guarded
def solve(si: ControlSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: SSTParams = SSTParams()) -> PlanResult:
    if not si.system.kinodynamic:
        raise ValueError("SST plans for kinodynamic systems only")
    began = time.perf_counter()
    search = _Search(si, pdef, rng, params, stop.time_is_up)
    solved = start_in_goal(si, pdef, search.tree, began)
    if solved is not None:
        return solved
    objective = pdef.objective
    improvements: list[tuple[float, float]] = []
    while True:
        limit = stop.status(search.iterations)
        if limit is not None:
            break
        goal_node = search.iterate()
        if goal_node is None:
            continue
        search.accept(goal_node)
        cost = search.costs[goal_node]
        improvements.append((time.perf_counter() - began, cost))
        if objective is None or objective.satisfied(cost):
            limit = PlanStatus.SOLVED
            break
    status = limit if search.best is None else PlanStatus.SOLVED
    return search.result(status, began, improvements)
