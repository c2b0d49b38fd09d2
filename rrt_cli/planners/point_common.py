"""Small helpers shared by the point-vehicle planners (RRT-Connect, PRM, PRM*)
and the path smoother: path length, path checks.

Paths here are sequences of ``(x, y)`` points joined by straight segments,
each checked exactly against the grid (SPEC 2: printed points strictly inside
the map).
"""

from __future__ import annotations

import math
from typing import Sequence

from planning_core.worlds.grid import GridWorld


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
