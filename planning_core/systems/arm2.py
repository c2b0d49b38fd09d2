"""The two-link planar arm of SPEC 5.2 (seed 004): state (theta1, theta2), both
angles, so its configuration space is a torus.

``elbow = base + l1 (cos t1, sin t1)``, ``tip = elbow + l2 (cos(t1 + t2),
sin(t1 + t2))``; the links are the closed segments base -> elbow and elbow ->
tip, and a configuration is valid when both lie inside the world box and off
every obstacle (``planning_core.kinoplan.state_validator``). A cosine or sine
below ``shapes.SNAP`` counts as 0, as for a placed body, so quarter turns are
exact (``planning_core.worlds.link_tests.joints``). ``position_indices`` are
(theta1, theta2): the plane of the configuration-space square.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import ClassVar

from planning_core.systems.family import Defaults, GeometricFamily
from planning_core.worlds import link_tests
from planning_core.worlds.shapes import Segment

Point = tuple[float, float]
DEFAULTS = Defaults(bounds={}, metric=(("theta1,theta2", 1.0),), check=0.01)


@dataclass(frozen=True)
class Arm2(GeometricFamily):
    base_x: float = 0.0
    """x of the shoulder joint (``param base_x``)."""
    base_y: float = 0.0
    """y of the shoulder joint (``param base_y``)."""
    l1: float = 1.0
    """Length of the first link, shoulder to elbow (``param l1``), > 0."""
    l2: float = 1.0
    """Length of the second link, elbow to tip (``param l2``), > 0."""

    name: ClassVar[str] = "arm2"
    state_names: ClassVar[tuple[str, ...]] = ("theta1", "theta2")
    angle_names: ClassVar[tuple[str, ...]] = ("theta1", "theta2")
    params: ClassVar[tuple[str, ...]] = ("base_x", "base_y", "l1", "l2")
    positive_params: ClassVar[frozenset[str]] = frozenset({"l1", "l2"})
    occupies: ClassVar[str] = "links"
    DEFAULTS: ClassVar[Defaults] = DEFAULTS

    def joints(self, state: Sequence[float]) -> tuple[Point, Point, Point]:
        """Base, elbow and tip positions (``link_tests.joints``)."""
        ex, ey, tx, ty = link_tests.joints(self.base_x, self.base_y, self.l1, self.l2,
                                           state[0], state[1])
        return (self.base_x, self.base_y), (ex, ey), (tx, ty)

    def links(self, state: Sequence[float]) -> tuple[Segment, Segment]:
        """The two links as closed segments: base -> elbow, elbow -> tip."""
        (bx, by), (ex, ey), (tx, ty) = self.joints(state)
        return Segment._trusted(bx, by, ex, ey), Segment._trusted(ex, ey, tx, ty)


SYSTEM = Arm2()
