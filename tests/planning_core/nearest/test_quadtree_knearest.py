"""QuadtreeNearest.k_nearest equals a brute-force scan: every point sorted by
(squared distance, insertion index), the first k kept."""

import math
import random

import pytest

from planning_core.nearest.quadtree import QuadtreeNearest


def brute_force(xs, ys, x, y, k):
    order = sorted(range(len(xs)), key=lambda i: ((xs[i] - x) ** 2 + (ys[i] - y) ** 2, i))
    return order[:max(k, 0)]


@pytest.mark.parametrize("width,height,spread,duplicates", [
    (10, 9, 1.0, False), (300, 300, 0.05, False), (4, 200, 1.0, True), (10, 10, 0.01, True),
])
def test_k_nearest_matches_brute_force(width, height, spread, duplicates):
    rng = random.Random(width * 31 + height)
    tree = QuadtreeNearest(width, height)
    for i in range(1500):
        if duplicates and i % 4 == 0 and i:
            x, y = tree.xs[rng.randrange(i)], tree.ys[rng.randrange(i)]
        else:
            x, y = rng.random() * width * spread, rng.random() * height * spread
        tree.add(x, y)
        if i % 25 == 0:
            qx, qy = rng.random() * width, rng.random() * height
            for k in (1, 3, 10, 40):
                assert tree.k_nearest(qx, qy, k) == brute_force(tree.xs, tree.ys, qx, qy, k)


def test_ties_go_to_the_earliest_inserted():
    tree = QuadtreeNearest(10, 10)
    for x, y in [(1.0, 1.0), (3.0, 1.0), (2.0, 2.0), (2.0, 0.0), (1.0, 1.0)]:
        tree.add(x, y)
    # (2, 1) is exactly 1 from the first four; index 4 duplicates index 0.
    assert tree.k_nearest(2.0, 1.0, 3) == [0, 1, 2]
    assert tree.k_nearest(2.0, 1.0, 5) == [0, 1, 2, 3, 4]


def test_small_or_empty_structures():
    tree = QuadtreeNearest(5, 5)
    assert tree.k_nearest(1.0, 1.0, 3) == []
    tree.add(4.0, 4.0)
    tree.add(1.0, 1.0)
    assert tree.k_nearest(0.0, 0.0, 10) == [1, 0]
    assert tree.k_nearest(0.0, 0.0, 0) == []
    assert tree.nearest(0.0, 0.0) == 1  # nearest() is unchanged by the new method


def test_within_and_remove_match_brute_force():
    """``within`` keeps (squared distance, index) order and its boundary; a removed
    point is found by no query (SST takes replaced nodes out this way)."""
    rng = random.Random(5)
    tree = QuadtreeNearest(20, 20)
    removed = set()
    for i in range(1200):
        tree.add(rng.random() * 20 * (0.1 if i % 3 else 1.0), rng.random() * 20)
        if i % 3 == 1:
            gone = rng.randrange(i + 1)
            if gone not in removed:
                tree.remove(gone)
                removed.add(gone)
        if i % 20 == 0:
            qx, qy = rng.random() * 20, rng.random() * 20
            alive = [k for k in brute_force(tree.xs, tree.ys, qx, qy, len(tree.xs))
                     if k not in removed]
            if alive:
                assert tree.nearest(qx, qy) == alive[0]
            assert tree.k_nearest(qx, qy, 7) == alive[:7]
            d2 = [(tree.xs[k] - qx) ** 2 + (tree.ys[k] - qy) ** 2 for k in alive]
            radius = math.sqrt(d2[min(len(d2) - 1, rng.randrange(30))]) if d2 else 1.0
            inside = [k for k, d in zip(alive, d2) if d <= radius * radius]
            assert tree.within(qx, qy, radius) == inside
            if alive:  # few cost values: ties go to the nearer, then the earlier
                costs = [float(rng.randrange(3)) for _ in tree.xs]
                assert tree.cheapest_within(qx, qy, radius, costs) == (
                    min(inside, key=costs.__getitem__) if inside else alive[0])
                assert tree.cheapest_within(qx, qy, 0.0, costs) == alive[0]
    with pytest.raises(ValueError):
        tree.remove(next(iter(removed)))
    with pytest.raises(ValueError):
        tree.within(1.0, 1.0, -1.0)
