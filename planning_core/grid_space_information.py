"""The grid's SpaceInformations: the course's vehicles on a ``.sw`` map
(:mod:`planning_core.space_information` says what each answers).

:class:`GridGeometricSpaceInformation`, the point vehicle: straight segments
checked exactly (every cell a segment touches), nearest by position (a quadtree),
targets over the open map or the free cells, the frontier of a tree and a proof
that the start and goal are cut off. :class:`GridControlSpaceInformation`, the
spaceships: a control held for one step of 20 slices, every slice's position
checked, nearest by position, and what KPIECE1 and RG-RRT ask, set by
:class:`GridControlOptions`.

Compiled (mypyc, ``rrt_startup.compiled``): the grid planners ask these several
times per iteration, so their methods are native calls into the compiled world.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from planning_core.interrupt import Stop
from planning_core.nearest.index import NearestIndex
from planning_core.samplers import randint, uniform
from planning_core.worlds.grid import GridWorld, SegmentHit

TYPE_CHECKING = False
if TYPE_CHECKING:  # for the annotation only: the quadtree is imported when a planner asks
    from typing import Any, Callable, Optional, Sequence
    from planning_core.nearest.quadtree import QuadtreeNearest

# Ranks a braking line that meets a blocked cell after every free one (well below
# the distance's "unreachable", so those still order among themselves).
BLOCKED_BRAKING_PENALTY = 1e6


class GridGeometricSpaceInformation:
    """The point vehicle on a grid: straight segments, checked exactly."""

    def __init__(self, system: Any, world: GridWorld) -> None:
        self.system = system
        self.world = world
        self.dimension = 2
        self.rechecks_prefix = False
        """The cell walk is exact: a prefix of a free segment is free."""
        self.lazy_edges = False
        """A roadmap checks each edge when it is made (the walk is cheap)."""
        self.free_targets = True
        """Uniform over the free cells (on mazes most map targets lie in walls)."""
        self.wall_clearance = 1.0
        """A segment cut short stops a map unit before the wall (docs/parameter-history.md)."""
        self.rrt_guided_targets = 0.0
        """RRT is the course's reference loop: uniform targets."""
        self.printable = world.point_strictly_inside

    @property
    def space(self) -> Any:
        """The map's rectangle (spaces.StateSpace)."""
        return self.system.state_space(self.world.width, self.world.height)

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        return math.hypot(b[0] - a[0], b[1] - a[1])

    def interpolate(self, a: Sequence[float], b: Sequence[float],
                    t: float) -> tuple[float, float]:
        return (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)

    def is_valid(self, state: Sequence[float]) -> bool:
        """The position is free (SPEC 1: in the map, not in a blocked cell)."""
        return self.world.point_free(state[0], state[1])

    def can_end_at(self, state: Sequence[float]) -> bool:
        """Free and printable (SPEC 2: strictly inside the map)."""
        world = self.world
        return (world.point_free(state[0], state[1])
                and world.point_strictly_inside(state[0], state[1]))

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> SegmentHit | None:
        """Where the segment a -> b first enters a blocked cell (or leaves the
        map), walked exactly; None when it is free."""
        return self.world.first_blocked_cell_on_segment(a[0], a[1], b[0], b[1])

    def sample_target(self, rng: random.Random) -> tuple[float, float]:
        """A uniform position of the open map (blocked cells included)."""
        return self.world.sample_open_position(rng)

    def free_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], Any]:
        """``draw()``: uniform over the free cells (built once: it may walk the map)."""
        from planning_core.worlds.grid_cells import sample_free_point
        free_cells, width = self.world.free_cell_indices(stop), self.world.width
        return lambda: sample_free_point(rng, free_cells, width)

    def roadmap_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], Any]:
        """A roadmap's vertices: uniform over the free cells, as :meth:`free_sampler`."""
        return self.free_sampler(rng, stop)

    def new_nearest(self) -> PositionNearest:
        """An empty nearest-node index (a quadtree over the map, by position)."""
        return PositionNearest(self.world.width, self.world.height)

    def goal_target(self, goal: Any, rng: random.Random) -> tuple[float, float]:
        """The goal point, nudged inside the map when it lies on the left or bottom
        edge (a node there could not be printed). No ``rng``."""
        return self.world.printable_point(goal.point)

    def goal_configuration(self, goal: Any, rng: random.Random) -> tuple[float, float]:
        """Where a path ends: :meth:`goal_target`."""
        return self.world.printable_point(goal.point)

    def goal_center(self, goal: Any) -> tuple[float, float]:
        """The goal point itself (the region is the disc of the tolerance around it)."""
        return (goal.point[0], goal.point[1])

    def certainly_unreachable(self, start: Sequence[float], goal: Any,
                              stop: Stop = None) -> bool:
        """No chain of free cells joins the start's and the goal's (8-connected)."""
        return self.world.certainly_disconnected(start, goal.point, stop)

    def frontier(self) -> Any:
        """An empty frontier of the map's free cells."""
        return self.world.frontier()

    def bend_points(self) -> list[tuple[float, float]]:
        """The map's corners between two diagonal blocked cells that a path may pass
        through (:meth:`GridWorld.pinch_points`), then its convex corners, where
        shortest paths bend (:meth:`GridWorld.convex_corners`)."""
        return self.world.pinch_points() + self.world.convex_corners()

    def distance_along_free_space(self, goal: Any, stop: Stop = None,
                                  focus: Optional[Sequence[float]] = None) -> Any:
        """Position -> distance to the goal along the free cells (Dijkstra; lazy, toward
        ``focus``'s position, when one is given), with ``ahead_of(state, cells)``: a
        point that many cells down the way."""
        return self.world.distance_along_cells(goal.point, stop, focus)

    def prepare_distance_along_free_space(self) -> None:
        """Import the Dijkstra's module (the set-up of a planner that guides)."""
        self.world.prepare_distance_along_cells()


