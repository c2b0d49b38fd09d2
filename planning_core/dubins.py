"""Dubins paths (Dubins 1957): the shortest curves of bounded curvature between two
poses (x, y, heading) for a car that only drives forward, in the closed forms of
Shkel and Lumelsky (2001), as Walker's and OMPL's libraries state them.

A shortest path is one of six words of at most three segments, each a left turn
(L), a right turn (R) or a straight line (S): LSL, RSR, LSR, RSL, RLR, LRL.
Lengths are in map units; a word's three segment lengths are stored in units of
the radius (an arc's angle in radians, a line's length over the radius).

A pose may also leave its heading free: a 2-tuple ``(x, y)``. A path from such a
start takes the best of :data:`FREE_HEADINGS` evenly spaced headings and the
bearing toward the end; a path to such an end, the best of the same headings and
the bearing from the start. (The exact optimum with a free heading is a CS or CC
curve (Bui et al. 1994); the candidates keep one formula for both ends.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterator, Optional, Sequence

TWO_PI = 2.0 * math.pi
WORDS = ("LSL", "RSR", "LSR", "RSL", "RLR", "LRL")
TURN = {"L": 1.0, "S": 0.0, "R": -1.0}
WHOLE_TURN_SNAP = 1e-7
"""An arc this close below a whole turn (radians) is no arc: rounding turns a zero angle
into 2 pi minus a hair (a pose one quarter circle from another had a shortest path of
a circle and a quarter)."""
TANGENT_SLACK = 1e-14
"""A tangent's squared length down to ``-TANGENT_SLACK * (1 + d**2)`` is zero, not
missing: rounding, when two turning circles touch (the end then misses by ~1e-7 radii)."""
FREE_HEADINGS = 32
"""Candidate headings of a pose whose heading is free (besides the bearing)."""


def mod2pi(angle: float) -> float:
    """``angle`` in [0, 2 pi)."""
    wrapped = math.fmod(angle, TWO_PI)
    if wrapped < 0.0:
        wrapped += TWO_PI
    return 0.0 if wrapped >= TWO_PI else wrapped


@dataclass(frozen=True)
class DubinsPath:
    """One word's path from ``start``: three segments of ``lengths`` (radius units)."""

    start: tuple[float, float, float]
    word: str
    lengths: tuple[float, float, float]
    radius: float

    @property
    def length(self) -> float:
        """In map units."""
        return (self.lengths[0] + self.lengths[1] + self.lengths[2]) * self.radius

    def pose_at(self, s: float) -> tuple[float, float, float]:
        """The pose after arc length ``s`` (map units, clamped to the path)."""
        x, y, heading = self.start
        r = self.radius
        left = max(0.0, min(s, self.length)) / r
        for letter, piece in zip(self.word, self.lengths):
            step = min(piece, left)
            x, y, heading = advance(x, y, heading, TURN[letter], step, r)
            left -= step
            if left <= 0.0:
                break
        return (x, y, mod2pi(heading))

    def end(self) -> tuple[float, float, float]:
        return self.pose_at(self.length)


def advance(x: float, y: float, heading: float, turn: float, step: float,
            r: float) -> tuple[float, float, float]:
    """Drive ``step`` (radius units) from a pose: ``turn`` +1 left, -1 right, 0 straight."""
    if turn == 0.0:
        return (x + step * r * math.cos(heading), y + step * r * math.sin(heading), heading)
    after = heading + turn * step
    return (x + turn * r * (math.sin(after) - math.sin(heading)),
            y - turn * r * (math.cos(after) - math.cos(heading)), after)


def _arc(angle: float) -> float:
    """A segment's turn in [0, 2 pi), a hair short of a whole turn being none."""
    wrapped = mod2pi(angle)
    return 0.0 if TWO_PI - wrapped < WHOLE_TURN_SNAP else wrapped


def _tangent(p2: float, d: float) -> float:
    """A straight segment's length from its square, or -1 where it has none."""
    if p2 < 0.0:
        if p2 < -TANGENT_SLACK * (1.0 + d * d):
            return -1.0
        return 0.0
    return math.sqrt(p2)


_NONE = (-1.0, 0.0, 0.0)
""":func:`_lengths`' answer for a word without a path (plain floats, so that the
compiled build passes three lengths without making a tuple object)."""


def _word_lengths(word: str, d: float, a: float, b: float) -> Optional[tuple[float, float, float]]:
    """The segment lengths of ``word`` in the normalised frame (the end at distance
    ``d`` along the x axis, headings ``a`` and ``b``), or None where it has none."""
    lengths = _lengths(WORDS.index(word), d, a, b, math.sin(a), math.sin(b), math.cos(a),
                       math.cos(b), math.cos(a - b))
    return None if lengths[0] < 0.0 else lengths


