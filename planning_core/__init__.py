"""Shared core of the planner and the validator: the grid problem, the world's
collision tests, the vehicles' dynamics and the plan text format.

Pure Python on purpose: the planner starts in a few tens of milliseconds because
nothing here imports numpy.
"""
