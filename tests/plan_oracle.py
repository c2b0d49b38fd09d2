"""A deliberately simple reader of the plan format, used only by tests as an
oracle for :func:`planning_core.plan_reader.read_plan` (which must agree with it
on every plan it accepts and fail on the same line). Tuples of floats, whole text
in memory: clear, not fit for hostile input."""

from __future__ import annotations

import math
from dataclasses import dataclass

from planning_core.plan_text import PlanParseError

Row = tuple[float, ...]


@dataclass(frozen=True)
class PlanText:
    """The numbers of a plan, as read; line numbers kept for error messages."""

    trajectory: tuple[Row, ...]
    tree: tuple[Row, ...]
    trajectory_first_line: int  # line number of trajectory[0]
    tree_first_line: int        # line number of tree[0]
    trailing_line: int | None = None  # first non-blank line after the tree, if any


def _parse_count(line: str, number: int, what: str, lines_left: int) -> int:
    text = line.strip()
    if not text.isdigit() or not text.isascii():
        raise PlanParseError(number, f"expected the {what} count (a non-negative integer), "
                                     f"got {_show(text)}")
    count = int(text)
    if count > lines_left:
        raise PlanParseError(number, f"{what} count {count} but only {lines_left} lines follow")
    return count


def _show(text: str, limit: int = 60) -> str:
    return repr(text if len(text) <= limit else text[:limit] + "...")


def _parse_row(line: str, number: int, fields: int, what: str) -> Row:
    tokens = line.split()
    if len(tokens) != fields:
        raise PlanParseError(number, f"expected {fields} numbers on a {what} line, "
                                     f"got {len(tokens)}: {_show(line.strip())}")
    values = []
    for token in tokens:
        try:
            value = float(token)
        except ValueError:
            raise PlanParseError(number, f"{_show(token)} is not a number") from None
        if not math.isfinite(value):
            raise PlanParseError(number, f"{_show(token)} is not a finite number")
        values.append(value)
    return tuple(values)


def parse_plan(text: str, trajectory_fields: int, tree_fields: int) -> PlanText:
    """Read a plan. ``*_fields``: 2 and 4 for the point vehicle, 6 and 6 for spaceships."""
    lines = text.split("\n")
    if lines and lines[-1].strip() == "":
        lines.pop()  # the final newline
    lines = [line.rstrip("\r") for line in lines]
    index = 0
    # Blank lines are not part of the format; skip them before each count.
    while index < len(lines) and not lines[index].strip():
        index += 1
    if index >= len(lines):
        raise PlanParseError(1, "output is empty: expected the trajectory count")
    n = _parse_count(lines[index], index + 1, "trajectory", len(lines) - index - 1)
    index += 1
    trajectory_first = index + 1
    trajectory = tuple(_parse_row(lines[index + k], index + k + 1, trajectory_fields,
                                  "trajectory") for k in range(n))
    index += n
    while index < len(lines) and not lines[index].strip():
        index += 1
    if index >= len(lines):
        raise PlanParseError(index + 1, "output ended before the tree count")
    m = _parse_count(lines[index], index + 1, "tree", len(lines) - index - 1)
    index += 1
    tree_first = index + 1
    tree = tuple(_parse_row(lines[index + k], index + k + 1, tree_fields, "tree")
                 for k in range(m))
    index += m
    # Text after the tree is tolerated (the course checker ignored it); callers may warn.
    trailing = next((k + 1 for k in range(index, len(lines)) if lines[k].strip()), None)
    return PlanText(trajectory, tree, trajectory_first, tree_first, trailing)
