"""What the straight-line planners (RRT-Connect, PRM, PRM*) and the path smoother
share about paths: sequences of states joined by straight motions, checked as
their geometric space information checks them."""

from __future__ import annotations

from typing import Callable, Sequence

from planning_core.space_information import GeometricSpaceInformation

NO_GOAL_CONFIGURATION = "no valid configuration in the goal region was found"


def path_length(path: Sequence[Sequence[float]],
                distance: Callable[[Sequence[float], Sequence[float]], float]) -> float:
    return sum(distance(a, b) for a, b in zip(path, path[1:]))


def first_blocked_segment(si: GeometricSpaceInformation,
                          path: Sequence[Sequence[float]]) -> int | None:
    """Index ``i`` of the first motion ``path[i] -> path[i+1]`` that meets an invalid
    state (checked in the direction it is travelled), or None."""
    first_hit = si.first_hit
    for i in range(len(path) - 1):
        if first_hit(path[i], path[i + 1]) is not None:
            return i
    return None
