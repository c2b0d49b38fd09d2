"""The trees' frontier on the grid (planning_core.worlds.grid_frontier): which cells it
holds as nodes are added, and that its samples lie in those cells."""

import random

from planning_core.problem import Problem
from planning_core.worlds.grid_frontier import FrontierCells

# 4 x 3, row 0 at the bottom; '#' blocked:
#   row 2:  . . . .
#   row 1:  . # . .
#   row 0:  . . . #
ROWS = ["...#", ".#..", "...."]
BLOCKED = bytes(1 if ch == "#" else 0 for row in ROWS for ch in row)
PROBLEM = Problem(4, 3, BLOCKED, (0.5, 0.5), (3.5, 2.5))


def cells(frontier: FrontierCells) -> set[tuple[int, int]]:
    return {(cell % 4, cell // 4) for cell in frontier.cells}  # (column, row)


def test_a_node_puts_its_free_uncovered_side_neighbours_on_the_frontier():
    frontier = FrontierCells(PROBLEM)
    frontier.cover((0.5, 0.5))
    # (1, 1) is diagonal, and blocked anyway; only side neighbours count.
    assert cells(frontier) == {(1, 0), (0, 1)}


def test_covered_cells_leave_the_frontier_and_blocked_cells_never_join():
    frontier = FrontierCells(PROBLEM)
    frontier.cover((0.5, 0.5))
    frontier.cover((1.2, 0.7))   # cell (1, 0): off the frontier, adds (2, 0)
    assert cells(frontier) == {(0, 1), (2, 0)}
    frontier.cover((2.9, 0.1))   # (2, 0): its right neighbour (3, 0) is blocked
    assert cells(frontier) == {(0, 1), (2, 1)}
    frontier.cover((2.5, 0.5))   # a second node in a covered cell changes nothing
    assert cells(frontier) == {(0, 1), (2, 1)}
    assert len(frontier) == 2


def test_frontier_empties_when_everything_reachable_is_covered():
    frontier = FrontierCells(PROBLEM)
    for cell, blocked in enumerate(BLOCKED):
        if not blocked:
            frontier.cover((cell % 4 + 0.5, cell // 4 + 0.5))
    assert len(frontier) == 0


def test_samples_lie_in_frontier_cells():
    frontier = FrontierCells(PROBLEM)
    frontier.cover((0.5, 0.5))
    frontier.cover((1.5, 0.5))
    rng = random.Random(3)
    seen = set()
    for _ in range(200):
        x, y = frontier.sample(rng)
        seen.add((int(x), int(y)))
    assert seen == cells(frontier)
