"""Shortcut smoothing of a point vehicle's path (the ``-smooth`` option).

Two passes, both keeping the path exactly collision-free (every new segment is
checked with :meth:`GridWorld.first_blocked_cell_on_segment`, in the direction
it is travelled) and its first and last points where they were:

1. Vertex pruning, greedy: from each kept vertex, jump to the farthest later
   vertex it sees directly (the "string pulling" idea of Geraerts & Overmars
   2007, "Creating high-quality paths for motion planning", IJRR).
2. Random shortcuts between points in the middle of two segments, as OMPL's
   PathSimplifier::shortcutPath does: pick two random points on the path; if
   the straight segment between them is free and shorter, it replaces the part
   of the path between them. This cuts corners that no pair of vertices can.

Randomness comes only from the ``random.Random`` passed in.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Sequence

from planning_core.worlds.grid import GridWorld

Point = tuple[float, float]

# A shortcut must save at least this much length: ends rounding-level churn.
_MIN_GAIN = 1e-9


@dataclass(frozen=True)
class SmoothingParams:
    shortcut_attempts: int = 200
    """Random shortcuts tried (pass 2); 0 keeps only the vertex pruning."""
    max_failures_in_a_row: int = 60
    """Pass 2 ends early after this many attempts in a row that shorten nothing."""


def smooth_path(world: GridWorld, path: Sequence[Sequence[float]], rng: random.Random,
                params: SmoothingParams = SmoothingParams()) -> tuple[Point, ...]:
    """A path no longer than ``path``, with the same first and last points, whose
    segments are all exactly free and whose points are strictly inside the map.

    ``path`` must itself be such a path (a planner's point trajectory).
    """
    points = [(float(p[0]), float(p[1])) for p in path]
    if len(points) <= 2:
        return tuple(points)
    points = prune_vertices(world, points)
    points = random_shortcuts(world, points, rng, params)
    # Shortcuts may have lined up vertices that now see past each other.
    return tuple(prune_vertices(world, points))


def _free(world: GridWorld, a: Point, b: Point) -> bool:
    return world.first_blocked_cell_on_segment(a[0], a[1], b[0], b[1]) is None


def prune_vertices(world: GridWorld, points: list[Point]) -> list[Point]:
    """Greedy: from each kept vertex, the farthest later vertex in direct sight.

    The next vertex is always in sight (the path is free), so this ends, and
    each jump replaces a chain of segments by one no longer (triangle inequality).
    """
    kept = [points[0]]
    i, last = 0, len(points) - 1
    while i < last:
        j = last
        while j > i + 1 and not _free(world, points[i], points[j]):
            j -= 1
        kept.append(points[j])
        i = j
    return kept


def random_shortcuts(world: GridWorld, points: list[Point], rng: random.Random,
                     params: SmoothingParams) -> list[Point]:
    failures = 0
    for _ in range(params.shortcut_attempts):
        if failures >= params.max_failures_in_a_row or len(points) < 3:
            break
        shorter = _try_shortcut(world, points, rng)
        if shorter is None:
            failures += 1
        else:
            points, failures = shorter, 0
    return points


def _try_shortcut(world: GridWorld, points: list[Point], rng: random.Random) -> list[Point] | None:
    segments = len(points) - 1
    first, second = sorted((int(rng.random() * segments), int(rng.random() * segments)))
    if second - first < 1:
        return None  # two points on one segment: nothing to cut
    a = _between(points[first], points[first + 1], rng.random())
    b = _between(points[second], points[second + 1], rng.random())
    if not (_printable(world, a) and _printable(world, b)):
        return None
    old = (math.dist(a, points[first + 1]) + _length(points[first + 1:second + 1])
           + math.dist(points[second], b))
    if math.dist(a, b) >= old - _MIN_GAIN:
        return None
    # a and b lie on free segments, but computed points carry rounding: check
    # every new segment, not only the shortcut.
    if not (_free(world, points[first], a) and _free(world, a, b)
            and _free(world, b, points[second + 1])):
        return None
    return points[:first + 1] + [a, b] + points[second + 1:]


def _between(p: Point, q: Point, t: float) -> Point:
    return (p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t)


def _printable(world: GridWorld, p: Point) -> bool:
    return world.point_strictly_inside(p[0], p[1]) and world.point_free(p[0], p[1])


def _length(points: Sequence[Point]) -> float:
    return sum(math.dist(p, q) for p, q in zip(points, points[1:]))
