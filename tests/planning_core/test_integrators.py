"""The integrators of SPEC 5.2 (planning_core.integrators): euler and rk4 slices
against hand-computed values, angles wrapped after every slice, K slices as K
applications, and the compiled propagator bit for bit equal to the readable
reference on every family system and both schemes."""

from __future__ import annotations

import math
import random

import pytest

from planning_core.integrators import (
    REFERENCE_SLICES,
    Dynamics,
    compile_propagator,
    compile_rates,
    euler_slice,
    rk4_slice,
    slice_count,
)
from planning_core.systems import load

DECAY = Dynamics(("x",), (), ("-x",), (False,))                     # x' = -x
SPIN = Dynamics(("a", "r"), ("w",), ("w", "0.5 * r"), (True, False))   # a' = w, r' = r / 2
FAMILY = ("pendulum", "car2", "unicycle", "car1")


def test_one_euler_slice_by_hand():
    assert euler_slice(compile_rates(DECAY), (2.0,), (), 0.1, (False,)) == (2.0 - 0.1 * 2.0,)


def test_one_rk4_slice_by_hand_is_the_fourth_order_taylor_step():
    h = 0.1
    (x,) = rk4_slice(compile_rates(DECAY), (1.0,), (), h, (False,))
    # For x' = -x, classic RK4 multiplies by 1 - h + h^2/2 - h^3/6 + h^4/24 exactly.
    assert x == pytest.approx(1 - h + h ** 2 / 2 - h ** 3 / 6 + h ** 4 / 24, abs=1e-15)
    assert x != pytest.approx(math.exp(-h), abs=1e-9)   # (and not the exact solution)


def test_rk4_stages_by_hand_with_a_state_dependent_rate():
    rates = compile_rates(SPIN)
    h, a, r, w = 0.2, 0.3, 2.0, 1.5
    k1 = 0.5 * r
    k2 = 0.5 * (r + h / 2 * k1)
    k3 = 0.5 * (r + h / 2 * k2)
    k4 = 0.5 * (r + h * k3)
    expected = (a + h / 6 * (w + 2 * w + 2 * w + w), r + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4))
    assert rk4_slice(rates, (a, r), (w,), h, (True, False)) == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
def test_angles_are_wrapped_after_every_slice(scheme):
    propagate = compile_propagator(SPIN, scheme, 0.5)
    out = []
    end = propagate((3.0, 1.0), (1.0, 4), None, out)
    assert [s[0] for s in out] == pytest.approx(
        [math.remainder(3.0 + 0.5 * k, 2 * math.pi) for k in range(1, 5)], abs=1e-12)
    assert all(-math.pi <= s[0] <= math.pi for s in out)
    assert out[0][0] < 0.0          # 3.5 went past pi: wrapped to 3.5 - 2 pi
    assert end == out[-1]


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
def test_k_slices_are_k_applications_of_one_slice(scheme):
    rates, step = compile_rates(SPIN), REFERENCE_SLICES[scheme]
    propagate = compile_propagator(SPIN, scheme, 0.05)
    state = (0.4, -1.25)
    for _ in range(7):
        state = step(rates, state, (2.5,), 0.05, (True, False))
    assert propagate((0.4, -1.25), (2.5, 7)) == state


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
@pytest.mark.parametrize("name", FAMILY)
def test_compiled_equals_the_reference_bit_for_bit(name, scheme):
    system = load(name)
    dynamics = Dynamics(system.state_names, system.control_names[:-1], system.rates,
                        tuple(n in system.angle_names for n in system.state_names),
                        tuple((p, getattr(system, p)) for p in system.params))
    rates, step = compile_rates(dynamics), REFERENCE_SLICES[scheme]
    propagate = compile_propagator(dynamics, scheme, 0.07)
    rng = random.Random(3)
    for _ in range(200):
        state = tuple(rng.uniform(-3.0, 3.0) for _ in system.state_names)
        control = system.sample_control(rng)[:-1]
        k = rng.randint(1, 6)
        expected = state
        for _ in range(k):
            expected = step(rates, expected, control, 0.07, dynamics.angles)
        assert propagate(state, (*control, k)) == expected


def test_valid_stops_at_the_first_rejected_slice_and_out_gets_each_slice():
    propagate = compile_propagator(DECAY, "euler", 0.5)
    seen, out = [], []

    def valid(state):
        seen.append(state)
        return state[0] > 0.2

    assert propagate((1.0,), (10,), valid, out) is None
    assert seen == [(0.5,), (0.25,), (0.125,)]           # stopped at the third slice
    assert out == [(0.5,), (0.25,)]                      # a rejected slice is not appended
    assert propagate((1.0,), (2,), valid) == (0.25,)


def test_inputs_are_not_modified_and_lists_give_what_tuples_give():
    propagate = compile_propagator(SPIN, "rk4", 0.1)
    state, control = [0.5, 1.0], [2.0, 3]
    assert propagate(state, control) == propagate((0.5, 1.0), (2.0, 3))
    assert state == [0.5, 1.0] and control == [2.0, 3]


def test_slice_count_takes_integral_floats_only():
    assert slice_count(3) == 3 and slice_count(3.0) == 3
    assert compile_propagator(DECAY, "euler", 0.5)((1.0,), (2.0,)) == (0.25,)
    for bad in (2.5, math.nan, math.inf):
        with pytest.raises(ValueError, match="whole number of slices"):
            slice_count(bad)


@pytest.mark.parametrize("names, rates, message", [
    (("state",), ("1",), "cannot be a variable name"),      # the generated function's own
    (("_x",), ("1",), "cannot be a variable name"),
    (("cos",), ("1",), "cannot be a variable name"),
    (("x", "x"), ("1", "1"), "used twice"),
    (("x",), ("1", "2"), "one rate"),
])
def test_dynamics_rejects_names_the_generated_code_could_not_use(names, rates, message):
    with pytest.raises(ValueError, match=message):
        Dynamics(names, (), rates, (False,) * len(names))


def test_unknown_scheme_and_bad_dt_are_rejected():
    with pytest.raises(ValueError, match="unknown scheme"):
        compile_propagator(DECAY, "midpoint", 0.1)
    for dt in (0.0, -0.1, math.inf, math.nan):
        with pytest.raises(ValueError, match="DT"):
            compile_propagator(DECAY, "rk4", dt)
