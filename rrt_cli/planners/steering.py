"""How a tree node moves toward a random target, by the kind of system.

Geometric systems go straight to the target when the motion is free (checked
exactly on the grid, at the check step for the geometric family); otherwise,
with ``partial_extension``, toward the first invalid state, stopping
``wall_clearance`` short of it (``si``'s clearance: on the grid that many map
units, for the family one check step). Kinodynamic systems try
``controls_per_extension`` random controls, each held for one step (kinoplan
systems: K slices, K drawn with the control); the valid one ending closest to
the target by ``si.closeness`` wins (SPEC 2: by position on the grid; SPEC 5.3:
by the metric for kinoplan systems).
"""

from __future__ import annotations

import math
import random
from typing import Any, Callable

from planning_core.space_information import AnySpaceInformation
from rrt_cli.planners.point_common import straight_lines


class StraightLineSteering:
    def __init__(self, si: AnySpaceInformation, partial_extension: bool, min_extension: float,
                 wall_clearance: float):
        lines = straight_lines(si)
        self.first_hit, self.can_end_at = lines.first_hit, lines.can_end_at
        self.distance, self.interpolate = lines.distance, lines.interpolate
        self.rechecks_prefix = lines.rechecks_prefix
        self.partial_extension = partial_extension
        self.min_extension = min_extension
        self.wall_clearance = lines.clearance(wall_clearance)

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
    def __init__(self, si: AnySpaceInformation, controls_per_extension: int):
        self.controls_per_extension = controls_per_extension
        # Bound once: this loop is the kinodynamic RRT's hot path (compiled, hot-paths.md).
        self.sample_control: Callable[[random.Random], Any] = si.sample_control
        self.propagate_valid: Callable[[Any, Any], Any] = si.propagate_valid
        self.closeness: Callable[[Any, Any], float] = si.closeness

    def extend(self, state: tuple[float, ...], target: tuple[float, ...],
               rng: random.Random) -> Any:
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


def make_steering(si: AnySpaceInformation, params):
    """The steering RRT-like planners use for ``si``'s kind of system."""
    if si.system.kinodynamic:
        return ControlSamplingSteering(si, params.controls_per_extension)
    return StraightLineSteering(si, params.partial_extension, params.min_extension,
                                params.wall_clearance)
