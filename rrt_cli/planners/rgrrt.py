"""RG-RRT for the spaceships: reachability-guided RRT (A. Shkolnik, M. Walter and
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
whose reachable set holds a state within ``goal_tolerance`` of the goal ends the
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

Reachable positions live in a :class:`~rrt_cli.nearest.QuadtreeNearest`; each
point's index maps to its node and control.
"""

from __future__ import annotations

import heapq
import math
import random
import time
from dataclasses import dataclass

from planning_core.cell_distance import CellDistanceToGoal
from planning_core.problem import Problem
from planning_core.vehicles import Vehicle, spaceship
from planning_core.world import GridWorld
from rrt_cli.nearest import QuadtreeNearest
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition
from rrt_cli.planners.rrt import (
    sample_target, ship_theta_range, start_state, trajectory_rows, tree_rows)


@dataclass(frozen=True)
class RGRRTParams:
    goal_bias: float = 0.05
    """Probability that the random target is the goal (as RRT's, SPEC 2)."""
    guided_share: float = 0.2
    """With ``goal_distance="cells"``: share of the iterations that take the
    best-first step (see ``goal_distance``) instead of drawing a target. It was
    ``goal_bias`` (0.05) until 2026-11-23; with ``guide_by_stopping_point`` 0.2
    was 1.8-5 times faster (median, 8 seeds, both ships) on maze-100,
    narrow-50, narrow-100, open-100 and random-d20-100, and none got slower."""
    guide_by_stopping_point: bool = True
    """The best-first step ranks a reachable state by the free-cell distance to
    the goal of the point where the ship would come to rest under full braking
    (``speed**2 / (2 * 0.5)`` ahead along its velocity); a state whose braking
    line meets a blocked cell comes after every other. False: by the distance of
    its own position. Ranked by position, the step favours the fastest states
    down a corridor, which then cannot take the next corner, and a maze's
    corners become plateaus of thousands of such states. maze-100, 30 s,
    ``guided_share`` 0.2: ``-grad`` 2 of 4 seeds solved by position, 8 of 8 by
    the braking point (median 0.6 s); left-only a median 3.2 s (4 seeds)
    against 0.9 s (8 seeds)."""
    goal_tolerance: float = 0.1
    """A node within this distance of the goal solves the problem."""
    angles: int = 8
    """Thrust directions in each node's reachable set, evenly spaced from 0
    (straight ahead): over [0, 2 pi) for the plain ship, over [0, pi] with both
    ends for the left-only ship, so that full braking (theta = pi, which SPEC 3
    allows) is in its set. Until 2026-11-23 the left-only set stopped at 7/8 pi,
    and could brake only while turning left: 4 seeds, 30 s, maze-100 2/4 solved
    against 4/4, narrow-100 a median 11.6 s against 3.3 s."""
    thrusts: tuple[float, ...] = (0.5,)
    """Thrust magnitudes used at every angle; zero thrust (coasting) is always in
    the set as well. Default: the extreme one only. Adding the middle thrust
    (0.25) was measured slower on the course maps and mazes, and far slower for
    the left-only ship (docs/planners-spaceship.md): the weak-thrust states sit
    close to their node, so they win many nearest queries while making little
    progress."""
    goal_controls: int = 10
    """Random controls added to the reachable set of a node that the goal is
    within one step's reach of (its distance to the goal at most its speed plus
    the largest thrust). The fixed set's full-thrust and coasting steps jump
    over the 0.1 goal disc: one ``-grad`` narrow-100 run got a node 0.11 from
    the goal within 2 000 iterations and ran 60 s more before it landed. 0 is
    the paper (the fixed set only); see also KPIECE1's ``goal_controls``."""
    random_controls: int = 0
    """Extra random controls per node (theta uniform over the range, thrust
    uniform in [0, 0.5]), drawn once when the node is added. 0: the reachable
    set is the fixed one only, as in the paper."""

    goal_distance: str = "cells"
    """"cells" (default): ``guided_share`` of the iterations add the unused
    reachable state of the whole tree that is nearest the goal along the free
    cells (:class:`planning_core.cell_distance.CellDistanceToGoal`), a greedy
    best-first step; the others draw a target (the goal with ``goal_bias``).
    "euclidean": every iteration draws a target, as the paper has it. Seed 1,
    30 s, ``-grad``, when the step took 5% of the iterations and ranked by
    position: maze-20 in 0.11 s against 16 s, maze-50 in 14 s and open-100 in
    1.2 s against not at all."""

    def __post_init__(self):
        if self.goal_distance not in ("euclidean", "cells"):
            raise ValueError("goal_distance must be 'euclidean' or 'cells'")
        for name in ("goal_bias", "guided_share"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise ValueError(f"{name} must be in [0, 1]")
        if not self.goal_tolerance > 0.0:
            raise ValueError("goal_tolerance must be positive")
        if self.angles < 1:
            raise ValueError("angles must be at least 1")
        for name in ("random_controls", "goal_controls"):
            if getattr(self, name) < 0:
                raise ValueError(f"{name} must be non-negative")
        for thrust in self.thrusts:
            if not 0.0 < thrust <= spaceship.MAX_THRUST:
                raise ValueError(f"thrusts must be in (0, {spaceship.MAX_THRUST}]")


Params = RGRRTParams


def reachable_controls(params: RGRRTParams, theta_range: float) -> list[tuple[float, float]]:
    """The fixed control set: coasting, then every thrust at every angle."""
    controls = [(0.0, 0.0)]
    # The plain ship's range is a full turn: [0, 2 pi) holds every direction once.
    # The left-only ship's [0, pi] is closed (the validator accepts theta = pi,
    # SPEC 3) and both ends are in the set: straight ahead and full braking.
    full_turn = theta_range >= spaceship.THETA_RANGE
    spacing = theta_range / (params.angles if full_turn or params.angles == 1
                             else params.angles - 1)
    for k in range(params.angles):
        theta = min(spacing * k, theta_range)
        controls.extend((theta, thrust) for thrust in params.thrusts)
    return controls


def solve(problem: Problem, vehicle: Vehicle, stop: StopCondition, rng: random.Random,
          params: RGRRTParams = RGRRTParams()) -> PlanResult:
    if not vehicle.is_spaceship:
        raise ValueError("RG-RRT plans for the spaceships only")
    began = time.perf_counter()
    world = GridWorld(problem)
    blocked, width, height = world.blocked, world.width, world.height
    gx, gy = problem.goal
    tolerance2 = params.goal_tolerance * params.goal_tolerance * (1 - 1e-9)
    theta_range = ship_theta_range(vehicle)
    fixed_controls = reachable_controls(params, theta_range)
    integrate = spaceship.integrate

    states = [start_state(problem, vehicle)]
    parents = [-1]
    controls: list[tuple[float, float] | None] = [None]
    # One entry per reachable state, indexed like the quadtree's points.
    reachable = QuadtreeNearest(width, height)
    reach_states: list[tuple[float, float, float, float]] = []
    reach_owner: list[int] = []
    reach_control: list[tuple[float, float]] = []
    reach_used = bytearray()
    # The node each used reachable state became (-1 while unused).
    reach_child: list[int] = []
    # Node k's reachable states are the ids reach_first[k] .. reach_first[k + 1] - 1.
    reach_first: list[int] = [0]
    iterations = 0
    guided = params.goal_distance == "cells"
    if guided:
        cell_distance = CellDistanceToGoal(problem)
        # Every reachable state by its distance to the goal; used ones are
        # skipped when they come to the top.
        by_distance: list[tuple[float, int]] = []
        guide_key = (stopping_point_key(cell_distance, world) if params.guide_by_stopping_point
                     else lambda state: cell_distance(state[0], state[1]))

    def result(status: PlanStatus, goal_node: int | None, message: str = "") -> PlanResult:
        return PlanResult(status, trajectory_rows(states, parents, controls, vehicle, goal_node),
                          tree_rows(states, parents, controls, vehicle),
                          PlanStats(iterations, len(states), time.perf_counter() - began),
                          message)

    def add_node(parent: int, state, control) -> int:
        states.append(state)
        parents.append(parent)
        controls.append(control)
        return len(states) - 1

    def expand_reachable(node: int) -> int | None:
        """File the node's reachable states; a goal node made from one, if any."""
        state = states[node]
        extra = params.random_controls
        x, y, dx, dy = state
        if params.goal_controls and (math.hypot(x - gx, y - gy)
                                     <= math.hypot(dx, dy) + spaceship.MAX_THRUST):
            extra += params.goal_controls
        node_controls = fixed_controls
        if extra:
            node_controls = fixed_controls + [
                (rng.random() * theta_range, rng.random() * spaceship.MAX_THRUST)
                for _ in range(extra)]
        for control in node_controls:
            end = integrate(state, control, blocked, width, height)
            # Printed states must lie strictly inside the map (SPEC 2).
            if end is None or not (end[0] > 0.0 and end[1] > 0.0) or end == state:
                continue  # (coasting at rest goes nowhere: no duplicate node)
            if (end[0] - gx) ** 2 + (end[1] - gy) ** 2 <= tolerance2:
                return add_node(node, end, control)
            reachable.add(end[0], end[1])
            reach_states.append(end)
            reach_owner.append(node)
            reach_control.append(control)
            reach_used.append(0)
            reach_child.append(-1)
            if guided:
                heapq.heappush(by_distance, (guide_key(end), len(reach_states) - 1))
        reach_first.append(len(reach_states))
        return None

    def take_reachable(chosen: int) -> int | None:
        """Make reachable state ``chosen`` a node; a goal node it leads to, if any."""
        reach_used[chosen] = 1
        node = add_node(reach_owner[chosen], reach_states[chosen], reach_control[chosen])
        reach_child[chosen] = node
        return expand_reachable(node)

    if (problem.start[0] - gx) ** 2 + (problem.start[1] - gy) ** 2 <= tolerance2:
        return result(PlanStatus.SOLVED, 0)
    goal_node = expand_reachable(0)
    if goal_node is not None:
        return result(PlanStatus.SOLVED, goal_node)

    while True:
        limit = stop.status(iterations)
        if limit is not None:
            return result(limit, None)
        if len(reach_states) == len(states) - 1:
            # Every reachable state is a node already (all but the start are).
            return result(PlanStatus.UNREACHABLE, None,
                          "no reachable state is left to extend to")
        iterations += 1
        if guided and rng.random() < params.guided_share:
            # Best-first toward the goal along the free cells (goal_distance).
            chosen = -1
            while by_distance:
                _, candidate = heapq.heappop(by_distance)
                if not reach_used[candidate]:
                    chosen = candidate
                    break
            if chosen < 0:
                continue
            goal_node = take_reachable(chosen)
            if goal_node is not None:
                return result(PlanStatus.SOLVED, goal_node)
            continue
        if rng.random() < params.goal_bias:
            tx, ty = gx, gy
        else:
            tx, ty = sample_target(rng, width, height)

        chosen = reachable.nearest(tx, ty)
        while chosen >= 0 and reach_used[chosen]:
            # That state is a node already: go on from it, to its own reachable
            # state closest to the target, or give up on the target if the node
            # is closer than all of them (the same rule as below, one level down).
            node = reach_child[chosen]
            nx, ny = states[node][0], states[node][1]
            best, best_d2 = -1, (nx - tx) ** 2 + (ny - ty) ** 2
            for candidate in range(reach_first[node], reach_first[node + 1]):
                rx, ry = reach_states[candidate][0], reach_states[candidate][1]
                d2 = (rx - tx) ** 2 + (ry - ty) ** 2
                if d2 <= best_d2:
                    best, best_d2 = candidate, d2
            chosen = best
        if chosen < 0:
            continue
        owner = reach_owner[chosen]
        ox, oy = states[owner][0], states[owner][1]
        rx, ry = reach_states[chosen][0], reach_states[chosen][1]
        if (ox - tx) ** 2 + (oy - ty) ** 2 < (rx - tx) ** 2 + (ry - ty) ** 2:
            continue  # the target lies behind the node: no move of it gets closer
        goal_node = take_reachable(chosen)
        if goal_node is not None:
            return result(PlanStatus.SOLVED, goal_node)


# Ranks a braking line that meets a blocked cell after every free one (well below
# CellDistanceToGoal's "unreachable", so those still order among themselves).
_BLOCKED_BRAKING_PENALTY = 1e6


def stopping_point_key(cell_distance: CellDistanceToGoal, world: GridWorld):
    """State -> free-cell distance to the goal of where full braking would stop it."""
    # Constant deceleration a from speed v stops after v**2 / (2 a); along the
    # velocity (dx, dy) of length v that is (dx, dy) * v / (2 a).
    reach = 1.0 / (2.0 * spaceship.MAX_THRUST)
    unreachable = cell_distance.unreachable

    def key(state) -> float:
        x, y, dx, dy = state
        ahead = math.hypot(dx, dy) * reach
        sx, sy = x + dx * ahead, y + dy * ahead
        distance = cell_distance(sx, sy)
        if (distance >= unreachable
                or world.first_blocked_cell_on_segment(x, y, sx, sy) is not None):
            return cell_distance(x, y) + _BLOCKED_BRAKING_PENALTY
        return distance

    return key
