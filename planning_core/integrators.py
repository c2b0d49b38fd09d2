"""SPEC 5.2's integrators: one slice of ``dt`` by ``euler`` or classic ``rk4``,
then every angle wrapped with ``math.remainder(angle, 2*pi)``; a control is
held for K slices.

A system states its dynamics as one Python expression per state variable over
its state names, control names and constants (:class:`Dynamics`, e.g. the
car's ``"v * cos(theta)"``). :func:`compile_propagator` unrolls the chosen
scheme over those expressions once per configured system, as
``spaces.compile_distance`` does for the metric, because planners call it in
their innermost loops: plain float locals, and a state tuple per slice only
when a caller looks at the slices. :func:`euler_slice` and :func:`rk4_slice`
are the readable reference over tuples; they do the same float operations in
the same order, so the two agree bit for bit (tested).
"""

from __future__ import annotations

import keyword
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Optional

from planning_core import compiled

TAU = 2.0 * math.pi
SCHEMES = ("euler", "rk4")
# What a rate expression may call, besides the names the system declares.
FUNCTIONS = {"cos": math.cos, "sin": math.sin, "tan": math.tan, "sqrt": math.sqrt}
# The generated functions' own parameters (their locals all start with "_").
RESERVED = frozenset({"state", "control", "valid", "out", "self", "kmax", "pi"})

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


def _namespace(dynamics: Dynamics) -> dict:
    namespace = {"__builtins__": {"range": range, "int": int}, "_rem": math.remainder, "_TAU": TAU}
    namespace.update(FUNCTIONS)
    namespace.update((name, float(value)) for name, value in dynamics.constants)
    return namespace


def _run(source: str, namespace: dict, name: str) -> Callable:
    # Source built only from the declared identifiers and the system's own expressions.
    exec(source, namespace)  # noqa: S102
    return namespace[name]


def _bind(dynamics: Dynamics, indent: str) -> list[str]:
    """Lines binding the state and control names from ``state`` and ``control``."""
    lines = [f"{indent}{', '.join(dynamics.state_names)}, = state"]
    lines += [f"{indent}{u} = control[{j}]" for j, u in enumerate(dynamics.control_names)]
    return lines


def compile_rates(dynamics: Dynamics) -> Rates:
    """``rates(state, control) -> tuple``: the derivative at one state."""
    lines = ["def rates(state, control):", *_bind(dynamics, "    "),
             f"    return ({', '.join(f'({r})' for r in dynamics.rates)},)"]
    return _run("\n".join(lines), _namespace(dynamics), "rates")


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


# ----- the compiled propagator ------------------------------------------------------


def _stage(dynamics: Dynamics, k: int, origin: str, step: str, pad: str) -> list[str]:
    """Rates ``_k{k}_i`` at the current names, then names = ``origin + step * _k{k}_i``."""
    names, n = dynamics.state_names, len(dynamics.state_names)
    lines = [f"{pad}_k{k}_{i} = ({dynamics.rates[i]})" for i in range(n)]
    if step:
        lines += [f"{pad}{names[i]} = {origin}{i} + {step} * _k{k}_{i}" for i in range(n)]
    return lines


def _slice_lines(dynamics: Dynamics, scheme: str, pad: str) -> list[str]:
    names, n = dynamics.state_names, len(dynamics.state_names)
    if scheme == "euler":
        lines = _stage(dynamics, 1, "", "", pad)
        lines += [f"{pad}{names[i]} = {names[i]} + _DT * _k1_{i}" for i in range(n)]
    else:
        lines = [f"{pad}_s{i} = {names[i]}" for i in range(n)]
        lines += _stage(dynamics, 1, "_s", "_HALF", pad)
        lines += _stage(dynamics, 2, "_s", "_HALF", pad)
        lines += _stage(dynamics, 3, "_s", "_DT", pad)
        lines += _stage(dynamics, 4, "", "", pad)
        lines += [f"{pad}{names[i]} = _s{i} + _SIXTH * "
                  f"(_k1_{i} + 2.0 * _k2_{i} + 2.0 * _k3_{i} + _k4_{i})" for i in range(n)]
    lines += [f"{pad}{name} = _rem({name}, _TAU)"
              for name, angle in zip(names, dynamics.angles) if angle]
    return lines


def slice_count(k) -> int:
    """K as an int: an int, or a float with an integral value (a parsed row)."""
    if isinstance(k, int):
        return k
    if isinstance(k, float) and k.is_integer():
        return int(k)
    raise ValueError(f"K = {k!r} is not a whole number of slices")


def _check_scheme(scheme: str, dt: float) -> None:
    if scheme not in SCHEMES:
        raise ValueError(f"integrate: unknown scheme {scheme!r} (euler | rk4)")
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"integrate: DT must be a finite number > 0, got {dt!r}")


