"""The spaceship of SPEC section 2: state <x, y, dx, dy>, control <theta, s>.

One control is held for one timestep, integrated in ``SLICES`` slices of
``1 / SLICES``. Both the planner and the validator integrate through
:func:`integrate`, so their numbers agree bit for bit.
"""

from __future__ import annotations

import math
from typing import Sequence

SLICES = 20
DT = 1.0 / SLICES
MAX_THRUST = 0.5
THETA_RANGE = 2.0 * math.pi        # theta drawn from [0, 2 pi)
LEFT_THETA_RANGE = math.pi         # left-only spaceship: [0, pi)

State = tuple[float, float, float, float]
Control = tuple[float, float]


def integrate(state: State, control: Control,
              blocked: Sequence[int] | None = None, width: int = 0, height: int = 0,
              slices_out: list[State] | None = None) -> State | None:
    """Apply ``control`` from ``state`` for one timestep.

    With ``blocked`` (the world's row-major cell list), returns None as soon as a
    slice's position collides. With ``slices_out``, appends the state after every
    slice. Otherwise returns the final state.
    """
    x, y, dx, dy = state
    theta, thrust = control
    step = DT * thrust
    atan2, cos, sin = math.atan2, math.cos, math.sin  # locals: this loop is the hot path
    for _ in range(SLICES):
        a = atan2(dy, dx) + theta
        dx = dx + step * cos(a)
        dy = dy + step * sin(a)
        x = x + DT * dx
        y = y + DT * dy
        if blocked is not None and (not (0.0 <= x < width and 0.0 <= y < height)
                                    or blocked[int(y) * width + int(x)]):
            return None
        if slices_out is not None:
            slices_out.append((x, y, dx, dy))
    return (x, y, dx, dy)


def propagate(state: State, control: Control) -> State:
    """The state one timestep later (no collision test)."""
    return integrate(state, control)  # type: ignore[return-value]


def slice_states(state: State, control: Control) -> list[State]:
    """The states after each of the ``SLICES`` slices, last one included."""
    out: list[State] = []
    integrate(state, control, slices_out=out)
    return out
