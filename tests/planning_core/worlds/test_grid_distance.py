"""Distance to the goal through the free cells (the guided planners' heuristic)."""

import math
import random

import pytest

from planning_core.interrupt import Interrupted
from planning_core.problem_text import parse_problem
from planning_core.worlds.grid import connected_free_cells
from planning_core.worlds.grid_distance import CellDistanceToGoal


def problem(rows: list[str], start, goal):
    text = f"{len(rows[0])}\n{len(rows)}\n" + "\n".join(rows) + "\n"
    return parse_problem(text + f"{start[0]}\n{start[1]}\n{goal[0]}\n{goal[1]}\n")


OPEN = problem(["_____"] * 5, (0.5, 0.5), (4.5, 4.5))
# Rows are top first: the wall is row y=2, with its gap at x=0.
WALLED = problem(["_____", "_____", "_####", "_____", "_____"], (4.5, 0.5), (4.5, 4.5))


def test_goal_cell_is_straight_line_distance():
    distance = CellDistanceToGoal(OPEN, OPEN.goal)
    assert distance(4.5, 4.5) == 0.0
    assert math.isclose(distance(4.2, 4.9), math.hypot(0.3, 0.4))


def test_open_map_gives_octile_distance_at_cell_centres():
    distance = CellDistanceToGoal(OPEN, OPEN.goal)
    for x in range(5):
        for y in range(5):
            dx, dy = 4 - x, 4 - y
            octile = max(dx, dy) + (math.sqrt(2) - 1) * min(dx, dy)
            assert math.isclose(distance(x + 0.5, y + 0.5), octile, abs_tol=1e-12)


def test_value_falls_along_a_straight_run_toward_the_goal():
    distance = CellDistanceToGoal(OPEN, OPEN.goal)
    values = [distance(0.5 + k * 0.01, 4.5) for k in range(400)]
    assert all(b < a for a, b in zip(values, values[1:]))


def test_a_wall_makes_the_way_round_count():
    distance = CellDistanceToGoal(WALLED, WALLED.goal)
    # Just below the wall, right under the goal: 2 units straight, but the gap is at x=0.
    below = distance(4.5, 1.5)
    assert below > 8.0
    assert below > distance(0.5, 1.5) > distance(0.5, 3.5)


def test_blocked_outside_and_cut_off_positions_are_unreachable():
    cut_off = problem(["___", "###", "___"], (0.5, 0.5), (0.5, 2.5))
    distance = CellDistanceToGoal(cut_off, cut_off.goal, unreachable=1e9)
    assert distance(1.5, 1.5) == 1e9          # blocked cell
    assert distance(-0.1, 2.5) == 1e9         # outside the map
    assert distance(3.0, 2.5) == 1e9          # x == W is outside (half-open cells)
    assert distance(0.5, 0.5) == 1e9          # free, but walled off from the goal
    assert distance(2.5, 2.5) < 1e9


def test_no_diagonal_step_through_a_blocked_corner():
    # Free cells (0,0) and (1,1) touch only at a corner between two blocked cells.
    corner = problem(["#_", "_#"], (0.5, 0.5), (1.5, 1.5))
    assert CellDistanceToGoal(corner, corner.goal, unreachable=1e9)(0.5, 0.5) == 1e9


def test_every_free_cell_joined_to_the_goal_gets_a_finite_distance():
    rng = random.Random(5)
    for _ in range(20):
        rows = ["".join("#" if rng.random() < 0.3 else "_" for _ in range(9)) for _ in range(7)]
        rows[-1] = "_" + rows[-1][1:]    # start cell (bottom-left) free
        rows[0] = rows[0][:-1] + "_"     # goal cell (top-right) free
        p = problem(rows, (0.5, 0.5), (8.5, 6.5))
        distance = CellDistanceToGoal(p, p.goal, unreachable=math.inf)
        joined = connected_free_cells(p, (8, 6), diagonal=False)
        for index, linked in enumerate(joined):
            row, column = divmod(index, 9)
            value = distance(column + 0.5, row + 0.5)
            if linked:
                assert math.isfinite(value)
                # Never shorter than the straight line between the centres.
                assert value >= math.hypot(8 - column, 6 - row) - 1e-9


def test_chain_runs_through_free_neighbours_to_the_goal_cell():
    distance = CellDistanceToGoal(WALLED, WALLED.goal)
    chain = distance.chain_from(4.5, 0.5)
    assert chain[0] == (4, 0) and chain[-1] == (4, 4)
    for (c0, r0), (c1, r1) in zip(chain, chain[1:]):
        assert max(abs(c1 - c0), abs(r1 - r0)) == 1
        assert not WALLED.is_blocked_cell(c1, r1)
        # A diagonal step has both cells beside it free: no blocked corner is cut.
        assert not (WALLED.is_blocked_cell(c1, r0) or WALLED.is_blocked_cell(c0, r1))
    assert (0, 2) in chain  # the wall's only gap
    # The chain's steps add up to the cell distance between the centres.
    steps = sum(math.dist(a, b) for a, b in zip(chain, chain[1:]))
    assert math.isclose(steps, distance.cell_distance[4], abs_tol=1e-12)


def test_no_chain_from_a_blocked_cell_or_outside():
    distance = CellDistanceToGoal(WALLED, WALLED.goal)
    assert distance.chain_from(2.5, 2.5) is None
    assert distance.chain_from(-1.0, 0.5) is None


