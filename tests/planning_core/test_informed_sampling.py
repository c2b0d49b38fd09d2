"""Informed sampling (planning_core.informed_sampling): every draw lies in the informed
set, and draws are uniform over it, by chi-square tests with fixed seeds: the prolate
hyperspheroid against a lattice count of its cells, the informed sampler's direct
draws against rejection from uniform states."""

import math
import random

import numpy as np
import pytest

from planning_core.informed_sampling import (InformedSampler, ProlateHyperspheroid,
                                             SolutionHeuristic, euclidean_group,
                                             unit_ball_measure)
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup, kinoplan_setup
from tests.conftest import COURSE_DIR, ROOT

FAMILY = ROOT / "benchmarks" / "problems" / "family"


def critical_value(dof: int, z: float = 3.09) -> float:
    """Chi-square's 0.999 quantile (Wilson & Hilferty's approximation): a uniform
    sampler fails one of these tests once in a thousand seeds."""
    return dof * (1.0 - 2.0 / (9.0 * dof) + z * math.sqrt(2.0 / (9.0 * dof))) ** 3


def chi_square(observed: np.ndarray, expected: np.ndarray) -> tuple[float, int]:
    """The statistic over bins expected to hold at least 5, the rest pooled; and its dof."""
    big = expected >= 5
    observed = np.append(observed[big], observed[~big].sum())
    expected = np.append(expected[big], expected[~big].sum())
    keep = expected > 0
    statistic = float((((observed - expected) ** 2)[keep] / expected[keep]).sum())
    return statistic, int(keep.sum()) - 1


def cell_counts(points: np.ndarray, lows: np.ndarray, highs: np.ndarray, cells: int) -> np.ndarray:
    scaled = np.floor((points - lows) / (highs - lows) * cells).astype(int)
    scaled = np.clip(scaled, 0, cells - 1)
    flat = np.ravel_multi_index(scaled.T, (cells,) * points.shape[1])
    return np.bincount(flat, minlength=cells ** points.shape[1]).astype(float)


def points_inside(a, b, diameter, lows, highs, count: int) -> np.ndarray:
    """About ``count`` uniform points of the hyperspheroid, by rejection from the box
    (numpy's own generator, seeded: independent of the sampler under test)."""
    generator, found, total = np.random.default_rng(0), [], 0
    while total < count:
        box = generator.uniform(lows, highs, size=(count, len(a)))
        box = box[np.linalg.norm(box - np.array(a), axis=1)
                  + np.linalg.norm(box - np.array(b), axis=1) <= diameter]
        found.append(box)
        total += len(box)
    return np.concatenate(found)


@pytest.mark.parametrize("a, b, diameter", [
    ((1.0, 2.0), (4.0, 3.0), 4.0),                   # oblique in the plane
    ((0.0, 0.0), (0.0, -2.0), 2.5),                  # along an axis, pointing down
    ((0.5, 0.5), (0.5, 0.5), 1.0),                   # a disc (equal foci)
    ((0.0, 1.0, 2.0), (2.0, -1.0, 3.0), 3.5),        # 3-D
])
def test_hyperspheroid_draws_lie_inside_and_are_uniform(a, b, diameter):
    spheroid = ProlateHyperspheroid(a, b)
    rng = random.Random(7)
    draws = np.array([spheroid.sample(rng, diameter) for _ in range(10000)])
    sums = (np.linalg.norm(draws - np.array(a), axis=1)
            + np.linalg.norm(draws - np.array(b), axis=1))
    assert sums.max() <= diameter * (1 + 1e-12)
    # Expected share of each cell of a box around it: numpy's uniform points of the
    # box that fall inside, 30 times as many as the draws.
    n, half = len(a), diameter / 2
    centre = (np.array(a) + np.array(b)) / 2
    lows, highs = centre - half, centre + half
    inside = points_inside(a, b, diameter, lows, highs, 30 * len(draws))
    cells = 8 if n == 2 else 4
    expected = cell_counts(inside, lows, highs, cells) / len(inside) * len(draws)
    statistic, dof = chi_square(cell_counts(draws, lows, highs, cells), expected)
    assert statistic < critical_value(dof), (statistic, dof)


def test_a_radius_drawn_uniformly_would_fail_the_uniformity_test():
    # The test above can fail: points at radius U (not sqrt U) crowd the centre.
    rng = random.Random(7)
    draws = []
    for _ in range(20000):
        angle, radius = rng.random() * 2 * math.pi, rng.random()
        draws.append((radius * math.cos(angle), radius * math.sin(angle)))
    lows, highs = np.array([-1.0, -1.0]), np.array([1.0, 1.0])
    inside = points_inside((0.0, 0.0), (0.0, 0.0), 2.0, lows, highs, 30 * len(draws))
    expected = cell_counts(inside, lows, highs, 8) / len(inside) * len(draws)
    statistic, dof = chi_square(cell_counts(np.array(draws), lows, highs, 8), expected)
    assert statistic > critical_value(dof)


