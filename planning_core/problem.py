"""The grid planning problem as a frozen value (what a `.sw` file describes)."""

from __future__ import annotations


class Problem:
    """A W x H occupancy grid with a start and a goal point.

    ``blocked`` is row-major from the BOTTOM row: cell ``(i, j)`` (column i from
    the left, row j from the bottom) is blocked when ``blocked[j * width + i]``
    is 1. Cell ``(i, j)`` covers ``[i, i+1) x [j, j+1)``.

    A plain class, not a dataclass: the validator reads the problem before it
    starts the planner, and ``dataclasses`` (with ``inspect``) would cost that
    wait about 10 ms. Compared, hashed and printed by its fields, and frozen.
    """

    FIELDS = ("width", "height", "blocked", "start", "goal")

    width: int
    height: int
    blocked: bytes
    start: tuple[float, float]
    goal: tuple[float, float]

    def __init__(self, width: int, height: int, blocked: bytes,
                 start: tuple[float, float], goal: tuple[float, float]) -> None:
        values = self.__dict__
        values["width"], values["height"], values["blocked"] = width, height, blocked
        values["start"], values["goal"] = start, goal

    def _fields(self) -> tuple:
        return (self.width, self.height, self.blocked, self.start, self.goal)

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return self._fields() == other._fields()  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return hash(self._fields())

    def __repr__(self) -> str:
        return "Problem(" + ", ".join(f"{name}={getattr(self, name)!r}"
                                      for name in self.FIELDS) + ")"

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field {name!r}: a Problem is frozen")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field {name!r}: a Problem is frozen")

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
