"""The generated kernels (planning_core/generated_kernels.py): the committed file is
what tools/generate_kernels.py writes, every registered family system runs them,
and each computes its reference's floats bit for bit: a metric class the space's
distance and interpolation and the reference box bound, an integrator class the
reference integrator's slices, stops and valid-state test."""

from __future__ import annotations

import dataclasses
import math
import random
from pathlib import Path

import pytest

from planning_core import generated_kernels, kernels
from planning_core.integrators import SCHEMES, ReferenceIntegrator
from planning_core.kinoplan import body_tester, make_goal
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.nearest.kdtree import angle_slack
from planning_core.nearest.metric import SpaceMetric
from planning_core.spaces import StateSpace, Variable
from planning_core.systems import SYSTEM_MODULES, load
from planning_core.systems.family import FamilySystem, KinodynamicFamily
from tests.planning_core.nearest.test_kdtree import make_state
from tools import generate_kernels

ROOT = Path(__file__).resolve().parents[2]
FAMILY = [name for name in SYSTEM_MODULES if isinstance(load(name), FamilySystem)]
KINODYNAMIC = [name for name in FAMILY if isinstance(load(name), KinodynamicFamily)]
SHIPS = [name for name, _ in generate_kernels.grid_state_spaces()]
EXAMPLES = {"pendulum": "pendulum-t3", "car2": "car2-corridors", "unicycle": "unicycle-circles",
            "car1": "car1-scene1", "arm2": "arm2-pair1", "rigid2": "rigid2-scene1"}


def example(name: str):
    """The example problem of a system (its bounds from its world box)."""
    path = ROOT / "benchmarks" / "problems" / "family" / f"{EXAMPLES[name]}.kp"
    return parse_kinoplan(path.read_text())


def hexes(values) -> list[str]:
    return [float(v).hex() for v in values]


def test_the_committed_file_is_what_the_generator_writes():
    assert generate_kernels.TARGET == ROOT / "planning_core" / "generated_kernels.py"
    assert generate_kernels.TARGET.read_text() == generate_kernels.module_text(), (
        "run: python tools/generate_kernels.py")


def goal_spaces(system) -> list:
    """The system's space, and the restriction of its metric to its position."""
    position = {system.state_names[i]: 0.0 for i in system.position_indices}
    return [system.space, make_goal(system.space, position, 1.0).space]


@pytest.mark.parametrize("name", FAMILY)
def test_every_family_system_runs_generated_metrics_and_integrators(name):
    system = load(name)
    for space in goal_spaces(system):
        assert type(kernels.space_metric(space)).__module__ == kernels.GENERATED
    for scheme in SCHEMES if system.kinodynamic else ():
        loop = kernels.integrator(type(system)(scheme=scheme))
        assert type(loop).__module__ == kernels.GENERATED
        assert kernels.integrator_version(loop) == "generated, interpreted"


def test_another_metric_shape_runs_the_reference_and_says_why():
    system = load("car2").configure(metric=(("x,y", 1.0), ("theta", 0.5)))
    metric = kernels.space_metric(system.space)
    assert type(metric) is SpaceMetric
    assert kernels.metric_version(metric) == (
        "reference, interpreted (no generated metric for its shape: a problem's own "
        "metric groups)")


def ship_state_space(name: str):
    """A grid ship's whole state on a 20 x 20 map, the velocities weighed 0.3 and, to be
    sampled, bounded to [-3, 3] (the same metric shape and weights)."""
    space = load(name).state_space(20.0, 20.0, velocity_weight=0.3)
    bounded = StateSpace.from_metric(
        tuple(v if v.low > -math.inf else Variable(v.name, -3.0, 3.0) for v in space.variables),
        {",".join(space.variables[i].name for i in group): weight
         for group, weight in space.groups})
    assert kernels.metric_key(bounded) == kernels.metric_key(space)
    assert bounded.groups == space.groups
    return bounded


