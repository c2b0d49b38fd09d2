"""Guided iterations: where the world measures the distance to the goal along its free
cells (``si.distance_along_free_space``: the grid), a share of a tree's iterations, until
its first solution, extends the node nearest the goal by that distance, each node once,
toward a state ``GUIDE_CELLS`` cells further down the cheapest chain of cells, or at the
end of the chain's straight run (``ahead_of``: the point's cell centre; the Dubins car's
pose where the chain leaves a cell). On a big map uniform targets fill the map before
they reach a far goal; these walk the tree down the way. RRT* and Informed RRT* guide every system
that has a way; RRT and RRT-Connect only where the space information asks
(``rrt_guided_targets``: the Dubins car).
"""

from __future__ import annotations

import random
from typing import Any, Optional

from planning_core.heap import HeapEntry, heap_pop, heap_push
from planning_core.interrupt import Interrupted, Stop
from planning_core.samplers import uniform

State = tuple[float, ...]
GUIDE_CELLS = 1
"""How far down the free cells a guided target lies from its node at least, in cells."""


class Guide:
    """The nodes not yet guided from, by their distance to the goal along the free
    cells (``along``), and the share of iterations that take one.

    A node waits under ``along.bound`` until it comes first; then it is measured
    (``along`` is lazy: measuring may walk the map) and waits again under its
    distance unless that still comes first. So only the nodes that come near the
    front are measured, and the one drawn is the nearest by distance."""

    def __init__(self, along: Any, share: float, root: State) -> None:
        self.along, self.share = along, share
        self.waiting: list[HeapEntry] = []
        self.measured: set[int] = set()
        self.add(0, root)

    @staticmethod
    def prepare(si: Any, share: float) -> None:
        """Before the planning clock, where iterations will be guided: load what
        :meth:`begin` measures with (the grid's Dijkstra module), so that the clock
        counts the measuring, not the import."""
        if share > 0.0:
            si.prepare_distance_along_free_space()

    @staticmethod
    def begin(si: Any, goal: Any, share: float, root: State,
              stop: Stop = None) -> Optional["Guide"]:
        """The guide of a tree that is ``root`` alone, or None without guided iterations
        (a share of 0, or a world that measures no way: the family). The grid's
        Dijkstra runs lazily from the goal toward ``root``, on the planning clock."""
        if share <= 0.0:
            return None
        along = si.distance_along_free_space(goal, stop, root)
        return None if along is None else Guide(along, share, root)

    def add(self, node: int, state: State) -> None:
        heap_push(self.waiting, HeapEntry(self.along.bound(state[0], state[1]), node))

    def draw(self, rng: random.Random, states: list[State]) -> Optional[tuple[int, State]]:
        """This iteration's guided node and its target, when it is a guided one (one
        draw of ``rng``): the waiting node nearest the goal that has a way on. None when
        it is not guided, or no node waits. When the time runs out while measuring,
        None, and the guide guides no more."""
        if uniform(rng) >= self.share:
            return None
        try:
            return self._nearest(states)
        except Interrupted:
            self.share = 0.0
            return None

    def _nearest(self, states: list[State]) -> Optional[tuple[int, State]]:
        along, waiting, measured = self.along, self.waiting, self.measured
        while waiting:
            node = heap_pop(waiting).order
            state = states[node]
            if node not in measured:
                measured.add(node)
                distance: float = along(state[0], state[1])
                if waiting and distance > waiting[0].key:
                    heap_push(waiting, HeapEntry(distance, node))
                    continue
            ahead = along.ahead_of(state, GUIDE_CELLS)
            if ahead is not None:
                return node, ahead
        return None
