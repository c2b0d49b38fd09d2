"""The family's SpaceInformations (``kinoplan 1`` problems, SPEC 5):
:class:`FamilySpaceInformation`, what every family system answers, and
:class:`FamilyControlSpaceInformation`, the kinodynamic ones' (pendulum, car2,
unicycle, car1). The geometric ones' (arm2, rigid2) is in
:mod:`planning_core.family_geometric_space_information`.

Valid: the problem's state validator (bounds, body in the box, off every
obstacle); no printability test (the bounds are part of validity). Targets are
uniform states of the system's space; nearest neighbours and closeness are by the
metric (an exact kd-tree).
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any, Optional, Sequence

from planning_core.interrupt import Stop
from planning_core.kernels import space_metric
from planning_core.kinoplan import body_tester, invalid_reason, state_validator
from planning_core.samplers import MotionSampler

State = tuple[float, ...]


class FamilySpaceInformation:
    """A family system in its continuous world: what both kinds answer."""

    def __init__(self, problem: Any) -> None:
        self.problem = problem
        self.system = system = problem.system
        self.world = problem.world
        self.space = system.space
        self.is_valid = state_validator(system, self.world)
        self.kernels: dict[str, Any] = {"metric": space_metric(self.space)}
        """The hot kernels' objects by name, as ``planning_core.kernels.describe`` names
        their versions."""
        self._sample = self.space.sample_uniform
        self.sample_target = self._sample  # the method below, bound (the hot path)

    def sample_target(self, rng: random.Random) -> State:
        """A uniform state of the system's space (valid or not)."""
        return self._sample(rng)

    def frontier(self) -> None:
        """No frontier of cells in a continuous space."""
        return None

    def bend_points(self) -> list:
        """Empty: no state of a continuous world is singled out."""
        return []

    def distance_along_free_space(self, goal: Any, stop: Stop = None,
                                  focus: Any = None) -> None:
        """No cells to walk in a continuous world."""
        return None

    def prepare_distance_along_free_space(self) -> None:
        """Nothing to load."""

    def goal_target(self, goal: Any, rng: random.Random) -> State:
        """The goal's values; the variables it does not name from a uniform sample
        (one draw per variable; none when the goal names every variable)."""
        if goal.full:
            return goal.target
        return goal.complete(self._sample(rng))

    def new_nearest(self) -> Any:
        """An empty nearest-node index over full states (kd-tree, the metric; leaves
        of 24: RG-RRT's inserts cheapest, RRT's queries as fast as with 16,
        docs/planners-family.md)."""
        from planning_core.nearest.kdtree import KDTree
        return KDTree(self.space, leaf_capacity=24)

    def invalid_reason(self, state: Sequence[float]) -> Optional[str]:
        """Why ``state`` is not valid (a bound, the box, which obstacle), or None."""
        return invalid_reason(self.system, self.world, state, self.problem.obstacle_lines)

    def certainly_unreachable(self, start: State, goal: Any, stop: Stop = None) -> bool:
        """Never proved in a continuous world."""
        return False


@dataclass(frozen=True)
class FamilyControlOptions:
    """How the family's kinodynamic systems move for the planners that ask more."""

    controls_per_extension: int = 1
    """RRT: random controls tried per extension (1, as OMPL's control RRT, beat 10 on
    every family problem: docs/planners-family.md)."""
    projection_cells: int = 64
    """KPIECE1's grid: each of the system's ``projection_names`` cut into this many cells."""
    reach_levels: int = 2
    """RG-RRT's reachable set: each held control at this many evenly spaced values
    over its bounds, every combination (2: the corners of the control box)."""
    reach_seconds: float = 0.5
    """RG-RRT's reachable set: how long each control is held (K is this over DT,
    rounded, within [KMIN, KMAX])."""
    selection_share: float = 0.01
    """SST's selection radius as a share of the metric's largest distance
    (``StateSpace.maximum_extent``: the systems' spaces differ a hundredfold)."""
    pruning_share: float = 0.005
    """SST's pruning radius (a witness's region), as ``selection_share``."""

    def __post_init__(self) -> None:
        for name in ("controls_per_extension", "projection_cells", "reach_levels"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} must be at least 1")
        if not (self.selection_share >= 0.0 and self.pruning_share >= 0.0):
            raise ValueError("selection_share and pruning_share must be >= 0")
        if not self.reach_seconds > 0.0:
            raise ValueError("reach_seconds must be positive")


