"""The compiled samplers draw exactly what the references draw (a seed fixes a run)."""

from __future__ import annotations

import math
import random

import pytest

from planning_core.samplers import BoxSampler, ControlSampler, gauss, randint, uniform
from planning_core.spaces import StateSpace, Variable
from planning_core.systems import load


class _Halved(random.Random):
    """A generator of another class: uniform() and randint() must ask its own methods."""

    def random(self):
        return super().random() / 2.0

    def getrandbits(self, k):
        return super().getrandbits(k) >> 1 if k > 1 else super().getrandbits(k)


@pytest.mark.parametrize("kind", [random.Random, _Halved])
def test_uniform_and_randint_are_the_generators_own(kind):
    mine, theirs = kind(11), kind(11)
    for _ in range(500):
        assert uniform(mine) == theirs.random()
        assert randint(mine, 1, 100) == theirs.randint(1, 100)
    assert mine.getstate() == theirs.getstate()


@pytest.mark.parametrize("a, b", [(0, 0), (1, 10), (1, 16), (1, 17), (-5, 5), (3, 2 ** 40)])
def test_randint_is_the_random_modules(a, b):
    mine, theirs = random.Random(a * 7 + b), random.Random(a * 7 + b)
    assert [randint(mine, a, b) for _ in range(500)] == [theirs.randint(a, b) for _ in range(500)]
    assert mine.random() == theirs.random()  # and the stream goes on alike


@pytest.mark.parametrize("sigma", [0.0, 1.0 / 3.0, 7.5])
def test_gauss_is_the_random_modules_with_its_cached_second_value(sigma):
    mine, theirs = random.Random(5), random.Random(5)
    for k in range(2001):  # odd and even calls, other draws between some of them
        assert gauss(mine, 0.5, sigma) == theirs.gauss(0.5, sigma)
        if k % 7 == 0:
            assert mine.random() == theirs.random()
        assert mine.getstate() == theirs.getstate()


def test_a_bounded_space_samples_as_its_reference_method():
    space = StateSpace.from_metric(
        (Variable("x", -3.0, 7.5), Variable("theta", angle=True), Variable("v", 0.1, 0.3)),
        {"x": 1.0, "theta": 0.5, "v": 0.2})
    mine, theirs = random.Random(4), random.Random(4)
    for _ in range(300):
        got = space.sample_uniform(mine)
        assert got == StateSpace.sample_uniform(space, theirs)
        assert -math.pi <= got[1] < math.pi


def test_an_unbounded_space_still_refuses_to_sample():
    space = StateSpace.from_metric((Variable("x"),), {"x": 1.0})
    with pytest.raises(ValueError, match="unbounded"):
        space.sample_uniform(random.Random(1))


@pytest.mark.parametrize("name", ["pendulum", "car2", "unicycle", "car1"])
def test_a_systems_controls_are_its_reference_draws(name):
    system = load(name)
    mine, theirs = random.Random(9), random.Random(9)
    for _ in range(300):
        values = tuple(lo + (hi - lo) * theirs.random() for lo, hi in system.controls)
        assert system.sample_control(mine) == (*values, theirs.randint(system.kmin, system.kmax))
    sampler = ControlSampler(BoxSampler([0.0], [1.0]), 2, 2)
    assert sampler.sample(random.Random(1))[-1] == 2
