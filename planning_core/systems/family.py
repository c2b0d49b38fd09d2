"""What the six systems of SPEC 5.2 share (pendulum, car2, unicycle, car1: kinodynamic;
arm2, rigid2: geometric). Not a system itself: each system is a subclass in its own
module, with its names, dynamics and ``DEFAULTS`` (SPEC 5.2's table).

A configured system is a frozen dataclass: bounds, metric and body (every system),
control bounds, integrator and duration (kinodynamic), check step (geometric),
then the system's own parameters. A field left at None takes the system's
default; :meth:`FamilySystem.configure` builds one from a problem's items.
Systems know nothing of worlds: a system says what it puts in the workspace
(``occupies``: its ``footprint`` or its ``links``), ``planning_core.kinoplan``
tests that against a world, and ``propagate_while`` takes the test as a function.
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar, Optional

from planning_core import kernels
from planning_core.integrators import Dynamics, check_scheme, slice_count
from planning_core.samplers import BoxSampler, ControlSampler
from planning_core.spaces import StateSpace, Variable
from planning_core.worlds.shapes import ConvexPolygon, Rect, body_polygon, place

State = tuple[float, ...]
Bounds = tuple[tuple[float, float], ...]
Metric = tuple[tuple[tuple[str, ...], float], ...]
# One held control may run at most this many slices (a larger KMAX is a bad problem).
MAX_SLICES = 1_000_000
UNBOUNDED = (-math.inf, math.inf)
ANGLE_RANGE = (-math.pi, math.pi)  # what an angle's bound reads as (angles wrap: unused)


@dataclass(frozen=True)
class Defaults:
    """A system's row of SPEC 5.2's table; anything absent is unbounded or not used."""

    bounds: Mapping[str, tuple[float, float]]
    """Validity bounds of the non-angle state variables that have one."""
    metric: Metric
    """The distance's groups: variable names and weight."""
    controls: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    """Bounds of each held control (kinodynamic)."""
    integrate: tuple[str, float] = ("rk4", 0.05)
    """Scheme and slice length DT in seconds (kinodynamic)."""
    duration: tuple[int, int] = (1, 1)
    """KMIN, KMAX: a control is held for a whole number of slices in this range."""
    check: float = 0.01
    """Geometric: motions are checked at samples at most this far apart."""
    body: Optional[tuple[str, tuple[float, ...]]] = None
    """``(KIND, dims)`` of SPEC 5.1's ``body``, or None (no body, or required)."""


def _metric(groups) -> Metric:
    return tuple((tuple(n.split(",")) if isinstance(n, str) else tuple(n), float(w))
                 for n, w in groups)


