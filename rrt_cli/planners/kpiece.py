"""KPIECE1 for kinodynamic systems: Kinodynamic motion Planning by Interior-Exterior
Cell Exploration (I. A. Sucan and L. E. Kavraki, "Kinodynamic motion planning by
interior-exterior cell exploration", WAFR 2008; "A sampling-based tree planner
for systems with complex dynamics", IEEE Trans. Robotics 28(1), 2012).

KPIECE1 grows one tree of motions without a nearest-neighbour search and
without random targets. It lays a grid over a projection of the state (here the
position and the velocity by default, or the position alone) and keeps, per
grid cell, the motions that end in it. Each iteration:

1. picks a cell: an exterior cell (fewer than ``2 * dims`` axis neighbours in
   the grid) with probability ``max(border_fraction, share of exterior cells)``,
   else an interior one; within the chosen group, the cell of highest
   importance ``score / ((neighbours + 1) * coverage * selections)``, where
   ``score`` starts at ``(1 + log(iteration of creation)) / (0.001 + distance to
   goal)`` (measured along the free cells by default, see below) and shrinks
   by ``good_score_factor`` after each successful expansion from the cell and
   by ``bad_score_factor`` after each failed one;
2. picks a motion of that cell, by a half-normal distribution favouring the
   newest ones (with probability ``goal_bias``, instead, the motion closest to
   the goal among the ``close_samples`` closest, whose recorded distance is then
   inflated so that the others get their turn);
3. applies one random control for a random duration, as long as every slice
   is valid (``si.random_motion``: on the grid's ships a control held for 1 to
   10 steps, in the family a control held for K in [KMIN, KMAX] slices; a
   goal-biased expansion instead holds the best of ``goal_controls`` random
   controls toward the goal: a departure from the paper, see
   ``KPIECEParams.goal_controls``; ``goal_controls=1`` restores it);
4. adds the motion if it is "interesting" (it reaches a new cell or a cell with
   less than two thirds of the average coverage, else with probability 0.05),
   then rewards or penalises the start cell.

The grid's output format holds one control for exactly one step per tree edge
(SPEC 2), so there a motion of ``k`` steps becomes ``k`` chained tree nodes, each
filed in the cell of its own state (OMPL splits motions at cell boundaries to the
same end); in the family a motion is one node. A node in the goal region ends the
search.

The second departure: "distance to goal" (cell scores, close motions, goal
steering) is by default measured along free space where the world offers it
(``KPIECEParams.goal_distance``; the grid's free cells), not in a straight line,
so on a maze the search is drawn along the corridors that lead to the goal rather
than into the wall nearest it. OMPL leaves this to the goal's own distance
function, which is ours to define; ``goal_distance="euclidean"`` (and every
family problem: there are no cells to walk) takes the goal's own distance. The
goal test itself is always the goal region's.

The grid is laid over ``si.projection()`` (as OMPL's default projection of a state
space): the grid's ships project on position and velocity, the family's systems
on their ``projection_names`` (the pendulum (theta, omega), the cars (x, y)).
docs/planners-family.md has the family's measurements.

The design follows OMPL's ``control::KPIECE1`` (read for ideas, not copied).
"""

from __future__ import annotations

import math
import random
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Final, Optional, cast

from planning_core.heap import HeapEntry, heap_pop, heap_push, heapify
from planning_core.interrupt import Stop
from planning_core.problem_definition import ProblemDefinition
from planning_core.samplers import gauss, uniform
from planning_core.space_information import ControlSpaceInformation
from rrt_cli.planners.base import PlanResult, StopCondition, guarded
from rrt_cli.planners.tree import MotionTree, TreeSearch, run_tree_search

if TYPE_CHECKING:  # for the annotation only: nothing more imported at run time
    from planning_core.worlds.grid_distance import CellDistanceToGoal

# Keeps the initial score finite for a cell that contains the goal (as OMPL does).
_GOAL_DISTANCE_OFFSET: Final = 1e-3
# Each selection of a close-to-goal motion inflates its distance by this factor.
_CLOSE_SAMPLE_INFLATION: Final = 1.1
# Share of uninteresting motions that are kept anyway.
_KEEP_UNINTERESTING: Final = 0.05
# A cell score below this lifts every score (scores only shrink; _select_cell).
_EPSILON: Final = sys.float_info.epsilon


