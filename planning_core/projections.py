"""Projections of states onto integer cells (OMPL's ProjectionEvaluator): KPIECE1
keeps its grid over one. A space information makes its own (the grid's ships: the
position and the velocity; the family: the system's ``projection_names``).

Compiled (mypyc): KPIECE1 projects every state it adds.
"""

from __future__ import annotations

import math
from collections.abc import Sequence


class AxesProjection:
    """State -> integer cell coordinates, ``floor((state[index] - low) * scale)`` per
    ``(index, low, scale)`` axis, in order."""

    def __init__(self, axes: list[tuple[int, float, float]]) -> None:
        self.indices = [index for index, _, _ in axes]
        self.lows = [low for _, low, _ in axes]
        self.scales = [scale for _, _, scale in axes]

    def __call__(self, state: Sequence[float]) -> tuple[int, ...]:
        indices, lows, scales = self.indices, self.lows, self.scales
        return tuple([math.floor((state[indices[k]] - lows[k]) * scales[k])
                      for k in range(len(indices))])