@dataclass(frozen=True)
class FamilySystem:
    """The fields and queries every family system has.

    A subclass declares, as class variables: ``name``; ``state_names`` and which
    of them are ``angle_names``; ``position_indices`` (what a drawing projects
    on); its ``params`` (dataclass fields of its own) and which must be > 0;
    whether it ``needs_world``; what it ``occupies``; and ``DEFAULTS``.
    """

    bounds: Optional[Bounds] = None
    """(low, high) per state variable in state order; angles (-pi, pi), unused."""
    metric: Optional[Metric] = None
    """Metric groups ``((names, weight), ...)`` (SPEC 5.3)."""
    body: Optional[ConvexPolygon] = None
    """The footprint in the body frame (None: the system has no body)."""

    name: ClassVar[str] = ""
    kinodynamic: ClassVar[bool] = False
    state_names: ClassVar[tuple[str, ...]] = ()
    angle_names: ClassVar[tuple[str, ...]] = ()
    position_indices: ClassVar[tuple[int, int]] = (0, 1)
    velocity_indices: ClassVar[tuple[int, ...]] = ()
    params: ClassVar[tuple[str, ...]] = ()
    positive_params: ClassVar[frozenset[str]] = frozenset()
    needs_world: ClassVar[bool] = True
    # What the system puts in the workspace: "body" (``footprint(state)``, a placed
    # polygon), "links" (``links(state)``, segments) or "" (nothing: the pendulum).
    occupies: ClassVar[str] = "body"
    DEFAULTS: ClassVar[Defaults]

    def __post_init__(self) -> None:
        d = self.DEFAULTS
        bounds = self.bounds
        if bounds is None:
            bounds = tuple(d.bounds.get(n, UNBOUNDED) for n in self.state_names)
        if len(bounds) != len(self.state_names):
            raise ValueError(f"{self.name}: one bound per state variable {self.state_names}")
        self._set("bounds", tuple(ANGLE_RANGE if n in self.angle_names else (float(lo), float(hi))
                                  for n, (lo, hi) in zip(self.state_names, bounds)))
        self._set("metric", _metric(d.metric if self.metric is None else self.metric))
        if self.body is None and d.body is not None:
            self._set("body", body_polygon(*d.body))
        self._check_params()
        self._set("space", StateSpace.from_metric(self.variables(), self.metric))

    def _set(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, value)

    def __reduce__(self):
        # The bound samplers and integrator cannot be pickled: rebuild them from the fields.
        return (type(self), tuple(getattr(self, f.name) for f in fields(self)))

    def _check_params(self) -> None:
        for name in self.params:
            value = getattr(self, name)
            if not math.isfinite(value) or (name in self.positive_params and value <= 0.0):
                raise ValueError(f"{self.name}: param {name} = {value!r} must be a finite "
                                 f"number{' > 0' if name in self.positive_params else ''}")

    def variables(self) -> tuple[Variable, ...]:
        return tuple(Variable(n, lo, hi, angle=n in self.angle_names)
                     for n, (lo, hi) in zip(self.state_names, self.bounds))

    # ----- building one from a problem ---------------------------------------------

    @classmethod
    def configure(cls, *, params: Mapping[str, float] = None, bounds: Mapping = None,
                  metric=None, body: Optional[ConvexPolygon] = None,
                  world_box: Optional[Rect] = None, **more) -> FamilySystem:
        """The system with a problem's items over its defaults. ``bounds`` by
        variable name; without one, x and y take the world box's extent."""
        merged = dict(cls.DEFAULTS.bounds)
        if world_box is not None and "x" in cls.state_names:
            merged.update(x=(world_box.x0, world_box.x1), y=(world_box.y0, world_box.y1))
        merged.update(bounds or {})
        unknown = set(merged) - set(cls.state_names) | set(params or {}) - set(cls.params)
        if unknown:
            raise ValueError(f"{cls.name}: no variable or param {', '.join(sorted(unknown))}")
        return cls(bounds=tuple(merged.get(n, UNBOUNDED) for n in cls.state_names),
                   metric=metric, body=body, **cls._more_fields(**more), **(params or {}))

    @classmethod
    def _more_fields(cls, **more) -> dict:
        if more:
            raise ValueError(f"{cls.name}: takes no {', '.join(sorted(more))}")
        return {}

    # ----- states ---------------------------------------------------------------------

    def state_space(self, *_grid_size) -> StateSpace:
        """The variables with their bounds and the metric. (The grid systems take
        the map's size; a family system carries its bounds, so it ignores it.)"""
        return self.space

    def start_state(self, *position: float) -> State:
        """A state with ``position_indices`` at ``position``, the rest 0 (at rest).
        A problem's own start is ``KinoplanProblem.start``."""
        state = [0.0] * len(self.state_names)
        for i, value in zip(self.position_indices, position):
            state[i] = value
        return tuple(state)

    def bounds_violation(self, state: Sequence[float]) -> Optional[str]:
        """Why ``state`` is outside its bounds (or not finite), or None."""
        if len(state) != len(self.state_names):
            return f"{len(state)} values for the {len(self.state_names)} state variables"
        for value, v in zip(state, self.space.variables):
            if not math.isfinite(value):
                return f"{v.name} = {value!r} is not a finite number"
            if not v.angle and not v.low <= value <= v.high:
                return f"{v.name} = {value!r} is outside its bound [{v.low:g}, {v.high:g}]"
        return None

    def in_bounds(self, state: Sequence[float]) -> bool:
        """Every value finite, every non-angle within its closed bounds
        (``space.satisfies_bounds``)."""
        return self.space.satisfies_bounds(state)

    def footprint(self, state: Sequence[float]) -> ConvexPolygon:
        """The body placed at the state's (x, y, theta)."""
        if self.body is None:
            raise ValueError(f"{self.name} has no body (a problem must give one)")
        return place(self.body, state[0], state[1], state[2])


# ----- kinodynamic -----------------------------------------------------------------------


