"""Exact nearest neighbours in any :class:`~planning_core.spaces.StateSpace`.

:class:`KDTree` answers the same as :class:`LinearScan` (every point sorted by
``(space.distance(query, point), index)``), bit for bit, ties to the earliest
inserted, while points are added one at a time between queries, as a growing
planner tree does. SPEC 5.3 asks for this: the weighted-group metric, angles
wrapping, and not a linear scan.

Why it is exact: a node keeps the tight box of its points' coordinates (angles
as ``remainder(angle, 2*pi)``). Its lower bound is the metric applied to the
per-axis gaps from the query to the box, an angle's gap taken the shorter way
round the circle. Each gap is at most the matching difference as the distance
computes it, and the bound combines the gaps with the same float operations in
the same order, so the bound never exceeds a point's distance (an angle's gap
gives up a few ulps, ``slack``, for the rounding in ``b - a``). A node is
skipped only when its bound is strictly greater than the worst distance kept,
so an equal-distance point with a smaller index is never missed.

It measures with the space's metric as ``planning_core.kernels.space_metric`` gives
it (``nearest.metric.SpaceMetric``: distance, box bound, wrap). Measured with
``python -m benchmarks.bench_kdtree``.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from typing import Any, Final

from planning_core.kernels import space_metric
from planning_core.nearest.index import NearestIndex
from planning_core.nearest.metric import TAU as _METRIC_TAU
from planning_core.nearest.metric import SpaceMetric

State = tuple[float, ...]
"""As :data:`planning_core.spaces.State`; the compiled build does not follow imports into
uncompiled modules, and a type from one is ``Any`` here (every ``key[i]`` a generic look-up)."""
TAU: Final[float] = _METRIC_TAU
"""2 pi, read natively in the compiled build (a global read from the module's dict else)."""
BALANCE: Final[float] = 0.7
"""A scapegoat tree's alpha: a subtree of n points is rebuilt when an add lands deeper
than log(n) / log(1 / BALANCE) below it (about twice a balanced tree's depth)."""
_DEPTH_PER_LOG: Final[float] = 1.0 / math.log(1.0 / BALANCE)
_SPLIT_SAMPLE: Final[int] = 64
"""A split's median is of at most about this many of the bucket's values."""


class KDTree(NearestIndex):
    """A bucketed kd-tree with incremental inserts.

    A leaf holds up to ``leaf_capacity`` point indices; past that it splits at
    the median of its widest axis (width times the axis's metric weight). A subtree
    that an add finds too deep for its size is rebuilt from its points (a scapegoat
    tree's rule, ``BALANCE``), so points added in a walk stay O(log n) deep. A
    query goes depth-first, the child on the query's side of the split first;
    the other child waits on the stack with its box bound and is skipped if
    that bound exceeds the worst distance kept by then. A leaf reached on the
    query's side checks its own box before its points are scanned.
    """

    def __init__(self, space: Any, leaf_capacity: int = 8):
        if leaf_capacity < 2:
            raise ValueError("leaf_capacity must be at least 2")
        self.space = space
        self.leaf_capacity = leaf_capacity
        self._points: list[State] = []
        self._keys: list[State] = []  # the points with angles wrapped: boxes and splits use these
        # A native object in the compiled build, so that its methods are direct calls.
        self._metric: SpaceMetric = space_metric(space)
        weight: dict[int, float] = {i: w for indices, w in space.groups for i in indices}
        self._dimension: int = space.dimension
        # Only axes the metric weighs are worth splitting on. (Typed: compiled, an
        # untyped index made every key[i] and lo[i] a generic look-up.)
        self._axes: tuple[int, ...] = tuple(i for i in sorted(weight) if weight[i] > 0.0)
        self._weights: tuple[float, ...] = tuple(weight.get(i, 0.0)
                                                 for i in range(space.dimension))
        self._angles: tuple[int, ...] = tuple(i for i, v in enumerate(space.variables)
                                              if v.angle)
        self._extent = 0.0  # the largest |angle| added, for the slack
        self._slack_extent, self._slack = 0.0, angle_slack(0.0)  # the last slack and its extent
        self._root: _Node | None = None
        self._path: list[_Node] = []  # add()'s inner nodes, reused

    def __len__(self) -> int:
        return len(self._points)

    def __getitem__(self, index: int) -> State:
        return self._points[index]

    def add(self, state: Sequence[float]) -> int:
        """Insert a state; returns its index (insertion order)."""
        point = _checked(state, self._dimension)
        key, extent = self._key(point)
        if extent > self._extent:
            self._extent = extent
        index = len(self._points)
        self._points.append(point)
        self._keys.append(key)
        node = self._root
        if node is None:
            self._root = self._leaf([index])
            return index
        axes, path = self._axes, self._path
        path.clear()
        while True:
            _widen(node.lo, node.hi, key, axes)
            node.size += 1
            bucket = node.bucket
            if bucket is not None:
                break
            path.append(node)
            child = node.left if key[node.axis] < node.split else node.right
            assert child is not None  # an inner node has both children
            node = child
        bucket.append(index)
        if len(bucket) > self.leaf_capacity:
            self._split(node)
            if node.bucket is None:
                path.append(node)  # now inner, above the new point's leaf
        if path and len(path) > self._depth_limit(path[0].size):  # path[0]: the root
            self._rebalance(path)
        return index

    @staticmethod
    def _depth_limit(size: int) -> float:
        """How deep below a node of ``size`` points a leaf may lie before the node is
        rebuilt: ``log(size) / log(1 / BALANCE)``."""
        return math.log(size) * _DEPTH_PER_LOG

    def _rebalance(self, path: list[_Node]) -> None:
        """A scapegoat tree's repair (Galperin and Rivest 1993): rebuild the lowest
        node on ``path`` (the root first) that is deeper above the new point's leaf
        than :meth:`_depth_limit` of its own size allows; the root is, so one is.
        Points added in a walk (SST's best-first steps down a corridor) would otherwise
        make a chain of splits, each add and query as deep as it."""
        height = 0
        for node in reversed(path):
            height += 1
            if height > self._depth_limit(node.size):
                self._rebuild(node)
                return

    def _rebuild(self, node: _Node) -> None:
        """``node``'s subtree made anew from the points still in it (median splits,
        tight boxes), in place: its parent keeps pointing at it."""
        indices: list[int] = []
        stack = [node]
        while stack:
            below = stack.pop()
            bucket = below.bucket
            if bucket is None:
                assert below.left is not None and below.right is not None
                stack.append(below.right)
                stack.append(below.left)
            else:
                indices.extend(bucket)
        fresh = self._leaf(indices)  # never empty: it holds the point just added
        self._split(fresh)
        node.lo, node.hi, node.axis, node.split = fresh.lo, fresh.hi, fresh.axis, fresh.split
        node.left, node.right, node.bucket, node.size = (fresh.left, fresh.right,
                                                         fresh.bucket, fresh.size)

    def remove(self, index: int) -> None:
        """No query finds point ``index`` any more: it leaves its leaf's bucket, found
        by the path :meth:`add` took (boxes stay as they were: still bounds)."""
        key, node = self._keys[index], self._root
        while node is not None:
            bucket = node.bucket
            if bucket is not None:
                if index in bucket:
                    bucket.remove(index)
                    return
                break
            node = node.left if key[node.axis] < node.split else node.right
        raise ValueError(f"point {index} is not in the structure")

    def _leaf(self, indices: list[int]) -> _Node:
        """A leaf over ``indices`` with their tight box."""
        keys, axes = self._keys, self._axes
        lo, hi = list(keys[indices[0]]), list(keys[indices[0]])
        for index in indices:
            _widen(lo, hi, keys[index], axes)
        return _Node(lo, hi, indices)

    def _split(self, node: _Node) -> None:
        """Split an overfull leaf at the median of its widest weighted axis."""
        lo, hi, weights = node.lo, node.hi, self._weights
        axis, widest = -1, 0.0  # the first of the widest, as max() picks
        for i in self._axes:
            width = (hi[i] - lo[i]) * weights[i]
            if axis < 0 or width > widest:
                axis, widest = i, width
        bucket = node.bucket
        if axis < 0 or hi[axis] <= lo[axis] or bucket is None:
            return  # all points coincide on the metric axes: the leaf just grows
        keys = self._keys
        # A big bucket (a rebuild's) splits at the median of a sample: the same halves
        # near enough, without sorting every point at every level.
        step = len(bucket) // _SPLIT_SAMPLE + 1
        values = sorted([keys[i][axis] for i in bucket[::step]])
        if values[0] == values[-1] and step > 1:  # the sample all equal: every value
            values = sorted([keys[i][axis] for i in bucket])
        split = values[len(values) // 2]
        if split == values[0]:  # keep the left side non-empty: the next larger value
            split = values[bisect.bisect_right(values, split)]
        left = self._leaf([i for i in bucket if keys[i][axis] < split])
        right = self._leaf([i for i in bucket if keys[i][axis] >= split])
        node.axis, node.split, node.left, node.right, node.bucket = axis, split, left, right, None
        for child in (left, right):
            if child.bucket is not None and len(child.bucket) > self.leaf_capacity:
                self._split(child)

    def _prepare(self, query: Sequence[float]) -> tuple[State, State, float]:
        """The query, its wrapped key and the angle slack (a few ulps)."""
        q = _checked(query, self._dimension)
        if not self._angles:
            return q, q, 0.0
        key, extent = self._key(q)
        extent = max(extent, self._extent)
        if extent != self._slack_extent:
            self._slack_extent, self._slack = extent, angle_slack(extent)
        return q, key, self._slack

    def _key(self, point: State) -> tuple[State, float]:
        """The point with its angles wrapped, and its largest ``|angle|``. An angle
        within [-pi, pi] is its own ``remainder(angle, 2*pi)``: such points are
        their own key."""
        extent = 0.0
        for i in self._angles:
            if abs(point[i]) > extent:
                extent = abs(point[i])
        return (point if extent <= math.pi else self._metric.wrap(point)), extent

    def nearest(self, query: Sequence[float]) -> int:
        """Index of the nearest point; ties go to the earliest inserted.

        :meth:`k_nearest` for k = 1 (the same visits and pruning), by recursion with
        the best so far passed down and returned: a planner asks this every
        iteration, and compiled, a stack of nodes and bounds cost as much as the
        distances."""
        root = self._root
        if root is None:
            raise ValueError("nearest() on an empty structure")
        q, key, slack = self._prepare(query)
        if root.bucket is None:
            return self._nearest_below(root, q, key, slack, math.inf, -1)[1]
        return self._nearest_in_leaf(root, q, math.inf, -1)[1]

    def nearest_within(self, query: Sequence[float], radius: float) -> int:
        """:meth:`nearest` when it lies at most ``radius`` away, else -1: the same search
        with ``radius`` as the best so far from the start, so that no box farther away is
        opened (SST's witness lookup, which asks only for a witness that close)."""
        root = self._root
        if root is None:
            return -1
        q, key, slack = self._prepare(query)
        none = len(self._points)  # above every index: a point exactly ``radius`` away wins
        if root.bucket is None:
            found = self._nearest_below(root, q, key, slack, radius, none)[1]
        else:
            found = self._nearest_in_leaf(root, q, radius, none)[1]
        return -1 if found == none else found

    def cheapest_within(self, query: Sequence[float], radius: float,
                        costs: list[float]) -> int:
        """:meth:`NearestIndex.cheapest_within` in one search: a box is skipped when its
        bound exceeds both ``radius`` and the nearest distance so far, so it visits what
        :meth:`within` visits when a point lies within ``radius``, else what
        :meth:`nearest` visits."""
        root = self._root
        if root is None:
            raise ValueError("cheapest_within() on an empty structure")
        q, key, slack = self._prepare(query)
        metric, points = self._metric, self._points
        near_d, near_i = math.inf, -1
        cost, cost_d, cost_i = math.inf, math.inf, -1
        nodes, bounds = [root], [0.0]
        while nodes:
            node, b = nodes.pop(), bounds.pop()
            if b > radius and b > near_d:
                continue
            bucket = node.bucket
            if bucket is None:
                near, far = _children(node, key)
                for child in (far, near):  # the near child popped first
                    b = metric.bound(key, child.lo, child.hi, slack)
                    if not (b > radius and b > near_d):
                        nodes.append(child)
                        bounds.append(b)
                continue
            for i in bucket:
                d = metric.distance(q, points[i])
                if d < near_d or (d == near_d and i < near_i):
                    near_d, near_i = d, i
                if d <= radius:
                    c = costs[i]
                    if c < cost or (c == cost and (d < cost_d or (d == cost_d and i < cost_i))):
                        cost, cost_d, cost_i = c, d, i
        return cost_i if cost_i >= 0 else near_i

    def _nearest_below(self, node: _Node, q: State, key: State, slack: float,
                       best: float, best_i: int) -> tuple[float, int]:
        """The best of ``(best, best_i)`` and an inner node's points: the child on the
        query's side first (a leaf there only when its box may hold a better point),
        then the other when its box's bound is at most the best by then."""
        near, far = _children(node, key)
        far_bound = self._metric.bound(key, far.lo, far.hi, slack)
        if near.bucket is None:
            best, best_i = self._nearest_below(near, q, key, slack, best, best_i)
        elif not self._metric.bound(key, near.lo, near.hi, slack) > best:
            best, best_i = self._nearest_in_leaf(near, q, best, best_i)
        if far_bound > best:
            return best, best_i
        if far.bucket is None:
            return self._nearest_below(far, q, key, slack, best, best_i)
        return self._nearest_in_leaf(far, q, best, best_i)

    def _nearest_in_leaf(self, leaf: _Node, q: State, best: float,
                         best_i: int) -> tuple[float, int]:
        metric, points = self._metric, self._points
        bucket = leaf.bucket
        assert bucket is not None
        for i in bucket:
            d = metric.distance(q, points[i])
            if d < best or (d == best and i < best_i):
                best, best_i = d, i
        return best, best_i

    def k_nearest(self, query: Sequence[float], k: int) -> list[int]:
        """Indices of the ``k`` nearest points, nearest first (ties: smaller index
        first); all points when there are fewer than ``k``."""
        if k <= 0 or self._root is None:
            return []
        import heapq  # here, not at the top: most runs never ask (start-up, docs/hot-paths.md)
        q, key, slack = self._prepare(query)
        metric, points = self._metric, self._points
        # Max-heap of the k best as (-d, -index): the top is the worst kept.
        kept: list[tuple[float, int]] = []
        worst = math.inf
        nodes, bounds = [self._root], [-1.0]
        while nodes:
            node, b = nodes.pop(), bounds.pop()
            if b > worst:
                continue
            bucket = node.bucket
            if bucket is not None:
                if b < 0.0 and metric.bound(key, node.lo, node.hi, slack) > worst:
                    continue
                for i in bucket:
                    d = metric.distance(q, points[i])
                    if len(kept) < k:
                        heapq.heappush(kept, (-d, -i))
                        if len(kept) == k:
                            worst = -kept[0][0]
                    elif d < worst or (d == worst and i < -kept[0][1]):
                        heapq.heapreplace(kept, (-d, -i))
                        worst = -kept[0][0]
                continue
            near, far = _children(node, key)
            b = metric.bound(key, far.lo, far.hi, slack)
            if b <= worst:
                nodes.append(far)
                bounds.append(b)
            nodes.append(near)
            bounds.append(-1.0)
        kept.sort(reverse=True)
        return [-negated for _, negated in kept]

    def within(self, query: Sequence[float], radius: float) -> list[int]:
        """Indices of the points at distance <= ``radius``, sorted by
        (distance, index)."""
        if not radius >= 0.0:
            raise ValueError(f"radius must be a number >= 0, got {radius!r}")
        if self._root is None:
            return []
        q, key, slack = self._prepare(query)
        metric, points = self._metric, self._points
        found: list[tuple[float, int]] = []
        nodes = [self._root]
        while nodes:
            node = nodes.pop()
            if metric.bound(key, node.lo, node.hi, slack) > radius:
                continue
            bucket = node.bucket
            if bucket is None:
                nodes.extend(_children(node, key)[::-1])
                continue
            for i in bucket:
                d = metric.distance(q, points[i])
                if d <= radius:
                    found.append((d, i))
        found.sort()
        return [i for _, i in found]


class _Node:
    """A kd-tree node: the tight box ``[lo, hi]`` of its points' keys; a leaf
    holds their indices in ``bucket``, an inner node splits at ``split`` on
    ``axis`` (keys below it go ``left``) and has ``bucket = None``."""

    __slots__ = ("lo", "hi", "axis", "split", "left", "right", "bucket", "size")

    def __init__(self, lo: list[float], hi: list[float], bucket: list[int] | None) -> None:
        self.lo = lo
        self.hi = hi
        self.size: int = 0 if bucket is None else len(bucket)
        """Points added below since the node was made (removed ones too): balance."""
        self.axis = -1
        self.split = 0.0
        self.left: _Node | None = None
        self.right: _Node | None = None
        self.bucket = bucket


def _widen(lo: list[float], hi: list[float], key: State, axes: tuple[int, ...]) -> None:
    """The box ``[lo, hi]`` widened on ``axes`` to hold ``key``."""
    for i in axes:
        v = key[i]
        if v < lo[i]:
            lo[i] = v
        elif v > hi[i]:
            hi[i] = v


def _children(node: _Node, key: State) -> tuple[_Node, _Node]:
    """An inner node's children, the one on ``key``'s side of the split first."""
    left, right = node.left, node.right
    assert left is not None and right is not None
    return (left, right) if key[node.axis] < node.split else (right, left)


class LinearScan:
    """The baseline: every point's distance, the same interface and answers."""

    def __init__(self, space: Any):
        self.space = space
        self._points: list[State] = []
        self._distance = space.distance

    def __len__(self) -> int:
        return len(self._points)

    def __getitem__(self, index: int) -> State:
        return self._points[index]

    def add(self, state: Sequence[float]) -> int:
        self._points.append(_checked(state, self.space.dimension))
        return len(self._points) - 1

    def _distances(self, query: Sequence[float]) -> list[float]:
        q = _checked(query, self.space.dimension)
        dist = self._distance
        return [dist(q, p) for p in self._points]

    def nearest(self, query: Sequence[float]) -> int:
        if not self._points:
            raise ValueError("nearest() on an empty structure")
        distances = self._distances(query)
        return distances.index(min(distances))  # the first of equals: the smallest index

    def k_nearest(self, query: Sequence[float], k: int) -> list[int]:
        if k <= 0:
            return []
        import heapq  # as in KDTree.k_nearest
        ranked = heapq.nsmallest(k, zip(self._distances(query), range(len(self._points))))
        return [i for _, i in ranked]

    def within(self, query: Sequence[float], radius: float) -> list[int]:
        if not radius >= 0.0:
            raise ValueError(f"radius must be a number >= 0, got {radius!r}")
        found = sorted((d, i) for i, d in enumerate(self._distances(query)) if d <= radius)
        return [i for _, i in found]


def angle_slack(extent: float) -> float:
    """What an angle's gap gives up for rounding, angles up to ``extent`` in size.

    The distance rounds ``b - a`` (at most half an ulp of ``|a| + |b|``), the
    gap rounds one or two sums near 2*pi; eight ulps of the largest covers both.
    """
    return 8.0 * math.ulp(2.0 * extent + 2.0 * TAU)


def _checked(state: Sequence[float], dimension: int) -> State:
    """``state`` as a tuple, or ValueError if its length is wrong or a value is not finite."""
    point = tuple(state)
    if len(point) != dimension:
        raise ValueError(f"a state of {len(point)} values in a {dimension}-D space")
    for v in point:
        if math.isinf(v) or math.isnan(v):  # (isfinite is a generic call compiled)
            raise ValueError(f"a state with a non-finite value: {point!r}")
    return point
