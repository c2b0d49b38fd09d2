"""The spaceship's dynamics: SPEC 2's check value and the slice bookkeeping."""

import math

import pytest

from planning_core.problem_text import parse_problem
from planning_core.systems import spaceship
from planning_core.worlds.grid import GridWorld


def test_spec_check_value():
    state = spaceship.SYSTEM.propagate((0.1, 1.54, 0.0, 0.0), (0.25, 0.5))
    assert state == pytest.approx((0.279372, 1.720952, 0.301223, 0.382995), abs=1e-6)


def test_slices_end_at_the_propagated_state_and_follow_the_spec_order():
    start, control = (1.0, 1.0, 0.3, -0.1), (1.0, 0.4)
    slices = spaceship.SYSTEM.slice_states(start, control)
    assert len(slices) == spaceship.SLICES == 20
    assert slices[-1] == spaceship.SYSTEM.propagate(start, control)
    # First slice by hand: velocity first, then position with the new velocity.
    a = math.atan2(-0.1, 0.3) + 1.0
    dx = 0.3 + (1 / 20) * 0.4 * math.cos(a)
    dy = -0.1 + (1 / 20) * 0.4 * math.sin(a)
    assert slices[0] == pytest.approx((1.0 + dx / 20, 1.0 + dy / 20, dx, dy), abs=1e-15)


def test_at_rest_theta_is_measured_from_plus_x():
    x, y, dx, dy = spaceship.SYSTEM.propagate((1.0, 1.0, 0.0, 0.0), (0.0, 0.5))
    assert dy == 0.0 and dx > 0 and x > 1.0 and y == 1.0


def test_collision_on_any_slice_returns_none():
    world = GridWorld(parse_problem("4\n3\n____\n__#_\n___#\n0.1\n1.54\n3.8\n1.1\n"))
    # Fast toward +x from (1.5, 1.5): crosses blocked cell (2, 1) mid-step, ends beyond it.
    state = (1.5, 1.5, 1.6, 0.0)
    assert spaceship.SYSTEM.propagate(state, (0.0, 0.0))[0] > 3.0
    assert spaceship.SYSTEM.propagate_while(state, (0.0, 0.0), world) is None
    assert spaceship.SYSTEM.propagate_while((0.5, 2.5, 0.2, 0.0), (0.0, 0.0),
                                            world) is not None
