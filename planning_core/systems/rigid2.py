"""The rigid body in SE(2) of SPEC 5.2 (seed 004): state (x, y, theta), the
problem's convex ``body`` placed at (x, y) and rotated by theta; metric
``0.7 * translation + 0.3 * rotation`` by default. The body has no default: a
problem must give one (``SYSTEM``, the registry's unconfigured instance, has none).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, GeometricFamily

DEFAULTS = Defaults(bounds={}, metric=(("x,y", 0.7), ("theta", 0.3)), check=0.01)


@dataclass(frozen=True)
class Rigid2(GeometricFamily):
    name: ClassVar[str] = "rigid2"
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "theta")
    angle_names: ClassVar[tuple[str, ...]] = ("theta",)
    DEFAULTS: ClassVar[Defaults] = DEFAULTS


SYSTEM = Rigid2()
