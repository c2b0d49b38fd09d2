"""SPEC 5.2's integrators: one slice of ``dt`` by ``euler`` or classic ``rk4``,
then every angle wrapped with ``math.remainder(angle, 2*pi)``; a control is
held for K slices.

A system states its dynamics as one Python expression per state variable over
its state names, control names and constants (:class:`Dynamics`, e.g. the
car's ``"v * cos(theta)"``). This module is the readable reference:
:meth:`Dynamics.rates` evaluates the expressions, :func:`euler_slice` and
:func:`rk4_slice` take one slice over tuples, and :class:`ReferenceIntegrator`
holds a control slice by slice with the valid-state test. The registered systems
run generated classes that unroll the same float operations in the same order
(``planning_core/generated_kernels.py``, picked by ``planning_core.kernels``); the
tests compare the two bit for bit.
"""

from __future__ import annotations

import keyword
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Optional

TAU = 2.0 * math.pi
SCHEMES = ("euler", "rk4")
# What a rate expression may call, besides the names the system declares.
FUNCTIONS = {"cos": math.cos, "sin": math.sin, "tan": math.tan, "sqrt": math.sqrt}
# The generated code's own parameters (its locals and fields all start with "_").
RESERVED = frozenset({"state", "control", "valid", "out", "self", "kmax", "k", "pi"})

State = tuple[float, ...]
Rates = Callable[[Sequence[float], Sequence[float]], State]


@dataclass(frozen=True)
class Dynamics:
    """``d state_i / dt = rates[i]``, evaluated with the state, control and
    constant names bound to their values."""

    state_names: tuple[str, ...]
    """The state variables, in state order."""
    control_names: tuple[str, ...]
    """The held control values, in control order (K, the slice count, follows them)."""
    rates: tuple[str, ...]
    """One Python expression per state variable: its time derivative."""
    angles: tuple[bool, ...]
    """Per state variable: wrapped to [-pi, pi] after every slice."""
    constants: tuple[tuple[str, float], ...] = ()
    """System parameters by name (the pendulum's ``g``, the car's ``L``)."""
    _codes: tuple = field(init=False, repr=False, compare=False)
    _globals: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        n = len(self.state_names)
        if not n or len(self.rates) != n or len(self.angles) != n:
            raise ValueError("dynamics: one rate and one angle flag per state variable")
        names = [*self.state_names, *self.control_names, *(c for c, _ in self.constants)]
        for name in names:
            if not name.isidentifier() or keyword.iskeyword(name) or name.startswith("_") \
                    or name in FUNCTIONS or name in RESERVED:
                raise ValueError(f"dynamics: {name!r} cannot be a variable name")
        if len(set(names)) != len(names):
            raise ValueError(f"dynamics: a name is used twice in {names}")
        for name, value in self.constants:
            if not math.isfinite(value):
                raise ValueError(f"dynamics: constant {name} = {value!r} is not finite")
        object.__setattr__(self, "_codes", tuple(compile(rate, f"<rate of {v}>", "eval")
                                                 for v, rate in zip(self.state_names, self.rates)))
        object.__setattr__(self, "_globals", {"__builtins__": {}, **FUNCTIONS, **{
            name: float(value) for name, value in self.constants}})

    def rates_at(self, state: Sequence[float], control: Sequence[float]) -> State:
        """The derivative at one state: each rate expression evaluated with the state,
        control and constant names bound to their values."""
        names = dict(zip(self.state_names, state))
        names.update(zip(self.control_names, control))
        return tuple([eval(code, self._globals, names) for code in self._codes])  # noqa: S307


# ----- the reference slices ---------------------------------------------------------


def wrap_angles(state: Sequence[float], angles: Sequence[bool]) -> State:
    """Angles to ``math.remainder(angle, 2*pi)``, the rest unchanged."""
    return tuple(math.remainder(v, TAU) if a else v for v, a in zip(state, angles))


