"""The grid planning problem as a frozen value (what a `.sw` file describes)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """A W x H occupancy grid with a start and a goal point.

    ``blocked`` is row-major from the BOTTOM row: cell ``(i, j)`` (column i from
    the left, row j from the bottom) is blocked when ``blocked[j * width + i]``
    is 1. Cell ``(i, j)`` covers ``[i, i+1) x [j, j+1)``.
    """

    width: int
    height: int
    blocked: bytes
    start: tuple[float, float]
    goal: tuple[float, float]

    def is_blocked_cell(self, column: int, row: int) -> bool:
        return bool(self.blocked[row * self.width + column])

    def point_in_collision(self, x: float, y: float) -> bool:
        """SPEC 1: outside ``[0, W) x [0, H)`` or inside a blocked cell."""
        if not (0.0 <= x < self.width and 0.0 <= y < self.height):
            return True
        return bool(self.blocked[int(y) * self.width + int(x)])

    def text_rows(self) -> list[str]:
        """Rows as in the file: first row is the TOP of the world."""
        w = self.width
        rows = []
        for row in range(self.height - 1, -1, -1):
            cells = self.blocked[row * w:(row + 1) * w]
            rows.append("".join("#" if c else "_" for c in cells))
        return rows
