"""The frontier of a growing tree on the grid: free cells no node lies in yet
that share a side with a cell some node does lie in.

RRT-Connect draws most of its targets here (``RRTConnectParams.frontier_targets``).
With uniform targets a tree in a maze spends almost every iteration on a target
whose nearest node is behind a wall (nothing added) or in a corridor it already
fills (a node added where it brings nothing); a frontier target lies next to a
covered cell, so its nearest node is usually in sight and the extension
advances into new space. This is the exterior-cell idea of KPIECE1 applied to
target sampling, with the map's own cells as the grid.
"""

from __future__ import annotations

import random
from collections.abc import Sequence

from planning_core.problem import Problem
from planning_core.worlds.grid_cells import sample_free_point

Point = tuple[float, float]


class FrontierCells:
    """The frontier, kept up to date as nodes are added (``cover``).

    Cells are row-major indices (``row * width + column``). The frontier is a
    list with each cell's slot in a dict, so adding, removing and drawing a
    uniform cell are O(1) and the order (hence a seeded run) is reproducible.
    """

    def __init__(self, problem: Problem):
        self.width: int = problem.width
        self.height: int = problem.height
        self.blocked: bytes = bytes(problem.blocked)  # typed: indexed natively, compiled
        self.covered = bytearray(len(problem.blocked))
        self.cells: list[int] = []
        self.slot: dict[int, int] = {}

    def __len__(self) -> int:
        return len(self.cells)

    def cover(self, point: Sequence[float]) -> None:
        """Record a node at ``point`` (strictly inside the map)."""
        width = self.width
        cell = int(point[1]) * width + int(point[0])
        if self.covered[cell]:
            return
        self.covered[cell] = 1
        self._remove(cell)
        row, column = divmod(cell, width)
        # Side neighbours only: a diagonal neighbour is often behind a wall
        # corner, and the uniform share of targets still reaches it.
        for neighbour, inside in ((cell - width, row > 0), (cell + width, row + 1 < self.height),
                                  (cell - 1, column > 0), (cell + 1, column + 1 < width)):
            if inside and not self.blocked[neighbour] and not self.covered[neighbour] \
                    and neighbour not in self.slot:
                self.slot[neighbour] = len(self.cells)
                self.cells.append(neighbour)

    def _remove(self, cell: int) -> None:
        index = self.slot.pop(cell, None)
        if index is None:
            return
        last = self.cells.pop()
        if last != cell:
            self.cells[index] = last
            self.slot[last] = index

    def sample(self, rng: random.Random) -> Point:
        """A uniform point in a uniform frontier cell (the frontier is not empty)."""
        return sample_free_point(rng, self.cells, self.width)
