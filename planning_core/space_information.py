"""What planners ask of the space they plan in: OMPL's two SpaceInformations, as
typed protocols.

A :class:`GeometricSpaceInformation` joins a system whose motions are straight
lines in its state space (the point vehicle on a grid; arm2 and rigid2) with a
world: validity, the motion check, sampling, nearest neighbours. A
:class:`ControlSpaceInformation` joins a system driven by controls (the grid's
spaceships; the pendulum and the cars) with a world: validity, propagation while
valid, control sampling, nearest neighbours, and what KPIECE1 and RG-RRT ask.
Start and goal are apart, in a :class:`~planning_core.problem_definition.ProblemDefinition`.

Each substrate implements both where it has such systems
(:mod:`planning_core.grid_space_information`,
:mod:`planning_core.family_space_information`,
:mod:`planning_core.family_geometric_space_information`); planners ask only what
is declared here, so none of them branches on the substrate or the vehicle. What
only some worlds can answer (a frontier of cells, distance along free space, a
proof that start and goal are cut off) is a capability: it answers None (or False)
where the world has none. A capability that may walk every cell of a big map takes
a ``stop`` and raises :class:`~planning_core.interrupt.Interrupted` when it says
the time is up. :mod:`planning_core.setups` builds the right one for a problem.

The protocols, with the goal's (:class:`Goal`), are for annotations only: modules
import this one under ``if TYPE_CHECKING``, so that no run imports ``typing``
(docs/setup-and-startup.md). They are not compiled: a compiled planner sees them as
``Any`` and calls whichever implementation it is given.
"""

from __future__ import annotations

import random
from typing import Any, Callable, Optional, Protocol, Sequence

from planning_core.interrupt import Stop
from planning_core.nearest.index import NearestIndex

State = tuple[float, ...]


class Goal(Protocol):
    """A goal region (a :class:`~planning_core.problem_definition.ProblemDefinition`'s)."""

    tolerance: float
    """The largest :meth:`distance` of a state in the region (so ``distance - tolerance``
    is a lower bound on the distance to the region: informed sampling's cost-to-go)."""

    def distance(self, state: Sequence[float]) -> float:
        """How far ``state`` is from the goal (the grid: by position; the family: the
        goal's metric)."""

    def accepts(self, state: Sequence[float]) -> bool:
        """The validator's test: within the tolerance."""

    def reached(self, state: Sequence[float]) -> bool:
        """The planners' test: a hair inside the tolerance (``goal.PLANNER_MARGIN``)."""


class MotionHit(Protocol):
    """Where a straight motion first meets an invalid state."""

    fraction: float
    """Of the motion's length, in (0, 1]."""


class GeometricSpaceInformation(Protocol):
    """A system moving along straight lines in its state space, in a world."""

    system: Any
    """The system (its names and rows: ``planning_core.plan_rows``)."""
    dimension: int
    """Of the state space (PRM*'s neighbour count)."""
    rechecks_prefix: bool
    """A motion cut short must be checked again (its samples are not the longer one's)."""
    lazy_edges: bool
    """A roadmap checks an edge only when a path takes it (cheap motion checks: no)."""
    free_targets: bool
    """Uniform targets from valid states only pay here (RRT-Connect's default)."""
    wall_clearance: float
    """How far a motion cut short stops before its first invalid state (the grid:
    a map unit; the family: one check step)."""
    rrt_guided_targets: float
    """RRT's and RRT-Connect's share of guided iterations by default (their params'
    ``guided_targets``): the Dubins car's 0.5, 0 elsewhere (the point's RRT is the
    course's reference loop)."""
    space: Any
    """The state space (``spaces.StateSpace``): bounds, angles and metric groups, whose
    distance :meth:`distance` is never below (informed sampling's ellipsoid)."""

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The state space's distance; also the cost of the straight motion a -> b (a
        path's cost is its length: map units for the point, the metric for arm2 and
        rigid2)."""

    def interpolate(self, a: Sequence[float], b: Sequence[float], t: float) -> State: ...

    def is_valid(self, state: Sequence[float]) -> bool: ...

    def can_end_at(self, state: Sequence[float]) -> bool:
        """Valid, and a path may end or turn there (the grid: strictly inside the map)."""

    def first_hit(self, a: Sequence[float], b: Sequence[float]) -> Optional[MotionHit]:
        """The first invalid state of the motion a -> b (``a`` not tested), or None."""

    def sample_target(self, rng: random.Random) -> State:
        """A uniform state, valid or not."""

    def free_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], State]:
        """``draw()``: a uniform valid state."""

    def roadmap_sampler(self, rng: random.Random, stop: Stop = None) -> Callable[[], State]:
        """``draw()``: a roadmap's next vertex."""

    def new_nearest(self) -> NearestIndex: ...

    def goal_target(self, goal: Goal, rng: random.Random) -> State:
        """A goal-biased target: a state of the goal region, valid or not."""

    def goal_configuration(self, goal: Goal, rng: random.Random) -> Optional[State]:
        """A valid state of the goal region where a path may end, or None."""

    def goal_center(self, goal: Goal) -> Optional[State]:
        """The state whose ball of ``goal.tolerance`` under :meth:`distance` is the goal
        region (the grid: the goal point; the family: a goal that names every
        variable), or None when the region is no such ball."""

    def certainly_unreachable(self, start: State, goal: Goal, stop: Stop = None) -> bool:
        """True only when it is proved that no motion joins start and goal."""

    def frontier(self) -> Any:
        """An empty frontier of cells (RRT-Connect's targets), or None."""

    def bend_points(self) -> Sequence[State]:
        """States where shortest paths bend or pass only exactly through (a grid's
        convex corners and its corners between two diagonal blocked cells): RRT*'s
        occasional targets once it has a solution."""

    def distance_along_free_space(self, goal: Goal, stop: Stop = None,
                                  focus: Optional[State] = None) -> Any:
        """Position -> distance to the goal along free space, with ``ahead_of(state,
        cells)`` (a state that many cells down the way, or None) and ``bound(x, y)`` (at
        most the distance, without measuring), for the guided targets; or None (the
        family). With a ``focus`` (a tree's root) the world may measure lazily, the
        way toward the focus first."""

    def prepare_distance_along_free_space(self) -> None:
        """Load the code :meth:`distance_along_free_space` runs: a planner's set-up,
        so that its first measuring on the planning clock pays no import."""


