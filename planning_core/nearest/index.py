"""What the tree planners ask of a nearest-neighbour structure, as one base class.

Planners hold whichever structure their SpaceInformation makes (the grid's
quadtree by position, the kd-tree by a metric). Compiled (mypyc), a method call on
an untyped object goes through the method's Python wrapper, its arguments checked
and converted each time; typed as this base class, the call is native, to the
subclass's own method.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any



class NearestIndex:
    """Insert states, ask for the one nearest a query; both by insertion index."""

    def add(self, state: Any) -> int:
        """Insert a state; returns its index (insertion order)."""
        raise NotImplementedError

    def nearest(self, query: Any) -> int:
        """Index of the nearest inserted state (ties: the earliest)."""
        raise NotImplementedError

    def k_nearest(self, query: Any, k: int) -> list[int]:
        """Indices of the ``k`` nearest inserted states, nearest first."""
        raise NotImplementedError

    def nearest_within(self, query: Any, radius: float) -> int:
        """:meth:`nearest` if it is at most ``radius`` from ``query``, else -1."""
        raise NotImplementedError

    def cheapest_within(self, query: Any, radius: float, costs: list[float]) -> int:
        """Of the states at most ``radius`` from ``query``, the one of least ``costs[i]``
        (ties: the nearer, then the earliest); none there, :meth:`nearest` (SST's
        best-near selection). A structure may answer it in one search."""
        near = self.within(query, radius)
        if not near:
            return self.nearest(query)
        return min(near, key=costs.__getitem__)

    def within(self, query: Any, radius: float) -> list[int]:
        """Indices of the states at most ``radius`` from ``query`` (by the distance
        the structure orders by), sorted by (distance, index)."""
        raise NotImplementedError

    def remove(self, index: int) -> None:
        """No query finds the state inserted as ``index`` any more (indices of the
        others are kept; removing all of them leaves ``nearest`` answering -1)."""
        raise NotImplementedError
