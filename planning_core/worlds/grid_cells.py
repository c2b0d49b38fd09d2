"""Sampling over a grid's free cells (shared by the frontier and the point planners)."""

from __future__ import annotations

import random
from typing import Sequence


def sample_free_point(rng: random.Random, free_cells: Sequence[int],
                      width: int) -> tuple[float, float]:
    """Uniform over the free space: a uniform free cell, then uniform inside it.

    Every cell has the same area, so this is exactly uniform over the free
    region, without the rejections that make sampling the whole map slow on
    crowded maps. The point is strictly inside the map.
    """
    while True:
        row, column = divmod(free_cells[int(rng.random() * len(free_cells))], width)
        x, y = column + rng.random(), row + rng.random()
        # Cell 0's lower edge is the map's edge: x == 0 or y == 0 is not printable.
        if x > 0.0 and y > 0.0:
            return (x, y)
