"""The Dubins car (Dubins 1957) on the grid maps: a pose <x, y, heading> that drives
forward only, turning no tighter than ``radius``; a motion between two poses is the
shortest Dubins path (:mod:`planning_core.dubins`), so motions are directed.

A geometric system: no controls. Its output rows are not its states but the
curves between them, sampled at most ``SAMPLE_STEP`` apart, as point rows <x, y>
(:meth:`trajectory_rows`, :meth:`tree_rows`): the course's validator reads them
as a point path. A pose given as ``(x, y)`` leaves its heading free (the start,
and the goal where a planner ends a path at it).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import ClassVar

from planning_core import dubins
from planning_core.worlds.grid import SAMPLE_STEP

DEFAULT_RADIUS = 0.5
"""The turning radius without ``-radius`` (map units)."""
RADIUS_RANGE = (1e-6, 1e6)
"""The radii ``-radius`` takes (map units): the Dubins formulas divide by the radius
(1e-300 overflowed to a traceback) and a planner's curves scale with it (1e300 ran past
its time limit)."""


@dataclass(frozen=True)
class DubinsOptions:
    """The Dubins car's settings on a grid (``-dubins -radius R``)."""

    radius: float = DEFAULT_RADIUS
    """The least turning radius, map units (> 0)."""


@dataclass(frozen=True)
class DubinsCar:
    """Pose (x, y, heading), forward motions of curvature at most 1 / ``radius``."""

    radius: float = DEFAULT_RADIUS
    """The least turning radius (map units), > 0."""
    name: str = "dubins"
    """The name the registry and the validator's report use."""

    kinodynamic: ClassVar[bool] = False
    directed: ClassVar[bool] = True
    """A motion a -> b is not b -> a travelled back (the planners' registry asks)."""
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "heading")
    row_names: ClassVar[tuple[str, ...]] = ("x", "y")
    """What each output row holds: a sampled position."""
    control_names: ClassVar[tuple[str, ...]] = ()
    position_indices: ClassVar[tuple[int, ...]] = (0, 1)
    velocity_indices: ClassVar[tuple[int, ...]] = ()

    def __post_init__(self) -> None:
        if not (math.isfinite(self.radius) and self.radius > 0.0):
            raise ValueError(f"the turning radius must be a positive number, got {self.radius!r}")

    free_start_names: ClassVar[tuple[str, ...]] = ("heading",)
    """Left out of the start state: the planner chooses them (a free heading)."""

    def state_space(self, width: float, height: float):
        """The map's rectangle and the heading, SE(2) (bounds and names; the planners'
        distance is the Dubins path length, not this space's)."""
        from planning_core.spaces import StateSpace
        return StateSpace.compound([StateSpace.real_vector(("x", "y"), (0.0, 0.0),
                                                           (width, height)),
                                    StateSpace.so2("heading")])

    def start_state(self, x: float, y: float) -> tuple[float, float]:
        """The start, its heading free (:attr:`free_start_names`)."""
        return (x, y)

    def curve(self, a: Sequence[float], b: Sequence[float]) -> dubins.DubinsPath:
        """The motion a -> b: the shortest Dubins path."""
        return dubins.shortest(a, b, self.radius)

    def curve_positions(self, a: Sequence[float], b: Sequence[float],
                        path: dubins.DubinsPath | None = None) -> Iterator[tuple[float, float]]:
        """The motion a -> b's positions (``path``: its curve, if known), at most
        ``SAMPLE_STEP`` apart along it: ``a``'s first, ``b``'s last, exactly (the
        chords the planners check are the ones printed). Lazy: a check stops early."""
        curve = self.curve(a, b) if path is None else path
        yield (a[0], a[1])
        yield from dubins.sample_positions(curve, dubins.sample_count(curve.length, SAMPLE_STEP))
        yield (b[0], b[1])

    def curve_points(self, a: Sequence[float], b: Sequence[float]) -> list[tuple[float, float]]:
        """:meth:`curve_positions` as a list."""
        return list(self.curve_positions(a, b))

    def trajectory_rows(self, path: Sequence[Sequence[float]]) -> tuple[tuple[float, ...], ...]:
        """The path's curves as positions, each joint printed once."""
        if len(path) == 1:
            return ((path[0][0], path[0][1]),)
        rows: list[tuple[float, ...]] = []
        for a, b in zip(path, path[1:]):
            points = self.curve_points(a, b)
            rows.extend(points if not rows else points[1:])
        return tuple(rows)

    def tree_rows(self, edges: Iterable[tuple]) -> tuple[tuple[float, ...], ...]:
        """Each edge's curve as chords ``x1 y1 x2 y2``."""
        rows: list[tuple[float, ...]] = []
        for a, _, b in edges:
            points = self.curve_points(a, b)
            rows.extend(p + q for p, q in zip(points, points[1:]))
        return tuple(rows)


SYSTEM = DubinsCar()
