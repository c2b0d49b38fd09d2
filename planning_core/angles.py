"""``math.remainder`` for compiled code, where the library's is a generic call.

The kd-tree's metric, the family's slice loops and the arm's link tests wrap an
angle on every call; compiled (mypyc), a call to ``math.remainder`` reads the
module's dict and boxes its floats; this one is native.
"""

from __future__ import annotations

import math


def remainder(x: float, y: float) -> float:
    """``math.remainder(x, y)``, the same float: computed here for ``|x| < y``, as
    the library does it (there ``fmod(|x|, y)`` is ``|x|``: the result is ``x`` or
    ``x`` less ``y`` toward zero, exact), else by the library (the half-way case,
    ``y`` not positive, NaN and infinities too)."""
    m = abs(x)
    if m < y:
        c = y - m
        if m < c:
            return math.copysign(1.0, x) * m
        if m > c:
            return math.copysign(1.0, x) * -c
    return math.remainder(x, y)