@dataclass(frozen=True)
class GridControlOptions:
    """How the grid's ships move for the planners that ask more than one step."""

    controls_per_extension: int = 10
    """RRT: random controls tried per extension, the valid one ending closest wins."""
    min_steps: int = 1
    """KPIECE1's random motion: fewest steps (one step: one control for 20 slices) kept."""
    max_steps: int = 10
    """KPIECE1's random motion: most steps a random control is held for."""
    cell_size: Optional[float] = None
    """KPIECE1's projection cell side in map units; None: half a map cell on maps
    under 20 cells a side, one map cell (a maze corridor's width) on larger ones."""
    velocity_cell_size: Optional[float] = 0.2
    """With a value, KPIECE1 projects on position and velocity, velocities binned at
    this size (map units per step); None: the position only."""
    reach_angles: int = 8
    """RG-RRT's reachable set: thrust directions, evenly spaced from straight ahead
    over the ship's theta range (a half turn closed at both ends: braking included)."""
    reach_thrusts: tuple[float, ...] = (0.5,)
    """RG-RRT's reachable set: thrust magnitudes at every angle (coasting always too)."""
    velocity_weight: float = 1.0
    """SST's witnesses: the weight of the velocity (map units per step) beside the
    position's in :meth:`GridControlSpaceInformation.state_distance`."""
    selection_radius: float = 0.25
    """SST: a node is chosen as the cheapest active one this close to a target, map units."""
    target_speed: float = 1.0
    """SST's targets are whole states: each velocity component uniform in
    ``[-target_speed, target_speed]`` (map units per step) beside the target position."""
    pruning_radius: float = 0.25
    """SST: a witness's region, map units (at most one active node in each)."""

    def __post_init__(self) -> None:
        if self.controls_per_extension < 1 or self.reach_angles < 1:
            raise ValueError("controls_per_extension and reach_angles must be at least 1")
        if not 1 <= self.min_steps <= self.max_steps:
            raise ValueError("need 1 <= min_steps <= max_steps")
        for name in ("cell_size", "velocity_cell_size"):
            value = getattr(self, name)
            if value is not None and not value > 0.0:
                raise ValueError(f"{name} must be positive")
        if not (self.selection_radius >= 0.0 and self.pruning_radius >= 0.0
                and self.velocity_weight >= 0.0 and self.target_speed >= 0.0):
            raise ValueError("selection_radius, pruning_radius, velocity_weight and "
                             "target_speed must be >= 0")
        if not all(thrust > 0.0 for thrust in self.reach_thrusts):
            raise ValueError("reach_thrusts must be positive")


def derived_cell_size(width: float, height: float) -> float:
    """KPIECE1's projection cell side on a map of this size (GridControlOptions.cell_size)."""
    return 0.5 if max(width, height) < 20 else 1.0


