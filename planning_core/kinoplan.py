"""A ``kinoplan 1`` problem (SPEC 5) as frozen values: the configured system, the
world, the start and the goal region. ``kinoplan_text`` reads one from text.

The goal names some state variables and a tolerance: a state is in it when the
metric restricted to those variables (each group keeps only its named members,
with its weight; angle differences wrapped) is at most the tolerance.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Optional

from planning_core.goal import PLANNER_MARGIN, MetricGoalTest
from planning_core.spaces import StateSpace
from planning_core.systems.family import FamilySystem
from planning_core.worlds.continuous import CLEARANCE_MARGIN, OUTSIDE_BOX, ContinuousWorld
from planning_core.worlds.body_tests import BodyTest
from planning_core.worlds.link_tests import LinkTests

State = tuple[float, ...]

MAX_MAGNITUDE = 1e9
"""The largest magnitude of a problem's numbers (and of an answer's angles): within
it, a system's arithmetic over KMAX slices, the metric's and angle differences stay
finite."""
MIN_POSITIVE = 1e-9
"""The least value of a problem's number that must be > 0 (a length, a step, a
weight, a tolerance): car1's ``v / L`` stays finite, and no step is subnormal."""


@dataclass(frozen=True)
class FamilyGoal:
    """Named state variables, their values and the tolerance around them."""

    space: StateSpace
    """The state space, its metric restricted to the goal's variables."""
    values: tuple[tuple[str, float], ...]
    """``(name, value)`` per goal variable, in the order the problem gives them."""
    tolerance: float
    """Largest accepted restricted distance."""
    target: State = field(init=False, repr=False, compare=False)
    """A full state: the goal values at their indices, 0 elsewhere (unused by the metric)."""

    def __post_init__(self) -> None:
        from planning_core.kernels import space_metric
        target = [0.0] * self.space.dimension
        for name, value in self.values:
            target[self.space.index(name)] = value
        object.__setattr__(self, "target", self.space.wrap(target))
        # The planners ask these per motion: bound to the instance, native calls in
        # the compiled build (the methods below say the same).
        test = MetricGoalTest(space_metric(self.space), self.target, self.tolerance)
        object.__setattr__(self, "metric", test.metric)  # (what -stats names)
        object.__setattr__(self, "distance", test.distance)
        object.__setattr__(self, "reached", test.reached)

    def __reduce__(self):
        # The bound test cannot be pickled: rebuild it from the fields.
        return (type(self), (self.space, self.values, self.tolerance))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(name for name, _ in self.values)

    @property
    def full(self) -> bool:
        """The goal names every state variable: it is one state and its surroundings."""
        return len(self.values) == self.space.dimension

    def distance(self, state: Sequence[float]) -> float:  # (shadowed: goal.MetricGoalTest)
        return self.space.distance(state, self.target)

    def accepts(self, state: Sequence[float]) -> bool:
        """The validator's test: within the tolerance."""
        return self.space.distance(state, self.target) <= self.tolerance

    def reached(self, state: Sequence[float]) -> bool:
        """The planners' test, a hair inside the tolerance (as ``goal.GoalRegion``;
        shadowed by ``goal.MetricGoalTest``'s, the same floats)."""
        return self.space.distance(state, self.target) <= self.tolerance * (1 - PLANNER_MARGIN)

    def complete(self, state: Sequence[float]) -> State:
        """``state`` with the goal's variables set to their values (a goal-biased target)."""
        out = list(state)
        for name, _ in self.values:
            i = self.space.index(name)
            out[i] = self.target[i]
        return tuple(out)


def make_goal(space: StateSpace, values: Mapping[str, float], tolerance: float) -> FamilyGoal:
    """The goal region of ``values`` within ``tolerance`` under ``space``'s metric.

    ValueError when a goal variable is in no metric group (its distance would be 0).
    """
    named = {space.index(name) for name in values}
    grouped = {i for indices, _ in space.groups for i in indices}
    for name in values:
        if space.index(name) not in grouped:
            raise ValueError(f"goal variable {name} is in no metric group")
    groups = tuple((kept, weight) for kept, weight in
                   ((tuple(i for i in indices if i in named), weight)
                    for indices, weight in space.groups) if kept)
    return FamilyGoal(StateSpace(space.variables, groups), tuple(values.items()),
                      float(tolerance))


