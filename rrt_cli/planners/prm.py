"""PRM, the probabilistic roadmap (Kavraki, Svestka, Latombe & Overmars 1996,
"Probabilistic roadmaps for path planning in high-dimensional configuration
spaces", IEEE Trans. Robotics and Automation), for the point vehicle and the
geometric family (arm2, rigid2); and the roadmap machinery that PRM*
(:mod:`rrt_cli.planners.prmstar`) shares.

Construction and query are separate steps, run in a loop as OMPL's PRM does:

* Construction adds vertices drawn from the free space (``roadmap_sampler``:
  uniform on the grid; for the family half uniform, half by the bridge test)
  and joins each new vertex to its ``k`` nearest roadmap vertices (by the
  metric) by every straight motion that is free (exactly on the grid). The
  family's roadmap is lazy (``lazy_edges``): it joins all ``k`` and checks a
  motion, at the check step, only when a query's path takes it. A union-find
  structure tracks the connected components as edges are added.
* The query (A* with the metric as heuristic, :mod:`rrt_cli.graph_search`)
  runs once the start and goal vertices are in one component and the roadmap
  has at least ``min_vertices`` vertices; until then construction goes on, one
  vertex at a time, until the :class:`StopCondition` ends it.

The start and the goal are roadmap vertices from the beginning, so the path
ends exactly at the goal (``goal_configuration``: on the grid nudged into the
map only when the goal sits on the map's left or bottom edge). The output's
tree section is the roadmap's edges found free.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from typing import Callable

from planning_core.problem_definition import ProblemDefinition
from planning_core.space_information import GeometricSpaceInformation
from rrt_cli.graph_search import astar_search
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition, guarded
from rrt_cli.planners.paths import NO_GOAL_CONFIGURATION, path_length

START, GOAL = 0, 1  # the roadmap's first two vertices
LAZY_RETRY_GROWTH = 1.1
"""A lazy roadmap whose query failed is queried again once it has grown this much."""
LAZY_CHECK_AROUND_AFTER = 32
"""From this A* run of one query on, a lazy roadmap also checks every edge at a blocked
step's ends (``Roadmap.check_around``; why: docs/planners-geometric-family.md)."""


@dataclass(frozen=True)
class PRMParams:
    """PRM's settings (``-planner prm``)."""

    neighbors: int = 10
    """k: each new vertex tries to connect to its k nearest vertices (OMPL's default, 10)."""
    min_vertices: int = 0
    """The query waits until the roadmap has this many vertices (0: query as soon
    as start and goal are connected)."""


Params = PRMParams