def test_measures():
    assert unit_ball_measure(2) == pytest.approx(math.pi)
    assert unit_ball_measure(3) == pytest.approx(4 * math.pi / 3)
    spheroid = ProlateHyperspheroid((0.0, 0.0), (3.0, 4.0))  # foci 5 apart
    assert spheroid.radii(13.0) == (6.5, 6.0)
    assert spheroid.measure(13.0) == pytest.approx(math.pi * 6.5 * 6.0)


def family_setup(name: str):
    return kinoplan_setup(parse_kinoplan((FAMILY / f"{name}.kp").read_text()))


def informed_draws(setup, cost: float, count: int, seed: int) -> np.ndarray:
    sampler = InformedSampler(setup.si, setup.pdef, random.Random(seed))
    draws = []
    while len(draws) < count:
        state = sampler.sample(cost)
        if state is not None:
            draws.append(state)
    return np.array(draws)


def rejection_draws(setup, cost: float, count: int, seed: int) -> np.ndarray:
    """The brute force: uniform states, kept when the heuristic is at most ``cost``."""
    heuristic, rng, draws = SolutionHeuristic(setup.si, setup.pdef), random.Random(seed), []
    while len(draws) < count:
        state = setup.si.sample_target(rng)
        if heuristic(state) <= cost:
            draws.append(state)
    return np.array(draws)


@pytest.mark.parametrize("name, factor", [("rigid2-scene3", 1.3), ("rigid2-scene1", 1.25)])
def test_rigid2_draws_are_uniform_over_the_informed_set(name, factor):
    # rigid2-scene3 turns by 3.03 rad: the heading's share narrows the ellipse.
    setup = family_setup(name)
    si, pdef = setup.si, setup.pdef
    assert euclidean_group(si.space) == ((0, 1), 0.7)
    heuristic = SolutionHeuristic(si, pdef)
    cost = factor * heuristic(pdef.start)
    sampler = InformedSampler(si, pdef, random.Random(1))
    diameter = (cost + pdef.goal.tolerance - sampler.rest) / sampler.weight
    assert sampler.spheroid.measure(diameter) < sampler.box_measure  # drawn directly
    direct = informed_draws(setup, cost, 4000, seed=2)
    assert max(heuristic(tuple(s)) for s in direct) <= cost
    brute = rejection_draws(setup, cost, 4000, seed=3)
    lows = np.array([v.low for v in si.space.variables])
    highs = np.array([v.high for v in si.space.variables])
    counts = [cell_counts(draws, lows, highs, 4) for draws in (direct, brute)]
    # Two samples of equal size: sum (a - b)^2 / (a + b) is chi-square.
    both = counts[0] + counts[1]
    statistic = float((((counts[0] - counts[1]) ** 2)[both > 0] / both[both > 0]).sum())
    assert statistic < critical_value(int((both > 0).sum()) - 1)


def test_arm2_has_no_euclidean_group_and_falls_back_to_rejection():
    setup = family_setup("arm2-pair1")
    si, pdef = setup.si, setup.pdef
    assert euclidean_group(si.space) is None
    heuristic = SolutionHeuristic(si, pdef)
    lowest = heuristic(pdef.start)
    sampler = InformedSampler(si, pdef, random.Random(4))
    assert sampler.indices == ()
    draws = [sampler.sample(1.2 * lowest) for _ in range(500)]
    assert all(heuristic(s) <= 1.2 * lowest for s in draws if s is not None)
    assert sum(s is not None for s in draws) > 400
    # Below every path's cost nothing qualifies: the draw gives up.
    assert sampler.sample(0.9 * lowest) is None


def test_point_draws_print_strictly_inside_the_map_and_before_a_solution_are_uniform():
    setup = grid_setup(parse_problem((COURSE_DIR / "space-2.sw").read_text()), "point")
    si, pdef = setup.si, setup.pdef
    sampler = InformedSampler(si, pdef, random.Random(5))
    assert sampler.sample(math.inf) == si.sample_target(random.Random(5))
    heuristic = SolutionHeuristic(si, pdef)
    cost = 1.5 * heuristic(pdef.start)  # an ellipse wider than the map's bottom rows
    for state in informed_draws(setup, cost, 3000, seed=6):
        assert si.world.point_strictly_inside(*state) and heuristic(tuple(state)) <= cost


def test_the_heuristic_never_exceeds_a_path_through_the_state_into_the_goal_region():
    setup = grid_setup(parse_problem((COURSE_DIR / "space-1.sw").read_text()), "point")
    si, goal = setup.si, setup.pdef.goal
    heuristic, rng = SolutionHeuristic(si, setup.pdef), random.Random(8)
    gx, gy = goal.point
    for _ in range(2000):
        state = si.sample_target(rng)
        angle, radius = rng.random() * 2 * math.pi, goal.tolerance * math.sqrt(rng.random())
        end = (gx + radius * math.cos(angle), gy + radius * math.sin(angle))
        path = si.distance(setup.pdef.start, state) + si.distance(state, end)
        assert heuristic(state) <= path + 1e-12
    # It is tight on the way: a state on the segment to the goal's edge.
    assert heuristic(goal.point) == pytest.approx(si.distance(setup.pdef.start, goal.point))
