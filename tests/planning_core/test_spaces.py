"""State spaces: SPEC 5.1's metric and angle rules against hand-computed values."""

import math
import pickle
import random

import pytest

from planning_core.spaces import StateSpace, Variable

PI = math.pi


def se2(weights=(0.7, 0.3)):
    """SPEC's ``metric x,y 0.7 theta 0.3`` over a 10 x 10 world."""
    variables = (Variable("x", 0, 10), Variable("y", 0, 10), Variable("theta", angle=True))
    return StateSpace.from_metric(variables, [("x,y", weights[0]), ("theta", weights[1])])


def trailer():
    """5-D with two angles sharing a group: ``metric x,y 1 theta,psi 0.5 v 0.3``."""
    variables = (Variable("x", -5, 5), Variable("y", -5, 5), Variable("theta", angle=True),
                 Variable("psi", angle=True), Variable("v", -2, 2))
    return StateSpace.from_metric(variables, {"x,y": 1.0, "theta,psi": 0.5, "v": 0.3})


def unicycle():
    """SPEC 5.2's default: v and omega are in no metric group."""
    variables = (Variable("x", 0, 20), Variable("y", 0, 20), Variable("theta", angle=True),
                 Variable("v", -5, 5), Variable("omega", -PI / 2, PI / 2))
    return StateSpace.from_metric(variables, [("x,y", 1.0), ("theta", 0.5)])


# ----- distance -----

def test_se2_distance_by_hand():
    space = se2()
    assert space.distance((0, 0, 0), (3, 4, PI / 2)) == pytest.approx(0.7 * 5 + 0.3 * PI / 2, rel=1e-15)
    # 3.0 and -3.0 are 2*pi - 6 apart the short way, not 6.
    assert space.distance((1, 1, 3.0), (1, 1, -3.0)) == pytest.approx(0.3 * (2 * PI - 6), rel=1e-12)
    # Turns do not count.
    assert space.distance((0, 0, 0.5), (0, 0, 0.5 + 4 * PI)) == pytest.approx(0.0, abs=1e-15)


def test_exactly_pi_apart():
    space = StateSpace.so2()
    for a, b in [(0.0, PI), (PI, 0.0), (-PI, 0.0), (0.0, 3 * PI), (-PI / 2, PI / 2)]:
        assert space.distance((a,), (b,)) == PI
    assert space.distance((-PI,), (PI,)) == 0.0


def test_grouped_angles_and_unweighted_variables():
    space = trailer()
    a, b = (0, 0, 3.0, -1.0, 1.0), (1, 0, -3.0, -1.5, -1.0)
    dtheta, dpsi = 2 * PI - 6, -0.5
    expected = 1.0 * 1.0 + 0.5 * math.sqrt(dtheta ** 2 + dpsi ** 2) + 0.3 * 2.0
    assert space.distance(a, b) == pytest.approx(expected, rel=1e-12)
    uni = unicycle()
    assert uni.distance((0, 0, 0, -5, -1), (3, 4, 0, 5, 1)) == 5.0


def test_distance_is_symmetric():
    rng = random.Random(5)
    for space in (se2(), trailer(), unicycle(), StateSpace.so2(),
                  StateSpace.real_vector("abc", (0, 0, 0), (1, 1, 1))):
        for _ in range(2000):
            a = tuple(rng.uniform(-20, 20) for _ in range(space.dimension))
            b = tuple(rng.uniform(-20, 20) for _ in range(space.dimension))
            assert space.distance(a, b) == space.distance(b, a)


# ----- interpolate and wrap -----

def test_interpolate_by_hand():
    space = se2()
    assert space.interpolate((0, 0, 0), (2, 4, 1.0), 0.25) == (0.5, 1.0, 0.25)
    # Across the +-pi seam, the short way.
    mid = space.interpolate((0, 0, 3.0), (0, 0, -3.0), 0.25)[2]
    assert mid == pytest.approx(3.0 + 0.25 * (2 * PI - 6), rel=1e-12)
    late = space.interpolate((0, 0, 3.0), (0, 0, -3.0), 0.75)[2]
    assert late == pytest.approx(-3.0 - 0.25 * (2 * PI - 6), rel=1e-12)


def test_interpolate_exactly_pi_apart_follows_remainder():
    so2 = StateSpace.so2()
    # remainder(pi, 2 pi) = pi: counter-clockwise.
    assert so2.interpolate((0.0,), (PI,), 0.5) == pytest.approx((PI / 2,), rel=1e-15)
    # remainder(-pi, 2 pi) = -pi: clockwise, through the same midpoint reversed.
    assert so2.interpolate((PI,), (0.0,), 0.25) == pytest.approx((3 * PI / 4,), rel=1e-15)
    # remainder(3 pi, 2 pi) = -pi (the half rounds to the even turn): clockwise.
    assert math.remainder(3 * PI, 2 * PI) == -PI
    assert so2.interpolate((0.0,), (3 * PI,), 0.5) == pytest.approx((-PI / 2,), rel=1e-15)
    assert so2.interpolate((-PI / 2,), (PI / 2,), 0.5) == (0.0,)