def test_ahead_is_that_many_cells_down_the_chain_or_to_its_straight_runs_end():
    """``ahead_of(state, k)``: the centre of the chain's k-th cell from the state's, or
    of a later one while the chain goes straight on; the goal itself at the goal's
    cell; None where there is no chain."""
    distance = CellDistanceToGoal(WALLED, WALLED.goal)
    chain = distance.chain_from(4.5, 0.5)
    steps = [(c1 - c0, r1 - r0) for (c0, r0), (c1, r1) in zip(chain, chain[1:])]
    for k in range(1, len(chain)):
        target = distance.ahead_of((4.5, 0.5), k)
        end = len(chain) - 1 if target == WALLED.goal else \
            chain.index((int(target[0]), int(target[1])))
        assert target == WALLED.goal or target == (chain[end][0] + 0.5, chain[end][1] + 0.5)
        assert end >= k and set(steps[k - 1:end]) == {steps[k - 1]}
        assert end == len(chain) - 1 or steps[end] != steps[k - 1]
    assert distance.ahead_of((4.5, 0.5), 1) == (2.5, 0.5)  # along row 0 to where it turns
    assert distance.ahead_of((2.5, 2.5), 1) is None and distance.ahead_of((-1.0, 0.5), 1) is None


def random_rows(rng, width, height, density):
    rows = ["".join("#" if rng.random() < density else "_" for _ in range(width))
            for _ in range(height)]
    rows[-1] = "_" + rows[-1][1:]    # start cell (bottom-left) free
    rows[0] = rows[0][:-1] + "_"     # goal cell (top-right) free
    return rows


def chain_is_free_and_joined(p, chain, goal_cell):
    assert chain[-1] == goal_cell
    for (c0, r0), (c1, r1) in zip(chain, chain[1:]):
        assert max(abs(c1 - c0), abs(r1 - r0)) == 1
        assert not p.is_blocked_cell(c1, r1)
        assert not (p.is_blocked_cell(c1, r0) or p.is_blocked_cell(c0, r1))


def test_a_lazy_field_measures_what_the_eager_one_does():
    """With a focus the search is A* resumed per query: at every cell centre the same
    distance (to the heuristic's tie weight), chains through free cells to the goal,
    and the same cells cut off."""
    rng = random.Random(8)
    for _ in range(20):
        p = problem(random_rows(rng, 12, 9, 0.3), (0.5, 0.5), (11.5, 8.5))
        eager = CellDistanceToGoal(p, p.goal, unreachable=math.inf)
        focus = (rng.uniform(0, 12), rng.uniform(0, 9))
        lazy = CellDistanceToGoal(p, p.goal, unreachable=math.inf, focus=focus)
        cells = [(c, r) for c in range(12) for r in range(9)]
        rng.shuffle(cells)
        for c, r in cells:
            value, expected = lazy(c + 0.5, r + 0.5), eager(c + 0.5, r + 0.5)
            assert value == expected or math.isclose(value, expected, rel_tol=1e-5)
            assert lazy.bound(c + 0.5, r + 0.5) <= value
            if math.isfinite(value):
                chain_is_free_and_joined(p, lazy.chain_from(c + 0.5, r + 0.5), (11, 8))


def test_a_lazy_field_walks_only_the_way_on_an_open_map():
    """A 200 x 200 open map, the focus in the far corner: measuring there closes the
    diagonal's cells, not the map's 40 000."""
    p = problem(["_" * 200] * 200, (0.5, 0.5), (199.5, 199.5))
    lazy = CellDistanceToGoal(p, p.goal, focus=p.start)
    assert math.isclose(lazy(*p.start), 199 * math.sqrt(2), rel_tol=1e-5)
    assert sum(lazy._closed) <= 400


def test_a_lazy_field_asks_stop_while_it_measures():
    """A query that walks more than POLL_EVERY cells asks ``stop``, and raises
    Interrupted when it says so: a serpentine of 30 corridors 60 cells long."""
    rows = ["_" * 60 if k % 2 == 0 else ("#" * 59 + "_" if k % 4 == 1 else "_" + "#" * 59)
            for k in range(59)]
    p = problem(rows, (0.5, 0.5), (0.5, 58.5))
    asked = []
    lazy = CellDistanceToGoal(p, p.goal, stop=lambda: asked.append(1) or True,
                              focus=p.start)
    assert not asked  # nothing measured before the first query
    with pytest.raises(Interrupted):
        lazy(*p.start)
    assert asked
    assert math.isclose(CellDistanceToGoal(p, p.goal, focus=p.start)(*p.start),
                        CellDistanceToGoal(p, p.goal)(*p.start), rel_tol=1e-5)


def test_turning_the_lazy_search_asks_stop_and_cut_short_changes_nothing():
    """Aiming at a new cell measures every open cell's key again: that asks ``stop``
    too, and when it is cut short the search keeps its queue and its aim."""
    p = problem(["_" * 100] * 100, (0.5, 0.5), (99.5, 99.5))
    stopped = []
    lazy = CellDistanceToGoal(p, p.goal, stop=lambda: bool(stopped), focus=p.start)
    lazy(*p.start)
    lazy._queue = lazy._queue * 20  # more open entries than POLL_EVERY (duplicates allowed)
    before = ([(e.key, e.order) for e in lazy._queue], lazy._focus_col, lazy._focus_row)
    stopped.append(True)
    with pytest.raises(Interrupted):
        lazy(0.5, 99.5)
    assert ([(e.key, e.order) for e in lazy._queue], lazy._focus_col, lazy._focus_row) == before
