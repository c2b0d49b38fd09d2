"""The shortest collision-free path for arm2: the yardstick its path costs are judged by.

arm2's configurations are two joint angles on the torus, and a path's cost is the sum
of the metric (``metric theta1,theta2 1``: the Euclidean length of the wrapped angle
differences) over its straight segments, each checked as the validator checks it
(``validator.checks``: ``si.is_valid`` at the samples of ``system.motion_samples``). The configuration-space obstacles are curved, so there is no
finite visibility graph as for the point (``benchmarks/shortest_path.py``). Instead:

1. **Grid search**: a ``resolution`` x ``resolution`` grid of configurations on the
   torus (wrapping), each tested by ``si.is_valid``; Dijkstra over 16 neighbours
   (the 8 around and the 8 a knight's move away, whose lengths are within 2.7% of any
   direction's), an edge joining two valid cells. The path found is checked motion by
   motion with the real check; an edge that fails is dropped and the search repeated.
2. **String pulling**: from each vertex, the farthest later vertex it reaches by one
   valid straight motion (fewer, longer segments; the path only shortens).
3. **Elastic refinement**, in rounds: segments are cut at most ``spacing`` long (a
   cut whose pieces are not valid at their own samples, along a curved obstacle, is
   made a hair to the side), every inner vertex slides toward the straight line
   between its neighbours as far as both its motions stay valid (halving the step
   until they do), vertices whose neighbours see each other are dropped; ``spacing``
   halves each round, down to ``min_spacing``. The rounds stop when one shortens the
   path by less than ``tolerance`` (0.1%) of its length.

What this guarantees: the path is valid by the validator's checks (every motion is
tested by them before it is kept), so its length is an upper bound of the true
shortest. It is a locally shortest path of the homotopy class the grid search picks
(every vertex pulled taut against the obstacles, bends spaced ``min_spacing`` or
less); the last round's fall bounds how much more the refinement would find, and the
grid search's 2.7% direction error can only pick a class whose shortest path is within
about 3% (plus a cell) of the best class's. The tests compare the length with
rrtstar's best 10 s answers (it must not be longer) and, on a torus without obstacles,
with the straight distance. The goal is a region (``within`` the tolerance of the
goal configuration): the path ends at the goal configuration itself, so an answer may
end up to that tolerance shorter.
"""

from __future__ import annotations

import functools
import heapq
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

from planning_core.kinoplan import KinoplanProblem
from planning_core.setups import kinoplan_setup

State = tuple[float, float]
TAU = 2 * math.pi
NEIGHBOURS = ((1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1),
              (2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2), (2, -1))
"""Grid steps of the search: any direction's length is within 2.7% of the best of these."""


@dataclass(frozen=True)
class Arm2Options:
    """How fine the search and the refinement are."""

    resolution: int = 256
    """Grid cells per angle (2 pi / resolution apart)."""
    min_spacing: float = 0.02
    """The refinement's last round cuts segments at most this long (radians)."""
    tolerance: float = 1e-3
    """The refinement stops when a round shortens the path by less than this share."""


@dataclass(frozen=True)
class Arm2ShortestPath:
    """The path found: its length (the metric's), its configurations (angles unwrapped,
    consecutive ones less than pi apart per angle, so each segment is the motion the
    validator checks) and the refinement's rounds' lengths."""

    length: float
    points: tuple[State, ...]
    rounds: tuple[float, ...]


def _distance(a: State, b: State) -> float:
    """The length of the straight segment a -> b of the lifted plane."""
    return math.hypot(b[0] - a[0], b[1] - a[1])


def path_length(points) -> float:
    return sum(_distance(a, b) for a, b in zip(points, points[1:]))


class _Search:
    """The problem's validity and motion check, on the lifted plane."""

    def __init__(self, problem: KinoplanProblem):
        setup = kinoplan_setup(problem)
        self.si = setup.si
        self.samples = setup.si.system.motion_samples
        self.start = tuple(setup.pdef.start)
        self.goal = tuple(setup.pdef.goal.target)

    def valid(self, state: State) -> bool:
        return self.si.is_valid(state)

    def free(self, a: State, b: State) -> bool:
        """Whether the straight motion a -> b passes the validator's check (a and b less
        than pi apart per angle, so that it is the segment of the lifted plane). The
        planners' ``first_hit`` (fast, with clearance skips) rules out most motions; one
        it passes is tested at the validator's own samples (``system.motion_samples``,
        ``si.is_valid``): the refined path runs along the obstacles, where a sample
        computed another way may land on the other side of a boundary."""
        if max(abs(b[0] - a[0]), abs(b[1] - a[1])) >= math.pi:
            return False
        valid = self.si.is_valid
        return (valid(a) and self.si.first_hit(a, b) is None
                and all(valid(state) for state in self.samples(a, b)))


