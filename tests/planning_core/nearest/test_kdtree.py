"""The kd-tree answers exactly as a linear scan sorting by (distance, index).

The oracle here is that definition written out; ``LinearScan`` is checked
against it too. Points and queries mix uniform samples, RRT-like clusters,
duplicates, lattice points (many equal distances) and angles at, near and
beyond +-pi.
"""

import heapq
import math
import random

import pytest

from planning_core import kernels
from planning_core.nearest import kdtree
from planning_core.nearest.index import NearestIndex
from planning_core.nearest.kdtree import KDTree, LinearScan, angle_slack
from planning_core.nearest.metric import SpaceMetric
from planning_core.spaces import StateSpace, Variable
from tests.conftest import unit_sample

PI = math.pi


def r2():
    return StateSpace.real_vector(("x", "y"), (0, 0), (10, 10))


def se2():
    variables = (Variable("x", 0, 10), Variable("y", 0, 10), Variable("theta", angle=True))
    return StateSpace.from_metric(variables, [("x,y", 0.7), ("theta", 0.3)])


def trailer():
    """5-D, two angles sharing a group."""
    variables = (Variable("x", 0, 10), Variable("y", 0, 10), Variable("theta", angle=True),
                 Variable("psi", angle=True), Variable("v", -2, 2))
    return StateSpace.from_metric(variables, [("x,y", 1.0), ("theta,psi", 0.5), ("v", 0.3)])


def unicycle():
    """SPEC 5.2's default metric: v and omega weigh nothing."""
    variables = (Variable("x", 0, 10), Variable("y", 0, 10), Variable("theta", angle=True),
                 Variable("v", -5, 5), Variable("omega", -PI / 2, PI / 2))
    return StateSpace.from_metric(variables, [("x,y", 1.0), ("theta", 0.5)])


SPACES = {"R2": r2, "SE2": se2, "trailer5": trailer, "unicycle5": unicycle}

_SEAM = (PI, -PI, math.nextafter(PI, 0), math.nextafter(-PI, 0), 3 * PI, -3 * PI,
         PI - 1e-9, -PI + 1e-9, PI + 1e-9, 0.0, PI / 2, -PI / 2)


def make_state(space, rng, earlier):
    """A state of one of several kinds, chosen at random."""
    kind = rng.random()
    if earlier and kind < 0.08:
        return rng.choice(earlier)                        # an exact duplicate
    if earlier and kind < 0.35:                           # RRT-like: a small step from a point
        base = rng.choice(earlier)
        step = [rng.gauss(0, 0.05) for _ in base]
        return tuple(b + s for b, s in zip(base, step))
    state = list(space.sample_uniform(rng))
    if kind < 0.5:                                        # a lattice point: equal distances
        state = [float(round(v)) for v in state]
    for i, v in enumerate(space.variables):
        if v.angle and rng.random() < 0.4:
            state[i] = rng.choice(_SEAM) + (rng.gauss(0, 1e-3) if rng.random() < 0.5 else 0.0)
            if rng.random() < 0.2:
                state[i] += 2 * PI * rng.choice((-2, -1, 1, 2))   # an unwrapped turn
    return tuple(state)


def ranked(space, points, query):
    """The definition: every point as (distance, index); sorting ranks them."""
    return [(space.distance(query, p), i) for i, p in enumerate(points)]


def compare(space, n_points, n_queries, leaf_capacity, seed, scan_every=1):
    """Grow both structures point by point, querying in between."""
    rng = random.Random(seed)
    tree, scan = KDTree(space, leaf_capacity), LinearScan(space)
    points: list = []
    costs: list[float] = []  # few values: equal costs, ties broken by distance and index
    per_point = n_queries / n_points
    owed = 0.0
    for n in range(n_points):
        p = make_state(space, rng, points)
        points.append(p)
        costs.append(float(rng.randrange(4)))
        assert tree.add(p) == scan.add(p) == n
        owed += per_point
        while owed >= 1.0:
            owed -= 1.0
            q = make_state(space, rng, points)
            pairs = ranked(space, points, q)
            first = [i for _, i in heapq.nsmallest(20, pairs)]
            # Radius: often exactly some point's distance (the boundary is inclusive).
            radius = pairs[first[min(len(first) - 1, rng.randrange(12))]][0]
            if rng.random() < 0.3:
                radius *= rng.uniform(0.5, 2.0)
            inside = [i for _, i in sorted(pair for pair in pairs if pair[0] <= radius)]
            checked = [tree] + ([scan] if n % scan_every == 0 else [])
            for structure in checked:
                assert structure.nearest(q) == first[0], (n, q)
                for k in (1, 5, 20):
                    assert structure.k_nearest(q, k) == first[:k], (n, q, k)
                assert structure.within(q, radius) == inside, (n, q, radius)
            assert tree.nearest_within(q, radius) == (inside[0] if inside else -1)
            cheapest = min(inside, key=costs.__getitem__) if inside else first[0]
            assert tree.cheapest_within(q, radius, costs) == cheapest, (n, q, radius)
            assert NearestIndex.cheapest_within(tree, q, radius, costs) == cheapest
    assert len(tree) == len(scan) == n_points
    return tree