class Roadmap:
    """An undirected graph of valid states joined by free straight motions."""

    def __init__(self, si: GeometricSpaceInformation):
        self.si = si
        self.lazy = si.lazy_edges
        self.index = si.new_nearest()
        self.states: list[tuple[float, ...]] = []
        self.adjacency: list[list[tuple[int, float]]] = []
        self.edges: dict[tuple[int, int], None] = {}  # in the order added
        self.checked: set[tuple[int, int]] = set()  # motions found free, in that direction
        self._component_parent: list[int] = []
        self._components_stale = False

    def __len__(self) -> int:
        return len(self.states)

    def add_vertex(self, state: tuple[float, ...], neighbors: int) -> int:
        """Insert ``state`` and join it to each of its ``neighbors`` nearest vertices
        whose motion to it is free (``lazy``: to each, checked when a path takes
        it); returns the new vertex."""
        candidates = self.index.k_nearest(state, neighbors) if len(self) else []
        vertex = self.index.add(state)
        self.states.append(state)
        self.adjacency.append([])
        self._component_parent.append(vertex)
        first_hit, states, lazy = self.si.first_hit, self.states, self.lazy
        for other in candidates:
            if lazy or first_hit(state, states[other]) is None:
                self.add_edge(vertex, other)
        return vertex

    def add_edge(self, a: int, b: int) -> None:
        cost = self.si.distance(self.states[a], self.states[b])
        self.adjacency[a].append((b, cost))
        self.adjacency[b].append((a, cost))
        self.edges[(a, b)] = None
        if not self.lazy:
            self.checked.add((a, b))
        self._union(a, b)

    def remove_edge(self, a: int, b: int) -> None:
        """Drop an edge; the components are recomputed when next asked (union-find
        cannot split)."""
        self.adjacency[a] = [(v, c) for v, c in self.adjacency[a] if v != b]
        self.adjacency[b] = [(v, c) for v, c in self.adjacency[b] if v != a]
        self.edges.pop((a, b), None)
        self.edges.pop((b, a), None)
        self._components_stale = True

    def component(self, vertex: int) -> int:
        if self._components_stale:
            self._component_parent = list(range(len(self)))
            self._components_stale = False
            for u, v in self.edges:
                self._union(u, v)
        return self._root(vertex)

    def _root(self, vertex: int) -> int:
        parent = self._component_parent
        while parent[vertex] != vertex:
            parent[vertex] = parent[parent[vertex]]  # path halving
            vertex = parent[vertex]
        return vertex

    def _union(self, a: int, b: int) -> None:
        root_a, root_b = self.component(a), self.component(b)
        if root_a != root_b:
            self._component_parent[max(root_a, root_b)] = min(root_a, root_b)

    def blocked_steps(self, path: list[int]) -> list[tuple[int, int]]:
        """The steps ``(path[i], path[i+1])`` whose motion is not free in that
        direction (each step checked once): the first one, or for a lazy roadmap
        all of them (one A* run then rules out every blocked edge it took)."""
        first_hit, states, checked = self.si.first_hit, self.states, self.checked
        blocked = []
        for step in zip(path, path[1:]):
            if step in checked:
                continue
            if first_hit(states[step[0]], states[step[1]]) is None:
                checked.add(step)
                continue
            blocked.append(step)
            if not self.lazy:
                break
        return blocked

    def check_around(self, vertex: int) -> None:
        """Check each edge at ``vertex`` not checked yet (from it), dropping the
        blocked ones: where a path's step was blocked, the next path would likely
        try a neighbouring edge through the same obstacle (fewer A* runs)."""
        first_hit, states, checked = self.si.first_hit, self.states, self.checked
        for other, _ in list(self.adjacency[vertex]):
            if (vertex, other) in checked or (other, vertex) in checked:
                continue
            if first_hit(states[vertex], states[other]) is None:
                checked.add((vertex, other))
            else:
                self.remove_edge(vertex, other)

    def shortest_path(self, source: int, target: int) -> list[int] | None:
        """A* with the metric to ``target`` as the heuristic."""
        distance, states, goal = self.si.distance, self.states, self.states[target]
        return astar_search(self.adjacency, source, target,
                            lambda v: distance(states[v], goal))

    def points(self, path: list[int]) -> list[tuple[float, ...]]:
        return [self.states[v] for v in path]

    def edge_states(self) -> tuple[tuple, ...]:
        """``(from, None, to)`` per edge found free, in the order they were added."""
        states, checked = self.states, self.checked
        return tuple((states[a], None, states[b]) for a, b in self.edges
                     if (a, b) in checked or (b, a) in checked)


@dataclass(frozen=True)
class Refinement:
    """How a roadmap keeps growing after its first answer (PRM: not at all)."""

    growth: float = 1.0
    """Between two queries the roadmap grows by this factor (1.0: answer at once)."""
    min_improvement: float = 1.0
    """Grow again while the last growth shortened the path by at least this
    fraction of its length (1.0: never, one growth only)."""
    max_vertices: int = 0
    """Grow only while the grown roadmap stays within this many vertices; this
    binds the first growth too, so a first answer on a big roadmap is final
    (growing it would double the time already spent)."""
    min_vertices: int = 0
    """Below this many vertices, grow again even without improvement: a small
    roadmap's path moves in jumps, and one growth that gains nothing says little."""


