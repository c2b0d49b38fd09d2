"""A* over a graph of states (Hart, Nilsson & Raphael 1968, "A formal basis for
the heuristic determination of minimum cost paths").

Edge costs are metric lengths of straight motions (Euclidean in the plane, SPEC
5.3's metric for the family), so the metric distance to the target is a
consistent heuristic: the first time the target is popped its path is a
shortest one, and no node needs to be expanded twice.
"""

from __future__ import annotations

import heapq
import math
from typing import Callable, Sequence

Adjacency = Sequence[Sequence[tuple[int, float]]]
"""``adjacency[u]``: the ``(v, cost)`` pairs of the edges leaving ``u``."""


def astar(adjacency: Adjacency, xs: Sequence[float], ys: Sequence[float],
          source: int, target: int) -> list[int] | None:
    """:func:`astar_search` over points ``(xs[i], ys[i])`` of the plane."""
    tx, ty = xs[target], ys[target]
    return astar_search(adjacency, source, target,
                        lambda node: math.hypot(xs[node] - tx, ys[node] - ty))


def astar_search(adjacency: Adjacency, source: int, target: int,
                 heuristic: Callable[[int], float]) -> list[int] | None:
    """Node indices of a shortest path from ``source`` to ``target`` (both
    included), or None when the target cannot be reached. ``heuristic(node)``:
    a consistent lower bound of the cost from ``node`` to ``target``."""
    best_cost = {source: 0.0}
    came_from = {source: -1}
    closed = set()
    # (cost + heuristic, cost, node); equal keys pop in node order, deterministically.
    frontier = [(heuristic(source), 0.0, source)]
    while frontier:
        _, cost, node = heapq.heappop(frontier)
        if node in closed:
            continue
        if node == target:
            path = []
            while node != -1:
                path.append(node)
                node = came_from[node]
            path.reverse()
            return path
        closed.add(node)
        for neighbour, edge_cost in adjacency[node]:
            new_cost = cost + edge_cost
            if neighbour in closed or new_cost >= best_cost.get(neighbour, math.inf):
                continue
            best_cost[neighbour] = new_cost
            came_from[neighbour] = node
            heapq.heappush(frontier, (new_cost + heuristic(neighbour), new_cost, neighbour))
    return None
