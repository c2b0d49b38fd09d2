"""What the straight-line planners (RRT's steering, RRT-Connect, PRM, PRM*) and the
path smoother ask of a SpaceInformation, and the grid's answers.

A geometric family SpaceInformation
(:class:`~planning_core.geometric_space_information.GeometricSpaceInformation`)
answers these questions itself; :class:`GridLines` gives the grid's answers (the
plane's metric, the exact cell walk, free-cell sampling, a quadtree, the
frontier), computed exactly as the grid planners always did, so their outputs keep
their bytes. :func:`straight_lines` picks one. Paths are sequences of states
joined by straight motions.
"""

from __future__ import annotations

import math
import random
from typing import Sequence

from planning_core.interrupt import Stop
from planning_core.worlds.grid import GridWorld

NO_GOAL_CONFIGURATION = "no valid configuration in the goal region was found"


def plane_distance(a: Sequence[float], b: Sequence[float]) -> float:
    return math.hypot(b[0] - a[0], b[1] - a[1])


def plane_interpolate(a: Sequence[float], b: Sequence[float], t: float) -> tuple[float, float]:
    return (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)


class GridLines:
    """The point vehicle's straight lines on a grid (a grid SpaceInformation, or
    only its world for the smoother's callers)."""

    answers_straight_lines = True
    dimension = 2
    rechecks_prefix = False
    """The cell walk is exact: a prefix of a free segment is free."""
    lazy_edges = False
    """A roadmap checks each edge when it is made (the walk is cheap)."""
    distance = staticmethod(plane_distance)
    interpolate = staticmethod(plane_interpolate)

    def __init__(self, world: GridWorld, si=None):
        self.world, self.si = world, si
        self.first_hit = si.first_hit if si is not None else _cell_walk(world)
        self._free, self._inside = world.point_free, world.point_strictly_inside

    def can_end_at(self, q: Sequence[float]) -> bool:
        """Free and printable (SPEC 2: strictly inside the map)."""
        return self._free(q[0], q[1]) and self._inside(q[0], q[1])

    @staticmethod
    def clearance(requested: float) -> float:
        return requested

    def goal_configuration(self, rng: random.Random) -> tuple[float, float]:
        return self.world.printable_point(self.si.goal.point)

    def free_sampler(self, rng: random.Random, stop: Stop = None):
        """``draw()``: uniform over the free cells (built once: it may walk the map)."""
        from planning_core.worlds.grid_cells import sample_free_point
        free_cells, width = self.world.free_cell_indices(stop), self.world.width
        return lambda: sample_free_point(rng, free_cells, width)

    roadmap_sampler = free_sampler

    def new_index(self) -> "PlaneIndex":
        return PlaneIndex(self.world.width, self.world.height)

    def frontier(self):
        return self.world.frontier()


def _cell_walk(world: GridWorld):
    walk = world.first_blocked_cell_on_segment
    return lambda a, b: walk(a[0], a[1], b[0], b[1])


class PlaneIndex:
    """A quadtree over (x, y), asked with states like the kd-tree."""

    def __init__(self, width: float, height: float):
        from planning_core.nearest.quadtree import QuadtreeNearest
        index = QuadtreeNearest(width, height)
        self._add, self._nearest, self._k_nearest = index.add, index.nearest, index.k_nearest

    def add(self, q: Sequence[float]) -> int:
        return self._add(q[0], q[1])

    def nearest(self, q: Sequence[float]) -> int:
        return self._nearest(q[0], q[1])

    def k_nearest(self, q: Sequence[float], k: int) -> list[int]:
        return self._k_nearest(q[0], q[1], k)


def straight_lines(where):
    """What answers the straight-line questions for ``where``: a geometric family
    SpaceInformation itself; a grid SpaceInformation or GridWorld through :class:`GridLines`."""
    if getattr(where, "answers_straight_lines", False):
        return where
    if isinstance(where, GridWorld):
        return GridLines(where)
    return GridLines(where.world, where)


def path_length(path: Sequence[Sequence[float]], distance=plane_distance) -> float:
    return sum(distance(a, b) for a, b in zip(path, path[1:]))


def first_blocked_segment(where, path: Sequence[Sequence[float]]) -> int | None:
    """Index ``i`` of the first motion ``path[i] -> path[i+1]`` that meets an invalid
    state (checked in the direction it is travelled), or None."""
    first_hit = straight_lines(where).first_hit
    for i in range(len(path) - 1):
        if first_hit(path[i], path[i + 1]) is not None:
            return i
    return None