@dataclass(frozen=True)
class KPIECEParams:
    """KPIECE1's settings (``-planner kpiece``). The projection and a random
    motion's duration are the space information's (``si.projection``,
    ``si.random_motion``), as in OMPL."""

    goal_bias: float = 0.05
    """Probability of expanding the motion closest to the goal instead of a
    cell's motion (OMPL's default, 0.05)."""
    border_fraction: float = 0.8
    """Minimum probability of choosing an exterior cell (the paper's and OMPL's 0.8)."""
    good_score_factor: float = 0.9
    """A cell's score is multiplied by this after a successful expansion."""
    bad_score_factor: float = 0.45
    """A cell's score is multiplied by this after a failed expansion."""
    close_samples: int = 30
    """How many motions closest to the goal are kept for the goal bias."""
    prune_uninteresting: bool = True
    """Drop 95 % of the motions that only reach well-covered cells (as OMPL does)."""
    goal_controls: int = 10
    """Controls tried in a goal-biased expansion (each as ``si.sample_control`` draws
    it), the valid one ending nearest the goal kept; 1 is the published algorithm."""

    goal_distance: str = "cells"
    """"cells": distance to the goal along free space, where the world offers it
    (cell scores, close motions, goal steering); "euclidean": the goal's own distance
    (the paper's)."""

    def __post_init__(self):
        if self.goal_distance not in ("euclidean", "cells"):
            raise ValueError("goal_distance must be 'euclidean' or 'cells'")
        for name in ("good_score_factor", "bad_score_factor", "border_fraction"):
            if not 0.0 < getattr(self, name) <= 1.0:
                raise ValueError(f"{name} must be in (0, 1]")
        if self.goal_controls < 1:
            raise ValueError("goal_controls must be at least 1")


Params = KPIECEParams


class _Cell:
    """One projection cell: its motions and the numbers its importance is made of."""

    __slots__ = ("key", "motions", "coverage", "selections", "score", "created",
                 "neighbors", "importance", "version")

    def __init__(self, key: object, score: float, created: int):
        self.key = key
        """Its coordinates as :func:`_cell_key` packs them."""
        self.motions: list[int] = []
        self.coverage = 0
        self.selections = 1
        self.score = score
        self.created = created
        self.neighbors = 0
        self.importance = 0.0
        self.version = 0


class _HeapEntry(HeapEntry):
    """A cell in a heap as it was when pushed: by ``key``, the negated importance,
    then ``order``, the push counter (unique, so runs are reproducible)."""

    __slots__ = ("version", "cell")

    def __init__(self, key: float, order: int, version: int, cell: _Cell) -> None:
        super().__init__(key, order)
        self.version = version
        self.cell = cell


class _CellGrid:
    """The grid over the projection, split into exterior and interior cells.

    Each group is a max-heap by importance with lazy deletion: an update pushes
    a fresh entry and bumps the cell's version, and stale entries are dropped
    when they reach the top.
    """

    def __init__(self, dims: int):
        self.cells: dict[object, _Cell] = {}  # by _cell_key
        self.dims = dims
        self.full = 2 * dims  # axis neighbours of an interior cell
        self.exterior: list[HeapEntry] = []  # of _HeapEntry
        self.interior: list[HeapEntry] = []
        self.exterior_count = 0
        self._pushes = 0
        # The axis neighbours, in this order: +1 then -1 along each axis in turn.
        self._steps: list[tuple[int, int]] = [(axis, sign) for axis in range(dims)
                                              for sign in (1, -1)]

    def is_interior(self, cell: _Cell) -> bool:
        return cell.neighbors >= self.full

    def update(self, cell: _Cell) -> None:
        cell.importance = cell.score / ((cell.neighbors + 1) * cell.coverage * cell.selections)
        cell.version += 1
        self._pushes += 1
        heap = self.interior if self.is_interior(cell) else self.exterior
        # The push counter breaks ties in creation order, so runs are reproducible.
        heap_push(heap, _HeapEntry(-cell.importance, self._pushes, cell.version, cell))
        if self._pushes > 8 * len(self.cells) + 64:
            self.rebuild()

    def add(self, cell: _Cell) -> None:
        self.cells[cell.key] = cell
        self.exterior_count += 1
        key = cell.key
        for axis, sign in self._steps:
            other = self.cells.get(self.neighbour_key(key, axis, sign))
            if other is None:
                continue
            cell.neighbors += 1
            was_interior = self.is_interior(other)
            other.neighbors += 1
            if not was_interior and self.is_interior(other):
                self.exterior_count -= 1
            self.update(other)
        if self.is_interior(cell):
            self.exterior_count -= 1
        self.update(cell)

    def neighbour_key(self, key: object, axis: int, sign: int) -> object:
        """The key of the cell one step (``sign``, 1 or -1) along ``axis``."""
        if isinstance(key, int):
            shift = _KEY_BITS * axis
            moved = ((key >> shift) & _KEY_MASK) - _KEY_OFFSET + sign
            if -_KEY_LIMIT <= moved <= _KEY_LIMIT:
                return key + (sign << shift)
            coord = tuple([((key >> (_KEY_BITS * i)) & _KEY_MASK) - _KEY_OFFSET
                           for i in range(self.dims)])
        else:
            coord = cast(tuple, key)
        near = list(coord)
        near[axis] += sign
        return _cell_key(tuple(near))

    def top(self, exterior: bool) -> _Cell | None:
        heap = self.exterior if exterior else self.interior
        while heap:
            top = cast(_HeapEntry, heap[0])
            version, cell = top.version, top.cell
            if version == cell.version and self.is_interior(cell) != exterior:
                return cell
            heap_pop(heap)
        return None

    def rebuild(self) -> None:
        """Recompute every importance and drop stale heap entries."""
        self.exterior, self.interior, self._pushes = [], [], 0
        for cell in self.cells.values():
            cell.importance = cell.score / ((cell.neighbors + 1) * cell.coverage
                                            * cell.selections)
            cell.version += 1
            self._pushes += 1
            entry = _HeapEntry(-cell.importance, self._pushes, cell.version, cell)
            (self.interior if self.is_interior(cell) else self.exterior).append(entry)
        heapify(self.exterior)
        heapify(self.interior)