def compile_propagator(dynamics: Dynamics, scheme: str, dt: float) -> Callable:
    """``propagate(state, control, valid=None, out=None) -> state | None``.

    ``control`` is the held values followed by K. The state after each of the
    K slices is passed to ``valid`` (None is returned at the first one it
    rejects) and appended to ``out``; the last one is returned. The inputs are
    not modified.
    """
    _check_scheme(scheme, dt)
    state = ", ".join(dynamics.state_names)
    lines = ["def propagate(state, control, valid=None, out=None):",
             *_bind(dynamics, "    "),
             f"    _count = control[{len(dynamics.control_names)}]",
             "    if _count.__class__ is not int:",
             "        _count = _slice_count(_count)",
             "    _look = valid is not None or out is not None",
             "    for _ in range(_count):",
             *_slice_lines(dynamics, scheme, "        "),
             "        if _look:",
             f"            _after = ({state},)",
             "            if valid is not None and not valid(_after):",
             "                return None",
             "            if out is not None:",
             "                out.append(_after)",
             f"    return ({state},)"]
    namespace = _namespace(dynamics)
    namespace.update(_DT=dt, _HALF=dt / 2.0, _SIXTH=dt / 6.0, _slice_count=slice_count)
    return _run("\n".join(lines), namespace, "propagate")


def advance_source(dynamics: Dynamics, scheme: str,
                   free_args: Optional[tuple[str, ...]] = None) -> str:
    """The text of a module whose class ``Advance(dt, constants, lows, highs, free)``
    has the method ``advance(state, control, kmax) -> (state, k)``: the held
    ``control`` (its values; a K after them is ignored) for up to ``kmax`` slices,
    stopping before the first slice whose state is not finite, is outside the
    non-angle bounds ``[lows[i], highs[i]]``, or (with ``free_args``) fails
    ``free.free(*free_args)`` (``free`` a ``body_tests.BodyTest``: a native call
    when compiled). It returns the last state that passed (``state`` itself
    when the first slice fails) and how many slices did: the same floats as
    :func:`compile_propagator`'s for those slices, the test fused into the loop
    (the family planners' hot path). Its method ``propagate_valid(state, control)``
    holds the values for the K at the end of ``control``: the end state when every
    slice passed, else None.

    The numbers are the object's, not the text's, so one text serves every
    problem of a system and scheme: the compiled build compiles these texts
    ahead of time (:func:`advance_class` uses them when it can)."""
    if scheme not in SCHEMES:
        raise ValueError(f"integrate: unknown scheme {scheme!r} (euler | rk4)")
    names, n = dynamics.state_names, len(dynamics.state_names)
    state = ", ".join(names)
    bounded = [i for i in range(n) if not dynamics.angles[i]]
    tests = [f"{v} - {v} == 0.0" for v in names]
    tests += [f"_lo{i} <= {names[i]} <= _hi{i}" for i in bounded]
    if free_args is not None:
        tests.append(f"_free.free({', '.join(free_args)})")
    # The last state that passed, kept as floats (a tuple a slice cost an allocation).
    last = [f"_last{i}" for i in range(n)]

    def keep(indent: str) -> list[str]:
        return [f"{indent}{kept} = {name}" for kept, name in zip(last, names)]

    fields = [("_DT", "dt"), ("_HALF", "dt / 2.0"), ("_SIXTH", "dt / 6.0"), ("_TAU", "2.0 * pi")]
    fields += [(c, f"constants[{j}]") for j, (c, _) in enumerate(dynamics.constants)]
    fields += [(f"_{side}{i}", f"{array}[{i}]") for i in bounded
               for side, array in (("lo", "lows"), ("hi", "highs"))]
    lines = ["from __future__ import annotations",
             "from math import cos, pi, sin, sqrt, tan",
             "from planning_core.angles import remainder as _rem",
             *(["from planning_core.worlds.body_tests import BodyTest"] if free_args else []),
             "from typing import Any, Sequence",
             "", "", "class Advance:",
             "    def __init__(self, dt: float, constants: Sequence[float], lows: Sequence[float],",
             "                 highs: Sequence[float], free: Any) -> None:",
             *[f"        self.{name}: float = {value}" for name, value in fields],
             "        self._free: BodyTest = free" if free_args else "        self._free = free",
             "",
             "    def advance(self, state: Sequence[float], control: Sequence[float],",
             "                kmax: int) -> tuple[tuple[float, ...], int]:",
             *[f"        {name} = self.{name}" for name, _ in fields],
             "        _free = self._free",
             *_bind(dynamics, "        "),
             *keep("        "),
             "        for _k in range(kmax):",
             *_slice_lines(dynamics, scheme, "            "),
             f"            if not ({' and '.join(tests)}):",
             f"                return ({', '.join(last)},), _k",
             *keep("            "),
             f"        return ({state},), kmax",
             "",
             "    def propagate_valid(self, state: Sequence[float],",
             "                        control: Sequence[Any]) -> tuple[float, ...] | None:",
             "        k: int = control[-1]",
             "        end, done = self.advance(state, control, k)",
             "        return end if done == k else None",
             ""]
    return "\n".join(lines)


def advance_class(source: str) -> type:
    """The class ``Advance`` of an :func:`advance_source` text: from the compiled
    build when it holds that very text, else the text run here."""
    module = compiled.generated_module(source)
    if module is not None:
        return module.Advance
    namespace: dict = {"__name__": compiled.generated_name(source)}
    advance = _run(source, namespace, "Advance")
    namespace["_rem"] = math.remainder  # interpreted, the library's is the faster (same floats)
    return advance