def plan_with_roadmap(si: GeometricSpaceInformation, pdef: ProblemDefinition,
                      stop: StopCondition, rng: random.Random,
                      neighbor_count: Callable[[int], int], min_vertices: int,
                      refinement: Refinement, name: str) -> PlanResult:
    """Grow a roadmap until it answers the start-goal query or ``stop`` ends it.

    ``neighbor_count(n)``: how many nearest vertices a new vertex tries to join
    when the roadmap will have ``n`` vertices with it. The first query runs once
    start and goal are connected and the roadmap has ``min_vertices``. After it
    succeeds with ``n`` vertices, the roadmap grows as ``refinement`` says and is
    queried again after each growth (the answer can only get shorter). If
    ``stop`` fires in between, the best answer so far is returned.
    """
    if si.system.kinodynamic:
        raise ValueError(f"{name} plans for geometric systems only")
    began = time.perf_counter()
    roadmap = Roadmap(si)
    goal = si.goal_configuration(pdef.goal, rng)
    roadmap.add_vertex(pdef.start, neighbors=0)
    if goal is None:
        return PlanResult(PlanStatus.UNREACHABLE, si.system, (), (), (), PlanStats(
            0, 1, time.perf_counter() - began), NO_GOAL_CONFIGURATION)
    roadmap.add_vertex(goal, neighbors=1)

    answers = None

    def result(status: PlanStatus, path: list[int] | None, iterations: int, message=""):
        trajectory = () if path is None else tuple(roadmap.points(path))
        first = None if answers is None or answers.found_at is None else answers.found_at - began
        return PlanResult(status, si.system, trajectory, (), roadmap.edge_states(), PlanStats(
            iterations, len(roadmap), time.perf_counter() - began, first), message)

    if pdef.goal.reached(pdef.start):
        return result(PlanStatus.SOLVED, [START], 0)
    if si.certainly_unreachable(pdef.start, pdef.goal, stop.time_is_up):
        return result(PlanStatus.UNREACHABLE, None, 0,
                      "no chain of free cells joins the start and the goal")

    draw_free = si.roadmap_sampler(rng, stop.time_is_up)
    answers = _Answers(roadmap, stop, refinement, min_vertices)
    iterations = 0
    while not answers.final():
        limit = stop.status(iterations)
        if limit is not None:
            if answers.solution is not None:
                return result(PlanStatus.SOLVED, _query(roadmap, stop) or answers.solution,
                              iterations)
            return result(limit, None, iterations)
        iterations += 1
        roadmap.add_vertex(draw_free(), neighbor_count(len(roadmap) + 1))
    return result(PlanStatus.SOLVED, answers.solution, iterations)


class _Answers:
    """When a growing roadmap is queried, and when its answer is final."""

    def __init__(self, roadmap: Roadmap, stop: StopCondition, refinement: Refinement,
                 min_vertices: int):
        self.roadmap, self.stop, self.refinement = roadmap, stop, refinement
        self.solution: list[int] | None = None
        self.found_at: float | None = None
        """perf_counter() at the first answer (the roadmap may grow on for a shorter one)."""
        self.next_query, self.first_try = 0, min_vertices

    def final(self) -> bool:
        """Query the roadmap when it is time; True once the answer is final."""
        roadmap, refinement = self.roadmap, self.refinement
        if self.solution is None:
            if not (len(roadmap) >= self.first_try
                    and roadmap.component(START) == roadmap.component(GOAL)):
                return False
            self.solution = _query(roadmap, self.stop)
            if self.solution is None:
                if roadmap.lazy:
                    # Connected only through edges not yet checked: grow before retrying.
                    self.first_try = math.ceil(len(roadmap) * LAZY_RETRY_GROWTH)
                return False
            self.found_at = time.perf_counter()
            self.next_query = math.ceil(len(roadmap) * refinement.growth)
            # Final if no growth is asked for, if it is the straight line (a single
            # edge: nothing is shorter), or if growing passes the cap.
            return (refinement.growth <= 1.0 or len(self.solution) == 2
                    or self.next_query > refinement.max_vertices)
        if len(roadmap) < self.next_query:
            return False
        shorter = _query(roadmap, self.stop) or self.solution
        distance = roadmap.si.distance
        gain = 1.0 - (path_length(roadmap.points(shorter), distance)
                      / path_length(roadmap.points(self.solution), distance))
        self.solution = shorter
        self.next_query = math.ceil(len(roadmap) * refinement.growth)
        return (gain < refinement.min_improvement and len(roadmap) >= refinement.min_vertices
                or self.next_query > refinement.max_vertices)


def _query(roadmap: Roadmap, stop: StopCondition) -> list[int] | None:
    """A* from start to goal, checking the answer's motions in the direction they
    are travelled; an edge that fails that way (never checked: a lazy roadmap's;
    a rounding tie at a cell's edge; samples that differ the other way round) is
    dropped and the search runs again, until the time is up."""
    runs = 0
    while not stop.time_is_up():
        runs += 1
        path = roadmap.shortest_path(START, GOAL)
        if path is None:
            return None
        blocked = roadmap.blocked_steps(path)
        if not blocked:
            return path
        for a, b in blocked:
            roadmap.remove_edge(a, b)
        if roadmap.lazy and runs >= LAZY_CHECK_AROUND_AFTER:
            for vertex in {v for step in blocked for v in step}:
                roadmap.check_around(vertex)
    return None


@guarded
def solve(si: GeometricSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: PRMParams = PRMParams()) -> PlanResult:
    return plan_with_roadmap(si, pdef, stop, rng, lambda n: params.neighbors, params.min_vertices,
                             Refinement(), "prm")
