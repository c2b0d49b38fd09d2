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
    (0 bottom-left, 1 bottom-right, 2 top-left, 3 top-right of its centre).
    ``bx0``..``by1`` bound the points inserted under it (empty: +inf..-inf), far
    tighter than the box where a tree fills a corridor, so queries prune by them."""

    __slots__ = ("x0", "y0", "x1", "y1", "cx", "cy", "bx0", "by0", "bx1", "by1",
                 "children", "indices")

    def __init__(self, x0: float, y0: float, x1: float, y1: float) -> None:
        self.x0, self.y0, self.x1, self.y1 = x0, y0, x1, y1
        self.cx, self.cy = (x0 + x1) * 0.5, (y0 + y1) * 0.5
        self.bx0, self.by0, self.bx1, self.by1 = math.inf, math.inf, -math.inf, -math.inf
        self.children: list[_Node] | None = None
        self.indices: list[int] = []

    def quadrant(self, x: float, y: float) -> int:
        return (1 if x >= self.cx else 0) + (2 if y >= self.cy else 0)

    def cover(self, x: float, y: float) -> None:
        """Grow the points' bounds to hold (x, y)."""
        if x < self.bx0:
            self.bx0 = x
        if x > self.bx1:
            self.bx1 = x
        if y < self.by0:
            self.by0 = y
        if y > self.by1:
            self.by1 = y


def _gap2(node: _Node, x: float, y: float) -> float:
    """Squared distance from (x, y) to the bounds of the node's points (0 inside;
    a lower bound of the distance to each of them)."""
    gx = node.bx0 - x if x < node.bx0 else (x - node.bx1 if x > node.bx1 else 0.0)
    gy = node.by0 - y if y < node.by0 else (y - node.by1 if y > node.by1 else 0.0)
    return gx * gx + gy * gy


def _push(stack: list[_Node], top: int, node: _Node, x: float, y: float,
          bound: float) -> int:
    """Put ``node`` at ``stack[top]`` unless nothing there can be within ``bound``
    (an empty leaf, or a box farther than that squared distance); the new top.
    The list only grows: no pop shrinks and regrows it."""
    if (node.children is None and not node.indices) or _gap2(node, x, y) > bound:
        return top
    if top == len(stack):
        stack.append(node)
    else:
        stack[top] = node
    return top + 1


def _push_children(stack: list[_Node], top: int, node: _Node, x: float, y: float,
                   bound: float) -> int:
    """:func:`_push` ``node``'s four children, the quadrant of (x, y) last so that it
    pops first; the new top."""
    children = node.children
    assert children is not None
    q = (1 if x >= node.cx else 0) + (2 if y >= node.cy else 0)  # node.quadrant, inline
    top = _push(stack, top, children[3 - q], x, y, bound)
    top = _push(stack, top, children[q ^ 1], x, y, bound)
    top = _push(stack, top, children[q ^ 2], x, y, bound)
    return _push(stack, top, children[q], x, y, bound)


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
        self._stack: list[_Node] = [self.root]  # nearest()'s, reused; only grows

    def __len__(self) -> int:
        return len(self.xs)

    def add(self, x: float, y: float) -> int:
        """Insert a point; returns its index (insertion order)."""
        index = len(self.xs)
        self.xs.append(x)
        self.ys.append(y)
        node = self.root
        node.cover(x, y)
        children = node.children
        while children is not None:
            node = children[node.quadrant(x, y)]
            node.cover(x, y)
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
            child = children[node.quadrant(xs[index], ys[index])]
            child.indices.append(index)
            child.cover(xs[index], ys[index])
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
            if _gap2(node, x, y) > bound:
                continue
            children = node.children
            if children is None:
                if node.indices:
                    bound = keep.scan(node.indices)
                continue
            top = _push_children(stack, top, node, x, y, bound)

    def nearest(self, x: float, y: float) -> int:
        """Index of the point closest to (x, y); ties go to the earliest inserted.

        The planners' hot query, so :meth:`_search` specialised: the leaves read
        inline, a stack kept between queries, and a child pushed only if its box
        is within the best distance found so far (:class:`LinearNearest` is the
        reference it must equal)."""
        xs, ys = self.xs, self.ys
        if not xs:
            raise ValueError("nearest() on an empty structure")
        stack = self._stack
        stack[0] = self.root
        top = 1
        best_d2, best_index = math.inf, -1
        while top:
            top -= 1
            node = stack[top]
            if _gap2(node, x, y) > best_d2:
                continue
            children = node.children
            if children is None:
                for index in node.indices:
                    ddx = xs[index] - x
                    ddy = ys[index] - y
                    d2 = ddx * ddx + ddy * ddy
                    if d2 < best_d2 or (d2 == best_d2 and index < best_index):
                        best_d2, best_index = d2, index
                continue
            top = _push_children(stack, top, node, x, y, best_d2)
        return best_index

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

    def cheapest_within(self, x: float, y: float, radius: float, costs: list[float]) -> int:
        """Of the points within ``radius`` of (x, y) (by squared distance, as
        :meth:`within`), the one of least ``costs[i]`` (ties: the nearer, then the earliest
        inserted); none there, :meth:`nearest`. One walk, pruned by ``radius`` or by the
        nearest distance so far, whichever is larger (SST's best-near selection)."""
        if not self.xs:
            raise ValueError("cheapest_within() on an empty structure")
        found = _Cheapest(self.xs, self.ys, x, y, radius * radius, costs)
        self._search(x, y, found)
        return found.cost_index if found.cost_index >= 0 else found.near_index

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


class _Cheapest(_Scan):
    """The cheapest point within a squared distance, and the nearest point."""

    def __init__(self, xs: list[float], ys: list[float], x: float, y: float,
                 limit: float, costs: list[float]) -> None:
        self.xs, self.ys, self.x, self.y, self.limit, self.costs = xs, ys, x, y, limit, costs
        self.near_d2, self.near_index = math.inf, -1
        self.cost, self.cost_d2, self.cost_index = math.inf, math.inf, -1

    def scan(self, indices: list[int]) -> float:
        xs, ys, x, y, limit, costs = self.xs, self.ys, self.x, self.y, self.limit, self.costs
        near_d2, near_index = self.near_d2, self.near_index
        cost, cost_d2, cost_index = self.cost, self.cost_d2, self.cost_index
        for index in indices:
            ddx = xs[index] - x
            ddy = ys[index] - y
            d2 = ddx * ddx + ddy * ddy
            if d2 < near_d2 or (d2 == near_d2 and index < near_index):
                near_d2, near_index = d2, index
            if d2 <= limit:
                c = costs[index]
                if c < cost or (c == cost and (d2 < cost_d2 or (d2 == cost_d2
                                                               and index < cost_index))):
                    cost, cost_d2, cost_index = c, d2, index
        self.near_d2, self.near_index = near_d2, near_index
        self.cost, self.cost_d2, self.cost_index = cost, cost_d2, cost_index
        return near_d2 if near_d2 > limit else limit


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