class ControlSpaceInformation(Protocol):
    """A system driven by controls, in a world."""

    system: Any
    """The system (its names and rows: ``planning_core.plan_rows``)."""
    controls_per_extension: int
    """Random controls RRT tries per extension, the valid one ending closest wins
    (OMPL's directed control sampler: the grid's ships 10, the family 1)."""
    rrt_guided_targets: float
    """RRT's share of guided iterations by default (``RRTParams.guided_targets``): 0."""

    selection_radius: float
    """SST's default selection radius, in :meth:`distance`'s units (the grid's ships:
    map units; the family: a share of the metric's largest distance)."""
    pruning_radius: float
    """SST's default pruning radius (a witness's region), as ``selection_radius``."""

    def is_valid(self, state: Sequence[float]) -> bool: ...

    def sample_target(self, rng: random.Random) -> State:
        """A uniform target for :meth:`new_nearest` and :meth:`closeness` (the grid: a
        position; the family: a state)."""

    def goal_target(self, goal: Goal, rng: random.Random) -> State:
        """A goal-biased target, as :meth:`sample_target`'s."""

    def frontier(self) -> Any:
        """An empty frontier of cells (SST's targets until its first solution), or None."""

    def new_nearest(self) -> NearestIndex: ...

    def closeness(self, a: Sequence[float], b: Sequence[float]) -> float:
        """Orders pairs as the space's distance does (the grid: the squared distance
        of the positions; the family: the metric): compared, never added."""

    def native_extension(self, count: int) -> Optional[Callable[..., Any]]:
        """The control RRT's extension, ``count`` sampled controls and the valid end
        nearest the target, as one native call ``extend(state, target, rng)`` with the
        same draws and floats (the grid ships with the compiled build), or None."""

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The distance :meth:`new_nearest` orders by (the grid: of the positions; the
        family: the metric), for radii such as SST's."""

    def state_distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """A distance over the whole state (the grid's ships: position and velocity;
        the family: :meth:`distance`), for SST's witnesses: states close by it fare
        alike from there on, which the grid's distance of positions does not say."""

    def new_state_nearest(self) -> NearestIndex:
        """An empty index ordered by :meth:`state_distance`."""

    def state_target(self, target: Sequence[float], rng: random.Random) -> Sequence[float]:
        """A target (:meth:`sample_target`, :meth:`goal_target`, a frontier point) as a
        whole state, for SST's selection by :meth:`state_distance` (the grid's ships:
        the position with a random velocity; the family: the target itself)."""

    def motion_cost(self, a: Sequence[float], control: Any, b: Sequence[float]) -> float:
        """The cost of the motion ``a`` -> ``b`` under ``control`` (the grid's ships:
        the distance of its positions; the family: its duration, K slices of dt)."""

    def sample_control(self, rng: random.Random) -> Any: ...

    def propagate_valid(self, state: Sequence[float], control: Any) -> Optional[State]:
        """Where ``control`` leads from ``state`` if every slice is valid, else None."""

    def random_motion(self, state: Sequence[float], rng: random.Random,
                      whole: bool = False) -> Optional[tuple[Any, list[State]]]:
        """A random control held for a random duration, cut at the first invalid
        slice: the control and the states of the nodes it makes (the grid: one per
        step; the family: one); None when it is shorter than the least duration, or,
        with ``whole``, than the duration drawn (OMPL's SST keeps no cut motion)."""

    def projection(self) -> Callable[[Sequence[float]], tuple[int, ...]]:
        """State -> its cell in KPIECE1's grid over a projection of the state."""

    def reachable_controls(self) -> list:
        """RG-RRT's fixed set of controls: each node's reachable set is where they lead."""

    def step_reach(self, state: Sequence[float], ends: list) -> float:
        """How far, in the goal's distance, ``state`` may get in one motion
        (``ends``: where its fixed controls lead)."""

    def stay_controls(self, start: State, goal: Goal) -> Optional[tuple]:
        """For a start in the goal region: the path's controls (none: the system's
        rest control is printed), or None when the start cannot stay there."""

    def certainly_unreachable(self, start: State, goal: Goal, stop: Stop = None) -> bool:
        """True only when it is proved that no motion joins start and goal."""

    def distance_along_free_space(self, goal: Goal, stop: Stop = None) -> Any:
        """Position (x, y) -> distance to the goal along free space, or None."""

    def stopping_point_key(self, along: Any) -> Optional[Callable[[State], float]]:
        """State -> ``along``'s distance of where full braking would stop it, or None
        where the system cannot say."""
