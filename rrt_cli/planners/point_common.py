"""Small helpers shared by the point-vehicle planners (RRT-Connect, PRM, PRM*)
and the path smoother: where a path may end, path length, path checks.

Paths here are sequences of ``(x, y)`` points joined by straight segments,
each checked exactly against the grid (SPEC 2: printed points strictly inside
the map).
"""

from __future__ import annotations

import math
import random
from typing import Sequence

from planning_core.worlds.grid import GridWorld

# Moves a goal that lies on the map's left or bottom edge (x or y exactly 0,
# free but not printable) inward; far below the 0.1 goal tolerance and far
# inside the goal's cell.
_EDGE_NUDGE = 1e-6

Point = tuple[float, float]


def goal_vertex(world: GridWorld, goal: Point) -> Point:
    """The point a path should end at: the goal itself when it can be printed
    (strictly inside the map), else the goal nudged into the map's interior.

    The goal is free (the problem reader guarantees it), so it lies in
    ``[0, W) x [0, H)``; only ``x == 0`` or ``y == 0`` needs the nudge, and the
    nudged point stays in the goal's own cell.
    """
    x, y = goal
    if world.point_strictly_inside(x, y):
        return (x, y)
    return (max(x, _EDGE_NUDGE), max(y, _EDGE_NUDGE))


def path_length(path: Sequence[Sequence[float]]) -> float:
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(path, path[1:]))


def first_blocked_segment(world: GridWorld, path: Sequence[Sequence[float]]) -> int | None:
    """Index ``i`` of the first segment ``path[i] -> path[i+1]`` that meets a
    blocked cell (checked exactly, in the direction it is travelled), or None."""
    for i in range(len(path) - 1):
        (x0, y0), (x1, y1) = path[i][:2], path[i + 1][:2]
        if world.first_blocked_cell_on_segment(x0, y0, x1, y1) is not None:
            return i
    return None