@pytest.mark.parametrize("name", SHIPS)
def test_the_ships_whole_state_runs_a_generated_metric(name):
    assert type(kernels.space_metric(ship_state_space(name))).__module__ == kernels.GENERATED


@pytest.mark.parametrize("name", FAMILY + SHIPS)
def test_metrics_measure_bound_and_interpolate_as_the_references(name):
    rng = random.Random(name)
    spaces = [ship_state_space(name)] if name in SHIPS else goal_spaces(example(name).system)
    for space in spaces:
        fast, reference = kernels.space_metric(space), SpaceMetric(space)
        interpolates = "interpolate" in type(fast).__dict__
        points: list = []
        for _ in range(2000):
            a, b = make_state(space, rng, points), make_state(space, rng, points)
            points.append(a)
            assert fast.distance(a, b).hex() == space.distance(a, b).hex(), (a, b)
            lo = [min(c) for c in zip(space.wrap(a), space.wrap(b))]
            hi = [max(c) for c in zip(space.wrap(a), space.wrap(b))]
            q = space.wrap(make_state(space, rng, points))
            slack = angle_slack(max(abs(v) for v in q + a + b))
            assert (fast.bound(q, lo, hi, slack).hex()
                    == reference.bound(q, lo, hi, slack).hex())
            t = rng.choice((0.0, 1.0, 0.5, math.nextafter(0.5, 0.0), rng.random()))
            if interpolates:
                assert hexes(fast.interpolate(a, b, t)) == hexes(space.interpolate(a, b, t))


def states(system, rng, count: int):
    """Random states within and around the bounds, some not finite."""
    variables = system.space.variables
    for _ in range(count):
        state = []
        for v in variables:
            bounded = not v.angle and math.isfinite(v.high - v.low)
            lo, hi = (v.low, v.high) if bounded else (-4.0, 4.0)
            span = hi - lo
            state.append(rng.uniform(lo - 0.1 * span, hi + 0.1 * span))
        if rng.random() < 0.05:
            state[rng.randrange(len(state))] = rng.choice((math.nan, math.inf, -math.inf))
        yield tuple(state)


def outcome(run):
    """What ``run()`` returns as float hexes, or the exception it raises (an infinite
    angle has no cosine; both versions raise)."""
    try:
        found = run()
    except ValueError as error:
        return type(error)
    if isinstance(found, tuple) and found and isinstance(found[0], tuple):
        return hexes(found[0]), found[1]  # advance: (state, k)
    return None if found is None else hexes(found)


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("name", KINODYNAMIC)
def test_integrators_slice_stop_and_test_as_the_reference(name, scheme):
    problem = example(name)
    system = dataclasses.replace(problem.system, scheme=scheme, dt=0.07, kmax=12)
    fast = kernels.integrator(system, body_tester(system, problem.world))
    reference = ReferenceIntegrator(system.dynamics, scheme, 0.07, system.space.satisfies_bounds,
                                    body_tester(system, problem.world))
    assert type(fast).__module__ == kernels.GENERATED
    rng, stops = random.Random(f"{name} {scheme}"), set()
    for state in states(system, rng, 600):
        assert fast.valid(state) is reference.valid(state), state
        control = (*system.sample_values(rng), rng.randint(1, 12))
        out: list = []
        expected: list = []
        assert outcome(lambda: fast.slices(state, control, control[-1], out)) == outcome(
            lambda: reference.slices(state, control, control[-1], expected))
        assert [hexes(s) for s in out] == [hexes(s) for s in expected]
        advanced = outcome(lambda: fast.advance(state, control, control[-1]))
        assert advanced == outcome(lambda: reference.advance(state, control, control[-1]))
        assert (outcome(lambda: fast.propagate_valid(state, control))
                == outcome(lambda: reference.propagate_valid(state, control)))
        stops.add(advanced[1] == control[-1] if isinstance(advanced, tuple) else None)
    assert {True, False} <= stops


def test_interpreted_the_generated_code_wraps_angles_with_the_library():
    assert generated_kernels._rem is math.remainder  # (the same floats, faster interpreted)