# The unit run compares each space once, with leaf capacities 2 and 8 in turn; CI both.
SPACE_LEAVES = [(name, (2, 8)[k % 2]) for k, name in enumerate(sorted(SPACES))]
SPACE_LEAVES += [(name, 10 - leaf) for name, leaf in SPACE_LEAVES]


@pytest.mark.parametrize("name, leaf_capacity", unit_sample(
    [pytest.param(name, leaf, id=f"{leaf}-{name}") for name, leaf in SPACE_LEAVES],
    keep=len(SPACES)))
def test_equals_linear_scan(name, leaf_capacity):
    compare(SPACES[name](), n_points=400, n_queries=250, leaf_capacity=leaf_capacity,
            seed=len(name) * 10 + leaf_capacity, scan_every=3)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["R2", "SE2", "trailer5"])
@pytest.mark.parametrize("leaf_capacity", [3, 8])
def test_equals_linear_scan_10000_queries(name, leaf_capacity):
    compare(SPACES[name](), n_points=1000, n_queries=10_000, leaf_capacity=leaf_capacity,
            seed=7 + leaf_capacity, scan_every=10)


def test_lattice_ties_go_to_the_earliest():
    space = r2()
    tree = KDTree(space, leaf_capacity=2)
    for x, y in [(1, 1), (0, 0), (1, 0), (0, 1), (0, 0), (1, 1)]:
        tree.add((float(x), float(y)))
    centre = (0.5, 0.5)
    assert tree.nearest(centre) == 0
    assert tree.k_nearest(centre, 6) == [0, 1, 2, 3, 4, 5]
    assert tree.k_nearest((0.0, 0.0), 3) == [1, 4, 2]
    assert tree.within((0.0, 0.0), 1.0) == [1, 4, 2, 3]


def test_wraps_across_the_seam():
    space = se2()
    tree = KDTree(space, leaf_capacity=2)
    for theta in (0.0, 3.0, -2.0, 1.0, -3.1):
        tree.add((5.0, 5.0, theta))
    assert tree.nearest((5.0, 5.0, PI)) == 4          # -3.1 is 0.04 away over the seam
    assert tree.nearest((5.0, 5.0, 3.0 + 2 * PI)) == 1
    assert tree.k_nearest((5.0, 5.0, -PI), 2) == [4, 1]


def test_large_unwrapped_angles_stay_exact():
    space = se2()
    rng = random.Random(11)
    tree, scan = KDTree(space, 4), LinearScan(space)
    for _ in range(300):
        p = (rng.uniform(0, 10), rng.uniform(0, 10), rng.uniform(-1e7, 1e7))
        tree.add(p)
        scan.add(p)
    for _ in range(300):
        q = (rng.uniform(0, 10), rng.uniform(0, 10), rng.uniform(-1e7, 1e7))
        assert tree.k_nearest(q, 5) == scan.k_nearest(q, 5)


def test_the_spaces_here_measure_with_generated_metrics_and_the_reference():
    measured = {name: type(kernels.space_metric(SPACES[name]())) for name in SPACES}
    assert measured["R2"] is measured["trailer5"] is SpaceMetric   # shapes of no system
    assert measured["SE2"].__module__ == measured["unicycle5"].__module__ == kernels.GENERATED


@pytest.mark.parametrize("name", ["SE2", "unicycle5"])
def test_equals_linear_scan_measuring_with_the_reference_metric(name, monkeypatch):
    monkeypatch.setattr(kdtree, "space_metric", SpaceMetric)
    compare(SPACES[name](), n_points=300, n_queries=300, leaf_capacity=8, seed=len(name),
            scan_every=3)


def test_box_bound_never_exceeds_a_distance_inside():
    rng = random.Random(4)
    for space in (se2(), trailer()):
        bounds = (kernels.space_metric(space).bound, SpaceMetric(space).bound)
        for _ in range(3000):
            points = [space.wrap(make_state(space, rng, [])) for _ in range(rng.randint(1, 4))]
            lo = [min(c) for c in zip(*points)]
            hi = [max(c) for c in zip(*points)]
            q = make_state(space, rng, [])
            extent = max(abs(v) for v in q + tuple(c for p in points for c in p))
            for bound in bounds:
                b = bound(space.wrap(q), lo, hi, angle_slack(extent))
                assert all(b <= space.distance(q, p) for p in points)


