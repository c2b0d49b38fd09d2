"""Nearest-neighbour search over 2-D positions for growing trees.

:class:`QuadtreeNearest` is what the planners use; :class:`LinearNearest` is
the plain scan it is measured against (``benchmarks/bench_nearest.py``). A
uniform bucket grid was tried first and dropped: spaceship trees cluster
tightly, and a grid fine enough for the clusters made far queries walk
thousands of empty buckets.
"""

from __future__ import annotations

import math

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Final


class _Node:
    """A box of the quadtree: a leaf holds point indices, an inner node four children
    (0 bottom-left, 1 bottom-right, 2 top-left, 3 top-right of its centre)."""

    __slots__ = ("x0", "y0", "x1", "y1", "cx", "cy", "children", "indices")

    def __init__(self, x0: float, y0: float, x1: float, y1: float) -> None:
        self.x0, self.y0, self.x1, self.y1 = x0, y0, x1, y1
        self.cx, self.cy = (x0 + x1) * 0.5, (y0 + y1) * 0.5
        self.children: list[_Node] | None = None
        self.indices: list[int] = []

    def quadrant(self, x: float, y: float) -> int:
        return (1 if x >= self.cx else 0) + (2 if y >= self.cy else 0)


def _push(stack: list[_Node], top: int, node: _Node) -> int:
    """Put ``node`` at ``stack[top]`` unless it is an empty leaf (nothing to find
    there); the new top. The list only grows: no pop shrinks and regrows it."""
    if node.children is None and not node.indices:
        return top
    if top == len(stack):
        stack.append(node)
    else:
        stack[top] = node
    return top + 1


class _Scan:
    """What a query keeps while the walk visits leaves: ``scan`` reads a leaf's
    points and returns the squared distance to prune by from then on."""

    def scan(self, indices: list[int]) -> float:
        raise NotImplementedError


class QuadtreeNearest:
    """A bucketed point-region quadtree over the map's rectangle.

    Leaves hold up to ``leaf_capacity`` point indices and split into four when
    they overflow. A query descends depth-first, nearest child first, and skips
    every node whose box is farther than the best point found so far, so its
    cost grows with the tree's depth, not its size, whatever the clustering.
    """

    def __init__(self, width: float, height: float, leaf_capacity: int = 12) -> None:
        self.xs: list[float] = []
        self.ys: list[float] = []
        self.leaf_capacity = leaf_capacity
        self.root = _Node(0.0, 0.0, float(width), float(height))

    def __len__(self) -> int:
        return len(self.xs)

    def add(self, x: float, y: float) -> int:
        """Insert a point; returns its index (insertion order)."""
        index = len(self.xs)
        self.xs.append(x)
        self.ys.append(y)
        node = self.root
        children = node.children
        while children is not None:
            node = children[node.quadrant(x, y)]
            children = node.children
        node.indices.append(index)
        if len(node.indices) > self.leaf_capacity and node.x1 - node.x0 > _MIN_NODE_SIZE:
            self._split(node)
        return index

    def _split(self, node: _Node) -> None:
        x0, y0, x1, y1, cx, cy = node.x0, node.y0, node.x1, node.y1, node.cx, node.cy
        children = [_Node(x0, y0, cx, cy), _Node(cx, y0, x1, cy),
                    _Node(x0, cy, cx, y1), _Node(cx, cy, x1, y1)]
        node.children = children
        xs, ys = self.xs, self.ys
        for index in node.indices:
            children[node.quadrant(xs[index], ys[index])].indices.append(index)
        node.indices = []
        for child in children:
            # All points may land in one quadrant (duplicates, tight clusters).
            if len(child.indices) > self.leaf_capacity and child.x1 - child.x0 > _MIN_NODE_SIZE:
                self._split(child)

    def _search(self, x: float, y: float, keep: _Scan, bound: float = math.inf) -> None:
        """Walk the leaves that may hold a point closer than the bound (at first
        ``bound``, a squared distance), nearest quadrant first, ``keep.scan``
        reading each leaf that has points."""
        stack = [self.root]
        top = 1
        while top:
            top -= 1
            node = stack[top]
            # Squared distance from the query to the node's box.
            gx = node.x0 - x if x < node.x0 else (x - node.x1 if x > node.x1 else 0.0)
            gy = node.y0 - y if y < node.y0 else (y - node.y1 if y > node.y1 else 0.0)
            if gx * gx + gy * gy > bound:
                continue
            children = node.children
            if children is None:
                if node.indices:
                    bound = keep.scan(node.indices)
                continue
            # Push the far quadrants first so the query's own quadrant pops first.
            q = (1 if x >= node.cx else 0) + (2 if y >= node.cy else 0)  # node.quadrant, inline
            top = _push(stack, top, children[3 - q])
            top = _push(stack, top, children[q ^ 1])
            top = _push(stack, top, children[q ^ 2])
            top = _push(stack, top, children[q])

    def nearest(self, x: float, y: float) -> int:
        """Index of the point closest to (x, y); ties go to the earliest inserted."""
        if not self.xs:
            raise ValueError("nearest() on an empty structure")
        best = _Nearest(self.xs, self.ys, x, y)
        self._search(x, y, best)
        return best.index

    def k_nearest(self, x: float, y: float, k: int) -> list[int]:
        """Indices of the ``k`` points closest to (x, y), nearest first.

        Ties are broken by insertion order, so the answer equals sorting every
        point by ``(squared distance, index)`` and keeping the first ``k``.
        Fewer than ``k`` points: all of them.
        """
        if k <= 0:
            return []
        kept = _KNearest(self.xs, self.ys, x, y, k)
        self._search(x, y, kept)
        kept.heap.sort(reverse=True)
        return [-negated_index for _, negated_index in kept.heap]

    def within(self, x: float, y: float, radius: float) -> list[int]:
        """Indices of the points whose squared distance to (x, y) is at most
        ``radius * radius``, sorted by (squared distance, index)."""
        if not radius >= 0.0:
            raise ValueError(f"radius must be a number >= 0, got {radius!r}")
        limit = radius * radius
        found = _Within(self.xs, self.ys, x, y, limit)
        self._search(x, y, found, limit)
        found.pairs.sort()
        return [index for _, index in found.pairs]

    def remove(self, index: int) -> None:
        """No query finds point ``index`` any more: it leaves its leaf (found by
        the quadrants :meth:`add` took; leaves never merge back)."""
        x, y, node = self.xs[index], self.ys[index], self.root
        children = node.children
        while children is not None:
            node = children[node.quadrant(x, y)]
            children = node.children
        if index not in node.indices:
            raise ValueError(f"point {index} is not in the structure")
        node.indices.remove(index)


