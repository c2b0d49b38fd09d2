"""The course's names for the three grid systems, as the command-line flags say them.

``Vehicle`` is naming only: what each one is lives in :mod:`planning_core.systems`.
"""

from enum import Enum


class Vehicle(str, Enum):
    """The vehicles of SPEC section 2, by their command-line names."""

    POINT = "point"          # -ugrad (default): <x, y>, straight moves
    SPACESHIP = "spaceship"  # -grad: <x, y, dx, dy>, thrust held for one step
    LEFT_SPACESHIP = "left"  # -grad -left: thrust angle in [0, pi) only
    DUBINS = "dubins"        # -dubins [-radius R]: <x, y, heading>, forward Dubins paths

    @property
    def system(self):
        """The system this name stands for (:mod:`planning_core.systems`)."""
        from planning_core.systems import load
        return load(self.value)

    @property
    def is_spaceship(self) -> bool:
        return self.system.kinodynamic

    @property
    def flags(self) -> tuple[str, ...]:
        """The command-line flags that name it (``./run.sh`` and ``rrt-validator``)."""
        return _FLAGS[self.value]


_FLAGS = {"point": (), "spaceship": ("-grad",), "left": ("-grad", "-left"),
          "dubins": ("-dubins",)}
