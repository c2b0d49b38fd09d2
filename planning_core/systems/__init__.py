"""Systems: what moves and how (state and control variables, bounds, a pure
propagate for kinodynamic ones), knowing nothing of worlds.

Each system is a module with a ``SYSTEM`` object; :func:`load` finds it by name,
importing only that module. A new system is a new module and a line here.
"""

from __future__ import annotations

import importlib

SYSTEM_MODULES = {
    "point": "planning_core.systems.point",
    "spaceship": "planning_core.systems.spaceship",
    "left": "planning_core.systems.left_spaceship",
    "dubins": "planning_core.systems.dubins",
    "pendulum": "planning_core.systems.pendulum",
    "car2": "planning_core.systems.car2",
    "unicycle": "planning_core.systems.unicycle",
    "car1": "planning_core.systems.car1",
    "arm2": "planning_core.systems.arm2",
    "rigid2": "planning_core.systems.rigid2",
}


def load(name: str):
    """The system registered as ``name`` (KeyError for an unknown one)."""
    return importlib.import_module(SYSTEM_MODULES[name]).SYSTEM
