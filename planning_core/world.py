"""Moved to :mod:`planning_core.worlds.grid` (temporary re-export while the core is reshaped)."""
from planning_core.worlds.grid import *  # noqa: F401,F403
from planning_core.worlds.grid import SAMPLE_STEP, GridWorld, SegmentHit, connected_free_cells, segment_meets_cell  # noqa: F401
