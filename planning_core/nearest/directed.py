"""Nearest neighbours by a directed distance (the Dubins car's path length) whose
straight distance between positions is a lower bound. Compiled with the planners
(``rrt_startup.compiled``): they hold it typed as :class:`NearestIndex`."""

from __future__ import annotations

import math
from typing import Any, Callable

from planning_core.nearest.index import NearestIndex
from planning_core.nearest.quadtree import QuadtreeNearest

FIRST_BATCH = 8
"""Nodes re-ranked first; each further batch is 4 times larger."""


class DubinsNearest(NearestIndex):
    """Nearest by the Dubins path length from a node to the query: the nodes in
    order of straight distance (a quadtree), a lower bound of the Dubins length,
    each re-ranked exactly until the next straight distance exceeds the best found.
    Ties: the earliest node."""

    def __init__(self, distance: Callable[[Any, Any], float], width: float,
                 height: float) -> None:
        self.index = QuadtreeNearest(width, height)
        self.states: list[Any] = []
        self.distance = distance

    def add(self, state: Any) -> int:
        self.states.append(state)
        return self.index.add(state[0], state[1])

    def nearest(self, query: Any) -> int:
        return self.k_nearest(query, 1)[0]

    def k_nearest(self, query: Any, k: int) -> list[int]:
        """The ``k`` nodes nearest to ``query`` by the Dubins length, nearest first."""
        states, distance = self.states, self.distance
        exact: dict[int, float] = {}
        batch = max(FIRST_BATCH, 2 * k)
        while True:
            found = self.index.k_nearest(query[0], query[1], batch)
            for node in found:
                if node not in exact:
                    exact[node] = distance(states[node], query)
            ranked = sorted(exact, key=lambda node: (exact[node], node))[:k]
            if len(found) < batch:
                return ranked
            last = states[found[-1]]
            bound = math.hypot(last[0] - query[0], last[1] - query[1])
            if len(ranked) == k and bound > exact[ranked[-1]] * (1.0 + 1e-12):
                return ranked
            batch *= 4
