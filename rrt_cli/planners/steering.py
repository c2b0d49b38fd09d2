"""How a tree node moves toward a random target, by the kind of system.

Geometric systems go straight to the target when the motion is free (checked
exactly); otherwise, with ``partial_extension``, toward the first invalid state,
stopping ``wall_clearance`` short of it. Kinodynamic systems try
``controls_per_extension`` random controls, each held for one step (kinoplan
systems: K slices, K drawn with the control); the valid one ending closest to
the target by ``si.closeness`` wins (SPEC 2: by position on the grid; SPEC 5.3:
by the metric for kinoplan systems).
"""

from __future__ import annotations

import math
import random

from planning_core.space_information import SpaceInformation


class StraightLineSteering:
    def __init__(self, si: SpaceInformation, partial_extension: bool, min_extension: float,
                 wall_clearance: float):
        self.si = si
        self.partial_extension = partial_extension
        self.min_extension = min_extension
        self.wall_clearance = wall_clearance

    def extend(self, state: tuple[float, ...], target: tuple[float, float],
               rng: random.Random) -> tuple[tuple[float, float], None] | None:
        x0, y0 = state
        tx, ty = target
        hit = self.si.first_hit(state, target)
        if hit is None:
            return ((tx, ty), None)
        if not self.partial_extension:
            return None
        length = math.hypot(tx - x0, ty - y0)
        reach = hit.fraction * length - self.wall_clearance
        if reach < self.min_extension:
            return None
        t = reach / length
        end = (x0 + (tx - x0) * t, y0 + (ty - y0) * t)
        if not (self.si.is_valid(end) and self.si.printable(*end)):
            return None
        return (end, None)


class ControlSamplingSteering:
    def __init__(self, si: SpaceInformation, controls_per_extension: int):
        self.si = si
        self.controls_per_extension = controls_per_extension

    def extend(self, state: tuple[float, ...], target: tuple[float, ...],
               rng: random.Random):
        best = None
        best_d2 = math.inf
        si = self.si
        sample_control, propagate_valid, closeness = (si.sample_control, si.propagate_valid,
                                                      si.closeness)
        for _ in range(self.controls_per_extension):
            control = sample_control(rng)
            end = propagate_valid(state, control)
            if end is None:
                continue
            d2 = closeness(end, target)
            if d2 < best_d2:
                best, best_d2 = (end, control), d2
        return best


def make_steering(si: SpaceInformation, params):
    """The steering RRT-like planners use for ``si``'s kind of system."""
    if si.system.kinodynamic:
        return ControlSamplingSteering(si, params.controls_per_extension)
    return StraightLineSteering(si, params.partial_extension, params.min_extension,
                                params.wall_clearance)
