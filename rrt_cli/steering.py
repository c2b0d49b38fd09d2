"""How a tree node moves toward a random target, per vehicle.

Point vehicle: straight to the target when the segment is free (exact grid
walk); otherwise, with ``partial_extension``, toward the first blocked cell,
stopping ``wall_clearance`` short of it. Spaceships: ``controls_per_extension`` random controls, each held for
one step; the collision-free one ending closest to the target wins (SPEC 2).
"""

from __future__ import annotations

import math
import random

from planning_core.vehicles import spaceship
from planning_core.world import GridWorld

class PointSteering:
    def __init__(self, world: GridWorld, partial_extension: bool, min_extension: float,
                 wall_clearance: float):
        self.world = world
        self.partial_extension = partial_extension
        self.min_extension = min_extension
        self.wall_clearance = wall_clearance

    def extend(self, state: tuple[float, ...], target: tuple[float, float],
               rng: random.Random) -> tuple[tuple[float, float], None] | None:
        x0, y0 = state
        tx, ty = target
        hit = self.world.first_blocked_cell_on_segment(x0, y0, tx, ty)
        if hit is None:
            return ((tx, ty), None)
        if not self.partial_extension:
            return None
        length = math.hypot(tx - x0, ty - y0)
        reach = hit.fraction * length - self.wall_clearance
        if reach < self.min_extension:
            return None
        t = reach / length
        x, y = x0 + (tx - x0) * t, y0 + (ty - y0) * t
        if not (self.world.point_free(x, y) and self.world.point_strictly_inside(x, y)):
            return None
        return ((x, y), None)


class SpaceshipSteering:
    def __init__(self, world: GridWorld, theta_range: float, controls_per_extension: int):
        self.world = world
        self.theta_range = theta_range
        self.controls_per_extension = controls_per_extension

    def extend(self, state: tuple[float, ...], target: tuple[float, float],
               rng: random.Random):
        world = self.world
        blocked, width, height = world.blocked, world.width, world.height
        tx, ty = target
        best = None
        best_d2 = math.inf
        theta_range = self.theta_range
        integrate = spaceship.integrate
        for _ in range(self.controls_per_extension):
            control = (rng.random() * theta_range, rng.random() * spaceship.MAX_THRUST)
            end = integrate(state, control, blocked, width, height)
            if end is None or not (0.0 < end[0] and 0.0 < end[1]):
                continue
            d2 = (end[0] - tx) ** 2 + (end[1] - ty) ** 2
            if d2 < best_d2:
                best, best_d2 = (end, control), d2
        return best
