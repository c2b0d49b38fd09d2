"""PRM, the probabilistic roadmap (Kavraki, Svestka, Latombe & Overmars 1996,
"Probabilistic roadmaps for path planning in high-dimensional configuration
spaces", IEEE Trans. Robotics and Automation), for the point vehicle; and the
roadmap machinery that PRM* (:mod:`rrt_cli.planners.prmstar`) shares.

Construction and query are separate steps, run in a loop as OMPL's PRM does:

* Construction adds vertices drawn uniformly from the free space and joins each
  new vertex to its ``k`` nearest roadmap vertices by every straight segment
  that is exactly collision-free. A union-find structure tracks the connected
  components as edges are added.
* The query (A* with the Euclidean heuristic, :mod:`rrt_cli.graph_search`)
  runs once the start and goal vertices are in one component and the roadmap
  has at least ``min_vertices`` vertices; until then construction goes on, one
  vertex at a time, until the :class:`StopCondition` ends it.

The start and the goal are roadmap vertices from the beginning, so the path
ends exactly at the goal (nudged into the map only when the goal sits on the
map's left or bottom edge). The output's tree section is the roadmap's edges.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from typing import Callable

from planning_core.space_information import SpaceInformation
from planning_core.worlds.grid import GridWorld
from planning_core.worlds.grid_cells import sample_free_point
from rrt_cli.graph_search import astar
from planning_core.nearest.quadtree import QuadtreeNearest
from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition, guarded
from rrt_cli.planners.point_common import first_blocked_segment, path_length

START, GOAL = 0, 1  # the roadmap's first two vertices


@dataclass(frozen=True)
class PRMParams:
    neighbors: int = 10
    """k: each new vertex tries to connect to its k nearest vertices (OMPL's default, 10)."""
    min_vertices: int = 0
    """The query waits until the roadmap has this many vertices (0: query as soon
    as start and goal are connected)."""


Params = PRMParams


class Roadmap:
    """An undirected graph of free points joined by exactly collision-free segments."""

    def __init__(self, world: GridWorld):
        self.world = world
        self.index = QuadtreeNearest(world.width, world.height)
        self.xs, self.ys = self.index.xs, self.index.ys  # shared, not copied
        self.adjacency: list[list[tuple[int, float]]] = []
        self.edges: list[tuple[int, int]] = []
        self._component_parent: list[int] = []

    def __len__(self) -> int:
        return len(self.xs)

    def add_vertex(self, x: float, y: float, neighbors: int) -> int:
        """Insert (x, y) and join it to each of its ``neighbors`` nearest vertices
        whose segment to it is free; returns the new vertex."""
        candidates = self.index.k_nearest(x, y, neighbors) if len(self) else []
        vertex = self.index.add(x, y)
        self.adjacency.append([])
        self._component_parent.append(vertex)
        blocked_on = self.world.first_blocked_cell_on_segment
        xs, ys = self.xs, self.ys
        for other in candidates:
            ox, oy = xs[other], ys[other]
            if blocked_on(x, y, ox, oy) is None:
                self.add_edge(vertex, other)
        return vertex

    def add_edge(self, a: int, b: int) -> None:
        cost = math.hypot(self.xs[a] - self.xs[b], self.ys[a] - self.ys[b])
        self.adjacency[a].append((b, cost))
        self.adjacency[b].append((a, cost))
        self.edges.append((a, b))
        root_a, root_b = self.component(a), self.component(b)
        if root_a != root_b:
            self._component_parent[max(root_a, root_b)] = min(root_a, root_b)

    def remove_edge(self, a: int, b: int) -> None:
        """Drop an edge and recompute the components (union-find cannot split)."""
        self.adjacency[a] = [(v, c) for v, c in self.adjacency[a] if v != b]
        self.adjacency[b] = [(v, c) for v, c in self.adjacency[b] if v != a]
        self.edges = [e for e in self.edges if e not in ((a, b), (b, a))]
        self._component_parent = list(range(len(self)))
        for u, v in self.edges:
            root_u, root_v = self.component(u), self.component(v)
            if root_u != root_v:
                self._component_parent[max(root_u, root_v)] = min(root_u, root_v)

    def component(self, vertex: int) -> int:
        parent = self._component_parent
        while parent[vertex] != vertex:
            parent[vertex] = parent[parent[vertex]]  # path halving
            vertex = parent[vertex]
        return vertex

    def shortest_path(self, source: int, target: int) -> list[int] | None:
        return astar(self.adjacency, self.xs, self.ys, source, target)

    def points(self, path: list[int]) -> list[tuple[float, float]]:
        return [(self.xs[v], self.ys[v]) for v in path]

    def edge_states(self) -> tuple[tuple, ...]:
        """``(from, None, to)`` per edge, in the order they were added."""
        xs, ys = self.xs, self.ys
        return tuple(((xs[a], ys[a]), None, (xs[b], ys[b])) for a, b in self.edges)


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


def plan_with_roadmap(si: SpaceInformation, stop: StopCondition, rng: random.Random,
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
    world = si.world
    roadmap = Roadmap(world)
    roadmap.add_vertex(*si.start, neighbors=0)
    roadmap.add_vertex(*world.printable_point(si.goal.point), neighbors=1)

    def result(status: PlanStatus, path: list[int] | None, iterations: int, message=""):
        trajectory = () if path is None else tuple(roadmap.points(path))
        return PlanResult(status, si.system, trajectory, (), roadmap.edge_states(), PlanStats(
            iterations, len(roadmap), time.perf_counter() - began), message)

    if si.goal.reached(si.start):
        return result(PlanStatus.SOLVED, [START], 0)
    if si.goal_certainly_unreachable(stop.time_is_up):
        return result(PlanStatus.UNREACHABLE, None, 0,
                      "no chain of free cells joins the start and the goal")

    free_cells = world.free_cell_indices(stop.time_is_up)
    width = world.width
    iterations = 0
    solution: list[int] | None = None
    next_query = 0
    while True:
        if solution is None:
            if (len(roadmap) >= min_vertices
                    and roadmap.component(START) == roadmap.component(GOAL)):
                solution = _query(roadmap, world)
                if solution is not None:
                    next_query = math.ceil(len(roadmap) * refinement.growth)
                    # Final if no growth is asked for, if it is the straight line
                    # (a single edge: nothing is shorter), or if growing passes the cap.
                    if (refinement.growth <= 1.0 or len(solution) == 2
                            or next_query > refinement.max_vertices):
                        return result(PlanStatus.SOLVED, solution, iterations)
        elif len(roadmap) >= next_query:
            shorter = _query(roadmap, world) or solution
            gain = 1.0 - (path_length(roadmap.points(shorter))
                          / path_length(roadmap.points(solution)))
            solution = shorter
            next_query = math.ceil(len(roadmap) * refinement.growth)
            if (gain < refinement.min_improvement and len(roadmap) >= refinement.min_vertices
                    or next_query > refinement.max_vertices):
                return result(PlanStatus.SOLVED, solution, iterations)
        limit = stop.status(iterations)
        if limit is not None:
            if solution is not None:
                return result(PlanStatus.SOLVED, _query(roadmap, world) or solution, iterations)
            return result(limit, None, iterations)
        iterations += 1
        x, y = sample_free_point(rng, free_cells, width)
        roadmap.add_vertex(x, y, neighbor_count(len(roadmap) + 1))


def _query(roadmap: Roadmap, world: GridWorld) -> list[int] | None:
    """A* from start to goal, re-checking the answer's segments in the direction
    they are travelled; an edge that fails that way (a rounding tie at a cell's
    edge) is dropped and the search runs again."""
    while True:
        path = roadmap.shortest_path(START, GOAL)
        if path is None:
            return None
        points = roadmap.points(path)
        bad = first_blocked_segment(world, points)
        if bad is None:
            return path
        roadmap.remove_edge(path[bad], path[bad + 1])


@guarded
def solve(si: SpaceInformation, stop: StopCondition, rng: random.Random,
          params: PRMParams = PRMParams()) -> PlanResult:
    return plan_with_roadmap(si, stop, rng, lambda n: params.neighbors, params.min_vertices,
                             Refinement(), "prm")
