"""The first-order car of SPEC 5.2 (seed 004): state (x, y, theta), controls v
(speed) and phi (steering angle): ``x' = v cos theta``, ``y' = v sin theta``,
``theta' = (v / L) tan(phi)``; a 0.2 x 0.1 rectangle body.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, KinodynamicFamily

WHEELBASE = 0.2
DEFAULTS = Defaults(
    bounds={},
    metric=(("x,y", 0.7), ("theta", 0.3)),
    controls={"v": (-0.5, 0.5), "phi": (-math.pi / 4, math.pi / 4)},
    integrate=("euler", 0.01),
    duration=(1, 250),
    body=("rect", (0.2, 0.1)),
)


@dataclass(frozen=True)
class Car1(KinodynamicFamily):
    L: float = WHEELBASE  # noqa: N815 - SPEC's name, as in ``param L 0.2``
    """Wheelbase (``param L``), > 0."""

    name: ClassVar[str] = "car1"
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "theta")
    angle_names: ClassVar[tuple[str, ...]] = ("theta",)
    control_names: ClassVar[tuple[str, ...]] = ("v", "phi", "K")
    rates: ClassVar[tuple[str, ...]] = ("v * cos(theta)", "v * sin(theta)",
                                        "(v / L) * tan(phi)")
    params: ClassVar[tuple[str, ...]] = ("L",)
    positive_params: ClassVar[frozenset[str]] = frozenset({"L"})
    DEFAULTS: ClassVar[Defaults] = DEFAULTS


SYSTEM = Car1()
