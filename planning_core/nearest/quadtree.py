"""Nearest-neighbour search over 2-D positions for growing trees.

:class:`QuadtreeNearest` is what the planners use; :class:`LinearNearest` is
the plain scan it is measured against (``benchmarks/bench_nearest.py``). A
uniform bucket grid was tried first and dropped: spaceship trees cluster
tightly, and a grid fine enough for the clusters made far queries walk
thousands of empty buckets.
"""

from __future__ import annotations

import heapq
import math



class QuadtreeNearest:
    """A bucketed point-region quadtree over the map's rectangle.

    Leaves hold up to ``leaf_capacity`` point indices and split into four when
    they overflow. A query descends depth-first, nearest child first, and skips
    every node whose box is farther than the best point found so far, so its
    cost grows with the tree's depth, not its size, whatever the clustering.
    """

    def __init__(self, width: float, height: float, leaf_capacity: int = 12):
        self.xs: list[float] = []
        self.ys: list[float] = []
        self.leaf_capacity = leaf_capacity
        # A node is a list: [x0, y0, x1, y1, children | None, indices | None].
        self.root: list = [0.0, 0.0, float(width), float(height), None, []]

    def __len__(self) -> int:
        return len(self.xs)

    def add(self, x: float, y: float) -> int:
        """Insert a point; returns its index (insertion order)."""
        index = len(self.xs)
        self.xs.append(x)
        self.ys.append(y)
        node = self.root
        while node[4] is not None:
            node = node[4][_quadrant(node, x, y)]
        node[5].append(index)
        if len(node[5]) > self.leaf_capacity and node[2] - node[0] > _MIN_NODE_SIZE:
            self._split(node)
        return index

    def _split(self, node: list) -> None:
        x0, y0, x1, y1 = node[0], node[1], node[2], node[3]
        cx, cy = (x0 + x1) * 0.5, (y0 + y1) * 0.5
        node[4] = [[x0, y0, cx, cy, None, []], [cx, y0, x1, cy, None, []],
                   [x0, cy, cx, y1, None, []], [cx, cy, x1, y1, None, []]]
        indices, node[5] = node[5], None
        xs, ys = self.xs, self.ys
        for index in indices:
            child = node[4][_quadrant(node, xs[index], ys[index])]
            child[5].append(index)
        for child in node[4]:
            # All points may land in one quadrant (duplicates, tight clusters).
            if len(child[5]) > self.leaf_capacity and child[2] - child[0] > _MIN_NODE_SIZE:
                self._split(child)

    def _search(self, x: float, y: float, visit) -> None:
        """Walk the leaves that may hold a point closer than the bound, nearest
        quadrant first: ``visit(indices)`` scans a leaf and returns the bound
        (squared distance) to prune by from then on."""
        bound = math.inf
        stack = [self.root]
        pop, push = stack.pop, stack.append
        while stack:
            node = pop()
            # Squared distance from the query to the node's box.
            gx = node[0] - x if x < node[0] else (x - node[2] if x > node[2] else 0.0)
            gy = node[1] - y if y < node[1] else (y - node[3] if y > node[3] else 0.0)
            if gx * gx + gy * gy > bound:
                continue
            children = node[4]
            if children is None:
                bound = visit(node[5])
                continue
            # Push the far quadrants first so the query's own quadrant pops first.
            q = _quadrant(node, x, y)
            push(children[3 - q])
            push(children[q ^ 1])
            push(children[q ^ 2])
            push(children[q])

    def nearest(self, x: float, y: float) -> int:
        """Index of the point closest to (x, y); ties go to the earliest inserted."""
        if not self.xs:
            raise ValueError("nearest() on an empty structure")
        xs, ys = self.xs, self.ys
        best = [math.inf, -1]  # squared distance, index

        def visit(indices: list[int]) -> float:
            best_d2, best_index = best
            for index in indices:
                ddx = xs[index] - x
                ddy = ys[index] - y
                d2 = ddx * ddx + ddy * ddy
                if d2 < best_d2 or (d2 == best_d2 and index < best_index):
                    best_d2, best_index = d2, index
            best[0], best[1] = best_d2, best_index
            return best_d2

        self._search(x, y, visit)
        return best[1]

    def k_nearest(self, x: float, y: float, k: int) -> list[int]:
        """Indices of the ``k`` points closest to (x, y), nearest first.

        Ties are broken by insertion order, so the answer equals sorting every
        point by ``(squared distance, index)`` and keeping the first ``k``.
        Fewer than ``k`` points: all of them.
        """
        if k <= 0:
            return []
        xs, ys = self.xs, self.ys
        # Max-heap of the k best so far, as (-d2, -index): the top is the worst kept.
        kept: list[tuple[float, int]] = []

        def visit(indices: list[int]) -> float:
            for index in indices:
                ddx = xs[index] - x
                ddy = ys[index] - y
                d2 = ddx * ddx + ddy * ddy
                if len(kept) < k:
                    heapq.heappush(kept, (-d2, -index))
                elif d2 < -kept[0][0] or (d2 == -kept[0][0] and index < -kept[0][1]):
                    heapq.heapreplace(kept, (-d2, -index))
            return -kept[0][0] if len(kept) == k else math.inf

        self._search(x, y, visit)
        kept.sort(reverse=True)
        return [-negated_index for _, negated_index in kept]


# Below this box width a leaf stops splitting (only exact duplicates get there).
_MIN_NODE_SIZE = 1e-9


def _quadrant(node: list, x: float, y: float) -> int:
    """0 bottom-left, 1 bottom-right, 2 top-left, 3 top-right of the node's centre."""
    return (x >= (node[0] + node[2]) * 0.5) + 2 * (y >= (node[1] + node[3]) * 0.5)


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