def _grid_path(search: _Search, resolution: int) -> list[State] | None:
    """Start, the grid path's cells (lifted to follow on from each other), goal."""
    step = TAU / resolution
    cell = lambda s: (round(s[0] / step) % resolution, round(s[1] / step) % resolution)  # noqa: E731
    valid = {}

    def is_free(c):
        if c not in valid:
            valid[c] = search.valid((c[0] * step, c[1] * step))
        return valid[c]

    source, target = cell(search.start), cell(search.goal)
    blocked_edges: set = set()
    while True:
        chain = _dijkstra(source, target, resolution, is_free, blocked_edges)
        if chain is None:
            return None
        points = _lift(search.start, chain, step)
        points.append(_lift_to(points[-1], search.goal))
        bad = [i for i in range(len(points) - 1) if not search.free(points[i], points[i + 1])]
        if not bad:
            return points
        if bad[0] == 0 or bad[-1] == len(points) - 2:  # the start or goal cannot reach its cell
            return None
        for i in bad:
            blocked_edges.add((chain[i - 1], chain[i]))


def _dijkstra(source, target, resolution, is_free, blocked_edges) -> list | None:
    """The cells of the cheapest 16-neighbour chain from source to target on the torus."""
    if not (is_free(source) and is_free(target)):
        return None
    cost, parent = {source: 0.0}, {source: None}
    frontier, closed = [(0.0, source)], set()
    while frontier:
        here_cost, here = heapq.heappop(frontier)
        if here in closed:
            continue
        closed.add(here)
        if here == target:
            chain = [here]
            while parent[chain[-1]] is not None:
                chain.append(parent[chain[-1]])
            return chain[::-1]
        for dx, dy in NEIGHBOURS:
            there = ((here[0] + dx) % resolution, (here[1] + dy) % resolution)
            if there in closed or not is_free(there) or (here, there) in blocked_edges:
                continue
            through = here_cost + math.hypot(dx, dy)
            if through < cost.get(there, math.inf):
                cost[there], parent[there] = through, here
                heapq.heappush(frontier, (through, there))
    return None


def _lift_to(previous: State, state: State) -> State:
    """``state`` turned by whole turns to lie within pi of ``previous`` per angle."""
    return tuple(p + math.remainder(s - p, TAU) for p, s in zip(previous, state))


def _lift(start: State, chain, step: float) -> list[State]:
    points = [start]
    for c in chain:
        points.append(_lift_to(points[-1], (c[0] * step, c[1] * step)))
    return points


def _pull(search: _Search, points: list[State]) -> list[State]:
    """String pulling: from each kept vertex, the farthest later one in one motion."""
    kept, here = [points[0]], 0
    while here < len(points) - 1:
        there = here + 1
        while there + 1 < len(points) and search.free(points[here], points[there + 1]):
            there += 1
        kept.append(points[there])
        here = there
    return kept


def _subdivide(search: _Search, points: list[State], spacing: float) -> list[State]:
    """Each segment cut into pieces at most ``spacing`` long, where every piece is valid
    (a piece is checked at samples of its own, not the segment's: one may touch)."""
    out = [points[0]]
    for a, b in zip(points, points[1:]):
        pieces = max(1, math.ceil(_distance(a, b) / spacing))
        cut = [(a[0] + (b[0] - a[0]) * k / pieces, a[1] + (b[1] - a[1]) * k / pieces)
               for k in range(1, pieces)]
        ends = [a, *cut, b]
        if all(search.free(p, q) for p, q in zip(ends, ends[1:])):
            out += cut
        elif pieces > 1:  # a piece's own samples touch: a midpoint a little to one side
            out += _offset_midpoint(search, a, b)
        out.append(b)
    return out


