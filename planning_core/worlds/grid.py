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
from array import array

from planning_core.interrupt import POLL_EVERY, Stop, check
from planning_core.problem import Problem
from planning_core.samplers import uniform

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Final, Optional, Sequence

SAMPLE_STEP = 0.05
# How far a point on the map's left or bottom edge (free, not printable) moves inward:
# far below the 0.1 goal tolerance and far inside its cell.
EDGE_NUDGE: Final = 1e-6
# How far a convex corner whose own cell is blocked moves into the free cell diagonally
# below-left of it: a path bending there is that much longer than through the corner.
CORNER_NUDGE: Final = 1e-9
# The four cells round a grid corner, as bits (GridWorld._corners).
_BELOW_LEFT: Final = 1
_BELOW_RIGHT: Final = 2
_ABOVE_LEFT: Final = 4
_ABOVE_RIGHT: Final = 8


class SegmentHit:
    """Where a segment first enters a blocked cell (or leaves the map). (A plain
    class: compiled, a frozen dataclass is built through its Python ``__init__``.)"""

    def __init__(self, fraction: float, column: int, row: int):
        self.fraction = fraction
        """Of the segment's length, in [0, 1]."""
        self.column = column
        self.row = row


class GridWorld:
    """Occupancy of a :class:`Problem`, with fast lookups for the hot paths."""

    def __init__(self, problem: Problem):
        self.problem = problem
        self.width: int = problem.width
        self.height: int = problem.height
        self.cells: bytes = bytes(problem.blocked)
        """Row-major, from the bottom row: 1 where a cell is blocked. Bytes, so that
        compiled loops index them natively (docs/hot-paths.md)."""

    def point_free(self, x: float, y: float) -> bool:
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return False
        return not self.cells[int(y) * self.width + int(x)]

    def point_strictly_inside(self, x: float, y: float) -> bool:
        """Printed points must satisfy ``0 < x < W`` and ``0 < y < H`` (SPEC 2)."""
        return 0.0 < x < self.width and 0.0 < y < self.height

    def printable_point(self, point: Sequence[float]) -> tuple[float, float]:
        """A free point where a path may end: itself when it prints strictly inside
        the map, else moved ``EDGE_NUDGE`` inward. A free point lies in ``[0, W) x
        [0, H)``, so only ``x == 0`` or ``y == 0`` moves, and it stays in its cell."""
        x, y = point[0], point[1]
        if self.point_strictly_inside(x, y):
            return (x, y)
        return (max(x, EDGE_NUDGE), max(y, EDGE_NUDGE))

    def sample_open_position(self, rng: random.Random) -> tuple[float, float]:
        """Uniform in the open map ``(0, W) x (0, H)``, blocked cells included, so
        the point prints strictly inside (x first, then y, from ``rng``)."""
        width, height = self.width, self.height
        while True:
            x, y = uniform(rng) * width, uniform(rng) * height
            if x > 0.0 and y > 0.0:
                return x, y

    def free_cell_indices(self, stop: Stop = None):
        """Row-major indices (``row * width + column``) of every free cell, in
        increasing order, as a sequence that is not listed
        (:class:`~planning_core.worlds.grid_cells.FreeCells`)."""
        from planning_core.worlds.grid_cells import FreeCells
        return FreeCells(self.problem.blocked, stop)

    def certainly_disconnected(self, a: Sequence[float], b: Sequence[float],
                               stop: Stop = None) -> bool:
        """No 8-connected chain of free cells joins the cells of positions a and b
        (an over-approximation of where a point moving straight can go)."""
        return not cells_joined(self.problem, (int(a[0]), int(a[1])), (int(b[0]), int(b[1])),
                                diagonal=True, stop=stop)

    def distance_along_cells(self, goal: Sequence[float], stop: Stop = None,
                             focus: Optional[Sequence[float]] = None):
        """Position -> distance to the point ``goal`` along the free cells (a
        heuristic; :class:`~planning_core.worlds.grid_distance.CellDistanceToGoal`),
        measured lazily toward the position ``focus`` when one is given."""
        from planning_core.worlds.grid_distance import CellDistanceToGoal
        return CellDistanceToGoal(self.problem, (goal[0], goal[1]), stop=stop,
                                  focus=None if focus is None else (focus[0], focus[1]))

    @staticmethod
    def prepare_distance_along_cells() -> None:
        """Import :meth:`distance_along_cells`'s module, which only guiding planners
        load (start-up), ahead of their planning clock."""
        import planning_core.worlds.grid_distance  # noqa: F401

    def frontier(self):
        """An empty :class:`~planning_core.worlds.grid_frontier.FrontierCells` of this map."""
        from planning_core.worlds.grid_frontier import FrontierCells
        return FrontierCells(self.problem)

    def pinch_points(self) -> list[tuple[float, float]]:
        """The interior grid corners a path may pass only exactly through: the cells
        below-right and above-left of the corner are blocked, the two others free.
        The corner itself lies in the free above-right cell (cells are half-open),
        so a segment from the below-left cell to it and on is free. Row by row from
        the bottom."""
        return [(float(col), float(row)) for col, row, around in self._corners()
                if around == _BELOW_RIGHT | _ABOVE_LEFT]

    def convex_corners(self) -> list[tuple[float, float]]:
        """The interior grid corners with exactly one blocked cell of the four around:
        a shortest path bends round such corners (and through pinches), so a node on
        one is worth having. Each as the free point on it: the corner itself, which
        lies in the cell above-right of it (cells are half-open), or, when that cell
        is the blocked one, the corner moved ``CORNER_NUDGE`` down-left into the free
        cell there. Row by row from the bottom."""
        corners: list[tuple[float, float]] = []
        for col, row, around in self._corners():
            if around == _ABOVE_RIGHT:
                corners.append((col - CORNER_NUDGE, row - CORNER_NUDGE))
            elif around in (_BELOW_LEFT, _BELOW_RIGHT, _ABOVE_LEFT):
                corners.append((float(col), float(row)))
        return corners

    def _corners(self) -> list[tuple[int, int, int]]:
        """Each interior grid corner with a blocked cell round it, row by row from the
        bottom: (column, row, which of the four are blocked, as ``_BELOW_LEFT`` ...
        bits)."""
        width, cells = self.width, self.cells
        corners: list[tuple[int, int, int]] = []
        for row in range(1, self.height):
            above = row * width
            below = above - width
            for col in range(1, width):
                around = ((_BELOW_LEFT if cells[below + col - 1] else 0)
                          | (_BELOW_RIGHT if cells[below + col] else 0)
                          | (_ABOVE_LEFT if cells[above + col - 1] else 0)
                          | (_ABOVE_RIGHT if cells[above + col] else 0))
                if around:
                    corners.append((col, row, around))
        return corners


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
        width, height, blocked = self.width, self.height, self.cells
        if not (self.point_free(x0, y0)):
            return SegmentHit(0.0, math.floor(x0), math.floor(y0))
        dx, dy = x1 - x0, y1 - y0
        first_col, last_col = math.floor(x0), math.floor(x1)
        col_step = 1 if last_col >= first_col else -1
        best: SegmentHit | None = None
        # Columns first_col .. last_col, and rows below, by while loops: compiled, a
        # range with a step known only at run time is a generic range object.
        col = first_col - col_step
        while col != last_col:
            col += col_step
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
            row, last_row = row_a - 2 * row_step, row_b + row_step
            while row != last_row:
                row += row_step
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
    met, lo, lo_open, hi, hi_open = _narrow(0.0, False, 1.0, False, x0, x1 - x0, column)
    if not met:
        return None
    met, lo, lo_open, hi, hi_open = _narrow(lo, lo_open, hi, hi_open, y0, y1 - y0, row)
    if not met:
        return None
    if lo < hi or (lo == hi and not lo_open and not hi_open):
        return lo
    return None


