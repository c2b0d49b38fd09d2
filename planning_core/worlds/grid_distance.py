"""Distance to the goal through the free cells: a heuristic for guided planners.

On a maze the straight-line distance to the goal says little about how far the
goal really is. :class:`CellDistanceToGoal` runs Dijkstra once over the free
cells, from the goal's cell outward (8 neighbours; a diagonal step only when
both cells beside it are free, so no step cuts a blocked corner), and answers
for any position in a free cell:

* in the goal's cell: the straight-line distance to the goal;
* elsewhere: the cell's distance (between cell centres, along the cheapest
  chain) minus the position's progress, inside its cell, toward the next cell of
  that chain -- so the value falls smoothly as a vehicle moves along the chain.

It is a heuristic, not a bound: it neither under- nor over-estimates reliably
(a spaceship can hop a thin wall between slices, and the chain of centres is
not the shortest curve). A position in a blocked cell, outside the map, or in a
free region cut off from the goal gets ``unreachable`` (a large finite value,
so sums and comparisons stay plain floats).
"""

from __future__ import annotations

import math
from array import array
from typing import Final, Sequence

from planning_core.heap import HeapEntry, heap_pop, heap_push, heapify
from planning_core.interrupt import POLL_EVERY, Stop, check
from planning_core.problem import Problem

_DIAGONAL = math.sqrt(2.0)
# Dijkstra's steps (column, row, cost); a cell's ``way`` is 1 + the index of the
# step that last lowered its distance (0: none), so 1 byte a cell says where its
# chain goes next.
_STEPS: Final = ((1, 0, 1.0), (-1, 0, 1.0), (0, 1, 1.0), (0, -1, 1.0),
          (1, 1, _DIAGONAL), (1, -1, _DIAGONAL), (-1, 1, _DIAGONAL), (-1, -1, _DIAGONAL))
# Unit vector from a cell's centre toward the next cell of its chain, by ``way``
# (the chain through step (dc, dr) goes back by (-dc, -dr)).
_TOWARD_X: Final = (0.0,) + tuple(-dc / cost for dc, _, cost in _STEPS)
_TOWARD_Y: Final = (0.0,) + tuple(-dr / cost for _, dr, cost in _STEPS)


FOCUS_TIE: Final = 1e-6
"""The lazy search's heuristic weight above 1 (its tie-break; see CellDistanceToGoal)."""
RUN_CELLS: Final = 64
"""How far a guided target may lie down a straight run of the chain, in cells."""


def _octile(dx: int, dy: int) -> float:
    """The length of the shortest 8-connected chain of (dx, dy) cells, ignoring walls."""
    dx, dy = abs(dx), abs(dy)
    return max(dx, dy) + (_DIAGONAL - 1.0) * min(dx, dy)


def _weighted_octile(dx: int, dy: int) -> float:
    """The lazy search's heuristic: :func:`_octile` weighted by ``1 + FOCUS_TIE``."""
    return _octile(dx, dy) * (1.0 + FOCUS_TIE)


def chain_step(chain: list[tuple[int, int]], k: int) -> tuple[int, int]:
    """The step (columns, rows) from ``chain[k - 1]`` to ``chain[k]``."""
    return (chain[k][0] - chain[k - 1][0], chain[k][1] - chain[k - 1][1])


def straight_run_end(chain: list[tuple[int, int]], cells: int) -> int:
    """The index ``cells`` steps down ``chain`` (its last at most), or further while
    the chain goes on by the same step: a guided target at the end of a straight run
    (a corridor's, an open map's diagonal) is reached in one extension."""
    end = min(cells, len(chain) - 1)
    if end > 0:
        step = chain_step(chain, end)
        while end + 1 < len(chain) and chain_step(chain, end + 1) == step:
            end += 1
    return end