def _lengths(word: int, d: float, a: float, b: float, sa: float, sb: float, ca: float,
             cb: float, cab: float) -> tuple[float, float, float]:
    """:func:`_word_lengths` of ``WORDS[word]`` given the frame's sines and cosines
    (computed once for all six words); :data:`_NONE` where it has none."""
    if word == 0:  # LSL
        p = _tangent(2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb), d)
        if p < 0.0:
            return _NONE
        turn = math.atan2(cb - ca, d + sa - sb)
        return (_arc(turn - a), p, _arc(b - turn))
    if word == 1:  # RSR
        p = _tangent(2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa), d)
        if p < 0.0:
            return _NONE
        turn = math.atan2(ca - cb, d - sa + sb)
        return (_arc(a - turn), p, _arc(turn - b))
    if word == 2:  # LSR
        p = _tangent(-2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb), d)
        if p < 0.0:
            return _NONE
        turn = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        return (_arc(turn - a), p, _arc(turn - b))
    if word == 3:  # RSL
        p = _tangent(-2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb), d)
        if p < 0.0:
            return _NONE
        turn = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        return (_arc(a - turn), p, _arc(b - turn))
    if word == 4:  # RLR
        c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0
        if abs(c) > 1.0:
            return _NONE
        p = mod2pi(TWO_PI - math.acos(c))
        t = _arc(a - math.atan2(ca - cb, d - sa + sb) + p / 2.0)
        return (t, p, _arc(a - b - t + p))
    # LRL
    c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0
    if abs(c) > 1.0:
        return _NONE
    p = mod2pi(TWO_PI - math.acos(c))
    t = _arc(-a + math.atan2(cb - ca, d + sa - sb) + p / 2.0)
    return (t, p, _arc(b - a - t + p))


def _frame(a: Sequence[float], b: Sequence[float], radius: float) -> tuple[float, float, float]:
    """The normalised frame: the distance in radii, and both headings from the bearing."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    d = math.hypot(dx, dy) / radius
    bearing = mod2pi(math.atan2(dy, dx)) if d > 0.0 else 0.0
    return d, mod2pi(a[2] - bearing), mod2pi(b[2] - bearing)


def word_path(word: str, a: Sequence[float], b: Sequence[float],
              radius: float) -> Optional[DubinsPath]:
    """The path of ``word`` from pose ``a`` to pose ``b``, or None where it has none."""
    lengths = _word_lengths(word, *_frame(a, b, radius))
    if lengths is None:
        return None
    return DubinsPath((a[0], a[1], a[2]), word, lengths, radius)


def all_words(a: Sequence[float], b: Sequence[float], radius: float) -> list[DubinsPath]:
    """Every word's path from pose ``a`` to pose ``b`` (those that exist)."""
    paths = (word_path(word, a, b, radius) for word in WORDS)
    return [path for path in paths if path is not None]


def shortest_between_poses(a: Sequence[float], b: Sequence[float],
                           radius: float) -> DubinsPath:
    """The shortest of the six words (ties: the first in :data:`WORDS`)."""
    d, ha, hb = _frame(a, b, radius)
    sa, sb, ca, cb, cab = math.sin(ha), math.sin(hb), math.cos(ha), math.cos(hb), math.cos(ha - hb)
    best, best_word, best_total = _NONE, -1, math.inf
    for word in range(6):
        lengths = _lengths(word, d, ha, hb, sa, sb, ca, cb, cab)
        if lengths[0] >= 0.0:
            total = lengths[0] + lengths[1] + lengths[2]
            if total < best_total:
                best, best_word, best_total = lengths, word, total
    assert best_word >= 0  # LSL or RSR always exists (Dubins 1957)
    return DubinsPath((a[0], a[1], a[2]), WORDS[best_word], best, radius)


def _candidate_headings(bearing: float) -> Iterator[float]:
    yield bearing
    for k in range(FREE_HEADINGS):
        yield TWO_PI * k / FREE_HEADINGS


def shortest(a: Sequence[float], b: Sequence[float], radius: float) -> DubinsPath:
    """The shortest path from ``a`` to ``b``; a 2-tuple leaves that pose's heading free
    (the best of the candidate headings, module docstring)."""
    if len(a) == 3 and len(b) == 3:
        return shortest_between_poses(a, b, radius)
    bearing = mod2pi(math.atan2(b[1] - a[1], b[0] - a[0]))
    best: Optional[DubinsPath] = None
    for heading in _candidate_headings(bearing):
        start = (a[0], a[1], a[2] if len(a) == 3 else heading)
        end = (b[0], b[1], b[2] if len(b) == 3 else heading)
        path = shortest_between_poses(start, end, radius)
        if best is None or path.length < best.length:
            best = path
    assert best is not None
    return best


def sample_positions(path: DubinsPath, pieces: int) -> Iterator[tuple[float, float]]:
    """The positions ``path.length * k / pieces`` along ``path``, k = 1 .. pieces - 1
    (the inner samples of a curve cut into ``pieces``), lazily: a check stops early.
    Each is :meth:`DubinsPath.pose_at`'s, bit for bit, from its segment's start
    (found once) instead of from the path's."""
    r, length, lengths, word = path.radius, path.length, path.lengths, path.word
    starts = [path.start]
    for j in range(3):
        x, y, heading = starts[j]
        starts.append(advance(x, y, heading, TURN[word[j]], lengths[j], r))
    for k in range(1, pieces):
        left = max(0.0, min(length * k / pieces, length)) / r
        x, y = starts[3][0], starts[3][1]
        for j in range(3):
            if left <= lengths[j]:
                x0, y0, heading = starts[j]
                x, y, _ = advance(x0, y0, heading, TURN[word[j]], left, r)
                break
            left -= lengths[j]
        yield (x, y)


def sample_count(length: float, step: float) -> int:
    """Pieces of at most ``step`` that a path of ``length`` is cut into (at least 1)."""
    return max(1, math.ceil(length / step))