@dataclass(frozen=True)
class KinodynamicFamily(FamilySystem):
    """A control held for K slices of ``dt``, integrated by ``scheme`` (SPEC 5.2).

    The control tuple is the held values followed by K, so a printed row is
    ``state + control`` (SPEC 5.4); ``control_names`` ends with ``"K"``.
    """

    controls: Optional[Bounds] = None
    """(low, high) per held control, in control order."""
    scheme: Optional[str] = None
    """``euler`` or ``rk4``."""
    dt: Optional[float] = None
    """One slice, in seconds."""
    kmin: Optional[int] = None
    """Fewest slices a control is held."""
    kmax: Optional[int] = None
    """Most slices a control is held (at most ``MAX_SLICES``)."""

    kinodynamic: ClassVar[bool] = True
    control_names: ClassVar[tuple[str, ...]] = ()
    rates: ClassVar[tuple[str, ...]] = ()
    # The state variables KPIECE1's grid projects on (docs/planners-family.md).
    projection_names: ClassVar[tuple[str, ...]] = ("x", "y")

    def __post_init__(self) -> None:
        super().__post_init__()
        d = self.DEFAULTS
        held = self.control_names[:-1]
        if self.controls is None:
            self._set("controls", tuple(d.controls[n] for n in held))
        for name, default in (("scheme", d.integrate[0]), ("dt", d.integrate[1]),
                              ("kmin", d.duration[0]), ("kmax", d.duration[1])):
            if getattr(self, name) is None:
                self._set(name, default)
        self._set("controls", tuple((float(lo), float(hi)) for lo, hi in self.controls))
        self._check_controls()
        # The two methods below, shadowed by compiled samplers making the same draws.
        values = BoxSampler([lo for lo, _ in self.controls], [hi - lo for lo, hi in self.controls])
        self._set("sample_values", values.sample)
        self._set("control_sampler", ControlSampler(values, self.kmin, self.kmax))
        self._set("sample_control", self.control_sampler.sample)
        check_scheme(self.scheme, float(self.dt))
        self._set("dynamics", Dynamics(self.state_names, held, self.rates,
                                       tuple(n in self.angle_names for n in self.state_names),
                                       tuple((p, getattr(self, p)) for p in self.params)))
        # The slices without a valid-state test: what propagate and slice_states run.
        self._set("_slicer", kernels.integrator(self))

    def _check_controls(self) -> None:
        if len(self.controls) != len(self.control_names) - 1:
            raise ValueError(f"{self.name}: one bound per control {self.control_names[:-1]}")
        for name, (lo, hi) in zip(self.control_names, self.controls):
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise ValueError(f"{self.name}: control {name} bounds [{lo!r}, {hi!r}]")
        if not (isinstance(self.kmin, int) and isinstance(self.kmax, int)
                and 1 <= self.kmin <= self.kmax <= MAX_SLICES):
            raise ValueError(f"{self.name}: duration needs 1 <= KMIN <= KMAX <= {MAX_SLICES}, "
                             f"got {self.kmin!r} {self.kmax!r}")

    @classmethod
    def _more_fields(cls, *, controls: Mapping = None, integrate=None, duration=None,
                     **more) -> dict:
        if more:
            raise ValueError(f"{cls.name} is kinodynamic: it takes no {', '.join(sorted(more))}")
        merged = dict(cls.DEFAULTS.controls)
        merged.update(controls or {})
        unknown = set(merged) - set(cls.control_names[:-1])
        if unknown:
            raise ValueError(f"{cls.name}: no control {', '.join(sorted(unknown))}")
        scheme, dt = integrate or cls.DEFAULTS.integrate
        kmin, kmax = duration or cls.DEFAULTS.duration
        return dict(controls=tuple(merged[n] for n in cls.control_names[:-1]),
                    scheme=scheme, dt=dt, kmin=kmin, kmax=kmax)

    def sample_values(self, rng: random.Random) -> tuple:
        """The held values, each uniform in [low, high) (one ``rng.random()`` each,
        in control order)."""
        return tuple([lo + (hi - lo) * rng.random() for lo, hi in self.controls])

    def sample_control(self, rng: random.Random) -> tuple:
        """:meth:`sample_values`, then K by ``rng.randint(kmin, kmax)``."""
        return (*self.sample_values(rng), rng.randint(self.kmin, self.kmax))

    def control_violation(self, control: Sequence[float]) -> Optional[str]:
        """Why a control (held values, then K) is out of bounds or duration, or None."""
        if len(control) != len(self.control_names):
            return (f"{len(control)} control values, expected {len(self.control_names)} "
                    f"({' '.join(self.control_names)})")
        for name, value, (lo, hi) in zip(self.control_names, control, self.controls):
            if not lo <= value <= hi:
                return f"control {name} = {value!r} is outside [{lo:g}, {hi:g}]"
        k = control[-1]
        try:
            k = slice_count(k)
        except ValueError as exc:
            return str(exc)
        if not self.kmin <= k <= self.kmax:
            return f"K = {k:.12g} is outside the duration [{self.kmin}, {self.kmax}]"
        return None

    def propagate_while(self, state: Sequence[float], control: Sequence[float],
                        state_valid: Optional[Callable[[State], bool]] = None,
                        slices_out: Optional[list] = None) -> Optional[State]:
        """The state after K slices; None at the first slice ``state_valid``
        rejects (``state`` itself is not tested). ``slices_out`` gets each slice
        that passed."""
        for sliced in self.slice_states(state, control):
            if state_valid is not None and not state_valid(sliced):
                return None
            if slices_out is not None:
                slices_out.append(sliced)
            state = sliced
        return tuple(state)

    def integrator(self, body: Any = None) -> Any:
        """The slice loop with the valid-state test fused in (``kernels.integrator``):
        its ``advance(state, control, kmax) -> (state, k)``, ``propagate_valid(state,
        control)`` and ``valid(state)`` test every slice for finite values, the bounds,
        then ``body.free(x, y, theta)`` when a ``body_tests.BodyTest`` is given."""
        return kernels.integrator(self, body)

    def reachable_controls(self, levels: int, k: int) -> list[tuple]:
        """RG-RRT's fixed reachable set: every combination of ``levels`` evenly
        spaced values per held control (both bounds included; 1: the middle), each
        held for ``k`` slices."""
        values = [[lo + (hi - lo) * (j / (levels - 1) if levels > 1 else 0.5)
                   for j in range(levels)] for lo, hi in self.controls]
        return [(*combination, k) for combination in itertools.product(*values)]

    def projection_axes(self, cells: int) -> list[tuple[int, float, float]]:
        """KPIECE1's grid: ``(index, low, scale)`` of each of :attr:`projection_names`,
        its bounds cut into ``cells`` equal cells; a state's cell on the axis is
        ``floor((state[index] - low) * scale)``. Bounds too close for a finite scale
        (equal, or a subnormal apart) make one cell (scale 0)."""
        space = self.space
        axes = []
        for name in self.projection_names:
            v = space.variables[space.index(name)]
            if not (math.isfinite(v.low) and math.isfinite(v.high) and v.low <= v.high):
                raise ValueError(f"{self.name}: projection on {name} needs finite bounds")
            scale = cells / (v.high - v.low) if v.low < v.high else 0.0
            axes.append((space.index(name), v.low, scale if math.isfinite(scale) else 0.0))
        return axes

    def propagate(self, state: Sequence[float], control: Sequence[float]) -> State:
        """The state after K slices (no validity test)."""
        return self._slicer.slices(state, control, slice_count(control[-1]), None)

    def slice_states(self, state: Sequence[float], control: Sequence[float]) -> list[State]:
        """The state after each of the K slices, the last one included."""
        out: list[State] = []
        self._slicer.slices(state, control, slice_count(control[-1]), out)
        return out