class GridControlSpaceInformation:
    """A spaceship on a grid: a control held for one step, every slice checked."""

    def __init__(self, system: Any, world: GridWorld,
                 options: GridControlOptions = GridControlOptions()) -> None:
        self.system = system
        self.world = world
        self.options = options
        self.controls_per_extension = options.controls_per_extension
        self.rrt_guided_targets = 0.0
        self.selection_radius = options.selection_radius
        self._state_metric: Any = None  # made on first use (SST's): start-up
        self.pruning_radius = options.pruning_radius
        self.printable = world.point_strictly_inside
        self.sample_control: Any = system.sample_control

    @property
    def space(self) -> Any:
        """Positions within the map, velocities unbounded (spaces.StateSpace)."""
        return self.system.state_space(self.world.width, self.world.height)

    def is_valid(self, state: Sequence[float]) -> bool:
        """The position is free (SPEC 1: in the map, not in a blocked cell)."""
        return self.world.point_free(state[0], state[1])

    def propagate_valid(self, state: Sequence[float], control: Any) -> Any:
        """Where ``control`` leads from ``state`` in one step if every slice is
        valid and the end prints strictly inside the map; else None."""
        end: Optional[tuple[float, ...]] = self.system.propagate_while(state, control,
                                                                       self.world)
        if end is None or not (end[0] > 0.0 and end[1] > 0.0):
            return None
        return end

    def native_extension(self, count: int) -> Any:
        """The control RRT's sampled extension (``count`` controls from
        :meth:`sample_control`, each through :meth:`propagate_valid`, the end nearest
        the target by :meth:`closeness`) in C, the same draws and floats
        (``systems/ship_kernel.c``): its ``extend(state, target, rng)``. Only the
        compiled build holds it, else None."""
        try:
            from planning_core.systems._ship_kernel import ShipKernel
        except ImportError:
            return None
        system, world = self.system, self.world
        return ShipKernel(world.cells, world.width, world.height, count, system.theta_range,
                          system.max_thrust).extend

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> SegmentHit | None:
        """Where the straight segment between two positions first meets a blocked
        cell, walked exactly; None when it is free."""
        return self.world.first_blocked_cell_on_segment(a[0], a[1], b[0], b[1])

    def sample_target(self, rng: random.Random) -> tuple[float, float]:
        """A uniform position of the open map (blocked cells included)."""
        return self.world.sample_open_position(rng)

    def goal_target(self, goal: Any, rng: random.Random) -> tuple[float, float]:
        """The goal point, nudged inside the map when it lies on the left or bottom
        edge. No ``rng``."""
        return self.world.printable_point(goal.point)

    def frontier(self) -> Any:
        """An empty frontier of the map's free cells (a node covers its position's)."""
        return self.world.frontier()

    def new_nearest(self) -> PositionNearest:
        """An empty nearest-node index (a quadtree over the map, by position)."""
        return PositionNearest(self.world.width, self.world.height)

    @staticmethod
    def closeness(end: tuple[float, ...], target: tuple[float, ...]) -> float:
        """The squared distance of the positions (products, not ``** 2``: compiled,
        a power is a generic call)."""
        dx, dy = end[0] - target[0], end[1] - target[1]
        return dx * dx + dy * dy

    @staticmethod
    def distance(a: Sequence[float], b: Sequence[float]) -> float:
        """The distance of the positions (what :meth:`new_nearest` orders by)."""
        return math.hypot(a[0] - b[0], a[1] - b[1])

    def state_distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The positions' distance plus ``velocity_weight`` times the velocities'."""
        metric = self._state_metric
        if metric is None:
            from planning_core.kernels import space_metric
            metric = self._state_metric = space_metric(self.state_space())
        distance: float = metric.distance(a, b)
        return distance

    def state_space(self) -> Any:
        """:meth:`space` with the velocities weighed (``velocity_weight``)."""
        return self.system.state_space(self.world.width, self.world.height,
                                       self.options.velocity_weight)

    def state_target(self, target: Sequence[float], rng: random.Random) -> tuple:
        """``target`` (a position) as a whole state: a velocity drawn uniformly in
        ``[-target_speed, target_speed]`` per component (x first)."""
        speed = self.options.target_speed
        return (target[0], target[1], (2.0 * uniform(rng) - 1.0) * speed,
                (2.0 * uniform(rng) - 1.0) * speed)

    def new_state_nearest(self) -> NearestIndex:
        """An empty kd-tree ordered by :meth:`state_distance`."""
        from planning_core.nearest.kdtree import KDTree
        return KDTree(self.state_space())

    def motion_cost(self, a: Sequence[float], control: Any, b: Sequence[float]) -> float:
        """One step's cost: the distance of its positions (a path's cost is the sum over
        its steps, the length of the polyline through its printed positions)."""
        return math.hypot(a[0] - b[0], a[1] - b[1])

    def random_motion(self, state: tuple[float, ...], rng: random.Random,
                      whole: bool = False) -> Optional[tuple[Any, list]]:
        """A random control held for ``min_steps`` to ``max_steps`` steps (drawn in
        that order), stopped before the first invalid step: the control and each
        step's state; None when fewer than ``min_steps`` were valid (``whole``: than
        the steps drawn)."""
        options = self.options
        control = self.sample_control(rng)
        wanted = randint(rng, options.min_steps, options.max_steps)
        steps: list = []
        at = state
        for _ in range(wanted):
            end = self.propagate_valid(at, control)
            if end is None:
                break
            steps.append(end)
            at = end
        return (control, steps) if len(steps) >= (wanted if whole else options.min_steps) \
            else None

    def projection(self) -> Any:
        """KPIECE1's cells: the position in cells of ``cell_size`` (and the velocity
        in cells of ``velocity_cell_size``)."""
        from planning_core.projections import AxesProjection
        options, system = self.options, self.system
        cell = options.cell_size or derived_cell_size(self.world.width, self.world.height)
        axes = [(system.position_indices[0], 0.0, 1.0 / cell),
                (system.position_indices[1], 0.0, 1.0 / cell)]
        velocity = options.velocity_cell_size
        if velocity is not None and system.velocity_indices:
            axes += [(index, 0.0, 1.0 / velocity) for index in system.velocity_indices[:2]]
        return AxesProjection(axes)

    def reachable_controls(self) -> list:
        """Coasting and every thrust at ``reach_angles`` directions (the system's)."""
        return self.system.reachable_controls(self.options.reach_angles,
                                              self.options.reach_thrusts)

    def step_reach(self, state: tuple[float, ...], ends: list) -> float:
        """How far the position can get in one step, at most (speed plus thrust)."""
        reach: float = self.system.step_reach(state)
        return reach

    def stay_controls(self, start: Sequence[float], goal: Any) -> Optional[tuple]:
        """A start in the goal region is the whole path; the rest control is printed."""
        return ()

    def certainly_unreachable(self, start: Sequence[float], goal: Any,
                              stop: Stop = None) -> bool:
        """Never proved: slices are checked only at their positions, so a ship may
        legally hop a thin wall."""
        return False

    def distance_along_free_space(self, goal: Any, stop: Stop = None) -> Any:
        """Position -> distance to the goal along the free cells (Dijkstra, once)."""
        return self.world.distance_along_cells(goal.point, stop)

    def stopping_point_key(self, along: Any) -> Callable[[Any], float]:
        """State -> ``along``'s distance of where full braking would stop the ship;
        a braking line that meets a blocked cell ranks after every free one."""
        stopping_point, first_hit = self.system.stopping_point, self.first_hit
        unreachable: float = along.unreachable

        def key(state: Any) -> float:
            stop_at = stopping_point(state)
            distance: float = along(stop_at[0], stop_at[1])
            if distance >= unreachable or first_hit(state, stop_at) is not None:
                penalised: float = along(state[0], state[1]) + BLOCKED_BRAKING_PENALTY
                return penalised
            return distance

        return key


class PositionNearest(NearestIndex):
    """The grid's nearest-node index: a quadtree over states' (x, y)."""

    def __init__(self, width: float, height: float):
        from planning_core.nearest.quadtree import QuadtreeNearest  # planners only: start-up
        self.index: QuadtreeNearest = QuadtreeNearest(width, height)

    def add(self, state: tuple[float, ...]) -> int:
        return self.index.add(state[0], state[1])

    def nearest(self, target: tuple[float, ...]) -> int:
        return self.index.nearest(target[0], target[1])

    def k_nearest(self, target: tuple[float, ...], k: int) -> list[int]:
        return self.index.k_nearest(target[0], target[1], k)

    def within(self, target: tuple[float, ...], radius: float) -> list[int]:
        """By the positions' distance (its square against ``radius``'s)."""
        return self.index.within(target[0], target[1], radius)

    def cheapest_within(self, target: tuple[float, ...], radius: float,
                        costs: list[float]) -> int:
        return self.index.cheapest_within(target[0], target[1], radius, costs)

    def remove(self, index: int) -> None:
        self.index.remove(index)
