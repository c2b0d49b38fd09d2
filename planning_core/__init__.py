"""Shared core of the planner and the validator: the problems (the course's grid, the
``kinoplan 1`` family), systems and worlds, the two SpaceInformation protocols and the
setups that build them, the hot kernels, and the plan text format.

Pure Python on purpose: the planner starts in a few tens of milliseconds because
nothing here imports numpy.
"""