# ----- geometric -------------------------------------------------------------------------


@dataclass(frozen=True)
class GeometricFamily(FamilySystem):
    """Straight motions in configuration space (angles the shorter way), checked
    at ``n + 1`` equally spaced samples (SPEC 5.2)."""

    check: Optional[float] = None
    """Motions are checked at samples at most this far apart (metric units)."""

    control_names: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.check is None:
            self._set("check", self.DEFAULTS.check)
        if not (math.isfinite(self.check) and self.check > 0.0):
            raise ValueError(f"{self.name}: check step must be a finite number > 0, "
                             f"got {self.check!r}")

    @classmethod
    def _more_fields(cls, *, check=None, **more) -> dict:
        if more:
            raise ValueError(f"{cls.name} is geometric: it takes no {', '.join(sorted(more))}")
        return {"check": check}

    def distance(self, a: Sequence[float], b: Sequence[float]) -> float:
        """The metric distance (SPEC 5.3)."""
        return self.space.distance(a, b)

    def interpolate(self, a: Sequence[float], b: Sequence[float], t: float) -> State:
        """The state a fraction ``t`` of the way, angles the shorter way."""
        return self.space.interpolate(a, b, t)

    def motion_samples(self, a: Sequence[float], b: Sequence[float],
                       step: Optional[float] = None, strict: bool = False) -> list[State]:
        """``a`` .. ``b`` at ``n + 1`` equally spaced samples, both ends included:
        ``n = max(1, ceil(d / step))`` (``strict``: ``ceil(10 d / step)``)."""
        step = self.check if step is None else step
        d = self.space.distance(a, b)
        span = (10.0 * d if strict else d) / step
        if not math.isfinite(span):
            raise ValueError(f"motion of length {d!r} at step {step!r}: not a finite count")
        n = max(1, math.ceil(span))
        interpolate = self.space.interpolate
        return [interpolate(a, b, i / n) for i in range(n + 1)]
