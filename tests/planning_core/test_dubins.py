"""Dubins paths (planning_core.dubins): each word against its own curve, the shortest
against all six, known lengths, and the symmetries a wrong formula would break."""

import math
import random

import pytest

from planning_core import dubins
from planning_core.dubins import WORDS, all_words, shortest, word_path

RADII = (0.5, 2.0, 0.07)


def _poses(seed: int, count: int):
    rng = random.Random(seed)
    for _ in range(count):
        yield ((rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(0, 2 * math.pi)),
               (rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(0, 2 * math.pi)),
               rng.choice(RADII))


def _integrated(path: dubins.DubinsPath, pieces: int = 4000) -> tuple[float, tuple]:
    """The curve's length as the sum of ``pieces`` chords, and where it ends."""
    points = [path.pose_at(path.length * k / pieces) for k in range(pieces + 1)]
    return (math.fsum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:])),
            points[-1])


def _gap(a, b) -> float:
    return max(abs(a[0] - b[0]), abs(a[1] - b[1]), abs(math.remainder(a[2] - b[2], 2 * math.pi)))


def test_each_word_reaches_its_end_and_its_length_is_its_curves():
    seen = set()
    for a, b, radius in _poses(1, 10):
        for path in all_words(a, b, radius):
            seen.add(path.word)
            length, end = _integrated(path)
            assert _gap(end, b) < 1e-9, (path.word, a, b, radius)
            # chords fall short of the arcs by O(step^2 / radius): well under 1e-5 here
            assert length == pytest.approx(path.length, rel=1e-5, abs=1e-9), path.word
    assert seen == set(WORDS)


def test_shortest_is_the_least_of_the_six():
    for a, b, radius in _poses(2, 400):
        lengths = [p.length for p in all_words(a, b, radius)]
        assert shortest(a, b, radius).length == min(lengths)


def test_known_lengths():
    r = 0.5
    assert shortest((0, 0, 0), (3, 0, 0), r).length == pytest.approx(3.0)
    # a half turn to the left onto the parallel lane 2r over
    half = shortest((0, 0, 0), (0, 2 * r, math.pi), r)
    assert half.length == pytest.approx(math.pi * r) and half.word[0] == "L"
    assert shortest((0, 0, 0), (0, -2 * r, math.pi), r).length == pytest.approx(math.pi * r)
    # a quarter turn right, then straight
    assert shortest((0, 0, 0), (r, -r - 1.0, -math.pi / 2), r).length == pytest.approx(
        math.pi * r / 2 + 1.0)
    # the same pose: nothing to drive
    assert shortest((1, 1, 1), (1, 1, 1), r).length == pytest.approx(0.0, abs=1e-12)
    # just behind, same heading: LRL/RLR-sized loop, longer than 2 pi r
    assert shortest((0, 0, 0), (-0.1, 0, 0), r).length > 2 * math.pi * r


def test_reversed_travel_and_mirror_symmetries():
    """The path a -> b driven backward is reverse(b) -> reverse(a), same length; the
    mirror image (y -> -y, heading -> -heading) swaps L and R, same length."""
    swap = str.maketrans("LR", "RL")
    for a, b, radius in _poses(3, 300):
        forward = shortest(a, b, radius)
        back = shortest((b[0], b[1], b[2] + math.pi), (a[0], a[1], a[2] + math.pi), radius)
        assert back.length == pytest.approx(forward.length, rel=1e-9, abs=1e-9)
        mirrored = [word_path(w, (a[0], -a[1], -a[2]), (b[0], -b[1], -b[2]), radius)
                    for w in WORDS]
        for original in all_words(a, b, radius):
            image = mirrored[WORDS.index(original.word.translate(swap))]
            assert image is not None
            assert image.length == pytest.approx(original.length, rel=1e-9, abs=1e-9)


def test_length_scales_with_the_radius_and_bounds_the_straight_distance():
    for a, b, radius in _poses(4, 200):
        path = shortest(a, b, radius)
        assert path.length >= math.dist(a[:2], b[:2]) * (1 - 1e-12)
        scaled = shortest(tuple(v * 3 for v in a[:2]) + (a[2],),
                          tuple(v * 3 for v in b[:2]) + (b[2],), 3 * radius)
        assert scaled.length == pytest.approx(3 * path.length, rel=1e-9, abs=1e-9)


def test_a_free_heading_is_at_least_as_short_as_any_candidate():
    for a, b, radius in _poses(5, 100):
        free = shortest(a[:2], b, radius)
        assert free.length <= shortest((a[0], a[1], 0.0), b, radius).length
        assert free.length >= math.dist(a[:2], b[:2]) * (1 - 1e-12)
        assert _gap(free.end(), b) < 1e-9
    assert shortest((0, 0), (3, 4, math.atan2(4, 3)), 1.0).length == pytest.approx(5.0)
    to_free = shortest((0, 0, 0.3), (5, 1), 0.5)
    assert math.dist(to_free.end()[:2], (5, 1)) < 1e-9


@pytest.mark.parametrize("radius", RADII)
def test_a_quarter_circle_or_a_line_ahead_is_its_own_shortest_path(radius):
    """Poses one quarter circle apart (left or right) or straight ahead: the shortest
    path is that arc or line alone. Rounding once made a quarter circle's shortest
    path a whole circle and a quarter (a zero turn wrapped to 2 pi, a touching
    tangent's square a hair below zero), which left the cell a maze's corner allows."""
    for k in range(4):
        heading = k * math.pi / 2
        x, y = 3.0 + k, 0.5 * k  # exact halves, as the grid's guided targets
        ahead = (math.cos(heading), math.sin(heading))
        left = (-ahead[1], ahead[0])
        for side in (1.0, -1.0):
            end = (x + radius * (ahead[0] + side * left[0]), y + radius * (ahead[1] + side * left[1]),
                   dubins.mod2pi(heading + side * math.pi / 2))
            path = shortest((x, y, heading), end, radius)
            assert path.length == pytest.approx(radius * math.pi / 2, rel=1e-12)
            assert _gap(path.end(), end) < 1e-9
        line = shortest((x, y, heading), (x + 3 * ahead[0], y + 3 * ahead[1], heading), radius)
        assert line.length == pytest.approx(3.0, rel=1e-12)


def test_the_samples_are_pose_at_bit_for_bit():
    """sample_positions (what the planners check and print) against pose_at at the
    same fractions, exactly; ends of segments included."""
    for a, b, radius in _poses(7, 300):
        path = shortest(a, b, radius)
        pieces = dubins.sample_count(path.length, 0.05)
        expected = [path.pose_at(path.length * k / pieces)[:2] for k in range(1, pieces)]
        assert list(dubins.sample_positions(path, pieces)) == expected
    quarter = shortest((1.0, 0.5, 0.0), (1.5, 1.0, math.pi / 2), 0.5)
    assert list(dubins.sample_positions(quarter, 2)) == [quarter.pose_at(quarter.length / 2)[:2]]
