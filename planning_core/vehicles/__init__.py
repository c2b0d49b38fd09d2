"""Vehicle models: one module per vehicle, pure functions over plain tuples."""

from enum import Enum


class Vehicle(str, Enum):
    """The vehicles of SPEC section 2, by their command-line names."""

    POINT = "point"          # -ugrad (default): <x, y>, straight moves
    SPACESHIP = "spaceship"  # -grad: <x, y, dx, dy>, thrust held for one step
    LEFT_SPACESHIP = "left"  # -grad -left: thrust angle in [0, pi) only

    @property
    def is_spaceship(self) -> bool:
        return self is not Vehicle.POINT

    @property
    def line_fields(self) -> int:
        """Numbers per trajectory line in the plan format."""
        return 2 if self is Vehicle.POINT else 6