# A cell's key packs up to four coordinates into one int, _KEY_BITS each (offset to
# be non-negative) while every |coordinate| is at most _KEY_LIMIT (the neighbours then
# pack too); past that it is the coordinate tuple. One key per cell either way.
_KEY_BITS: Final = 15
_KEY_OFFSET: Final = 1 << (_KEY_BITS - 1)
_KEY_LIMIT: Final = _KEY_OFFSET - 2
_KEY_MASK: Final = (1 << _KEY_BITS) - 1


def _cell_key(coord: tuple[int, ...]) -> object:
    """The cells' dict key of ``coord``: an int, hashed and compared at once
    (a tuple key cost a tuple built and hashed for each of a new cell's neighbours)."""
    if len(coord) > 4:
        return coord
    key = 0
    for i in range(len(coord)):
        c = coord[i]
        if c < -_KEY_LIMIT or c > _KEY_LIMIT:
            return coord
        key |= (c + _KEY_OFFSET) << (_KEY_BITS * i)
    return key


class _CloseSamples:
    """The motions closest to the goal, as a bounded sorted list of (distance, node)."""

    def __init__(self, capacity: int):
        self.capacity = capacity
        self.items: list[tuple[float, int]] = []

    def consider(self, node: int, distance: float) -> None:
        items = self.items
        if len(items) >= self.capacity:
            if items[-1][0] <= distance:
                return
            items.pop()
        # (distance, node): ties go to the older node, deterministically.
        items.insert(_bisect(items, (distance, node)), (distance, node))

    def select(self) -> int | None:
        if not self.items:
            return None
        distance, node = self.items.pop(0)
        worst = self.items[-1][0] if self.items else distance
        self.consider(node, (distance + worst) * _CLOSE_SAMPLE_INFLATION / 2.0)
        return node


def _bisect(items: list, item) -> int:
    lo, hi = 0, len(items)
    while lo < hi:
        mid = (lo + hi) // 2
        if items[mid] < item:
            lo = mid + 1
        else:
            hi = mid
    return lo


