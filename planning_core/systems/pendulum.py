"""The torque-limited pendulum of SPEC 5.2 (seed 000): state (theta, omega),
control tau, ``theta' = omega``, ``omega' = -g cos(theta) + tau``.

theta is an angle (wrapped after every slice); theta = -pi/2 hangs down, pi/2 is
upright. The pendulum has no world, no body and no position: its
``position_indices`` are (theta, omega), the plane of its phase portrait.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, KinodynamicFamily

G = 9.81
DEFAULTS = Defaults(
    bounds={"omega": (-10.0, 10.0)},
    metric=(("theta", 1.0), ("omega", 1.0)),
    controls={"tau": (-3.0, 3.0)},
    integrate=("rk4", 0.05),
    duration=(1, 10),
)


@dataclass(frozen=True)
class Pendulum(KinodynamicFamily):
    g: float = G
    """Gravity, m/s^2 (``param g``)."""

    name: ClassVar[str] = "pendulum"
    state_names: ClassVar[tuple[str, ...]] = ("theta", "omega")
    angle_names: ClassVar[tuple[str, ...]] = ("theta",)
    control_names: ClassVar[tuple[str, ...]] = ("tau", "K")
    rates: ClassVar[tuple[str, ...]] = ("omega", "-g * cos(theta) + tau")
    params: ClassVar[tuple[str, ...]] = ("g",)
    position_indices: ClassVar[tuple[int, int]] = (0, 1)
    projection_names: ClassVar[tuple[str, ...]] = ("theta", "omega")
    needs_world: ClassVar[bool] = False
    occupies: ClassVar[str] = ""
    DEFAULTS: ClassVar[Defaults] = DEFAULTS


SYSTEM = Pendulum()
