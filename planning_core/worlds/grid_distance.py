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

from planning_core.heap import HeapEntry, heap_pop, heap_push
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


class CellDistanceToGoal:
    """Dijkstra from the goal's cell over the free cells, once, at construction;
    per cell a double (its distance) and a byte (its way), 9 bytes a cell.
    ``stop`` is asked every POLL_EVERY heap pops (:mod:`planning_core.interrupt`)."""

    def __init__(self, problem: Problem, goal: tuple[float, float], unreachable: float = 1e12,
                 stop: Stop = None):
        width, height = problem.width, problem.height
        blocked = bytes(problem.blocked)  # typed: compiled, the search indexes it natively
        self.width: int = width
        self.height: int = height
        self.goal = goal
        self.unreachable = unreachable
        gx, gy = goal
        self.goal_cell = int(gy) * width + int(gx)
        self.cell_distance = array("d", [math.inf]) * (width * height)
        self._way = bytearray(width * height)
        if not blocked[self.goal_cell]:
            self._search(blocked, stop)

    def _search(self, blocked: bytes, stop: Stop) -> None:
        width, height = self.width, self.height
        distance, way = self.cell_distance, self._way
        distance[self.goal_cell] = 0.0
        queue: list[HeapEntry] = [HeapEntry(0.0, self.goal_cell)]  # (distance, cell)
        steps: list[tuple[int, int, float, int]] = [
            (dc, dr, cost, code) for code, (dc, dr, cost) in enumerate(_STEPS, 1)]
        countdown = POLL_EVERY
        while queue:
            countdown -= 1
            if not countdown:
                countdown = POLL_EVERY
                check(stop)
            entry = heap_pop(queue)
            d, index = entry.key, entry.order
            best: float = distance[index]
            if d > best:
                continue
            row = index // width
            col = index - row * width
            for dc, dr, cost, code in steps:
                c, r = col + dc, row + dr
                if not (0 <= c < width and 0 <= r < height):
                    continue
                k = r * width + c
                if blocked[k]:
                    continue
                if dc and dr and (blocked[row * width + c] or blocked[r * width + col]):
                    continue
                known: float = distance[k]
                if d + cost < known:
                    distance[k] = d + cost
                    way[k] = code  # k's chain goes back through index
                    heap_push(queue, HeapEntry(d + cost, k))

    def __call__(self, x: float, y: float) -> float:
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return self.unreachable
        index = int(y) * self.width + int(x)
        if index == self.goal_cell:
            return math.hypot(x - self.goal[0], y - self.goal[1])
        d: float = self.cell_distance[index]
        if d == math.inf:
            return self.unreachable
        # Progress inside the cell toward the next one, from the cell's centre.
        way: int = self._way[index]
        return d - ((x - int(x) - 0.5) * _TOWARD_X[way] + (y - int(y) - 0.5) * _TOWARD_Y[way])

    def ahead(self, x: float, y: float, cells: int) -> tuple[float, float] | None:
        """The centre of the cell ``cells`` steps down the cheapest chain from (x, y)'s
        cell (the goal itself when the chain ends sooner); None when (x, y) has no
        chain. A walk of at most ``cells`` steps, whatever the chain's length."""
        chain = self.chain_ahead(x, y, cells)
        if chain is None:
            return None
        col, row = chain[-1]
        if row * self.width + col == self.goal_cell:
            return self.goal
        return (col + 0.5, row + 0.5)

    def ahead_of(self, state: Sequence[float], cells: int) -> tuple[float, float] | None:
        """:meth:`ahead` of a state's position (RRT*'s guided target)."""
        return self.ahead(state[0], state[1], cells)

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
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return -1
        index = int(y) * self.width + int(x)
        return -1 if self.cell_distance[index] == math.inf else index

    def _next_cell(self, index: int) -> int:
        """The cell after ``index`` on its chain (``index`` not the goal's)."""
        row, col = divmod(index, self.width)
        dc, dr, _ = _STEPS[self._way[index] - 1]
        return (row - dr) * self.width + col - dc