class _Search(TreeSearch):
    """One KPIECE1 run: the tree, the projection grid and the close-to-goal motions."""

    def __init__(self, si: ControlSpaceInformation, pdef: ProblemDefinition,
                 rng: random.Random, params: KPIECEParams, stop: Stop = None):
        self.si, self.rng, self.params = si, rng, params
        self.project = si.projection()
        self.start = pdef.start
        self.grid = _CellGrid(len(self.project(pdef.start)))
        self.close = _CloseSamples(params.close_samples)
        self.tree = MotionTree(pdef.start)
        self.goal = pdef.goal
        self.node_cells: list[_Cell] = []
        self.iterations = 0
        # Position -> distance along the free cells, where the world offers it.
        self.along: Optional[CellDistanceToGoal] = (
            si.distance_along_free_space(pdef.goal, stop) if params.goal_distance == "cells"
            else None)

    def goal_distance(self, state: Sequence[float]) -> float:
        """The distance to the goal that scores cells and ranks close motions."""
        along = self.along
        if along is not None:
            return along(state[0], state[1])
        return self.goal.distance(state)

    def file_node(self, node: int, key: object, distance: float) -> None:
        """Put a node in its cell (by its key, made on first use); one step of coverage."""
        cell = self.grid.cells.get(key)
        if cell is None:
            created = self.iterations + 1  # the start's cell: 1
            cell = _Cell(key, (1.0 + math.log(float(created)))
                         / (_GOAL_DISTANCE_OFFSET + distance), created)
            cell.motions.append(node)
            cell.coverage = 1
            self.grid.add(cell)
        else:
            cell.motions.append(node)
            cell.coverage += 1
            self.grid.update(cell)
        self.node_cells.append(cell)

    def pick(self) -> tuple[int, _Cell, bool]:
        """The node to expand, its cell, and whether to steer it toward the goal."""
        rng, params = self.rng, self.params
        node = self.close.select() if uniform(rng) < params.goal_bias else None
        if node is not None:
            return node, self.node_cells[node], params.goal_controls > 1
        cell = _select_cell(self.grid, rng, params.border_fraction)
        motions = cell.motions
        cell.selections += 1
        # Half-normal over the cell's motions, the newest most likely.
        back = int(abs(gauss(rng, 0.0, len(motions) / 3.0)))
        return motions[max(0, len(motions) - 1 - back)], cell, False

    def motion(self, state, steering: bool) -> tuple[object, list]:
        """A control and the valid states of the nodes it makes (maybe none)."""
        si, rng = self.si, self.rng
        if steering:
            control = _steer_to_goal(si, state, self.goal_distance,
                                     self.params.goal_controls, rng)
            end = None if control is None else si.propagate_valid(state, control)
            return control, ([] if end is None else [end])
        motion = si.random_motion(state, rng)
        return (None, []) if motion is None else motion

    def interesting(self, keys: list[object]) -> bool:
        """The motion reaches a new cell or one with under 2/3 of the average coverage."""
        cells = self.grid.cells
        two_thirds_average = (2 * len(self.tree)) / (3 * len(cells))
        for key in keys:
            cell = cells.get(key)
            if cell is None or cell.coverage <= two_thirds_average:
                return True
        return False

    def add_motion(self, node: int, control, steps, keys: list[object]) -> int | None:
        """Chain the motion's steps into the tree; the goal node, if one is reached."""
        for new_state, key in zip(steps, keys):
            node = self.tree.add(node, new_state, control)
            distance = self.goal_distance(new_state)
            self.file_node(node, key, distance)
            if self.goal.reached(new_state):
                return node
            self.close.consider(node, distance)
        return None

    def begin(self) -> None:
        """File the start in its cell and among the close motions."""
        start_distance = self.goal_distance(self.start)
        self.file_node(0, _cell_key(self.project(self.start)), start_distance)
        self.close.consider(0, start_distance)

    def iterate(self) -> int | None:
        """One expansion (steps 1-4 of the module docstring); a goal node or None."""
        params = self.params
        self.iterations += 1
        node, cell, steering = self.pick()
        control, steps = self.motion(self.tree.states[node], steering)
        if steps:
            keys = [_cell_key(self.project(s)) for s in steps]
            # A step steered to the goal is kept whatever the coverage: it is
            # there to close in on the goal, not to explore.
            keep = (steering or not params.prune_uninteresting or self.interesting(keys)
                    or uniform(self.rng) < _KEEP_UNINTERESTING)
            if keep:
                goal_node = self.add_motion(node, control, steps, keys)
                if goal_node is not None:
                    return goal_node
            cell.score *= params.good_score_factor
        else:
            cell.score *= params.bad_score_factor
        self.grid.update(cell)
        return None


@guarded
def solve(si: ControlSpaceInformation, pdef: ProblemDefinition, stop: StopCondition,
          rng: random.Random, params: KPIECEParams = KPIECEParams()) -> PlanResult:
    return run_tree_search(si, pdef, stop,
                           lambda: _Search(si, pdef, rng, params, stop.time_is_up), "KPIECE1")


def _steer_to_goal(si: ControlSpaceInformation, state, goal_distance, tries: int,
                   rng: random.Random):
    """The valid random control, of ``tries``, whose one step ends with the
    lowest ``goal_distance``."""
    best, best_distance = None, math.inf
    for _ in range(tries):
        control = si.sample_control(rng)
        end = si.propagate_valid(state, control)
        if end is None:
            continue
        distance = goal_distance(end)
        if distance < best_distance:
            best, best_distance = control, distance
    return best


def _select_cell(grid: _CellGrid, rng: random.Random, border_fraction: float) -> _Cell:
    exterior_share = grid.exterior_count / len(grid.cells)
    exterior = uniform(rng) < max(border_fraction, exterior_share)
    cell = grid.top(exterior) or grid.top(not exterior)
    assert cell is not None, "a grid with cells has a top cell"
    if cell.score < _EPSILON:
        # Scores only shrink; before they underflow, lift them all (as OMPL does).
        for other in grid.cells.values():
            other.score += 1.0 + math.log(float(other.created))
        grid.rebuild()
        cell = grid.top(exterior) or grid.top(not exterior)
        assert cell is not None
    return cell
