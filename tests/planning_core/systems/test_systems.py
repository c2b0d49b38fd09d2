"""The contract every registered system keeps (planning_core.systems.SYSTEM_MODULES):
what it declares, its start state and state space, and for kinodynamic systems
controls drawn within bounds and a pure ``propagate`` that ends where its slices end.
A new system gets these tests by being registered."""

import importlib
import math
import random

import pytest

from planning_core.systems import SYSTEM_MODULES, load

NAMES = sorted(SYSTEM_MODULES)
KINODYNAMIC = [name for name in NAMES if load(name).kinodynamic]
SEEDS = range(500)
WIDTH, HEIGHT = 7, 5


def some_states(system, rng: random.Random, count: int = 20):
    """States within the map: bounded variables uniform in their bounds, unbounded
    ones (velocities) in [-1, 1]; the start state at rest first."""
    states = [system.start_state(1.5, 2.5)]
    for _ in range(count):
        states.append(tuple(
            v.low + (v.high - v.low) * rng.random()
            if math.isfinite(v.low) and math.isfinite(v.high) else rng.uniform(-1.0, 1.0)
            for v in system.state_space(WIDTH, HEIGHT).variables))
    return states


@pytest.mark.parametrize("name", NAMES)
def test_module_has_its_system_under_its_name(name):
    module = importlib.import_module(SYSTEM_MODULES[name])
    assert module.SYSTEM.name == name
    assert load(name) is module.SYSTEM


@pytest.mark.parametrize("name", NAMES)
def test_declares_its_variables(name):
    system = load(name)
    assert isinstance(system.kinodynamic, bool)
    assert system.state_names and all(isinstance(n, str) and n for n in system.state_names)
    assert len(set(system.state_names)) == len(system.state_names)
    assert all(isinstance(n, str) and n for n in system.control_names)
    assert len(set(system.control_names)) == len(system.control_names)
    assert len(system.position_indices) == 2
    assert len(set(system.position_indices)) == 2
    assert all(0 <= i < len(system.state_names) for i in system.position_indices)


@pytest.mark.parametrize("name", NAMES)
def test_start_state_has_one_value_per_state_variable_and_sits_at_the_position(name):
    system = load(name)
    start = system.start_state(1.5, 2.5)
    # (a variable the planner chooses, such as the Dubins car's heading, is left out)
    assert len(start) == len(system.state_names) - len(getattr(system, "free_start_names", ()))
    ix, iy = system.position_indices
    assert (start[ix], start[iy]) == (1.5, 2.5)


@pytest.mark.parametrize("name", NAMES)
def test_state_space_has_one_dimension_per_state_variable(name):
    system = load(name)
    space = system.state_space(WIDTH, HEIGHT)
    assert space.dimension == len(system.state_names)
    assert tuple(v.name for v in space.variables) == system.state_names


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_sampled_controls_are_within_bounds(name):
    system = load(name)
    for seed in SEEDS:
        control = system.sample_control(random.Random(seed))
        assert len(control) == len(system.control_names)
        assert system.control_violation(control) is None, (seed, control)


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_propagate_ends_where_the_slices_end(name):
    system = load(name)
    rng = random.Random(1)
    for state in some_states(system, rng):
        control = system.sample_control(rng)
        slices = system.slice_states(state, control)
        assert slices and all(len(s) == len(system.state_names) for s in slices)
        assert system.propagate(state, control) == slices[-1]


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_propagate_is_pure(name):
    system = load(name)
    rng = random.Random(2)
    states = some_states(system, rng)
    controls = [system.sample_control(rng) for _ in states]
    first = []
    for state, control in zip(states, controls):
        state_list, control_list = list(state), list(control)
        end = system.propagate(state_list, control_list)
        # The inputs are left as they were, and a list gives what a tuple gives.
        assert state_list == list(state) and control_list == list(control)
        assert end == system.propagate(state, control)
        first.append(end)
    # No hidden state: the same inputs again, after other calls, give the same outputs.
    again = [system.propagate(state, control) for state, control in zip(states, controls)]
    assert again == first


LEFT_ONLY_REJECTED = [math.pi + 1e-9, 1.25 * math.pi, 1.5 * math.pi, 1.75 * math.pi,
                      2.0 * math.pi - 1e-9]


@pytest.mark.parametrize("theta", LEFT_ONLY_REJECTED)
def test_left_only_ship_rejects_thrust_to_the_right(theta):
    assert load("left").control_violation((theta, 0.25)) is not None


@pytest.mark.parametrize("theta", [0.0, 0.5 * math.pi, math.pi])
def test_left_only_ship_accepts_theta_up_to_pi(theta):
    assert load("left").control_violation((theta, 0.25)) is None