def _narrow(lo: float, lo_open: bool, hi: float, hi_open: bool, start: float, delta: float,
            cell_lo: int) -> tuple[bool, float, bool, float, bool]:
    """The interval of t (ends ``lo``, ``hi``, each open or not) narrowed to where
    ``start + t * delta`` lies in ``[cell_lo, cell_lo + 1)``; False first when nowhere.
    Moving forward, ``[cell_lo, cell_hi)`` maps to ``[t_enter, t_exit)``; backward, to
    ``(t_exit, t_enter]``: the open ends keep touching an excluded edge from counting."""
    cell_hi = cell_lo + 1
    if delta == 0.0:
        return cell_lo <= start < cell_hi, lo, lo_open, hi, hi_open
    t_enter, t_exit = (cell_lo - start) / delta, (cell_hi - start) / delta
    if delta > 0:
        a, a_open, b, b_open = t_enter, False, t_exit, True
    else:
        a, a_open, b, b_open = t_exit, True, t_enter, False
    if a > lo or (a == lo and a_open):
        lo, lo_open = a, a_open
    if b < hi or (b == hi and b_open):
        hi, hi_open = b, b_open
    return True, lo, lo_open, hi, hi_open


_SIDE_STEPS: Final = ((1, 0), (-1, 0), (0, 1), (0, -1))
_CORNER_STEPS: Final = ((1, 1), (1, -1), (-1, 1), (-1, -1))


