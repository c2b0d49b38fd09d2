"""The integrators of SPEC 5.2 (planning_core.integrators): euler and rk4 slices
against hand-computed values, angles wrapped after every slice, K slices as K
applications, and the reference integrator's stops and valid-state test. (The
generated integrators against it: test_generated_kernels.py.)"""

from __future__ import annotations

import math
import random

import pytest

from planning_core.integrators import (
    REFERENCE_SLICES,
    Dynamics,
    ReferenceIntegrator,
    check_scheme,
    euler_slice,
    rk4_slice,
    slice_count,
)

DECAY = Dynamics(("x",), (), ("-x",), (False,))                     # x' = -x
SPIN = Dynamics(("a", "r"), ("w",), ("w", "0.5 * r"), (True, False))   # a' = w, r' = r / 2


def unbounded(state) -> bool:
    return True


def integrator(dynamics, scheme, dt, in_bounds=unbounded, body=None):
    return ReferenceIntegrator(dynamics, scheme, dt, in_bounds, body)


def test_one_euler_slice_by_hand():
    assert euler_slice(DECAY.rates_at, (2.0,), (), 0.1, (False,)) == (2.0 - 0.1 * 2.0,)


def test_one_rk4_slice_by_hand_is_the_fourth_order_taylor_step():
    h = 0.1
    (x,) = rk4_slice(DECAY.rates_at, (1.0,), (), h, (False,))
    # For x' = -x, classic RK4 multiplies by 1 - h + h^2/2 - h^3/6 + h^4/24 exactly.
    assert x == pytest.approx(1 - h + h ** 2 / 2 - h ** 3 / 6 + h ** 4 / 24, abs=1e-15)
    assert x != pytest.approx(math.exp(-h), abs=1e-9)   # (and not the exact solution)


def test_rk4_stages_by_hand_with_a_state_dependent_rate():
    rates = SPIN.rates_at
    h, a, r, w = 0.2, 0.3, 2.0, 1.5
    k1 = 0.5 * r
    k2 = 0.5 * (r + h / 2 * k1)
    k3 = 0.5 * (r + h / 2 * k2)
    k4 = 0.5 * (r + h * k3)
    expected = (a + h / 6 * (w + 2 * w + 2 * w + w), r + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4))
    assert rk4_slice(rates, (a, r), (w,), h, (True, False)) == pytest.approx(expected, abs=1e-15)


def test_rates_are_the_expressions_evaluated_with_the_names_bound():
    car = Dynamics(("x", "theta"), ("v", "phi"), ("v * cos(theta)", "(v / L) * tan(phi)"),
                   (False, True), (("L", 0.2),))
    assert car.rates_at((1.0, 0.5), (2.0, 0.25)) == (2.0 * math.cos(0.5),
                                                      (2.0 / 0.2) * math.tan(0.25))


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
def test_angles_are_wrapped_after_every_slice(scheme):
    out = []
    end = integrator(SPIN, scheme, 0.5).slices((3.0, 1.0), (1.0, 4), 4, out)
    assert [s[0] for s in out] == pytest.approx(
        [math.remainder(3.0 + 0.5 * k, 2 * math.pi) for k in range(1, 5)], abs=1e-12)
    assert all(-math.pi <= s[0] <= math.pi for s in out)
    assert out[0][0] < 0.0          # 3.5 went past pi: wrapped to 3.5 - 2 pi
    assert end == out[-1]


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
def test_k_slices_are_k_applications_of_one_slice(scheme):
    step = REFERENCE_SLICES[scheme]
    state = (0.4, -1.25)
    for _ in range(7):
        state = step(SPIN.rates_at, state, (2.5,), 0.05, (True, False))
    assert integrator(SPIN, scheme, 0.05).slices((0.4, -1.25), (2.5, 7), 7) == state


def test_advance_stops_before_the_first_invalid_slice_and_propagate_valid_says_none():
    loop = integrator(DECAY, "euler", 0.5, lambda state: state[0] > 0.2)
    assert loop.advance((1.0,), (10,), 10) == ((0.25,), 2)      # 0.125 fails: two slices
    assert loop.advance((1.0,), (10,), 1) == ((0.5,), 1)
    assert loop.propagate_valid((1.0,), (10,)) is None
    assert loop.propagate_valid((1.0,), (2,)) == (0.25,)
    assert loop.valid((0.3,)) and not loop.valid((0.2,))


class Body:
    """A body test that remembers its poses and frees x > 0.4."""

    def __init__(self):
        self.poses = []

    def free(self, x, y, theta):
        self.poses.append((x, y, theta))
        return x > 0.4


def test_the_body_is_tested_at_the_first_three_values_after_the_bounds():
    three = Dynamics(("x", "y", "theta"), (), ("-x", "0.0", "1.0"), (False, False, True))
    body = Body()
    loop = integrator(three, "euler", 0.5, lambda state: state[1] < 10.0, body)
    assert loop.advance((1.0, 2.0, 0.0), (3,), 3) == ((0.5, 2.0, 0.5), 1)
    assert body.poses == [(0.5, 2.0, 0.5), (0.25, 2.0, 1.0)]
    assert not loop.valid((0.1, 11.0, 0.0)) and len(body.poses) == 2   # the bounds first


def test_inputs_are_not_modified_and_lists_give_what_tuples_give():
    loop = integrator(SPIN, "rk4", 0.1)
    state, control = [0.5, 1.0], [2.0, 3]
    assert loop.slices(state, control, 3) == loop.slices((0.5, 1.0), (2.0, 3), 3)
    assert state == [0.5, 1.0] and control == [2.0, 3]


def test_slice_count_takes_integral_floats_only():
    assert slice_count(3) == 3 and slice_count(3.0) == 3
    for bad in (2.5, math.nan, math.inf):
        with pytest.raises(ValueError, match="whole number of slices"):
            slice_count(bad)


@pytest.mark.parametrize("names, rates, message", [
    (("state",), ("1",), "cannot be a variable name"),      # the generated code's own
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
        check_scheme("midpoint", 0.1)
    with pytest.raises(ValueError, match="unknown scheme"):
        integrator(DECAY, "midpoint", 0.1)
    for dt in (0.0, -0.1, math.inf, math.nan):
        with pytest.raises(ValueError, match="DT"):
            integrator(DECAY, "rk4", dt)
