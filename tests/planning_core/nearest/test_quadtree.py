"""The quadtree's nearest neighbour equals a linear scan's, for any clustering."""

import random

import pytest

from planning_core.nearest.quadtree import LinearNearest, QuadtreeNearest
from tests.conftest import unit_sample


# The unit run keeps a clustered map without duplicates and a tight cluster with them.
@pytest.mark.parametrize("width,height,spread,duplicates", unit_sample([
    (500, 500, 0.2, False), (10, 10, 0.01, True), (10, 9, 1.0, False), (3, 300, 1.0, True),
], keep=2))
def test_matches_linear_scan(width, height, spread, duplicates):
    rng = random.Random(width * 7 + height)
    tree, scan = QuadtreeNearest(width, height), LinearNearest()
    for i in range(3000):
        if duplicates and i % 5 == 0 and i:
            x, y = tree.xs[-1], tree.ys[-1]
        else:
            x, y = rng.random() * width * spread, rng.random() * height * spread
        assert tree.add(x, y) == scan.add(x, y) == i
        if i % 3 == 0:
            qx, qy = rng.random() * width, rng.random() * height
            a, b = tree.nearest(qx, qy), scan.nearest(qx, qy)
            da = (tree.xs[a] - qx) ** 2 + (tree.ys[a] - qy) ** 2
            db = (scan.xs[b] - qx) ** 2 + (scan.ys[b] - qy) ** 2
            assert da == db
    assert len(tree) == 3000


def test_empty_structure_raises():
    with pytest.raises(ValueError):
        QuadtreeNearest(5, 5).nearest(1.0, 1.0)


# The unit run keeps the strip (its lattice has ties and duplicates too).
@pytest.mark.parametrize("width,height,spread",
                         unit_sample([(200, 20, 0.1), (4, 4, 1.0), (10, 9, 1.0)]))
def test_same_index_as_linear_scan_ties_included(width, height, spread):
    """nearest() is the fast version of LinearNearest's scan: the same index, ties
    (points and queries on a 0.5 lattice, duplicates) to the earliest, while the
    tree grows in a corridor-like strip where the points' bounds prune."""
    rng = random.Random(width + 3 * height)
    tree, scan = QuadtreeNearest(width, height, leaf_capacity=4), LinearNearest()
    for i in range(2500):
        x = round(rng.random() * width * spread * 2) / 2
        y = round(rng.random() * height * spread * 2) / 2
        tree.add(x, y)
        scan.add(x, y)
        qx, qy = round(rng.random() * width * 2) / 2, round(rng.random() * height * 2) / 2
        assert tree.nearest(qx, qy) == scan.nearest(qx, qy)
