"""The second-order unicycle of SPEC 5.2 (seed 003): state (x, y, theta, v, omega),
controls a and alpha (linear and angular acceleration): ``x' = v cos theta``,
``y' = v sin theta``, ``theta' = omega``, ``v' = a``, ``omega' = alpha``; a 2 x 1
rectangle body, its length along theta. omega is a bounded rate, not an angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, KinodynamicFamily

DEFAULTS = Defaults(
    bounds={"v": (-5.0, 5.0), "omega": (-math.pi / 2, math.pi / 2)},
    metric=(("x,y", 1.0), ("theta", 0.5)),
    controls={"a": (-2.0, 2.0), "alpha": (-math.pi / 2, math.pi / 2)},
    integrate=("euler", 0.1),
    duration=(1, 20),
    body=("rect", (2.0, 1.0)),
)


@dataclass(frozen=True)
class Unicycle(KinodynamicFamily):
    name: ClassVar[str] = "unicycle"
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "theta", "v", "omega")
    angle_names: ClassVar[tuple[str, ...]] = ("theta",)
    control_names: ClassVar[tuple[str, ...]] = ("a", "alpha", "K")
    rates: ClassVar[tuple[str, ...]] = ("v * cos(theta)", "v * sin(theta)", "omega", "a",
                                        "alpha")
    DEFAULTS: ClassVar[Defaults] = DEFAULTS


SYSTEM = Unicycle()
