"""planning_core.worlds.body_motion: the rigid body's motion check answers as testing
each of SPEC 5.2's samples with the state validator, on motions that touch every
obstacle kind, leave the bounds and wrap the angle."""

import math
import random

from planning_core.family_geometric_space_information import MotionHit
from planning_core.kinoplan import body_tester, state_validator
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.kernels import space_metric
from planning_core.worlds.body_motion import BodyMotionCheck

SCENE = """kinoplan 1
system rigid2
body polygon -0.2 -0.1 0.2 -0.1 0.25 0.05 -0.2 0.1
world 0 0 3.5 2
bound x 0 2.5
rect 0.9 0 1.1 1.2
circle 2.0 1.6 0.3
polygon 1.6 0.2 2.2 0.3 1.9 0.8
start x 0.3 y 0.3 theta 0
goal x 2.5 y 0.3 theta 0 within 0.05
"""


def reference_first_invalid(system, valid, a, b) -> int:
    samples = system.motion_samples(a, b)
    return next((i for i in range(1, len(samples)) if not valid(samples[i])), 0)


def test_first_invalid_is_the_first_sample_the_state_validator_rejects():
    problem = parse_kinoplan(SCENE)
    system, world = problem.system, problem.world
    valid = state_validator(system, world)
    variables = system.space.variables
    check = BodyMotionCheck(body_tester(system, world), [v.low for v in variables[:2]],
                            [v.high for v in variables[:2]], space_metric(system.space),
                            system.check, MotionHit)
    rng = random.Random(3)
    outcomes = set()
    for _ in range(400):
        a = (rng.uniform(-0.1, 3.6), rng.uniform(-0.1, 2.1), rng.uniform(-math.pi, math.pi))
        b = (rng.uniform(-0.1, 3.6), rng.uniform(-0.1, 2.1), rng.uniform(-math.pi, math.pi))
        expected = reference_first_invalid(system, valid, a, b)
        n = len(system.motion_samples(a, b)) - 1
        assert check.first_invalid(a, b, n) == expected, (a, b)
        hit = check.first_hit(a, b)
        assert (hit is None) if expected == 0 else (hit.fraction == expected / n)
        outcomes.add(min(expected, 2))
    assert outcomes == {0, 1, 2}  # free motions, at once and later blocked ones


def test_a_state_outside_the_bounds_or_not_finite_is_invalid():
    problem = parse_kinoplan(SCENE)
    system, world = problem.system, problem.world
    check = BodyMotionCheck(body_tester(system, world), [0.0, 0.0], [2.5, 2.0],
                            space_metric(system.space), system.check, MotionHit)
    assert check.in_bounds(2.5, 1.0, 3.0) and not check.in_bounds(2.51, 1.0, 0.0)
    assert not check.in_bounds(1.0, math.nan, 0.0) and not check.in_bounds(1.0, 1.0, math.inf)
    # x at 2.25, 2.5 (the bound: in), 2.75 (out, though the body is inside the world), 3.0
    assert check.first_invalid((2.0, 1.0, 0.0), (3.0, 1.0, 0.0), 4) == 3