def _steps(diagonal: bool) -> tuple[tuple[int, int], ...]:
    return _SIDE_STEPS + _CORNER_STEPS if diagonal else _SIDE_STEPS


def connected_free_cells(problem: Problem, start_cell: tuple[int, int],
                         diagonal: bool, stop: Stop = None) -> bytearray:
    """Flood fill of free cells from ``start_cell``: 1 where reachable.

    With ``diagonal`` cells touching only at a corner count as connected: an
    over-approximation of where a point can move, so a goal outside the fill is
    certainly unreachable. ``stop`` is asked every POLL_EVERY cells
    (:mod:`planning_core.interrupt`).
    """
    width, height = problem.width, problem.height
    blocked = bytes(problem.blocked)  # typed: compiled, the fill indexes it natively
    seen = bytearray(width * height)
    col, row = start_cell
    first = row * width + col
    if blocked[first]:
        return seen
    seen[first] = 1
    frontier = array("i", [first])  # 4 bytes a cell, not a list's 36
    steps = _steps(diagonal)
    countdown = POLL_EVERY
    while frontier:
        countdown -= 1
        if not countdown:
            countdown = POLL_EVERY
            check(stop)
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


def _toward_orders(steps) -> dict[tuple[int, int], tuple[tuple[int, int], ...]]:
    """For each sign pair (sx, sy) of the way to a target, the steps from the
    one leading farthest away to the one leading most toward it."""
    return {(sx, sy): tuple(sorted(steps, key=lambda step: step[0] * sx + step[1] * sy))
            for sx in (-1, 0, 1) for sy in (-1, 0, 1)}


_TOWARD = {diagonal: _toward_orders(_steps(diagonal)) for diagonal in (False, True)}


def cells_joined(problem: Problem, a_cell: tuple[int, int], b_cell: tuple[int, int],
                 diagonal: bool, stop: Stop = None) -> bool:
    """Whether a chain of free cells joins ``a_cell`` and ``b_cell`` (the
    neighbours of :func:`connected_free_cells`).

    Two fills, one from each cell, take turns one cell at a time, each depth
    first and trying first the step toward the other's cell. The first to touch
    a cell the other has filled proves a chain; the first with nothing left to
    fill proves there is none. So a goal walled into a small room is found out
    after about that room's cells, and an open map after about the cells of one
    chain, where one full fill would visit every cell joined to the start.
    """
    width, height = problem.width, problem.height
    blocked = bytes(problem.blocked)  # typed: compiled, the fill indexes it natively
    a = a_cell[1] * width + a_cell[0]
    b = b_cell[1] * width + b_cell[0]
    if blocked[a] or blocked[b]:
        return False
    if a == b:
        return True
    mark = bytearray(width * height)  # 1: filled from a, 2: from b
    mark[a], mark[b] = 1, 2
    orders: dict[tuple[int, int], tuple[tuple[int, int], ...]] = _TOWARD[diagonal]
    from_a, from_b = array("i", [a]), array("i", [b])
    countdown = POLL_EVERY
    while True:
        countdown -= 1
        if not countdown:
            countdown = POLL_EVERY
            check(stop)
        if not from_a:
            return False
        if _fill_next(from_a, b_cell, 1, 2, mark, blocked, width, height, orders):
            return True
        if not from_b:
            return False
        if _fill_next(from_b, a_cell, 2, 1, mark, blocked, width, height, orders):
            return True


def _fill_next(stack: Any, target: tuple[int, int], own: int, other: int, mark: bytearray,
               blocked: bytes, width: int, height: int,
               orders: dict[tuple[int, int], tuple[tuple[int, int], ...]]) -> bool:
    """One step of a :func:`cells_joined` fill: pop a cell of ``stack`` and fill its
    free neighbours, the step toward ``target`` last (popped next); True when a
    neighbour is the other fill's. (A function of typed arguments: compiled, the
    loop runs natively.)"""
    tc, tr = target
    index = int(stack.pop())
    row = index // width
    col = index - row * width
    for dc, dr in orders[(tc > col) - (tc < col), (tr > row) - (tr < row)]:
        c, r = col + dc, row + dr
        if 0 <= c < width and 0 <= r < height:
            k = r * width + c
            filled = mark[k]
            if filled == other:
                return True
            if not filled and not blocked[k]:
                mark[k] = own
                stack.append(k)
    return False
