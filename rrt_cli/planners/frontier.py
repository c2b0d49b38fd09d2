"""Moved to :mod:`planning_core.worlds.grid_frontier` (temporary re-export)."""
from planning_core.worlds.grid_frontier import FrontierCells  # noqa: F401