class CellDistanceToGoal:
    """Dijkstra from the goal's cell over the free cells; per cell a double (its
    distance), a byte (its way) and a byte (closed), 10 bytes a cell. ``stop`` is asked
    every POLL_EVERY heap pops (:mod:`planning_core.interrupt`).

    Without ``focus`` the search runs to the end at construction. With a ``focus``
    (a position: a tree's root) it is lazy: nothing is measured until a query, and a
    query whose cell is not closed resumes the search as A* toward that cell (first
    the focus's) until it is. A* keeps what it closed whatever cell it aims at, so a
    map whose queried ways are short and open is measured along them only. The
    heuristic is the octile distance to the aimed-at cell, weighted by
    ``1 + FOCUS_TIE``: of cells on equally short ways (an open map's straight ways
    all tie) the one nearer the aim comes first. A closed cell's distance is then the
    least to within ``FOCUS_TIE`` relative; its chain, and so its value inside the
    cell, may differ from the eager search's where chains tie."""

    def __init__(self, problem: Problem, goal: tuple[float, float], unreachable: float = 1e12,
                 stop: Stop = None, focus: tuple[float, float] | None = None):
        width, height = problem.width, problem.height
        self._blocked = bytes(problem.blocked)  # typed: compiled, the search indexes it natively
        self.width: int = width
        self.height: int = height
        self.goal = goal
        self.unreachable = unreachable
        gx, gy = goal
        self.goal_cell = int(gy) * width + int(gx)
        self.cell_distance = array("d", [math.inf]) * (width * height)
        self._way = bytearray(width * height)
        self._closed = bytearray(width * height)
        self._queue: list[HeapEntry] = []  # (distance, plus the heuristic when lazy; cell)
        self._steps: list[tuple[int, int, float, int]] = [
            (dc, dr, cost, code) for code, (dc, dr, cost) in enumerate(_STEPS, 1)]
        self._stop = stop
        self._lazy = focus is not None
        self._focus_col: int = int(focus[0]) if focus is not None else 0
        self._focus_row: int = int(focus[1]) if focus is not None else 0
        if not self._blocked[self.goal_cell]:
            self.cell_distance[self.goal_cell] = 0.0
            self._queue.append(HeapEntry(0.0, self.goal_cell))
        if not self._lazy:
            self._settle(-1)

    def _settle(self, until: int) -> None:
        """Close cells, nearest first, until ``until`` is closed or none is left open
        (``until`` -1: all of them). The lazy search first turns toward ``until``."""
        width, height = self.width, self.height
        if self._lazy and until >= 0:
            self._refocus(until % width, until // width)
        blocked, closed = self._blocked, self._closed
        distance, way, queue = self.cell_distance, self._way, self._queue
        lazy, stop, steps = self._lazy, self._stop, self._steps
        countdown = POLL_EVERY
        while queue:
            countdown -= 1
            if not countdown:
                countdown = POLL_EVERY
                check(stop)
            index = heap_pop(queue).order
            if closed[index]:
                continue
            closed[index] = 1
            d: float = distance[index]
            row = index // width
            col = index - row * width
            for dc, dr, cost, code in steps:
                c, r = col + dc, row + dr
                if not (0 <= c < width and 0 <= r < height):
                    continue
                k = r * width + c
                if blocked[k] or closed[k]:
                    continue
                if dc and dr and (blocked[row * width + c] or blocked[r * width + col]):
                    continue
                reached = d + cost
                if reached < distance[k]:
                    distance[k] = reached
                    way[k] = code  # k's chain goes back through index
                    key = reached + _weighted_octile(c - self._focus_col, r - self._focus_row) \
                        if lazy else reached
                    heap_push(queue, HeapEntry(key, k))
            if index == until:
                return

    def _refocus(self, col: int, row: int) -> None:
        """Aim the lazy search at cell (col, row): the open cells' keys measured again
        toward it. Closed cells keep their distances (least whatever the heuristic,
        A*'s own invariant), so each query walks from what is closed toward its cell.
        Asks ``stop`` as the search does; cut short, the search is as it was."""
        if (col, row) == (self._focus_col, self._focus_row):
            return
        width, closed, distance, stop = self.width, self._closed, self.cell_distance, self._stop
        seen: set[int] = set()
        queue: list[HeapEntry] = []
        countdown = POLL_EVERY
        for entry in self._queue:
            countdown -= 1
            if not countdown:
                countdown = POLL_EVERY
                check(stop)
            k = entry.order
            if closed[k] or k in seen:
                continue
            seen.add(k)
            queue.append(HeapEntry(distance[k] + _weighted_octile(k % width - col,
                                                                  k // width - row), k))
        heapify(queue)
        self._queue, self._focus_col, self._focus_row = queue, col, row

    def _closed_cell(self, x: float, y: float) -> int:
        """(x, y)'s cell, closed by the search when it is joined to the goal's; -1
        outside the map or blocked."""
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return -1
        index = int(y) * self.width + int(x)
        if self._blocked[index]:
            return -1
        if not self._closed[index]:
            self._settle(index)
        return index

    def bound(self, x: float, y: float) -> float:
        """At most :meth:`__call__`'s value, without a search: the octile distance
        between the cells less the most a position moves inside its cell."""
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return self.unreachable
        octile = _octile(int(x) - self.goal_cell % self.width,
                         int(y) - self.goal_cell // self.width)
        return octile * (1.0 - 1e-9) - _DIAGONAL / 2.0 - 1e-9

    def __call__(self, x: float, y: float) -> float:
        index = self._closed_cell(x, y)
        if index < 0:
            return self.unreachable
        if index == self.goal_cell:
            return math.hypot(x - self.goal[0], y - self.goal[1])
        d: float = self.cell_distance[index]
        if d == math.inf:
            return self.unreachable
        # Progress inside the cell toward the next one, from the cell's centre.
        way: int = self._way[index]
        return d - ((x - int(x) - 0.5) * _TOWARD_X[way] + (y - int(y) - 0.5) * _TOWARD_Y[way])

    def ahead_of(self, state: Sequence[float], cells: int) -> tuple[float, float] | None:
        """The centre of the cell ``cells`` steps down the cheapest chain from the
        state's cell, or further while the chain goes straight on
        (:func:`straight_run_end`); the goal itself when that is the goal's cell. None
        when the state's cell has no chain (RRT*'s guided target)."""
        chain = self.chain_ahead(state[0], state[1], max(cells, RUN_CELLS))
        if chain is None:
            return None
        col, row = chain[straight_run_end(chain, cells)]
        if row * self.width + col == self.goal_cell:
            return self.goal
        return (col + 0.5, row + 0.5)

    def chain_ahead(self, x: float, y: float, cells: int) -> list[tuple[int, int]] | None:
        """The first ``cells + 1`` cells (column, row) of :meth:`chain_from`'s chain, or
        fewer when it reaches the goal's cell sooner; a walk of at most ``cells`` steps."""
        index = self._chain_start(x, y)
        if index < 0:
            return None
        chain = []
        for _ in range(cells + 1):
            row, col = divmod(index, self.width)
            chain.append((col, row))
            if index == self.goal_cell:
                break
            index = self._next_cell(index)
        return chain

    def chain_from(self, x: float, y: float) -> list[tuple[int, int]] | None:
        """The cells (column, row) of the cheapest chain from (x, y)'s cell to the goal's.

        Consecutive cells share a side, or a corner with both side cells free, so
        the polyline through their centres stays in free cells. None when (x, y)
        has no chain (blocked, outside, or cut off from the goal).
        """
        index = self._chain_start(x, y)
        if index < 0:
            return None
        chain = []
        while True:
            row, col = divmod(index, self.width)
            chain.append((col, row))
            if index == self.goal_cell:
                return chain
            index = self._next_cell(index)

    def _chain_start(self, x: float, y: float) -> int:
        """(x, y)'s cell, or -1 when it has no chain (outside, blocked, cut off)."""
        index = self._closed_cell(x, y)
        return -1 if index < 0 or self.cell_distance[index] == math.inf else index

    def _next_cell(self, index: int) -> int:
        """The cell after ``index`` on its chain (``index`` not the goal's)."""
        row, col = divmod(index, self.width)
        dc, dr, _ = _STEPS[self._way[index] - 1]
        return (row - dr) * self.width + col - dc
