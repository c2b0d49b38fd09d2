"""The shortest collision-free path for the point vehicle: the optimum path lengths are judged by.

A blocked cell is a closed unit square, and a path may touch but not enter the
interior of their union (the closure of the free space). Every path the validator
accepts with ``-strict`` avoids the half-open blocked cells of SPEC 1 and so also
these interiors: the length found here is a lower bound on every valid answer,
and valid paths come arbitrarily close to it (shift the touching points off the
walls by a hair). It is the yardstick for "how much shorter could this path be".

Method: the shortest path among polygonal obstacles bends only at obstacle
vertices that point into the free space, so it is a shortest path in the
visibility graph of the start, the goal and those grid points (one blocked cell
of the four around them, or two diagonal ones). A* over that graph with the
straight-line heuristic, its edges tested lazily when a vertex is expanded, and
only edges tangent to the obstacle at their corner ends are tested at all (a
taut path cannot enter a corner's blocked cell on either side of the bend).
numpy filters the candidate edges per expansion; the exact test is plain Python.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

import numpy as np

from benchmarks.generator import PROBLEMS_DIR, problem_id, suite_files
from planning_core.worlds.grid_distance import CellDistanceToGoal
from planning_core.problem import Problem
from planning_core.problem_text import parse_problem

# Crossings of grid lines closer than this (in segment parameter) are one crossing,
# and a point this close to a grid line lies on it. Both only ever let a segment
# through, so rounding can make the bound lower, never higher.
_TOUCH = 1e-9


@dataclass(frozen=True)
class ShortestPath:
    """The optimum: its length and its corner points, start and goal included."""

    length: float
    points: tuple[tuple[float, float], ...]
    edges_tested: int  # exact segment tests run (the work done)


class _OpenObstacles:
    """The interior of the union of blocked cells (outside the map counts as blocked)."""

    def __init__(self, problem: Problem):
        self.width = problem.width
        self.height = problem.height
        self.blocked = problem.blocked

    def cell_blocked(self, column: int, row: int) -> bool:
        if not (0 <= column < self.width and 0 <= row < self.height):
            return True
        return bool(self.blocked[row * self.width + column])

    def point_inside(self, x: float, y: float) -> bool:
        """Whether (x, y), the midpoint of a piece between grid crossings, is inside."""
        column, row = math.floor(x), math.floor(y)
        on_vertical = abs(x - round(x)) < _TOUCH
        on_horizontal = abs(y - round(y)) < _TOUCH
        if on_vertical and on_horizontal:
            line_x, line_y = round(x), round(y)
            return all(self.cell_blocked(line_x - a, line_y - b) for a in (0, 1) for b in (0, 1))
        if on_vertical:
            line_x = round(x)
            return self.cell_blocked(line_x - 1, row) and self.cell_blocked(line_x, row)
        if on_horizontal:
            line_y = round(y)
            return self.cell_blocked(column, line_y - 1) and self.cell_blocked(column, line_y)
        return self.cell_blocked(column, row)

    def segment_clear(self, ax: float, ay: float, bx: float, by: float) -> bool:
        """Whether the segment stays out of the interior of every blocked cell.

        Walks the segment from a to b, cut where it crosses grid lines; each
        piece lies in one cell (or along one grid line), which its midpoint
        identifies. The walk stops at the first piece inside.
        """
        dx, dy = bx - ax, by - ay
        # Next grid line crossed in x and in y, as the segment parameter t.
        step_x = (dx > 0) - (dx < 0)
        step_y = (dy > 0) - (dy < 0)
        line_x = math.floor(ax) + 1 if step_x > 0 else math.ceil(ax) - 1
        line_y = math.floor(ay) + 1 if step_y > 0 else math.ceil(ay) - 1
        cross_x = (line_x - ax) / dx if step_x else math.inf
        cross_y = (line_y - ay) / dy if step_y else math.inf
        done = 0.0
        while True:
            cut = min(cross_x, cross_y, 1.0)
            if cut - done > _TOUCH:
                middle = (done + cut) / 2
                if self.point_inside(ax + dx * middle, ay + dy * middle):
                    return False
                done = cut
            if cut >= 1.0:
                return True
            if cross_x == cut:
                line_x += step_x
                cross_x = (line_x - ax) / dx
            else:
                line_y += step_y
                cross_y = (line_y - ay) / dy


def _corner_vertices(obstacles: _OpenObstacles) -> tuple[list[tuple[int, int]],
                                                         list[tuple[int, int]]]:
    """Grid points a shortest path can bend at, with the sign of their blocked quadrant.

    One blocked cell of four: a convex corner; the quadrant's signs (sx, sy) say
    where the cell lies. Two diagonal blocked cells: a pinch, (0, 0) (no pruning).
    """
    points, quadrants = [], []
    for x in range(1, obstacles.width):
        for y in range(1, obstacles.height):
            around = {(sx, sy): obstacles.cell_blocked(x + (sx - 1) // 2, y + (sy - 1) // 2)
                      for sx in (-1, 1) for sy in (-1, 1)}
            count = sum(around.values())
            if count == 1:
                points.append((x, y))
                quadrants.append(next(key for key, is_blocked in around.items() if is_blocked))
            elif count == 2 and around[(1, 1)] == around[(-1, -1)]:
                points.append((x, y))
                quadrants.append((0, 0))
    return points, quadrants


def _feasible_length(problem: Problem, obstacles: _OpenObstacles) -> float:
    """The length of some valid path (an upper bound on the optimum), inf if none.

    The cheapest chain of free cells to the goal's cell, through their centres,
    pulled tight greedily: from each point on, the last point of the chain that
    is still in sight. It prunes the search to the ellipse of points whose
    detour is no longer than this path.
    """
    chain = CellDistanceToGoal(problem, problem.goal).chain_from(*problem.start)
    if chain is None:
        return math.inf
    route = [problem.start, *((c + 0.5, r + 0.5) for c, r in chain), problem.goal]
    length, here = 0.0, 0
    while here < len(route) - 1:
        there = here + 1
        while there + 1 < len(route) and obstacles.segment_clear(*route[here], *route[there + 1]):
            there += 1
        length += math.dist(route[here], route[there])
        here = there
    return length


def shortest_path(problem: Problem, max_corners: float = math.inf) -> ShortestPath | None:
    """The shortest path from start to goal, or None when the goal is unreachable or the
    map has more than ``max_corners`` corners (not searched)."""
    obstacles = _OpenObstacles(problem)
    corners, quadrants = _corner_vertices(obstacles)
    if len(corners) > max_corners:
        return None
    # Relative slack: the optimum may equal the bound up to rounding. (No bound
    # when the chain of cells finds no way: a diagonal pinch may still pass.)
    bound = _feasible_length(problem, obstacles) * (1 + 1e-9)
    points = [problem.start, problem.goal, *corners]
    point_list = [(float(x), float(y)) for x, y in points]  # plain floats for the exact test
    xs = np.array([p[0] for p in points], dtype=float)
    ys = np.array([p[1] for p in points], dtype=float)
    # Start and goal are no bends: quadrant (0, 0), like a pinch's, makes the
    # tangent test's product 0, which passes.
    sxs = np.array([0, 0, *(q[0] for q in quadrants)], dtype=float)
    sys_ = np.array([0, 0, *(q[1] for q in quadrants)], dtype=float)
    to_goal = np.hypot(xs - problem.goal[0], ys - problem.goal[1])
    cost = np.full(len(points), math.inf)
    cost[0] = 0.0
    parent = np.full(len(points), -1)
    closed = np.zeros(len(points), dtype=bool)
    frontier = [(to_goal[0], 0)]
    tested = 0
    while frontier:
        _, vertex = heapq.heappop(frontier)
        if closed[vertex]:
            continue
        closed[vertex] = True
        if vertex == 1:
            break
        dx, dy = xs - xs[vertex], ys - ys[vertex]
        through = cost[vertex] + np.hypot(dx, dy)
        wanted = (~closed) & (through < cost) & (through + to_goal <= min(bound, cost[1]))
        # Tangent at the far end and at this one.
        wanted &= (dx * sxs * dy * sys_ <= 0) & (dx * sxs[vertex] * dy * sys_[vertex] <= 0)
        x0, y0 = point_list[vertex]
        for other in np.flatnonzero(wanted).tolist():
            tested += 1
            if obstacles.segment_clear(x0, y0, *point_list[other]):
                cost[other] = through[other]
                parent[other] = vertex
                heapq.heappush(frontier, (through[other] + to_goal[other], other))
    if not math.isfinite(cost[1]):
        return None
    path = [1]
    while path[-1] != 0:
        path.append(int(parent[path[-1]]))
    return ShortestPath(float(cost[1]),
                        tuple((float(xs[i]), float(ys[i])) for i in reversed(path)), tested)


MAX_CORNERS = 20_000
"""The reports' yardstick leaves out maps with more corners: the search's work grows
about as their square (random-d35-200's 19,362 take about a minute; the 500-cell maps
have 44-122 thousand)."""


def shortest_lengths(problem_ids: Iterable[str],
                     directory: Path = PROBLEMS_DIR) -> dict[str, float]:
    """The shortest path length of each named problem of the suite in ``directory``.

    Problems whose file is not there (a suite regenerated since the run), whose goal
    cannot be reached or which have more than ``MAX_CORNERS`` corners are left out.
    """
    wanted = set(problem_ids)
    lengths = {}
    for path in suite_files(directory):
        name = problem_id(path)
        if name in wanted:
            found = shortest_path(parse_problem(path.read_text()), MAX_CORNERS)
            if found is not None:
                lengths[name] = found.length
    return lengths
