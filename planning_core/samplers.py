"""Uniform samples on plain floats, compiled (mypyc, ``rrt_startup.compiled``):
the kinoplan planners draw a target state and a control every iteration, KPIECE1 a
motion of a cell by a normal draw and, on a family system, a random motion.

The draws are the references' own, in the same order: one ``rng.random()`` per
coordinate, ``low + span * r`` (``StateSpace.sample_uniform``,
``KinodynamicFamily.sample_values``), then K as ``rng.randint`` draws it.
"""

from __future__ import annotations

import math
import random

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Final

_GENERATOR: Final = random.Random
_RANDOM: Final = random.Random.random
_GETRANDBITS: Final = random.Random.getrandbits


def uniform(rng: Any) -> float:
    """``rng.random()``. Compiled, a method call on an untyped object looks the method
    up at every call (about two thirds of its cost); for a ``random.Random`` itself
    this calls the generator's C method directly: the same draw. (Any other
    generator, a subclass too, is asked as usual.)"""
    if type(rng) is _GENERATOR:
        return _RANDOM(rng)
    r: float = rng.random()
    return r


def randint(rng: Any, a: int, b: int) -> int:
    """``rng.randint(a, b)`` for ``a <= b``: the same ``getrandbits`` draws
    (CPython's ``randrange`` by rejection; a test holds it to ``rng.randint``)."""
    n = b - a + 1
    k = n.bit_length()
    direct = type(rng) is _GENERATOR  # as in uniform()
    r: int = _GETRANDBITS(rng, k) if direct else rng.getrandbits(k)
    while r >= n:
        r = _GETRANDBITS(rng, k) if direct else rng.getrandbits(k)
    return a + r


def gauss(rng: Any, mu: float, sigma: float) -> float:
    """``rng.gauss(mu, sigma)``: the same draws and the same cached second value
    (CPython's Box-Muller form, which keeps it in ``rng.gauss_next``; a test holds
    it to ``rng.gauss``)."""
    z: float | None = rng.gauss_next
    rng.gauss_next = None
    if z is None:
        x2pi: float = uniform(rng) * (2.0 * math.pi)
        g2rad = math.sqrt(-2.0 * math.log(1.0 - uniform(rng)))
        z = math.cos(x2pi) * g2rad
        rng.gauss_next = math.sin(x2pi) * g2rad
    return mu + z * sigma


class BoxSampler:
    """Uniform in ``[lows[i], lows[i] + spans[i])`` per coordinate, in order."""

    def __init__(self, lows: list[float], spans: list[float]) -> None:
        self.lows = lows
        self.spans = spans

    def sample(self, rng: Any) -> tuple[float, ...]:
        lows, spans = self.lows, self.spans
        return tuple([lows[i] + spans[i] * uniform(rng) for i in range(len(lows))])


class ControlSampler:
    """Held values from a :class:`BoxSampler`, then K in ``[kmin, kmax]``."""

    def __init__(self, values: BoxSampler, kmin: int, kmax: int) -> None:
        self.values = values
        self.kmin = kmin
        self.kmax = kmax

    def sample(self, rng: Any) -> tuple:
        # (Concatenated: compiled, a star-unpacked tuple display goes through a list.)
        values = self.values.sample(rng)
        return values + (randint(rng, self.kmin, self.kmax),)


class MotionSampler:
    """A random motion on a family system (OMPL's propagateWhileValid): held values
    from ``controls``' box and a K in ``[kmin, kmax]`` (``rng``: the values, then K),
    applied by ``advance`` (the generated slice loop's) up to the first invalid slice;
    ``((*values, k), [end])`` with ``k`` the slices done, or None when fewer than KMIN
    (``whole``: than K) were valid."""

    def __init__(self, controls: ControlSampler, advance: Any) -> None:
        self.controls = controls
        self.advance = advance

    def sample(self, state: Any, rng: Any, whole: bool = False) -> tuple | None:
        controls = self.controls
        values = controls.values.sample(rng)
        wanted = randint(rng, controls.kmin, controls.kmax)
        end, k = self.advance(state, values, wanted)
        return (values + (k,), [end]) if k >= (wanted if whole else controls.kmin) else None

