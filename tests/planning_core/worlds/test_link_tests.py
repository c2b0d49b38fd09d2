"""The arm's bound link tests (planning_core.worlds.link_tests, compiled) answer as
the interpreted code they replaced: ``valid`` as the bounds test then each link's
``segment_free``, ``reach`` as the clearance formula, the joints bit for bit, and
the arm's motion check as the old sample loop, on seeded random states and motions
(near obstacles, quarter turns, NaN and infinite values included)."""

from __future__ import annotations

import dataclasses
import math
import random
import sys

import pytest

from planning_core.kinoplan import link_tests, state_validator
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.setups import kinoplan_setup
from planning_core.worlds.continuous import CLEARANCE_MARGIN, ContinuousWorld
from planning_core.worlds.link_tests import LinkTests
from planning_core.worlds.shapes import SNAP
from tests.conftest import ROOT, unit_sample

FAMILY = ROOT / "benchmarks" / "problems" / "family"
SHAPES = """kinoplan 1
system arm2
param base_x 0.1
param base_y -0.05
param l1 1.1
param l2 0.8
world -2.2 -2.2 2.05 2.2
rect 0.6 0.6 1.3 1.3
circle -1.3 0.5 0.25
polygon -0.5 -1.9 0.4 -1.6 0.1 -1.2
start theta1 -0.5 theta2 -0.5
goal theta1 1.5 theta2 1.5 within 0.01
"""
SPECIAL = (math.nan, math.inf, -math.inf)
QUARTERS = (0.0, math.pi / 2, math.pi, -math.pi / 2, 3 * math.pi / 2, -math.pi)
REACH_WORTH, REACH_PAUSE = 3, 4


def problems():
    texts = [(FAMILY / f"arm2-pair{k}.kp").read_text() for k in range(1, 6)]
    texts.append(SHAPES)
    found = [parse_kinoplan(text) for text in texts]
    boxless = ContinuousWorld(None, found[-1].world.obstacles)  # no problem has none
    return found + [dataclasses.replace(found[-1], world=boxless)]


# ----- the code replaced, as it was -----------------------------------------------------

def reference_joints(arm, state):
    def cos_sin(angle):
        c, s = math.cos(angle), math.sin(angle)
        return (0.0 if abs(c) < SNAP else c), (0.0 if abs(s) < SNAP else s)
    c1, s1 = cos_sin(state[0])
    c12, s12 = cos_sin(state[0] + state[1])
    ex, ey = arm.base_x + arm.l1 * c1, arm.base_y + arm.l1 * s1
    return (arm.base_x, arm.base_y), (ex, ey), (ex + arm.l2 * c12, ey + arm.l2 * s12)


def reference_valid(arm, world):
    def valid(state):
        if not arm.in_bounds(state):
            return False
        (bx, by), (ex, ey), (tx, ty) = reference_joints(arm, state)
        return world.segment_free(bx, by, ex, ey) and world.segment_free(ex, ey, tx, ty)
    return valid


def reference_reach(arm, world):
    values = [abs(v) for o in world.obstacles for v in o.bbox]
    values += [abs(v) for v in world.box.bbox] if world.box is not None else []
    values += [abs(arm.base_x) + arm.l1 + arm.l2, abs(arm.base_y) + arm.l1 + arm.l2, 1.0]
    margin = CLEARANCE_MARGIN * max(values)
    l1, l2, clearance = arm.l1, arm.l2, world.segment_clearance

    def reach(state, step):
        (bx, by), (ex, ey), (tx, ty) = reference_joints(arm, state)
        move1 = l1 * abs(step[0])
        move2 = move1 + l2 * abs(step[0] + step[1])
        most = 1e9
        if move2 > 0.0:
            most = (clearance(ex, ey, tx, ty, margin + most * move2) - margin) / move2
        if move1 > 0.0:
            most = min(most, (clearance(bx, by, ex, ey, margin + most * move1) - margin) / move1)
        return int(max(0.0, min(most, 1e9)))
    return reach


def reference_first_hit(si, valid, reach, a, b):
    """The old ``first_hit``: the fraction of its first invalid sample (or None),
    and how many samples it tested."""
    n = si.samples_between(a, b)
    step = tuple(math.remainder(y - x, math.tau) / n for x, y in zip(a, b))
    i, wait, tested = 1, 0, 0
    while i <= n:
        q = si.space.interpolate(a, b, i / n)
        tested += 1
        if not valid(q):
            return i / n, tested
        if wait > 0 or i == n:
            i, wait = i + 1, wait - 1
            continue
        skip = reach(q, step)
        i, wait = i + 1 + skip, (REACH_PAUSE if skip < REACH_WORTH else 0)
    return None, tested


# ----- states to try ----------------------------------------------------------------------

def near_boundary(valid, interpolate, a, b):
    """States within a few ulps of where the motion a (valid) -> b (invalid) turns
    invalid (bisected): the links touch an obstacle or the box there."""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if valid(interpolate(a, b, mid)) else (lo, mid)
    edge = interpolate(a, b, lo)
    return [edge, interpolate(a, b, hi)] + [
        tuple(v + k * math.ulp(v) for v in edge) for k in (-3, -1, 1, 3)]


