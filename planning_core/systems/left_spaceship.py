"""The left-only spaceship (SPEC 2, ``-grad -left``): the spaceship's dynamics,
thrust only straight ahead or to the left of the motion (theta in ``[0, pi)``
when drawn, ``[0, pi]`` when checked)."""

import math

from planning_core.systems.spaceship import Spaceship

SYSTEM = Spaceship(name="left", theta_range=math.pi)
