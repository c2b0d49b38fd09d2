"""Shortcut smoothing of a geometric path (the ``-smooth`` option): the point
vehicle's on a grid, and the geometric family's (arm2, rigid2).

Two passes, both keeping every motion free (checked as the planners check it,
by the geometric space information: the grid's exact cell walk, the family's
samples at the check step, in the direction travelled) and the first and last
states where they were:

1. Vertex pruning, greedy: from each kept vertex, jump to the farthest later
   vertex it sees directly (the "string pulling" idea of Geraerts & Overmars
   2007, "Creating high-quality paths for motion planning", IJRR).
2. Random shortcuts between states in the middle of two motions, as OMPL's
   PathSimplifier::shortcutPath does: pick two random states on the path; if
   the straight motion between them is free and shorter, it replaces the part
   of the path between them. This cuts corners that no pair of vertices can.

Randomness comes only from the ``random.Random`` passed in.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Sequence

from planning_core.space_information import GeometricSpaceInformation
from rrt_cli.planners.paths import path_length

State = tuple[float, ...]

# A shortcut must save at least this much length: ends rounding-level churn.
_MIN_GAIN = 1e-9


@dataclass(frozen=True)
class SmoothingParams:
    """How ``-smooth`` shortens a path."""

    shortcut_attempts: int = 200
    """Random shortcuts tried (pass 2); 0 keeps only the vertex pruning."""
    max_failures_in_a_row: int = 60
    """Pass 2 ends early after this many attempts in a row that shorten nothing."""


def smooth_path(si: GeometricSpaceInformation, path: Sequence[Sequence[float]],
                rng: random.Random, params: SmoothingParams = SmoothingParams()
                ) -> tuple[State, ...]:
    """A path no longer than ``path``, with the same first and last states, whose
    motions are all free and whose states may end a path (on the grid: strictly
    inside the map).

    ``path`` must itself be such a path (a planner's trajectory).
    """
    points = [tuple(float(v) for v in p) for p in path]
    if len(points) <= 2:
        return tuple(points)
    points = prune_vertices(si, points)
    points = random_shortcuts(si, points, rng, params)
    # Shortcuts may have lined up vertices that now see past each other.
    return tuple(prune_vertices(si, points))


def prune_vertices(si: GeometricSpaceInformation, points: list[State]) -> list[State]:
    """Greedy: from each kept vertex, the farthest later vertex in direct sight.

    The next vertex is always in sight (the path is free), so this ends, and
    each jump replaces a chain of motions by one no longer (triangle inequality).
    """
    first_hit = si.first_hit
    kept = [points[0]]
    i, last = 0, len(points) - 1
    while i < last:
        j = last
        while j > i + 1 and first_hit(points[i], points[j]) is not None:
            j -= 1
        kept.append(points[j])
        i = j
    return kept


def random_shortcuts(si: GeometricSpaceInformation, points: list[State], rng: random.Random,
                     params: SmoothingParams) -> list[State]:
    failures = 0
    for _ in range(params.shortcut_attempts):
        if failures >= params.max_failures_in_a_row or len(points) < 3:
            break
        shorter = _try_shortcut(si, points, rng)
        if shorter is None:
            failures += 1
        else:
            points, failures = shorter, 0
    return points


def _try_shortcut(si: GeometricSpaceInformation, points: list[State],
                  rng: random.Random) -> list[State] | None:
    segments = len(points) - 1
    first, second = sorted((int(rng.random() * segments), int(rng.random() * segments)))
    if second - first < 1:
        return None  # two states on one motion: nothing to cut
    interpolate, distance, free = si.interpolate, si.distance, si.first_hit
    a = interpolate(points[first], points[first + 1], rng.random())
    b = interpolate(points[second], points[second + 1], rng.random())
    if not (si.can_end_at(a) and si.can_end_at(b)):
        return None
    old = (distance(a, points[first + 1]) + path_length(points[first + 1:second + 1], distance)
           + distance(points[second], b))
    if distance(a, b) >= old - _MIN_GAIN:
        return None
    # a and b lie on free motions, but computed states carry rounding (and the
    # family's samples move): check every new motion, not only the shortcut.
    if not (free(points[first], a) is None and free(a, b) is None
            and free(b, points[second + 1]) is None):
        return None
    return points[:first + 1] + [a, b] + points[second + 1:]