def euler_slice(rates: Rates, state: Sequence[float], control: Sequence[float],
                dt: float, angles: Sequence[bool]) -> State:
    """``s + dt * f(s, u)``, angles wrapped."""
    k = rates(state, control)
    return wrap_angles([s + dt * r for s, r in zip(state, k)], angles)


def rk4_slice(rates: Rates, state: Sequence[float], control: Sequence[float],
              dt: float, angles: Sequence[bool]) -> State:
    """Classic RK4: ``s + dt/6 (k1 + 2 k2 + 2 k3 + k4)``, angles wrapped."""
    half, sixth = dt / 2.0, dt / 6.0
    k1 = rates(state, control)
    k2 = rates([s + half * r for s, r in zip(state, k1)], control)
    k3 = rates([s + half * r for s, r in zip(state, k2)], control)
    k4 = rates([s + dt * r for s, r in zip(state, k3)], control)
    return wrap_angles([s + sixth * (a + 2.0 * b + 2.0 * c + d)
                        for s, a, b, c, d in zip(state, k1, k2, k3, k4)], angles)


REFERENCE_SLICES = {"euler": euler_slice, "rk4": rk4_slice}


class ReferenceIntegrator:
    """A control held slice by slice, and the valid-state test: what the generated
    integrators do, written plainly. A state is valid when ``in_bounds`` accepts it
    (finite, the bounds) and then, given a body test, ``body.free(x, y, theta)``."""

    def __init__(self, dynamics: Dynamics, scheme: str, dt: float,
                 in_bounds: Callable[[Sequence[float]], bool], body: Any = None) -> None:
        check_scheme(scheme, dt)
        self.dynamics, self.step, self.dt = dynamics, REFERENCE_SLICES[scheme], dt
        self.in_bounds, self.body = in_bounds, body

    def valid(self, state: Sequence[float]) -> bool:
        return self.in_bounds(state) and (self.body is None
                                          or self.body.free(state[0], state[1], state[2]))

    def slices(self, state: Sequence[float], control: Sequence[float], k: int,
               out: Optional[list] = None) -> State:
        """The state after ``k`` slices of the held ``control`` (its values; a K after
        them is ignored), each slice's state appended to ``out`` when given."""
        held, dynamics = control[:len(self.dynamics.control_names)], self.dynamics
        state = tuple(state)
        for _ in range(k):
            state = self.step(dynamics.rates_at, state, held, self.dt, dynamics.angles)
            if out is not None:
                out.append(state)
        return state

    def advance(self, state: Sequence[float], control: Sequence[float],
                kmax: int) -> tuple[State, int]:
        """``(state, k)``: up to ``kmax`` slices, stopped before the first invalid one;
        the last valid state (``state`` itself when the first slice fails) and how many
        slices led to it."""
        held, dynamics = control[:len(self.dynamics.control_names)], self.dynamics
        last = tuple(state)
        for k in range(kmax):
            state = self.step(dynamics.rates_at, last, held, self.dt, dynamics.angles)
            if not self.valid(state):
                return last, k
            last = state
        return last, kmax

    def propagate_valid(self, state: Sequence[float], control: Sequence[Any]) -> Optional[State]:
        """The end of the K slices at the end of ``control`` if every one is valid, else None."""
        k = control[-1]
        end, done = self.advance(state, control, k)
        return end if done == k else None


def slice_count(k) -> int:
    """K as an int: an int, or a float with an integral value (a parsed row)."""
    if isinstance(k, int):
        return k
    if isinstance(k, float) and k.is_integer():
        return int(k)
    raise ValueError(f"K = {k!r} is not a whole number of slices")


def check_scheme(scheme: str, dt: float) -> None:
    """ValueError for an unknown scheme or a slice that is not a finite number > 0."""
    if scheme not in SCHEMES:
        raise ValueError(f"integrate: unknown scheme {scheme!r} (euler | rk4)")
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"integrate: DT must be a finite number > 0, got {dt!r}")