class _Within(_Scan):
    """Every point within a fixed squared distance: ``(d2, index)`` pairs."""

    def __init__(self, xs: list[float], ys: list[float], x: float, y: float,
                 limit: float) -> None:
        self.xs, self.ys, self.x, self.y, self.limit = xs, ys, x, y, limit
        self.pairs: list[tuple[float, int]] = []

    def scan(self, indices: list[int]) -> float:
        xs, ys, x, y, limit, pairs = self.xs, self.ys, self.x, self.y, self.limit, self.pairs
        for index in indices:
            ddx = xs[index] - x
            ddy = ys[index] - y
            d2 = ddx * ddx + ddy * ddy
            if d2 <= limit:
                pairs.append((d2, index))
        return limit


class _Nearest(_Scan):
    """The nearest point so far: its squared distance and index."""

    def __init__(self, xs: list[float], ys: list[float], x: float, y: float) -> None:
        self.xs, self.ys, self.x, self.y = xs, ys, x, y
        self.d2 = math.inf
        self.index = -1

    def scan(self, indices: list[int]) -> float:
        xs, ys, x, y = self.xs, self.ys, self.x, self.y
        best_d2, best_index = self.d2, self.index
        for index in indices:
            ddx = xs[index] - x
            ddy = ys[index] - y
            d2 = ddx * ddx + ddy * ddy
            if d2 < best_d2 or (d2 == best_d2 and index < best_index):
                best_d2, best_index = d2, index
        self.d2, self.index = best_d2, best_index
        return best_d2


class _KNearest(_Scan):
    """The ``k`` best so far as a max-heap of ``(-d2, -index)``: the top is the worst kept."""

    def __init__(self, xs: list[float], ys: list[float], x: float, y: float, k: int) -> None:
        self.xs, self.ys, self.x, self.y, self.k = xs, ys, x, y, k
        self.heap: list[tuple[float, int]] = []

    def scan(self, indices: list[int]) -> float:
        import heapq  # here, not at the top: only PRM asks (start-up, docs/hot-paths.md)
        xs, ys, x, y, k, kept = self.xs, self.ys, self.x, self.y, self.k, self.heap
        for index in indices:
            ddx = xs[index] - x
            ddy = ys[index] - y
            d2 = ddx * ddx + ddy * ddy
            if len(kept) < k:
                heapq.heappush(kept, (-d2, -index))
            elif d2 < -kept[0][0] or (d2 == -kept[0][0] and index < -kept[0][1]):
                heapq.heapreplace(kept, (-d2, -index))
        return -kept[0][0] if len(kept) == k else math.inf


# Below this box width a leaf stops splitting (only exact duplicates get there).
_MIN_NODE_SIZE: Final = 1e-9


class LinearNearest:
    """The baseline: a scan of every point."""

    def __init__(self, width: float = 0.0, height: float = 0.0):
        self.xs: list[float] = []
        self.ys: list[float] = []

    def __len__(self) -> int:
        return len(self.xs)

    def add(self, x: float, y: float) -> int:
        self.xs.append(x)
        self.ys.append(y)
        return len(self.xs) - 1

    def nearest(self, x: float, y: float) -> int:
        best_index, best_d2 = -1, math.inf
        for index, (px, py) in enumerate(zip(self.xs, self.ys)):
            d2 = (px - x) * (px - x) + (py - y) * (py - y)
            if d2 < best_d2:
                best_d2, best_index = d2, index
        return best_index