def test_edges():
    space = se2()
    for structure in (KDTree(space), LinearScan(space)):
        with pytest.raises(ValueError):
            structure.nearest((0.0, 0.0, 0.0))
        assert structure.k_nearest((0.0, 0.0, 0.0), 3) == []
        assert structure.within((0.0, 0.0, 0.0), 1.0) == []
        with pytest.raises(ValueError):
            structure.add((0.0, 0.0))
        with pytest.raises(ValueError):
            structure.add((0.0, math.nan, 0.0))
        assert structure.add([1.0, 2.0, 3.0]) == 0
        assert structure[0] == (1.0, 2.0, 3.0)
        assert structure.k_nearest((0.0, 0.0, 0.0), 0) == []
        assert structure.k_nearest((0.0, 0.0, 0.0), 5) == [0]
        assert structure.within((0.0, 0.0, 0.0), math.inf) == [0]
        with pytest.raises(ValueError):
            structure.within((0.0, 0.0, 0.0), -1.0)
        with pytest.raises(ValueError):
            structure.nearest((0.0, 0.0, math.inf))


def test_all_duplicates_do_not_split_forever():
    space = trailer()
    tree = KDTree(space, leaf_capacity=2)
    for _ in range(200):
        tree.add((1.0, 2.0, PI, -PI, 0.5))
    assert tree.nearest((0.0, 0.0, 0.0, 0.0, 0.0)) == 0
    assert tree.within((1.0, 2.0, -PI, PI, 0.5), 0.0) == list(range(200))


def _queries_answer_as_defined(tree, space, points, removed, rng):
    """One random query of each kind answers as the definition over the points left."""
    q = make_state(space, rng, points)
    left = sorted(pair for pair in ranked(space, points, q) if pair[1] not in removed)
    if left:
        assert tree.nearest(q) == left[0][1]
    assert tree.k_nearest(q, 6) == [i for _, i in left[:6]]
    radius = left[min(len(left) - 1, rng.randrange(15))][0] if left else 1.0
    assert tree.within(q, radius) == [i for d, i in left if d <= radius]
    assert tree.nearest_within(q, radius) == (left[0][1] if left and left[0][0] <= radius
                                              else -1)
    if left:
        costs = [float(i % 3) for i in range(len(points))]
        inside = [i for d, i in left if d <= radius]
        assert tree.cheapest_within(q, radius, costs) == (
            min(inside, key=costs.__getitem__) if inside else left[0][1])


@pytest.mark.parametrize("name", sorted(SPACES))
def test_removed_points_are_found_by_no_query(name):
    """After ``remove``, every query answers as the definition over the points left."""
    space, rng = SPACES[name](), random.Random(len(name))
    tree, points, removed = KDTree(space, 4), [], set()
    for n in range(500):
        points.append(make_state(space, rng, points))
        tree.add(points[-1])
        if n % 2 and rng.random() < 0.8:
            gone = rng.randrange(n + 1)
            if gone not in removed:
                tree.remove(gone)
                removed.add(gone)
        if n % 10 == 0:
            _queries_answer_as_defined(tree, space, points, removed, rng)
    with pytest.raises(ValueError):
        tree.remove(next(iter(removed)))


def _depth(node) -> int:
    if node.bucket is not None:
        return 0
    return 1 + max(_depth(node.left), _depth(node.right))


@pytest.mark.parametrize("name", ["R2", "trailer5"])
def test_a_walk_of_inserts_stays_shallow_and_exact(name):
    """Points added along a walk (as SST's best-first steps down a corridor) would
    make a chain of splits; the tree rebuilds an unbalanced subtree, so its depth stays
    within the scapegoat bound, and every query still answers as the definition, with
    points removed on the way."""
    space, rng = SPACES[name](), random.Random(3)
    tree, points, removed = KDTree(space, 2), [], set()
    base = list(space.sample_uniform(rng))
    for n in range(900):
        row, step = divmod(n, 60)
        base[0], base[1] = (step if row % 2 == 0 else 59 - step) / 6.0, row / 1.5
        points.append(tuple(base))
        tree.add(points[-1])
        assert _depth(tree._root) <= math.log(n + 1) / math.log(1 / kdtree.BALANCE) + 1
        if n > 40 and n % 3:
            for gone in range(n - 40, n - 38):
                if gone not in removed:
                    tree.remove(gone)
                    removed.add(gone)
        if n % 25 == 0:
            _queries_answer_as_defined(tree, space, points, removed, rng)


def test_maximum_extent_is_the_largest_distance_within_the_bounds():
    space = se2()  # 0.7 * hypot(10, 10) + 0.3 * pi
    assert space.maximum_extent() == pytest.approx(0.7 * math.hypot(10, 10) + 0.3 * PI)
    corners = [(0.0, 0.0, 0.0), (10.0, 10.0, PI)]
    assert space.distance(*corners) == pytest.approx(space.maximum_extent())
    assert StateSpace.from_metric([Variable("v")], [("v", 1.0)]).maximum_extent() == math.inf
    unweighed = StateSpace.from_metric([Variable("x", 0, 3), Variable("v")],
                                       [("x", 2.0), ("v", 0.0)])
    assert unweighed.maximum_extent() == 6.0