OFFSETS = (0.001, -0.001, 0.003, -0.003, 0.01, -0.01)
"""Radians a refused cut may move off its segment, tried in turn (either side)."""


def _offset_midpoint(search: _Search, a: State, b: State) -> list[State]:
    """A point beside the middle of a -> b from which both halves are valid, or none.
    A segment that runs along a curved obstacle, valid at its own samples, cannot be
    cut on itself; cut a hair to its side, the next slides pull it taut again."""
    length = _distance(a, b)
    normal = ((a[1] - b[1]) / length, (b[0] - a[0]) / length)
    for offset in OFFSETS:
        middle = ((a[0] + b[0]) / 2 + offset * normal[0], (a[1] + b[1]) / 2 + offset * normal[1])
        if search.free(a, middle) and search.free(middle, b):
            return [middle]
    return []


def _slide(search: _Search, points: list[State], halvings: int = 8) -> list[State]:
    """One sweep: each inner vertex moved toward the nearest point of the segment between
    its neighbours, by the longest of 1, 1/2, 1/4, ... of the way keeping both motions
    valid (or not at all)."""
    points = list(points)
    for i in range(1, len(points) - 1):
        a, v, b = points[i - 1], points[i], points[i + 1]
        ab = (b[0] - a[0], b[1] - a[1])
        span = ab[0] ** 2 + ab[1] ** 2
        t = 0.5 if span == 0 else min(1.0, max(0.0, ((v[0] - a[0]) * ab[0]
                                                     + (v[1] - a[1]) * ab[1]) / span))
        aim = (a[0] + t * ab[0], a[1] + t * ab[1])
        share = 1.0
        for _ in range(halvings):
            moved = (v[0] + share * (aim[0] - v[0]), v[1] + share * (aim[1] - v[1]))
            if search.free(a, moved) and search.free(moved, b):
                points[i] = moved
                break
            share /= 2
    return points


def _prune(search: _Search, points: list[State]) -> list[State]:
    """Vertices whose neighbours see each other dropped, one pass."""
    kept = [points[0]]
    for i in range(1, len(points) - 1):
        if not search.free(kept[-1], points[i + 1]):
            kept.append(points[i])
    kept.append(points[-1])
    return kept


def _refine(search: _Search, points: list[State], options: Arm2Options
            ) -> tuple[list[State], list[float]]:
    """Rounds of cut, slide and prune; the lengths after each round."""
    spacing = 8 * TAU / options.resolution
    lengths = [path_length(points)]
    while True:
        candidate = _subdivide(search, points, spacing)
        for _ in range(4):
            candidate = _slide(search, candidate)
        candidate = _prune(search, candidate)
        length = path_length(candidate)
        if length <= lengths[-1]:  # a round never lengthens what it returns
            points = candidate
        fall = lengths[-1] - min(length, lengths[-1])
        lengths.append(min(length, lengths[-1]))
        if spacing <= options.min_spacing and fall < options.tolerance * lengths[-1]:
            return points, lengths
        spacing = max(options.min_spacing, spacing / 2)


def arm2_shortest_path(problem: KinoplanProblem, options: Arm2Options = Arm2Options()
                       ) -> Arm2ShortestPath | None:
    """The (near-)shortest valid path from start to the goal configuration, or None when
    the grid search finds none."""
    search = _Search(problem)
    points = _grid_path(search, options.resolution)
    if points is None:
        return None
    points, lengths = _refine(search, _pull(search, points), options)
    return Arm2ShortestPath(path_length(points), tuple(points), tuple(lengths))


@functools.lru_cache(maxsize=None)
def arm2_shortest_length(path: Path) -> float | None:
    """The shortest path's length for the arm2 problem in ``path`` (cached per file: it
    takes seconds)."""
    from cli_common import parse_any_problem
    found = arm2_shortest_path(parse_any_problem(Path(path).read_text()))
    return found.length if found else None


def arm2_shortest_lengths(problem_ids: Iterable[str]) -> dict[str, float]:
    """The shortest path length of each named arm2 problem of ``benchmarks/problems/family``."""
    from benchmarks.family import family_problems, system_of
    wanted = set(problem_ids)
    lengths = {}
    for path in family_problems():
        if path.stem in wanted and system_of(path) == "arm2":
            length = arm2_shortest_length(path)
            if length is not None:
                lengths[path.stem] = length
    return lengths