class FamilyControlSpaceInformation(FamilySpaceInformation):
    """A kinodynamic family system: controls held for K slices, K in [KMIN, KMAX]."""

    def __init__(self, problem: Any,
                 options: FamilyControlOptions = FamilyControlOptions()) -> None:
        super().__init__(problem)
        system = self.system
        self.options = options
        self.controls_per_extension = options.controls_per_extension
        self.rrt_guided_targets = 0.0
        extent = self.space.maximum_extent()
        self.selection_radius = options.selection_share * extent
        self.pruning_radius = options.pruning_share * extent
        self.duration = (system.kmin, system.kmax)
        # The metric as the kd-tree measures (compiled: a native call, the same floats).
        self.closeness = self.kernels["metric"].distance
        # The validity test fused into the integration loop (the hot path; the
        # generated class's methods, native calls in the compiled build).
        body = body_tester(system, self.world)
        fused = system.integrator(body)
        self.kernels.update({"integrator": fused, "body test": body})
        self.advance = fused.advance
        self.propagate_valid = fused.propagate_valid
        self.sample_control = system.sample_control
        # KPIECE1's and SST's random motion (samplers.MotionSampler: the draws, then
        # the slices).
        self.random_motion = MotionSampler(system.control_sampler, fused.advance).sample

    def propagate_valid(self, state: Sequence[float], control: Any) -> Optional[State]:
        """Where ``control`` leads from ``state`` if every slice is valid; else None.
        (Each instance shadows this with the fused version.)"""
        return self.system.propagate_while(state, control, self.is_valid)

    def advance(self, state: Sequence[float], control: Any, kmax: int) -> tuple[State, int]:
        """``(state, k)``: ``control``'s held values applied for up to ``kmax``
        slices, stopped before the first invalid one; the last valid state and
        how many slices led to it (each instance shadows this with the fused one)."""
        raise NotImplementedError

    @staticmethod
    def native_extension(count: int) -> None:
        """None: the family's control RRT extends by the steering's own loop."""
        return None

    def sample_control(self, rng: random.Random) -> tuple:
        return self.system.sample_control(rng)

    def closeness(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The metric (each instance shadows this with the kd-tree's)."""
        return self.space.distance(a, b)

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The metric (what :meth:`new_nearest` orders by)."""
        return self.closeness(a, b)

    def state_distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The metric, as :meth:`distance`: it weighs the whole state already."""
        return self.closeness(a, b)

    def new_state_nearest(self) -> Any:
        """As :meth:`new_nearest`."""
        return self.new_nearest()

    @staticmethod
    def state_target(target: Sequence[float], rng: random.Random) -> Sequence[float]:
        """``target`` itself: the family's targets are whole states already (no draw)."""
        return target

    def motion_cost(self, a: Sequence[float], control: Any, b: Sequence[float]) -> float:
        """The motion's duration: K (the control's last value) slices of dt."""
        return control[-1] * self.system.dt

    def random_motion(self, state: Sequence[float], rng: random.Random,
                      whole: bool = False) -> Optional[tuple[Any, list[State]]]:
        """Random held values and K (in that order), cut at the first invalid slice:
        the control with the slices done as its K, and its end; None under KMIN
        (``whole``: under K; each instance shadows this with
        ``samplers.MotionSampler.sample``)."""
        raise NotImplementedError

    def projection(self) -> Any:
        """KPIECE1's cells: ``projection_cells`` over each of the system's
        ``projection_names``' bounds."""
        from planning_core.projections import AxesProjection
        return AxesProjection(self.system.projection_axes(self.options.projection_cells))

    def reachable_controls(self) -> list:
        """Every combination of ``reach_levels`` values per held control, each held
        for ``reach_seconds``."""
        system, options = self.system, self.options
        k = min(max(round(options.reach_seconds / system.dt), system.kmin), system.kmax)
        return system.reachable_controls(options.reach_levels, k)

    def step_reach(self, state: State, ends: list) -> float:
        """The farthest of ``ends`` from ``state`` by the metric."""
        return max((self.closeness(state, end) for end in ends), default=0.0)

    def stay_controls(self, start: State, goal: Any) -> Optional[tuple]:
        """One held control, each value 0 clamped into its bounds, for KMIN slices,
        when every slice is valid and the end is still in the goal region; else None
        (then plan as usual)."""
        system = self.system
        control = tuple(min(max(0.0, lo), hi) for lo, hi in system.controls) + (system.kmin,)
        end = self.propagate_valid(start, control)
        return (control,) if end is not None and goal.reached(end) else None

    def stopping_point_key(self, along: Any) -> None:
        return None
