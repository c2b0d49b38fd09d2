"""RG-RRT for kinodynamic systems: reachability-guided RRT (A. Shkolnik, M. Walter and
R. Tedrake, "Reachability-guided sampling for planning under differential
constraints", IEEE ICRA 2009).

Plain RRT picks the node nearest to a random target by position, which for a
ship with momentum is often a node that cannot move toward the target at all:
it then keeps extending the same hopeless nodes. RG-RRT measures instead how
close each node can *get* to the target. Every node keeps its reachable set:
the end states, after one step, of a small fixed set of controls (no thrust,
and full thrust at ``angles`` evenly spaced angles over the vehicle's theta
range). Each iteration:

1. draws a target (the goal with probability ``goal_bias``, else a uniform
   point of the map; but see the departure below);
2. finds the reachable state closest to it (by position) over the whole tree,
   and so the node that owns it;
3. rejects the target when that node itself is closer to it than that closest
   reachable state: every move of the node would take it away from the target,
   so the target lies "behind" the node and would only waste an extension;
4. otherwise adds that reachable state as a new node, reached with its control
   held for one step, and computes the new node's reachable set.

The reachable states are integrated with collision checks when their node is
added (every slice free, every position strictly inside the map), so a
reachable state is always a legal child and step 4 integrates nothing. A
reachable state that becomes a node is marked used, so it is never added
twice: when the nearest reachable state is a used one, the search goes on from
the node it became, to that node's reachable state closest to the target, with
the same rejection rule (the quadtree has no deletion, and a used state sits
exactly on its node, so the answer is almost always one level down). A node
whose reachable set holds a state in the goal region ends the
search at once.

One departure from the paper, on by default (``RGRRTParams.goal_distance``):
a share of the iterations (``guided_share``) draws no target; each adds instead
the unused reachable state of the whole tree that lies nearest the goal along
the map's free cells, judged at the point where the ship would stop if it
braked now (``guide_by_stopping_point``). On a maze the straight line to the
goal points into walls, and a target pulls only the node nearest it in a
straight line; judged by its own position, the fastest state down a corridor
would win, and it cannot take the next corner.

A second departure (``goal_controls``): a node the goal is within one step's
reach of also gets a few random controls in its reachable set, as the fixed
full-thrust steps tend to jump over the small goal disc.

The fixed set of controls is the space information's (``si.reachable_controls``:
the grid's ships coast and thrust at 8 angles; a family system takes every
combination of its held controls' bounds, held 0.5 s), and so is "closest"
(``si.closeness``: by position on the grid, the metric over whole states in the
family) and "within one step's reach" (``si.step_reach``: the ship's speed plus
its thrust; a family node's farthest fixed reachable state).
docs/planners-family.md lists each system's set.

Reachable states live in ``si.new_nearest()`` (the grid: a quadtree by position;
the family: a kd-tree by the metric); each point's index maps to its node and control.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from planning_core.heap import HeapEntry, heap_pop, heap_push
from planning_core.interrupt import Stop
from planning_core.nearest.index import NearestIndex
from planning_core.problem_definition import ProblemDefinition
from planning_core.samplers import uniform
from planning_core.space_information import ControlSpaceInformation
from rrt_cli.planners.base import PlanResult, StopCondition, guarded
from rrt_cli.planners.tree import MotionTree, TreeSearch, run_tree_search


@dataclass(frozen=True)
class RGRRTParams:
    """RG-RRT's settings (``-planner rgrrt``). The fixed reachable set is the space
    information's (``si.reachable_controls``)."""

    goal_bias: float = 0.05
    """Probability that the random target is the goal (as RRT's, SPEC 2)."""
    guided_share: float = 0.2
    """With ``goal_distance="cells"``: share of the iterations that take the
    best-first step instead of drawing a target."""
    guide_by_stopping_point: bool = True
    """The best-first step ranks a state by the distance along free space of where
    full braking would stop it (a braking line into a wall ranks last); False: by its position."""
    goal_controls: int = 10
    """Random controls added to the reachable set of a node the goal is within one
    step's reach of (the fixed set tends to jump over the goal disc); 0 is the paper."""
    random_controls: int = 0
    """Extra random controls per node, drawn once when it is added; 0 is the paper."""

    goal_distance: str = "cells"
    """"cells": ``guided_share`` of the iterations add the unused reachable state
    nearest the goal along free space (greedy best-first); "euclidean": the paper's RG-RRT."""

    def __post_init__(self):
        if self.goal_distance not in ("euclidean", "cells"):
            raise ValueError("goal_distance must be 'euclidean' or 'cells'")
        for name in ("goal_bias", "guided_share"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise ValueError(f"{name} must be in [0, 1]")
        for name in ("random_controls", "goal_controls"):
            if getattr(self, name) < 0:
                raise ValueError(f"{name} must be non-negative")


Params = RGRRTParams


class _ReachableSets:
    """Every node's reachable states, indexed like the quadtree of their positions."""

    def __init__(self, si: Any) -> None:
        self.index: NearestIndex = si.new_nearest()  # typed: native calls
        self.closeness = si.closeness
        self.states: list[tuple[float, ...]] = []
        self.owner: list[int] = []
        self.control: list[tuple[float, ...]] = []
        self.used = bytearray()
        self.child: list[int] = []   # the node a used state became (-1 while unused)
        # Node k's reachable states are the ids first[k] .. first[k + 1] - 1.
        self.first: list[int] = [0]

    def __len__(self) -> int:
        return len(self.states)

    def add(self, owner: int, state, control) -> int:
        self.index.add(state)
        self.states.append(state)
        self.owner.append(owner)
        self.control.append(control)
        self.used.append(0)
        self.child.append(-1)
        return len(self.states) - 1

    def closest_of(self, node: int, node_state, target) -> int:
        """``node``'s reachable state closest to ``target`` (``si.closeness``), or
        -1 when the node itself is closer than all of them."""
        closeness = self.closeness
        best, best_d2 = -1, closeness(node_state, target)
        for candidate in range(self.first[node], self.first[node + 1]):
            d2 = closeness(self.states[candidate], target)
            if d2 <= best_d2:
                best, best_d2 = candidate, d2
        return best


class _Search(TreeSearch):
    """One RG-RRT run: the tree, the reachable sets and the best-first queue."""

    def __init__(self, si: ControlSpaceInformation, pdef: ProblemDefinition,
                 rng: random.Random, params: RGRRTParams, stop: Stop = None):
        self.si, self.rng, self.params = si, rng, params
        self.goal = pdef.goal
        self.fixed_controls = si.reachable_controls()
        self.tree = MotionTree(pdef.start)
        self.reach = _ReachableSets(si)
        self.iterations = 0
        along: Any = (si.distance_along_free_space(pdef.goal, stop)
                      if params.goal_distance == "cells" else None)
        self.guided = along is not None
        # Every reachable state by its distance to the goal; used ones are skipped
        # when they come to the top.
        self.by_distance: list[HeapEntry] = []  # (distance, reachable state)
        if self.guided:
            key = si.stopping_point_key(along) if params.guide_by_stopping_point else None
            self.guide_key = key or (lambda state: along(state[0], state[1]))

    def random_controls(self, state, ends: list) -> list:
        """Random controls for the node: ``random_controls``, and ``goal_controls``
        more when the goal is within one step's reach (``si.step_reach``)."""
        params, si = self.params, self.si
        extra = params.random_controls
        if params.goal_controls:
            reach = si.step_reach(state, ends)
            if self.goal.distance(state) <= reach:
                extra += params.goal_controls
        return [si.sample_control(self.rng) for _ in range(extra)]

    def expand(self, node: int) -> int | None:
        """File the node's reachable states; a goal node made from one, if any."""
        state = self.tree.states[node]
        ends: list = []
        for control in self.fixed_controls:
            goal_node = self.file(node, state, control, ends)
            if goal_node is not None:
                return goal_node
        for control in self.random_controls(state, ends):
            goal_node = self.file(node, state, control, ends)
            if goal_node is not None:
                return goal_node
        self.reach.first.append(len(self.reach))
        return None

    def file(self, node: int, state, control, ends: list) -> int | None:
        """One reachable state of ``node`` (appended to ``ends``); a goal node if
        it reaches the goal region, which then joins the tree at once."""
        si = self.si
        end = si.propagate_valid(state, control)
        if end is None or end == state:
            return None  # (coasting at rest goes nowhere: no duplicate node)
        if self.goal.reached(end):
            return self.tree.add(node, end, control)
        ends.append(end)
        chosen = self.reach.add(node, end, control)
        if self.guided:
            heap_push(self.by_distance, HeapEntry(self.guide_key(end), chosen))
        return None

    def take(self, chosen: int) -> int | None:
        """Make reachable state ``chosen`` a node; a goal node it leads to, if any."""
        reach = self.reach
        reach.used[chosen] = 1
        node = self.tree.add(reach.owner[chosen], reach.states[chosen], reach.control[chosen])
        reach.child[chosen] = node
        return self.expand(node)

    def best_first(self) -> int:
        """The unused reachable state nearest the goal by the guide, or -1."""
        while self.by_distance:
            candidate = heap_pop(self.by_distance).order
            if not self.reach.used[candidate]:
                return candidate
        return -1

    def toward(self, target) -> int:
        """The reachable state to add for ``target``, or -1 to reject it."""
        reach, states, closeness = self.reach, self.tree.states, self.si.closeness
        chosen = reach.index.nearest(target)
        while chosen >= 0 and reach.used[chosen]:
            # That state is a node already: go on from it, one level down, by the
            # same rule as below.
            node = reach.child[chosen]
            chosen = reach.closest_of(node, states[node], target)
        if chosen < 0:
            return -1
        if closeness(states[reach.owner[chosen]], target) < closeness(reach.states[chosen],
                                                                      target):
            return -1  # the target lies behind the node: no move of it gets closer
        return chosen

    def begin(self) -> int | None:
        return self.expand(0)

    def exhausted(self) -> str:
        # Every reachable state is a node already (all but the start are).
        if len(self.reach) == len(self.tree) - 1:
            return "no reachable state is left to extend to"
        return ""

    def iterate(self) -> int | None:
        """One iteration (module docstring); a goal node or None."""
        rng, params = self.rng, self.params
        self.iterations += 1
        if self.guided and uniform(rng) < params.guided_share:
            chosen = self.best_first()
        else:
            if uniform(rng) < params.goal_bias:
                target = self.si.goal_target(self.goal, rng)
            else:
                target = self.si.sample_target(rng)
            chosen = self.toward(target)
        return self.take(chosen) if chosen >= 0 else None


@guarded
def solve(si: ControlSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: RGRRTParams = RGRRTParams()) -> PlanResult:
    return run_tree_search(si, pdef, stop,
                           lambda: _Search(si, pdef, rng, params, stop.time_is_up), "RG-RRT")
