"""Sampling over a grid's free cells (shared by the frontier and the point planners),
and the free cells themselves as a sequence that is never listed."""

from __future__ import annotations

import random
from array import array
from bisect import bisect_right
from collections.abc import Sequence
from itertools import accumulate, repeat
from typing import Final

from planning_core.interrupt import POLL_EVERY, Stop, check
from planning_core.samplers import uniform

_BLOCK: Final = 64
"""Cells per block of :class:`FreeCells`: a lookup scans at most one block."""


class FreeCells:
    """The row-major indices of the free cells (byte 0 of ``blocked``), in
    increasing order: ``cells[k]`` is the k-th free cell (``len`` and indexing
    only, a plain class so that mypyc compiles it).

    A list of them costs 36 bytes a cell and a pass over the map in Python;
    this keeps one count per block of ``_BLOCK`` cells, made by ``bytes.count``
    (4 bytes per block), and finds ``cells[k]`` by a binary search over the
    blocks and a scan of one block. The k-th free cell is the same either way,
    so a seeded run draws the same cells.
    """

    def __init__(self, blocked: bytes, stop: Stop = None):
        self._blocked = bytes(blocked)
        cells = len(blocked)
        # _free_before[j]: free cells in the blocks before block j. A map without a
        # blocked cell needs none: its k-th free cell is cell k.
        self._free_before = array("i", [0])
        self._all_free = self._blocked.count(0) == cells
        if not self._all_free:
            chunk = _BLOCK * POLL_EVERY
            for begin in range(0, cells, chunk):
                check(stop)
                end = min(cells, begin + chunk)
                counts = map(self._blocked.count, repeat(0), range(begin, end, _BLOCK),
                             range(begin + _BLOCK, end + _BLOCK, _BLOCK))
                last = self._free_before.pop()
                self._free_before.extend(accumulate(counts, initial=last))
        self._count = cells if self._all_free else self._free_before[-1]

    def __len__(self) -> int:
        return self._count

    def __getitem__(self, k: int) -> int:
        if k < 0:
            k += self._count
        if not 0 <= k < self._count:
            raise IndexError("free cell index out of range")
        if self._all_free:
            return k
        block = bisect_right(self._free_before, k) - 1
        skip = k - self._free_before[block]
        begin = block * _BLOCK
        for offset, blocked in enumerate(self._blocked[begin:begin + _BLOCK]):
            if not blocked:
                if not skip:
                    return begin + offset
                skip -= 1
        raise AssertionError("block counts out of step with the map")


def sample_free_point(rng: random.Random, free_cells: Sequence[int] | FreeCells,
                      width: int) -> tuple[float, float]:
    """Uniform over the free space: a uniform free cell, then uniform inside it.

    Every cell has the same area, so this is exactly uniform over the free
    region, without the rejections that make sampling the whole map slow on
    crowded maps. The point is strictly inside the map.
    """
    while True:
        row, column = divmod(free_cells[int(uniform(rng) * len(free_cells))], width)
        x, y = column + uniform(rng), row + uniform(rng)
        # Cell 0's lower edge is the map's edge: x == 0 or y == 0 is not printable.
        if x > 0.0 and y > 0.0:
            return (x, y)
