"""The grid world of SPEC 1: collision tests for points, sampled and exact segments;
sampling of positions; and the grid-only capabilities planners use when the world
offers them (flood fill, distance along the free cells, the frontier of a tree).

A point collides when it is outside ``[0, W) x [0, H)`` or in a blocked cell
(cells are half-open, SPEC section 1). Two segment tests exist because they
answer different questions:

* :meth:`GridWorld.first_sampled_collision` is the course checker's rule: samples
  at most ``step`` apart, both endpoints included.
* :meth:`GridWorld.first_blocked_cell_on_segment` walks every cell the segment
  touches, so it also catches a segment that cuts a blocked cell's corner between
  two samples. The planner uses it, so no sampling checker can fault its paths.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Sequence

from planning_core.problem import Problem

SAMPLE_STEP = 0.05


@dataclass(frozen=True)
class SegmentHit:
    """Where a segment first enters a blocked cell (or leaves the map)."""

    fraction: float  # of the segment's length, in [0, 1]
    column: int
    row: int


class GridWorld:
    """Occupancy of a :class:`Problem`, with fast lookups for the hot paths."""

    def __init__(self, problem: Problem):
        self.problem = problem
        self.width = problem.width
        self.height = problem.height
        # A list indexes faster than bytes in CPython's inner loops.
        self.blocked = list(problem.blocked)

    def point_free(self, x: float, y: float) -> bool:
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return False
        return not self.blocked[int(y) * self.width + int(x)]

    def point_strictly_inside(self, x: float, y: float) -> bool:
        """Printed points must satisfy ``0 < x < W`` and ``0 < y < H`` (SPEC 2)."""
        return 0.0 < x < self.width and 0.0 < y < self.height

    def sample_open_position(self, rng: random.Random) -> tuple[float, float]:
        """Uniform in the open map ``(0, W) x (0, H)``, blocked cells included, so
        the point prints strictly inside (x first, then y, from ``rng``)."""
        width, height = self.width, self.height
        while True:
            x, y = rng.random() * width, rng.random() * height
            if x > 0.0 and y > 0.0:
                return x, y

    def free_cell_indices(self) -> list[int]:
        """Row-major indices (``row * width + column``) of every free cell."""
        return [index for index, blocked in enumerate(self.problem.blocked) if not blocked]

    def certainly_disconnected(self, a: Sequence[float], b: Sequence[float]) -> bool:
        """No 8-connected chain of free cells joins the cells of positions a and b
        (an over-approximation of where a point moving straight can go)."""
        reach = connected_free_cells(self.problem, (int(a[0]), int(a[1])), diagonal=True)
        return not reach[int(b[1]) * self.width + int(b[0])]

    def distance_along_cells(self):
        """Position -> distance to the problem's goal along the free cells (a
        heuristic; :class:`~planning_core.worlds.grid_distance.CellDistanceToGoal`)."""
        from planning_core.worlds.grid_distance import CellDistanceToGoal
        return CellDistanceToGoal(self.problem)

    def frontier(self):
        """An empty :class:`~planning_core.worlds.grid_frontier.FrontierCells` of this map."""
        from planning_core.worlds.grid_frontier import FrontierCells
        return FrontierCells(self.problem)


    def first_sampled_collision(self, x0: float, y0: float, x1: float, y1: float,
                                step: float = SAMPLE_STEP) -> tuple[float, float] | None:
        """First colliding sample on the segment, sampled from (x0, y0); None if free."""
        length = math.hypot(x1 - x0, y1 - y0)
        pieces = max(1, math.ceil(length / step))
        for k in range(pieces + 1):
            t = k / pieces
            x = x0 + (x1 - x0) * t
            y = y0 + (y1 - y0) * t
            if not self.point_free(x, y):
                return (x, y)
        return None

    def first_blocked_cell_on_segment(self, x0: float, y0: float, x1: float,
                                      y1: float) -> SegmentHit | None:
        """The blocked cell (or outside cell) the segment reaches first, exactly.

        Walks the columns the segment spans; in each, the rows its y-range
        covers. A candidate blocked cell is confirmed with the half-open test
        :func:`segment_meets_cell`, so grazing a blocked cell's right or top
        edge (which belongs to the neighbour) is not a collision.
        """
        width, height, blocked = self.width, self.height, self.blocked
        if not (self.point_free(x0, y0)):
            return SegmentHit(0.0, math.floor(x0), math.floor(y0))
        dx, dy = x1 - x0, y1 - y0
        first_col, last_col = math.floor(x0), math.floor(x1)
        col_step = 1 if last_col >= first_col else -1
        best: SegmentHit | None = None
        for col in range(first_col, last_col + col_step, col_step):
            # Parameter range of this column's slab [col, col+1], clipped to [0, 1].
            if dx == 0.0:
                t_lo, t_hi = 0.0, 1.0
            else:
                ta, tb = (col - x0) / dx, (col + 1 - x0) / dx
                t_lo, t_hi = max(0.0, min(ta, tb)), min(1.0, max(ta, tb))
            ya, yb = y0 + dy * t_lo, y0 + dy * t_hi
            row_a, row_b = math.floor(ya), math.floor(yb)
            row_step = 1 if row_b >= row_a else -1
            # One extra row each way absorbs rounding at exact row boundaries.
            for row in range(row_a - row_step, row_b + 2 * row_step, row_step):
                outside = not (0 <= col < width and 0 <= row < height)
                if not outside and not blocked[row * width + col]:
                    continue
                t = segment_meets_cell(x0, y0, x1, y1, col, row)
                if t is not None and (best is None or t < best.fraction):
                    best = SegmentHit(t, col, row)
            if best is not None:
                return best  # columns are walked in order along the segment
        return best


def segment_meets_cell(x0: float, y0: float, x1: float, y1: float,
                       column: int, row: int) -> float | None:
    """Smallest t in [0, 1] with P(t) in ``[column, column+1) x [row, row+1)``.

    Returns None when no point of the segment lies in the half-open cell. The
    interval bookkeeping keeps track of which ends are open so that touching the
    excluded edges does not count.
    """
    lo, lo_open, hi, hi_open = 0.0, False, 1.0, False
    for start, delta, cell_lo in ((x0, x1 - x0, column), (y0, y1 - y0, row)):
        cell_hi = cell_lo + 1
        if delta == 0.0:
            if not (cell_lo <= start < cell_hi):
                return None
            continue
        t_enter, t_exit = (cell_lo - start) / delta, (cell_hi - start) / delta
        # Moving forward, [lo, hi) maps to [t_enter, t_exit); backward, to (t_exit, t_enter].
        if delta > 0:
            a, a_open, b, b_open = t_enter, False, t_exit, True
        else:
            a, a_open, b, b_open = t_exit, True, t_enter, False
        if a > lo or (a == lo and a_open):
            lo, lo_open = a, a_open
        if b < hi or (b == hi and b_open):
            hi, hi_open = b, b_open
    if lo < hi or (lo == hi and not lo_open and not hi_open):
        return lo
    return None


def connected_free_cells(problem: Problem, start_cell: tuple[int, int],
                         diagonal: bool) -> bytearray:
    """Flood fill of free cells from ``start_cell``: 1 where reachable.

    With ``diagonal`` cells touching only at a corner count as connected: an
    over-approximation of where a point can move, so a goal outside the fill is
    certainly unreachable.
    """
    width, height, blocked = problem.width, problem.height, problem.blocked
    seen = bytearray(width * height)
    col, row = start_cell
    first = row * width + col
    if blocked[first]:
        return seen
    seen[first] = 1
    frontier = [first]
    steps = [(1, 0), (-1, 0), (0, 1), (0, -1)]
    if diagonal:
        steps += [(1, 1), (1, -1), (-1, 1), (-1, -1)]
    while frontier:
        index = frontier.pop()
        row, col = divmod(index, width)
        for dc, dr in steps:
            c, r = col + dc, row + dr
            if 0 <= c < width and 0 <= r < height:
                k = r * width + c
                if not seen[k] and not blocked[k]:
                    seen[k] = 1
                    frontier.append(k)
    return seen
