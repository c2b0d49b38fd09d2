"""A path's cost as the optimizing planners count it, for ``-stats`` and the
benchmarks: the sum of its motions' costs (``si.distance`` of a straight motion,
``si.motion_cost`` of a controlled one; docs/optimal-planning.md)."""

from __future__ import annotations

import math
from collections.abc import Sequence

TYPE_CHECKING = False
if TYPE_CHECKING:  # the annotation only: the validator's checks import this, not typing
    from typing import Any


def path_cost(si: Any, path: Sequence[Sequence[float]],
              controls: Sequence[Any] = ()) -> float:
    """The cost of ``path`` (states from the start) under ``controls`` (a kinodynamic
    system's, ``controls[i]`` leading from ``path[i]`` to ``path[i + 1]``); 0 for a
    path of one state."""
    if si.system.kinodynamic:
        # (A start in the goal region: one state, the controls that stay there.)
        last = len(path) - 1
        return math.fsum(si.motion_cost(path[min(i, last)], control, path[min(i + 1, last)])
                         for i, control in enumerate(controls))
    return math.fsum(si.distance(path[i], path[i + 1]) for i in range(len(path) - 1))
