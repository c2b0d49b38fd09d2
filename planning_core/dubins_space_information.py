"""The Dubins car on a grid as a :class:`~planning_core.space_information.GeometricSpaceInformation`:
states are poses (x, y, heading), a motion is the shortest Dubins path
(:mod:`planning_core.dubins`), so ``distance`` is that path's length and is
directed (not symmetric, not a metric).

A motion is checked along the very chords the output prints (the curve sampled at
most ``SAMPLE_STEP`` apart, :meth:`DubinsCar.curve_positions`), each chord walked
exactly through the grid's cells, each sample strictly inside the map: an answer
that passes here passes the validator's point checks, ``-strict`` included.

A state given as ``(x, y)`` has its heading free (the start; RRT-Connect's goal
root). :meth:`reverse_state` turns a pose around, so that a tree grown backward from
the goal (RRT-Connect) grows forward in reversed poses: the Dubins path a -> b,
travelled backward, is the path reverse(b) -> reverse(a).
"""

from __future__ import annotations

import math
import random
from itertools import chain
from typing import Any, Callable, Optional, Sequence

from planning_core.dubins import mod2pi, sample_count, sample_positions
from planning_core.interrupt import Stop
from planning_core.samplers import uniform
from planning_core.worlds.grid import SAMPLE_STEP, GridWorld
from planning_core.worlds.grid_distance import RUN_CELLS, chain_step, straight_run_end

TWO_PI = 2.0 * math.pi
CURVES_KEPT = 4096
"""Motions :meth:`DubinsSpaceInformation.curve` remembers before it forgets them all."""


PROBE_PIECES = 8
"""A curve cut into this many chords or more is probed first (:meth:`DubinsSpaceInformation.
first_hit`)."""


class CurveHit:
    """Where a curve first meets a blocked cell or the map's edge: :attr:`fraction` of
    its length, in (0, 1], worked out when first asked when a probe found the hit (a
    check that asks only whether there is one never walks the curve)."""

    def __init__(self, fraction: float, si: Any = None, a: Any = None, b: Any = None) -> None:
        self.known = fraction
        """The fraction, or -1 until it is asked for."""
        self.si, self.a, self.b = si, a, b

    @property
    def fraction(self) -> float:
        if self.known < 0.0:
            hit = self.si.walk(self.a, self.b)
            assert hit is not None  # the probe's sample is in a blocked cell
            self.known = hit.fraction
        return self.known