@dataclass(frozen=True)
class KinoplanProblem:
    """Everything a ``kinoplan 1`` text says, checked (start valid, goal sensible)."""

    system: FamilySystem
    """The configured system: bounds, metric, body, controls, integrator, duration, check."""
    world: Optional[ContinuousWorld]
    """The workspace and obstacles; None for the pendulum."""
    start: State
    """The start state, angles wrapped to [-pi, pi]."""
    goal: FamilyGoal
    """The goal region."""
    obstacle_lines: tuple[int, ...] = ()
    """The problem line of each obstacle, in world order (for messages)."""

    @property
    def system_name(self) -> str:
        return self.system.name

    @property
    def space(self) -> StateSpace:
        """Variables, bounds and the metric groups."""
        return self.system.space

    @property
    def control_bounds(self) -> tuple[tuple[float, float], ...]:
        return getattr(self.system, "controls", ())

    @property
    def integrator(self) -> Optional[tuple[str, float]]:
        """``(scheme, dt)``, kinodynamic systems only."""
        return (self.system.scheme, self.system.dt) if self.system.kinodynamic else None

    @property
    def duration(self) -> Optional[tuple[int, int]]:
        """``(KMIN, KMAX)``, kinodynamic systems only."""
        return (self.system.kmin, self.system.kmax) if self.system.kinodynamic else None

    @property
    def check(self) -> Optional[float]:
        """The motion check step, geometric systems only."""
        return None if self.system.kinodynamic else self.system.check


def state_validator(system: FamilySystem,
                    world: Optional[ContinuousWorld]) -> Callable[[Sequence[float]], bool]:
    """``valid(state)`` for ``system`` in ``world`` (SPEC 5.2): finite, within the
    bounds, and what the system occupies (its body placed at (x, y, theta), or
    the arm's two links) inside the closed world box and off every closed
    obstacle. Without a world, or for the pendulum, the bounds alone. Bind it
    once: the validator calls it after every slice. (A kinodynamic system's is its
    integrator's, the very test the planners' slice loop makes.)"""
    if system.kinodynamic:
        return system.integrator(body_tester(system, world)).valid
    in_bounds = system.in_bounds
    if world is None or not system.occupies:
        return in_bounds
    if system.occupies == "links":
        return link_tests(system, world).valid
    free = body_tester(system, world).free

    def valid(state: Sequence[float]) -> bool:
        return in_bounds(state) and free(state[0], state[1], state[2])
    return valid


def body_tester(system: FamilySystem, world: Optional[ContinuousWorld]) -> Optional[BodyTest]:
    """The body test (its ``free(x, y, theta)``) of a system whose body is placed at
    its first three state variables (``world.body_tester``); None when it puts no
    body in a world."""
    if world is None or system.occupies != "body":
        return None
    if system.body is None:
        raise ValueError(f"{system.name} has no body (a problem must give one)")
    return world.body_tester(system.body)


def link_tests(system: FamilySystem, world: Optional[ContinuousWorld]) -> Optional[LinkTests]:
    """The arm's links bound to ``world`` (``world.link_tests``: its validity test,
    motion reach and motion check), else None.

    The reach's margin, far above rounding, scales with the world's and the
    arm's extent."""
    if world is None or system.occupies != "links":
        return None
    margin = CLEARANCE_MARGIN * max(world.scale(), abs(system.base_x) + system.l1 + system.l2,
                                    abs(system.base_y) + system.l1 + system.l2)
    variables = system.space.variables
    lows = [-math.inf if v.angle else v.low for v in variables]
    highs = [math.inf if v.angle else v.high for v in variables]
    return world.link_tests(system.base_x, system.base_y, system.l1, system.l2,
                            lows, highs, margin)


def state_valid(system: FamilySystem, world: Optional[ContinuousWorld],
                state: Sequence[float]) -> bool:
    """One state's validity; in loops, bind :func:`state_validator` once."""
    return state_validator(system, world)(state)


def invalid_reason(system: FamilySystem, world: Optional[ContinuousWorld],
                   state: Sequence[float], obstacle_lines: Sequence[int] = ()) -> Optional[str]:
    """Why ``state`` is not valid (a bound, the world box, which obstacle and, given
    ``obstacle_lines``, its problem line), or None. Agrees with :func:`state_validator`."""
    reason = system.bounds_violation(state)
    if reason is not None or world is None or not system.occupies:
        return reason
    if system.occupies == "links":
        shapes = zip(("link 1 (base to elbow)", "link 2 (elbow to tip)"), system.links(state))
    else:
        shapes = (("the body", system.footprint(state)),)
    for what, shape in shapes:
        hit = world.first_obstacle(shape)
        if hit == OUTSIDE_BOX:
            return f"{what} is not inside the world box"
        if hit is not None:
            where = f" (line {obstacle_lines[hit]})" if hit < len(obstacle_lines) else ""
            return f"{what} touches obstacle {hit + 1}{where}"
    return None
