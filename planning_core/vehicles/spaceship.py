"""Moved to :mod:`planning_core.systems.spaceship` (temporary re-export)."""
import math

from planning_core.systems.spaceship import DT, MAX_THRUST, SLICES, SYSTEM  # noqa: F401

THETA_RANGE = 2.0 * math.pi
LEFT_THETA_RANGE = math.pi


def integrate(state, control, blocked=None, width=0, height=0, slices_out=None):
    free = None
    if blocked is not None:
        def free(x, y):
            return 0.0 <= x < width and 0.0 <= y < height and not blocked[int(y) * width + int(x)]
    return SYSTEM.propagate_while(state, control, free, slices_out)


propagate = SYSTEM.propagate
slice_states = SYSTEM.slice_states
