"""State spaces over plain tuples of floats: R^n, SO(2) and their compounds.

OMPL's idea (``base/spaces``) in Python idiom: a :class:`StateSpace` is a tuple
of :class:`Variable` s and metric groups. The distance is SPEC 5.1's ``metric``:
the sum over groups of ``weight * sqrt(sum of squared differences)``, where the
difference of two angles ``a``, ``b`` is ``math.remainder(b - a, 2*pi)`` (so
angles exactly pi apart go the way that expression says). A variable in no
group does not count (the unicycle's ``v`` and ``omega`` under SPEC's default
``metric x,y 1 theta 0.5``).

States stay bare tuples: nothing here allocates per state beyond the tuples it
returns. The methods here are the readable definitions; planners' inner loops
measure and interpolate through ``planning_core.kernels.space_metric(space)``, the
same floats (a generated class for the spaces of the registered systems).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from random import Random

from planning_core.samplers import BoxSampler

TAU = 2.0 * math.pi

State = tuple[float, ...]
Group = tuple[tuple[int, ...], float]


@dataclass(frozen=True)
class Variable:
    """One state variable. An angle wraps: its bounds are ignored (stored as
    -pi, pi), its range is ``math.remainder(angle, 2*pi)``'s, [-pi, pi]."""

    name: str
    low: float = -math.inf
    high: float = math.inf
    angle: bool = False

    def __post_init__(self) -> None:
        if not self.name or not isinstance(self.name, str):
            raise ValueError(f"a variable needs a non-empty name, got {self.name!r}")
        # An angle's bounds are ignored; normalised so equal variables compare equal.
        low, high = (-math.pi, math.pi) if self.angle else (self.low, self.high)
        object.__setattr__(self, "low", float(low))
        object.__setattr__(self, "high", float(high))
        if not self.angle and not self.low <= self.high:
            raise ValueError(f"variable {self.name}: low {self.low!r} > high {self.high!r}")