class DubinsSpaceInformation:
    """A Dubins car on a grid map: Dubins paths, checked chord by chord."""

    def __init__(self, system: Any, world: GridWorld) -> None:
        from planning_core.grid_space_information import GridGeometricSpaceInformation
        self.system = system
        self.world = world
        self.grid = grid = GridGeometricSpaceInformation(system, world)
        """The point's answers where a pose's position is all that counts."""
        self.is_valid, self.can_end_at = grid.is_valid, grid.can_end_at
        self.goal_configuration = grid.goal_configuration
        """The goal point (nudged inside the map), its heading free."""
        self.certainly_unreachable = grid.certainly_unreachable
        self.dimension = 3
        self.rechecks_prefix = True
        """A curve cut short is another Dubins path, with its own samples."""
        self.lazy_edges = False
        self.free_targets = True
        """Uniform over the free cells, as the point vehicle's."""
        self.wall_clearance = grid.wall_clearance
        """A curve cut short stops as far before the wall as the point's segment."""
        self.rrt_guided_targets = 0.5
        """Uniform targets rarely lead a car through a maze (docs/dubins.md)."""
        self.printable = world.point_strictly_inside
        self.curves: dict[tuple[Any, Any], Any] = {}
        """Motions measured lately (:meth:`curve`)."""

    def curve(self, a: Sequence[float], b: Sequence[float]) -> Any:
        """The car's motion a -> b (:meth:`DubinsCar.curve`), remembered: RRT* measures
        a motion and then checks it, and its nearest index measures what it then
        measures again (the last ``CURVES_KEPT`` pairs, forgotten all at once)."""
        key = (a, b)
        curve = self.curves.get(key)
        if curve is None:
            if len(self.curves) >= CURVES_KEPT:
                self.curves.clear()
            curve = self.curves[key] = self.system.curve(a, b)
        return curve

    @property
    def space(self) -> Any:
        """SE(2) over the map (names and bounds)."""
        return self.grid.space

    @staticmethod
    def goal_center(goal: Any) -> None:
        """None: the goal's heading is free, so no single pose is its centre (Informed
        RRT* then draws its targets by rejection from uniform poses)."""
        return None

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The length of the shortest Dubins path a -> b (directed)."""
        length: float = self.curve(a, b).length
        return length

    def interpolate(self, a: Sequence[float], b: Sequence[float],
                    t: float) -> tuple[float, float, float]:
        """The pose at fraction ``t`` of the Dubins path a -> b."""
        curve = self.curve(a, b)
        return curve.pose_at(curve.length * t)

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> Optional[CurveHit]:
        """The first chord of the curve a -> b that enters a blocked cell, or whose
        end does not print strictly inside the map; None when the curve is free.
        A long curve is probed first at its middle and quarters: a sample there in
        the open inside of a blocked cell, or not strictly inside the map, means a
        hit, whose place :meth:`walk` finds only if it is asked for."""
        curve = self.curve(a, b)
        pieces = sample_count(curve.length, SAMPLE_STEP)
        if pieces >= PROBE_PIECES:
            length, world = curve.length, self.world
            for k in (pieces // 2, pieces // 4, 3 * pieces // 4):
                x, y, _ = curve.pose_at(length * k / pieces)  # sample k, bit for bit
                if not world.point_strictly_inside(x, y) or (
                        x != int(x) and y != int(y) and not world.point_free(x, y)):
                    return CurveHit(-1.0, self, a, b)
        return self.walk(a, b)

    def walk(self, a: Sequence[float], b: Sequence[float]) -> Optional[CurveHit]:
        """:meth:`first_hit` by walking the curve's chords from ``a``."""
        curve = self.curve(a, b)
        pieces = sample_count(curve.length, SAMPLE_STEP)
        world = self.world
        x0, y0 = a[0], a[1]
        k = 0
        # The curve's inner samples, then b exactly, as printed.
        for x1, y1 in chain(sample_positions(curve, pieces), ((b[0], b[1]),)):
            hit = world.first_blocked_cell_on_segment(x0, y0, x1, y1)
            if hit is not None:
                return CurveHit(max((k + hit.fraction) / pieces, 1e-12))
            if not world.point_strictly_inside(x1, y1):
                return CurveHit((k + 1) / pieces)
            x0, y0, k = x1, y1, k + 1
        return None

    def _heading(self, rng: random.Random) -> float:
        return mod2pi(uniform(rng) * TWO_PI)

    def sample_target(self, rng: random.Random) -> tuple[float, float, float]:
        """A uniform position of the open map, then a uniform heading."""
        x, y = self.world.sample_open_position(rng)
        return (x, y, self._heading(rng))

    def free_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], Any]:
        """``draw()``: a uniform free position, then a uniform heading."""
        from planning_core.worlds.grid_cells import sample_free_point
        free_cells, width = self.world.free_cell_indices(stop), self.world.width

        def draw() -> tuple[float, float, float]:
            x, y = sample_free_point(rng, free_cells, width)
            return (x, y, self._heading(rng))

        return draw

    def roadmap_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], Any]:
        return self.free_sampler(rng, stop)

    def new_nearest(self) -> Any:
        """Nearest by the Dubins length to the query (:class:`DubinsNearest`)."""
        from planning_core.nearest.directed import DubinsNearest
        return DubinsNearest(self.distance, self.world.width, self.world.height)

    def goal_target(self, goal: Any, rng: random.Random) -> tuple[float, float, float]:
        """The goal point (nudged inside the map), with a uniform heading."""
        x, y = self.world.printable_point(goal.point)
        return (x, y, self._heading(rng))

    @staticmethod
    def reverse_state(state: Sequence[float]) -> tuple[float, ...]:
        """The pose turned around (a free heading stays free)."""
        if len(state) == 2:
            return (state[0], state[1])
        return (state[0], state[1], mod2pi(state[2] + math.pi))

    def frontier(self) -> Any:
        """The grid's frontier of the nodes' positions, its targets given a uniform
        heading as every target of the car's is (:class:`PoseFrontier`)."""
        return PoseFrontier(self.world.frontier(), self._heading)

    def bend_points(self) -> list[tuple[float, float, float]]:
        """The map's pinch points (:meth:`GridWorld.pinch_points`), each as the two
        poses that pass it along its free diagonal: heading up-right and down-left.
        Not the convex corners: a car turns round a corner, not on it."""
        poses = []
        for x, y in self.world.pinch_points():
            poses += [(x, y, 0.25 * math.pi), (x, y, 1.25 * math.pi)]
        return poses

    def distance_along_free_space(self, goal: Any, stop: Stop = None,
                                  focus: Optional[Sequence[float]] = None) -> "PoseGuide":
        """Position -> distance to the goal along the free cells (the grid's Dijkstra;
        lazy, toward ``focus``'s position, when one is given), with poses down the way
        for RRT*'s guided targets (:class:`PoseGuide`)."""
        cells = self.world.distance_along_cells(goal.point, stop, focus)
        return PoseGuide(cells, self.world.printable_point(goal.point))

    def prepare_distance_along_free_space(self) -> None:
        """Import the Dijkstra's module (the set-up of a planner that guides)."""
        self.world.prepare_distance_along_cells()


