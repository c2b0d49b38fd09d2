"""How a tree node moves toward a random target, by the kind of system.

Geometric systems go straight to the target when the motion is free (checked
exactly on the grid, at the check step for the geometric family); otherwise,
with ``partial_extension``, toward the first invalid state, stopping
``wall_clearance`` short of it (by default the space information's: on the grid
a map unit, in the family one check step). Kinodynamic systems try
``controls_per_extension`` random controls (by default the space information's),
each held for one step (family systems: K slices, K drawn with the control); the
valid one ending closest to the target by ``si.closeness`` wins (SPEC 2: by
position on the grid; SPEC 5.3: by the metric in the family).
"""

from __future__ import annotations

import math
import random

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Callable, Optional

    from planning_core.space_information import ControlSpaceInformation, GeometricSpaceInformation


class StraightLineSteering:
    def __init__(self, si: GeometricSpaceInformation, partial_extension: bool,
                 min_extension: float, wall_clearance: Optional[float]):
        self.first_hit, self.can_end_at = si.first_hit, si.can_end_at
        self.distance, self.interpolate = si.distance, si.interpolate
        self.rechecks_prefix = si.rechecks_prefix
        self.partial_extension = partial_extension
        self.min_extension = min_extension
        self.wall_clearance = si.wall_clearance if wall_clearance is None else wall_clearance

    def extend(self, state: tuple[float, ...], target: tuple[float, ...],
               rng: random.Random) -> tuple[tuple[float, ...], None] | None:
        hit = self.first_hit(state, target)
        if hit is None:
            return (tuple(target), None)
        if not self.partial_extension:
            return None
        length = self.distance(state, target)
        reach = hit.fraction * length - self.wall_clearance
        if reach < self.min_extension:
            return None
        end = self.interpolate(state, target, reach / length)
        if not self.can_end_at(end):
            return None
        if self.rechecks_prefix and self.first_hit(state, end) is not None:
            return None
        return (end, None)


class ControlSamplingSteering:
    def __init__(self, si: ControlSpaceInformation, controls_per_extension: int):
        self.controls_per_extension = controls_per_extension
        # Bound once: this loop is the kinodynamic RRT's hot path (compiled, hot-paths.md).
        self.sample_control: Callable[[random.Random], Any] = si.sample_control
        self.propagate_valid: Callable[[Any, Any], Any] = si.propagate_valid
        self.closeness: Callable[[Any, Any], float] = si.closeness
        self.native: Optional[Callable[[Any, Any, random.Random], Any]] = (
            si.native_extension(controls_per_extension))
        """This extension in C where the space information has it (the grid ships with
        the compiled build: the same draws and floats), else None."""

    def extend(self, state: tuple[float, ...], target: tuple[float, ...],
               rng: random.Random) -> Any:
        """Of ``controls_per_extension`` sampled controls, the valid one whose end is
        nearest the target: (end, control), or None."""
        native = self.native
        if native is not None:
            return native(state, target, rng)
        best = None
        best_d2 = math.inf
        sample_control, propagate_valid, closeness = (self.sample_control,
                                                      self.propagate_valid, self.closeness)
        for _ in range(self.controls_per_extension):
            control = sample_control(rng)
            end = propagate_valid(state, control)
            if end is None:
                continue
            d2: float = closeness(end, target)
            if d2 < best_d2:
                best, best_d2 = (end, control), d2
        return best


def make_steering(si: Any, params: Any):
    """The steering RRT-like planners use for ``si``'s kind of system."""
    if si.system.kinodynamic:
        return ControlSamplingSteering(si, params.controls_per_extension
                                       or si.controls_per_extension)
    return StraightLineSteering(si, params.partial_extension, params.min_extension,
                                params.wall_clearance)