@dataclass(frozen=True)
class StateSpace:
    """Variables and metric groups ``((indices, weight), ...)``.

    Each variable is in at most one group; weights are finite and >= 0.
    """

    variables: tuple[Variable, ...]
    groups: tuple[Group, ...]

    def __post_init__(self) -> None:
        variables = tuple(self.variables)
        groups = tuple((tuple(int(i) for i in indices), float(weight))
                       for indices, weight in self.groups)
        object.__setattr__(self, "variables", variables)
        object.__setattr__(self, "groups", groups)
        _check(variables, groups)
        # Precomputed once: the per-call code paths below only read these.
        object.__setattr__(self, "_index", {v.name: i for i, v in enumerate(variables)})
        object.__setattr__(self, "_angles", tuple(v.angle for v in variables))
        object.__setattr__(self, "_angle_indices",
                           tuple(i for i, v in enumerate(variables) if v.angle))
        object.__setattr__(self, "_plan", tuple(
            (indices, weight, tuple(variables[i].angle for i in indices))
            for indices, weight in groups))
        if all(v.angle or (math.isfinite(v.low) and math.isfinite(v.high)) for v in variables):
            sampler = BoxSampler([v.low for v in variables], [v.high - v.low for v in variables])
            object.__setattr__(self, "sample_uniform", sampler.sample)

    def __reduce__(self):
        # The bound sampler cannot be pickled; rebuild it from the fields.
        return (type(self), (self.variables, self.groups))

    # ----- constructors -----

    @classmethod
    def real_vector(cls, names: Sequence[str], lows: Sequence[float],
                    highs: Sequence[float]) -> StateSpace:
        """R^n with per-variable bounds, one Euclidean group of weight 1."""
        if not len(names) == len(lows) == len(highs):
            raise ValueError("real_vector: names, lows and highs differ in length")
        variables = tuple(Variable(n, float(lo), float(hi)) for n, lo, hi in zip(names, lows, highs))
        return cls(variables, ((tuple(range(len(variables))), 1.0),))

    @classmethod
    def so2(cls, name: str = "theta") -> StateSpace:
        """One angle, distance ``|remainder(b - a, 2*pi)|``."""
        return cls((Variable(name, -math.pi, math.pi, angle=True),), (((0,), 1.0),))

    @classmethod
    def compound(cls, spaces: Sequence[StateSpace],
                 weights: Sequence[float] | None = None) -> StateSpace:
        """Concatenate spaces; each component's groups are scaled by its weight.

        A one-group component (R^n, SO(2)) becomes one group with its weight,
        as OMPL's ``CompoundStateSpace`` (``SE2 = compound([R2, SO2], [w, w'])``).
        """
        weights = [1.0] * len(spaces) if weights is None else list(weights)
        if len(weights) != len(spaces):
            raise ValueError("compound: one weight per component space")
        variables: list[Variable] = []
        groups: list[Group] = []
        for space, weight in zip(spaces, weights):
            offset = len(variables)
            variables.extend(space.variables)
            groups.extend((tuple(i + offset for i in indices), w * weight)
                          for indices, w in space.groups)
        return cls(tuple(variables), tuple(groups))

    @classmethod
    def from_metric(cls, variables: Sequence[Variable],
                    metric: Mapping[str | Sequence[str], float]
                    | Iterable[tuple[str | Sequence[str], float]]) -> StateSpace:
        """Groups by variable name, SPEC 5.1's ``metric x,y 0.7 theta 0.3``:
        ``from_metric(vs, [("x,y", 0.7), ("theta", 0.3)])`` (or a dict, or
        name tuples such as ``(("x", "y"), 0.7)``)."""
        variables = tuple(variables)
        index = {v.name: i for i, v in enumerate(variables)}
        pairs = metric.items() if isinstance(metric, Mapping) else metric
        groups = []
        for names, weight in pairs:
            names = names.split(",") if isinstance(names, str) else list(names)
            missing = [n for n in names if n not in index]
            if missing:
                raise ValueError(f"metric names unknown variable(s) {', '.join(missing)}")
            groups.append((tuple(index[n] for n in names), float(weight)))
        return cls(variables, tuple(groups))

    # ----- queries -----

    @property
    def dimension(self) -> int:
        return len(self.variables)

    def index(self, name: str) -> int:
        """Position of the variable called ``name`` in a state."""
        try:
            return self._index[name]
        except KeyError:
            raise KeyError(f"no variable {name!r} (have {', '.join(self._index)})") from None

    def projection(self, names: Sequence[str]) -> Callable[[State], State]:
        """A function ``state -> tuple`` of the named components (e.g. ``("x", "y")``)."""
        indices = [self.index(n) for n in names]
        if len(indices) == 1:
            only = indices[0]
            return lambda state: (state[only],)
        return operator.itemgetter(*indices)

    def distance(self, a: State, b: State) -> float:
        """The metric distance (SPEC 5.1/5.3): the definition, which the generated
        metrics (``planning_core.kernels.space_metric``) equal bit for bit."""
        total = 0.0
        for indices, weight, angles in self._plan:
            if len(indices) == 1:
                i = indices[0]
                d = b[i] - a[i]
                total += weight * abs(math.remainder(d, TAU) if angles[0] else d)
                continue
            squares = 0.0
            for i, is_angle in zip(indices, angles):
                d = b[i] - a[i]
                if is_angle:
                    d = math.remainder(d, TAU)
                squares += d * d
            total += weight * math.sqrt(squares)
        return total

    def maximum_extent(self) -> float:
        """The largest distance two states within the bounds can be apart (OMPL's
        ``getMaximumExtent``): per group, its weight times the norm of its spans, an
        angle's span pi. Infinite when a weighed variable is unbounded."""
        total = 0.0
        for indices, weight, angles in self._plan:
            if weight == 0.0:
                continue  # (an unbounded variable there weighs nothing: not 0 * inf)
            spans = [math.pi if is_angle else self.variables[i].high - self.variables[i].low
                     for i, is_angle in zip(indices, angles)]
            total += weight * math.sqrt(math.fsum(span * span for span in spans))
        return total

    def interpolate(self, a: State, b: State, t: float) -> State:
        """The state a fraction ``t`` of the way from ``a`` to ``b``.

        Angles go the shorter way (``a + t * remainder(b - a, 2*pi)``, wrapped).
        Evaluated from the nearer end, so ``t = 0`` gives ``a`` and ``t = 1``
        gives ``b`` exactly (angles wrapped). The definition, as :meth:`distance`.
        """
        out = []
        for x, y, is_angle in zip(a, b, self._angles):
            d = math.remainder(y - x, TAU) if is_angle else y - x
            v = x + t * d if t < 0.5 else y - (1.0 - t) * d
            out.append(math.remainder(v, TAU) if is_angle else v)
        return tuple(out)

    def wrap(self, state: State) -> State:
        """Angles to ``math.remainder(angle, 2*pi)``, the rest unchanged."""
        if not self._angle_indices:
            return tuple(state)
        return tuple(math.remainder(v, TAU) if is_angle else v
                     for v, is_angle in zip(state, self._angles))

    def sample_uniform(self, rng: Random) -> State:
        """A uniform state: angles in [-pi, pi), the rest in [low, high).

        One ``rng.random()`` per variable, in order, so a seed fixes the sample.
        (A bounded space shadows this with ``samplers.BoxSampler``: the same draws.)
        """
        out = []
        for v in self.variables:
            if v.angle:
                out.append(-math.pi + TAU * rng.random())
            elif math.isfinite(v.low) and math.isfinite(v.high):
                out.append(v.low + (v.high - v.low) * rng.random())
            else:
                raise ValueError(f"sample_uniform: variable {v.name} is unbounded")
        return tuple(out)

    def satisfies_bounds(self, state: State) -> bool:
        """Every value finite, every non-angle within its closed bounds."""
        if len(state) != len(self.variables):
            return False
        for value, v in zip(state, self.variables):
            if not math.isfinite(value):
                return False
            if not v.angle and not v.low <= value <= v.high:
                return False
        return True


def _check(variables: tuple[Variable, ...], groups: tuple[Group, ...]) -> None:
    """Reject what would make the metric ambiguous: duplicate names, unknown
    or repeated indices, empty groups, negative or non-finite weights."""
    names = [v.name for v in variables]
    if len(set(names)) != len(names):
        raise ValueError(f"variable named twice in {names}")
    seen: set[int] = set()
    for indices, weight in groups:
        if not indices:
            raise ValueError("an empty metric group")
        if not (math.isfinite(weight) and weight >= 0.0):
            raise ValueError(f"metric weight {weight!r} is not a finite number >= 0")
        for i in indices:
            if not 0 <= i < len(variables):
                raise ValueError(f"metric index {i} out of range 0..{len(variables) - 1}")
            if i in seen:
                raise ValueError(f"variable {variables[i].name} is in two metric groups")
            seen.add(i)
