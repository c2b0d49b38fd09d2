"""Moved to :mod:`planning_core.worlds.grid_distance` (temporary re-export)."""
from planning_core.worlds.grid_distance import *  # noqa: F401,F403
from planning_core.worlds.grid_distance import CellDistanceToGoal  # noqa: F401
