"""planning_core.angles: the library's remainder, bit for bit."""

import math
import random

from planning_core.angles import remainder


def check_remainder(seed: int, count: int = 200_000) -> None:
    """``remainder(x, y)`` is ``math.remainder(x, y)`` bit for bit: y = 2 pi (the
    angles) on uniform, tiny and special values, and a few other y."""
    rng = random.Random(seed)
    tau = 2.0 * math.pi
    special = [0.0, -0.0, 5e-324, math.pi, -math.pi, tau, -tau, 3 * math.pi, 1e300,
               math.nan, math.inf, -math.inf]
    special += [math.nextafter(v, w) for v in (math.pi, -math.pi, tau, -tau)
                for w in (math.inf, -math.inf)]
    values = special + [rng.uniform(-3 * tau, 3 * tau) for _ in range(count)]
    values += [rng.uniform(-1e-300, 1e-300) for _ in range(1000)]
    cases = [(x, tau) for x in values]
    for y in (1.0, math.pi, 360.0, 1e-3, 0.0, -tau, math.inf, math.nan):
        cases += [(x, y) for x in special + [rng.uniform(-3 * y, 3 * y) if math.isfinite(y)
                                            else rng.uniform(-10.0, 10.0) for _ in range(1000)]]

    def outcome(f, x, y):
        try:
            return f(x, y).hex()
        except ValueError:  # an infinity, or y = 0
            return "ValueError"

    for x, y in cases:
        assert outcome(remainder, x, y) == outcome(math.remainder, x, y), (x, y)


def test_remainder_is_the_library_s():
    check_remainder(seed=2)
