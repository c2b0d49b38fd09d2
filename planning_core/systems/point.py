"""The point vehicle of SPEC 2: state <x, y>, moving along straight segments.

A geometric system: no controls; a motion is the segment between two states,
checked exactly against the world.
"""

from __future__ import annotations

from dataclasses import dataclass

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import ClassVar

State = tuple[float, float]


class PointVariables:
    """The point's declarations (a plain base: mypyc drops ``ClassVar`` from a
    dataclass's own annotations)."""

    kinodynamic: ClassVar[bool] = False
    state_names: ClassVar[tuple[str, ...]] = ("x", "y")
    control_names: ClassVar[tuple[str, ...]] = ()
    position_indices: ClassVar[tuple[int, ...]] = (0, 1)
    velocity_indices: ClassVar[tuple[int, ...]] = ()


@dataclass(frozen=True)
class PointVehicle(PointVariables):
    """The point vehicle of SPEC 1-2: state (x, y), straight segments, no controls."""

    name: str = "point"
    """The name the registry and the validator's report use."""

    def state_space(self, width: float, height: float):
        """The map's rectangle, Euclidean distance."""
        from planning_core.spaces import StateSpace
        return StateSpace.real_vector(("x", "y"), (0.0, 0.0), (width, height))

    def start_state(self, x: float, y: float) -> State:
        return (x, y)


SYSTEM = PointVehicle()