def random_states(rng: random.Random, si, count: int) -> list:
    valid, interpolate = si.is_valid, si.space.interpolate
    states = [si.sample_target(rng) for _ in range(count)]
    states += [(rng.uniform(-9.0, 9.0), rng.uniform(-9.0, 9.0)) for _ in range(count // 4)]
    states += [(rng.choice(QUARTERS), rng.choice(QUARTERS)) for _ in range(count // 10)]
    states += [(rng.choice(QUARTERS) + rng.choice((-1, 1)) * 1e-13, rng.choice(QUARTERS))
               for _ in range(count // 10)]
    states += [(rng.choice(SPECIAL + (0.5,)), rng.choice(SPECIAL + (-0.5,)))
               for _ in range(20)]
    for _ in range(count // 10):
        a, b = si.sample_target(rng), si.sample_target(rng)
        if valid(a) and not valid(b):
            states += near_boundary(valid, interpolate, a, b)
    return states


# ----- the checks ---------------------------------------------------------------------------

def check_against_reference(seed: int, count: int = 2000, tests: list[int] | None = None) -> None:
    """Every problem's ``valid``, ``reach``, joints and motion check against the
    references, bit for bit (also run with the compiled build: tests/test_compiled.py);
    ``tests`` counts the samples the motion check tests, when it can."""
    rng = random.Random(seed)
    for problem in problems():
        arm, world = problem.system, problem.world
        si = kinoplan_setup(problem).si
        valid, old_valid = state_validator(arm, world), reference_valid(arm, world)
        reach, old_reach = link_tests(arm, world).reach, reference_reach(arm, world)
        states = random_states(rng, si, count)
        answers = set()
        for state in states + [list(s) for s in states[:50]]:
            answers.add(valid(state))
            assert valid(state) == old_valid(state), state
            if not all(math.isfinite(v) for v in state):
                continue
            assert repr(arm.joints(state)) == repr(reference_joints(arm, state))
            for scale in (1e-4, 0.01, 0.3):
                step = (rng.uniform(-scale, scale), rng.uniform(-scale, scale))
                assert reach(state, step) == old_reach(state, step), (state, step)
        assert answers == {True, False}
        check_motions(rng, si, old_valid, old_reach, count // 4, tests or [0])


def count_calls(monkeypatch, cls: type, name: str) -> list[int]:
    """``[calls]``, counting the calls of ``cls.name`` from now on; interpreted only
    (a native class's methods cannot be replaced): otherwise never counts."""
    calls = [0]
    if not sys.modules[cls.__module__].__file__.endswith(".py"):
        return calls
    method = getattr(cls, name)

    def counted(*args):
        calls[0] += 1
        return method(*args)
    monkeypatch.setattr(cls, name, counted)
    return calls


def check_motions(rng: random.Random, si, old_valid, old_reach, count: int,
                  tests: list[int]) -> None:
    """``si.first_hit`` answers as the old loop, on random motions; interpreted, it
    tests the same number of samples (``tests`` counts them)."""
    tested = total = hits = 0
    draw = si.free_sampler(rng)
    for _ in range(count):
        a = draw() if rng.random() < 0.8 else si.sample_target(rng)
        b = si.sample_target(rng)
        if rng.random() < 0.3:  # a short motion
            b = si.space.interpolate(a, b, rng.uniform(0.0, 0.1))
        before = tests[0]
        hit = si.first_hit(a, b)
        fraction, count_tested = reference_first_hit(si, old_valid, old_reach, a, b)
        assert (None if hit is None else hit.fraction) == fraction, (a, b)
        assert tests[0] - before in (0, count_tested)  # 0: not counted (compiled)
        hits += fraction is not None
        tested += count_tested
        total += si.samples_between(a, b)
    assert 0 < hits < count and tested < total / 2  # blocked and free motions; skips


@pytest.mark.parametrize("count", unit_sample([300, 800]))  # 300: blocked and free motions
def test_valid_reach_joints_and_motions_answer_as_before(monkeypatch, count):
    check_against_reference(seed=11, count=count,
                            tests=count_calls(monkeypatch, LinkTests, "in_bounds"))


def test_odd_states():
    for problem in problems()[:1]:
        valid = state_validator(problem.system, problem.world)
        assert not valid(()) and not valid((0.5,)) and not valid((0.5, 0.5, 0.5))
        assert valid((0, 0)) == valid((0.0, 0.0))
        reach = link_tests(problem.system, problem.world).reach
        with pytest.raises(ValueError):
            reach((math.inf, 0.0), (0.01, 0.01))
        assert reach((0.0, 0.0), (math.nan, 0.0)) == 10 ** 9
        assert reach((0.0, 0.0), (0.0, 0.0)) == 10 ** 9


def test_no_link_tests_without_a_world_or_for_a_body():
    text = (FAMILY / "rigid2-scene1.kp").read_text()
    problem = parse_kinoplan(text)
    assert link_tests(problem.system, problem.world) is None
    assert link_tests(problems()[0].system, None) is None
