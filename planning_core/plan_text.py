"""Write and read the planner's output: trajectory, then motion tree (SPEC 2).

Point vehicle: ``N``, N lines ``x y``, ``M``, M lines ``x1 y1 x2 y2``.
Spaceship: ``N``, N lines ``x y dx dy theta s``, ``M``, M lines of the same six
numbers (a parent state and the control of the edge to its child).

Floats are written with ``repr`` (shortest round-trip form) so that a checker
that re-simulates gets the planner's numbers bit for bit. The one reader is
:mod:`planning_core.plan_reader` (bounded memory, for any planner's output); its
failures are a :class:`PlanParseError` naming the 1-based line.
"""

from __future__ import annotations

from collections.abc import Sequence

Row = tuple[float, ...]


class PlanParseError(ValueError):
    def __init__(self, line: int, message: str):
        super().__init__(f"line {line}: {message}")
        self.line = line
        self.message = message


def _row_text(values: Sequence[float]) -> str:
    return " ".join(repr(float(v)) for v in values)


def _row_text_with_count(values: Sequence[float]) -> str:
    """A kinodynamic kinoplan row: floats, then K, a whole number (SPEC 5.4)."""
    return " ".join([*(repr(float(v)) for v in values[:-1]), str(int(values[-1]))])


def format_plan(trajectory: Sequence[Sequence[float]], tree: Sequence[Sequence[float]],
                ends_in_count: bool = False) -> str:
    """Both sections; rows are 2 or 6 numbers (trajectory) and 4 or 6 (tree), or a
    kinoplan system's. ``ends_in_count``: every row ends in K, printed as an integer
    (a kinodynamic kinoplan system's rows)."""
    row_text = _row_text_with_count if ends_in_count else _row_text
    parts = [str(len(trajectory))]
    parts.extend(row_text(row) for row in trajectory)
    parts.append(str(len(tree)))
    parts.extend(row_text(row) for row in tree)
    return "\n".join(parts) + "\n"
