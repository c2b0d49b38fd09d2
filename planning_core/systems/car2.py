"""The second-order car of SPEC 5.2 (seed 000): state (x, y, theta, v), controls
omega (turn rate) and a (acceleration): ``x' = v cos theta``, ``y' = v sin theta``,
``theta' = omega``, ``v' = a``; a 1.5 x 1.5 square body centred on (x, y).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, KinodynamicFamily

DEFAULTS = Defaults(
    bounds={"v": (-5.0, 5.0)},
    metric=(("x,y", 1.0), ("theta", 0.5), ("v", 0.3)),
    controls={"omega": (-2.0, 2.0), "a": (-3.0, 3.0)},
    integrate=("rk4", 0.05),
    duration=(1, 20),
    body=("square", (1.5,)),
)


@dataclass(frozen=True)
class Car2(KinodynamicFamily):
    name: ClassVar[str] = "car2"
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "theta", "v")
    angle_names: ClassVar[tuple[str, ...]] = ("theta",)
    control_names: ClassVar[tuple[str, ...]] = ("omega", "a", "K")
    rates: ClassVar[tuple[str, ...]] = ("v * cos(theta)", "v * sin(theta)", "omega", "a")
    DEFAULTS: ClassVar[Defaults] = DEFAULTS


SYSTEM = Car2()