def test_interpolate_endpoints_exact():
    rng = random.Random(2)
    for space in (se2(), trailer()):
        for _ in range(500):
            a = tuple(rng.uniform(-9, 9) for _ in range(space.dimension))
            b = tuple(rng.uniform(-9, 9) for _ in range(space.dimension))
            assert space.interpolate(a, b, 0.0) == space.wrap(a)
            assert space.interpolate(a, b, 1.0) == space.wrap(b)


def test_wrap():
    space = se2()
    assert space.wrap((12.5, -1.0, 3 * PI / 2)) == (12.5, -1.0, pytest.approx(-PI / 2, rel=1e-15))
    assert space.wrap((0, 0, PI)) == (0, 0, PI)      # remainder keeps +pi ...
    assert space.wrap((0, 0, -PI)) == (0, 0, -PI)    # ... and -pi
    assert space.wrap((0, 0, 7.0)) == (0, 0, 7.0 - 2 * PI)
    assert StateSpace.real_vector("xy", (0, 0), (1, 1)).wrap([2.0, 3.0]) == (2.0, 3.0)


# ----- sampling and bounds -----

def test_sample_uniform_seeded_and_in_bounds():
    space = trailer()
    samples = [space.sample_uniform(random.Random(9)) for _ in range(2)]
    assert samples[0] == samples[1]
    rng = random.Random(3)
    samples = [space.sample_uniform(rng) for _ in range(3000)]
    for s in samples:
        assert space.satisfies_bounds(s)
        assert -5 <= s[0] < 5 and -2 <= s[4] < 2
        assert -PI <= s[2] < PI and -PI <= s[3] < PI
    thetas = [s[2] for s in samples]
    assert min(thetas) < -3.0 and max(thetas) > 3.0


def test_satisfies_bounds():
    space = unicycle()
    assert space.satisfies_bounds((0, 20, 100.0, 5, -PI / 2))      # closed bounds, angle ignored
    assert not space.satisfies_bounds((0, 20.001, 0, 0, 0))
    assert not space.satisfies_bounds((0, 0, math.nan, 0, 0))
    assert not space.satisfies_bounds((0, 0, 0, 0))
    with pytest.raises(ValueError):
        StateSpace.from_metric((Variable("x"),), {"x": 1}).sample_uniform(random.Random(0))


# ----- construction -----

def test_constructors_agree():
    by_metric = se2()
    composed = StateSpace.compound(
        [StateSpace.real_vector(("x", "y"), (0, 0), (10, 10)), StateSpace.so2("theta")], (0.7, 0.3))
    assert composed == by_metric and hash(composed) == hash(by_metric)
    assert composed.groups == (((0, 1), 0.7), ((2,), 0.3))
    nested = StateSpace.compound([composed, StateSpace.so2("psi")], (2.0, 1.0))
    assert nested.groups == (((0, 1), 1.4), ((2,), 0.6), ((3,), 1.0))
    assert StateSpace.from_metric(by_metric.variables, [(("x", "y"), 0.7), (("theta",), 0.3)]) == by_metric


def test_names_projection_dimension():
    space = unicycle()
    assert space.dimension == 5
    assert space.index("theta") == 2
    with pytest.raises(KeyError):
        space.index("z")
    position = space.projection(("x", "y"))
    assert position((1.0, 2.0, 3.0, 4.0, 5.0)) == (1.0, 2.0)
    assert space.projection(["omega"])((1.0, 2.0, 3.0, 4.0, 5.0)) == (5.0,)


@pytest.mark.parametrize("variables,groups", [
    ((Variable("x"), Variable("x")), (((0,), 1.0),)),            # a name twice
    ((Variable("x"), Variable("y")), (((0, 1), 1.0), ((1,), 1.0))),  # a variable in two groups
    ((Variable("x"),), (((1,), 1.0),)),                          # an index out of range
    ((Variable("x"),), (((), 1.0),)),                            # an empty group
    ((Variable("x"),), (((0,), -1.0),)),                         # a negative weight
    ((Variable("x"),), (((0,), math.inf),)),
])
def test_rejects_ambiguous_metrics(variables, groups):
    with pytest.raises(ValueError):
        StateSpace(variables, groups)


def test_rejects_bad_variables_and_metric_names():
    with pytest.raises(ValueError):
        Variable("x", 1.0, 0.0)
    with pytest.raises(ValueError):
        Variable("")
    with pytest.raises(ValueError, match="unknown"):
        StateSpace.from_metric(se2().variables, {"x,z": 1.0})


def test_pickles():
    space = trailer()
    copy = pickle.loads(pickle.dumps(space))
    assert copy == space
    a, b = (0, 0, 3.0, 1.0, 0.5), (1, 2, -3.0, 2.0, -0.5)
    assert copy.distance(a, b) == space.distance(a, b)