class PoseGuide:
    """The grid's distance down the free cells (:class:`~planning_core.worlds.
    grid_distance.CellDistanceToGoal`), with guided targets that are poses.

    A pose's target is where the cheapest chain of cells leaves the cell the pose is
    heading into: the middle of the side it crosses (the corner, on a diagonal step),
    heading across. In a corridor one cell wide, consecutive targets are joined by
    a straight line or a quarter circle of radius half a cell inside one cell: a car
    of radius 0.5 or less drives a maze from target to target. The goal's cell's
    target is the goal, heading from the pose to it."""

    NUDGE = 1e-9
    """How far ahead along its heading a pose's cell is looked up, so that a pose on
    a cell's side belongs to the cell it is entering."""

    def __init__(self, cells: Any, goal: tuple[float, float]) -> None:
        self.cells = cells
        self.goal = goal

    def __call__(self, x: float, y: float) -> float:
        distance: float = self.cells(x, y)
        return distance

    def bound(self, x: float, y: float) -> float:
        """At most the distance at (x, y), without measuring."""
        bound: float = self.cells.bound(x, y)
        return bound

    def ahead_of(self, state: Sequence[float], steps: int) -> Optional[tuple[float, float, float]]:
        """The pose ``steps`` sides down the chain from ``state``'s cell, or further
        while the chain goes straight on (:func:`~planning_core.worlds.grid_distance.
        straight_run_end`); in the goal's cell the goal; None without a chain, or at
        the goal."""
        x, y = state[0], state[1]
        if len(state) > 2:
            x, y = x + self.NUDGE * math.cos(state[2]), y + self.NUDGE * math.sin(state[2])
        chain = self.cells.chain_ahead(x, y, max(steps, RUN_CELLS))
        if chain is None:
            return None
        if len(chain) == 1:  # the goal's cell
            gx, gy = self.goal
            if (gx, gy) == (state[0], state[1]):
                return None
            return (gx, gy, mod2pi(math.atan2(gy - state[1], gx - state[0])))
        end = straight_run_end(chain, steps)
        step = chain_step(chain, end)
        (before_col, before_row), (col, row) = chain[end - 1], chain[end]
        return (0.5 * (col + before_col) + 0.5, 0.5 * (row + before_row) + 0.5,
                mod2pi(math.atan2(step[1], step[0])))


class PoseFrontier:
    """A grid frontier (:class:`~planning_core.worlds.grid_frontier.FrontierCells`) for
    poses: a node covers its position's cell, a target is a frontier point with a
    uniform heading."""

    def __init__(self, cells: Any, heading: Callable[[random.Random], float]) -> None:
        self.cells = cells
        self.heading = heading

    def __len__(self) -> int:
        return len(self.cells)

    def cover(self, state: Sequence[float]) -> None:
        self.cells.cover(state)

    def sample(self, rng: random.Random) -> tuple[float, float, float]:
        x, y = self.cells.sample(rng)
        return (x, y, self.heading(rng))
