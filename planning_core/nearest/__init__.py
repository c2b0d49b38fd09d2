"""Nearest-neighbour structures for growing planner trees.

``quadtree``: 2-D positions, what the grid planners use (their nearest node is by
position). ``kdtree``: exact nearest, k-nearest and radius queries in any state
space (weighted metric groups, wrapped angles), with incremental inserts.
Each has a linear scan beside it, the baseline it must equal
(``benchmarks/bench_nearest.py``, ``benchmarks/bench_kdtree.py``).
"""
