"""The shortest-path yardstick: against a brute-force reference, and as a lower bound."""

import math
import random
from fractions import Fraction
from pathlib import Path

import pytest

from benchmarks.generator import PROBLEMS_DIR
from benchmarks.shortest_path import shortest_lengths, shortest_path
from planning_core.setups import grid_setup
from tests.conftest import solve_on, unit_sample
from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from rrt_cli.planners import PLANNERS
from rrt_cli.planners.base import StopCondition
from validator.checks import validate_output

COURSE_PROBLEMS = sorted((PROBLEMS_DIR / "course").glob("*.sw"))


def grid_problem(rows: list[str], start, goal) -> Problem:
    text = f"{len(rows[0])}\n{len(rows)}\n" + "\n".join(rows) + "\n"
    return parse_problem(text + f"{start[0]}\n{start[1]}\n{goal[0]}\n{goal[1]}\n")


def _meets_open_cell(a, b, column: int, row: int) -> bool:
    """Whether segment ab (exact Fractions) has a point strictly inside the cell."""
    low, high = Fraction(-10**9), Fraction(10**9)  # the open t-interval of the cell
    for start, end, cell in ((a[0], b[0], column), (a[1], b[1], row)):
        delta = end - start
        if delta == 0:
            if not cell < start < cell + 1:
                return False
            continue
        t_a, t_b = (cell - start) / delta, (cell + 1 - start) / delta
        low, high = max(low, min(t_a, t_b)), min(high, max(t_a, t_b))
    return low < high and low < 1 and high > 0


def _runs_along_wall(a, b, blocked) -> bool:
    """Whether segment ab runs along a grid line between two blocked cells for a while."""
    for axis in (0, 1):
        other = 1 - axis
        if a[axis] != b[axis] or a[axis].denominator != 1:
            continue
        line = int(a[axis])
        low, high = sorted((a[other], b[other]))
        for cell in range(math.floor(low), math.ceil(high)):
            if max(low, cell) < min(high, cell + 1):
                sides = [(line - 1, cell), (line, cell)]
                if axis == 1:
                    sides = [(cell, line - 1), (cell, line)]
                if all(blocked(c, r) for c, r in sides):
                    return True
    return False


def brute_force_length(problem: Problem) -> float | None:
    """Dijkstra over every grid point, start and goal, every pair joined when the
    segment stays out of the blocked cells' interiors: exact arithmetic, no pruning."""
    width, height = problem.width, problem.height

    def blocked(column, row):
        return not (0 <= column < width and 0 <= row < height) or \
            problem.is_blocked_cell(column, row)

    cells = [(c, r) for c in range(width) for r in range(height) if blocked(c, r)]
    points = [tuple(map(Fraction, problem.start)), tuple(map(Fraction, problem.goal))]
    points += [(Fraction(x), Fraction(y)) for x in range(width + 1) for y in range(height + 1)]

    def clear(a, b):
        return not any(_meets_open_cell(a, b, c, r) for c, r in cells) and \
            not _runs_along_wall(a, b, blocked)

    cost = [math.inf] * len(points)
    cost[0] = 0.0
    done = [False] * len(points)
    while True:
        here = min((i for i in range(len(points)) if not done[i]), key=cost.__getitem__)
        if cost[here] == math.inf:
            return None
        if here == 1:
            return cost[1]
        done[here] = True
        for there in range(len(points)):
            if not done[there]:
                step = math.dist(map(float, points[here]), map(float, points[there]))
                if cost[here] + step < cost[there] and clear(points[here], points[there]):
                    cost[there] = cost[here] + step


def random_problem(rng: random.Random, size: int, density: float) -> Problem:
    rows = ["".join("#" if rng.random() < density else "_" for _ in range(size))
            for _ in range(size)]
    free = [(c, size - 1 - r) for r, line in enumerate(rows) for c, ch in enumerate(line)
            if ch == "_"]
    (sc, sr), (gc, gr) = rng.sample(free, 2)
    # Eighths, so that some starts and goals sit on grid lines.
    start = (sc + rng.randrange(8) / 8, sr + rng.randrange(8) / 8)
    goal = (gc + rng.randrange(8) / 8, gr + rng.randrange(8) / 8)
    return grid_problem(rows, start, goal)


@pytest.mark.parametrize("seed", range(24))
def test_matches_brute_force_on_random_maps(seed):
    rng = random.Random(seed)
    problem = random_problem(rng, 5, rng.choice((0.2, 0.35, 0.5)))
    expected = brute_force_length(problem)
    found = shortest_path(problem)
    if expected is None:
        assert found is None
    else:
        assert found is not None and found.length == pytest.approx(expected, rel=1e-9)


def test_path_is_its_length_and_joins_start_to_goal():
    problem = parse_problem((PROBLEMS_DIR / "maze-10.sw").read_text())
    found = shortest_path(problem)
    assert found.points[0] == problem.start and found.points[-1] == problem.goal
    assert found.length == pytest.approx(sum(map(math.dist, found.points, found.points[1:])))
    # A maze's shortest path bends, and only at grid points.
    assert len(found.points) > 2
    assert all(x == int(x) and y == int(y) for x, y in found.points[1:-1])


def test_open_map_is_the_straight_line_and_a_walled_goal_has_none():
    assert shortest_path(grid_problem(["____"] * 3, (0.5, 0.5), (3.5, 2.5))).length == \
        pytest.approx(math.hypot(3, 2))
    assert shortest_path(grid_problem(["_#__", "_#__", "_#__"], (0.5, 0.5), (3.5, 2.5))) is None


def test_a_diagonal_pinch_lets_the_path_through():
    # Blocked cells touching only at a corner: the path may pass through that point.
    problem = grid_problem(["_#", "#_"], (0.5, 1.5), (1.5, 0.5))
    assert shortest_path(problem).length == pytest.approx(math.sqrt(2))
    assert brute_force_length(problem) == pytest.approx(math.sqrt(2))


@pytest.mark.parametrize("name", ["rrt", "prmstar", "rrtconnect"])
@pytest.mark.parametrize("path", unit_sample(  # the unit run: space-0, a map with walls
    sorted(COURSE_PROBLEMS, key=lambda p: p.stem != "space-0")), ids=lambda p: p.stem)
def test_no_valid_answer_is_shorter(name, path: Path):
    problem = parse_problem(path.read_text())
    optimum = shortest_path(problem).length
    for seed in range(3):
        planner = PLANNERS[name].load()
        result = solve_on(planner, grid_setup(problem, Vehicle.POINT), StopCondition(time_limit=30),
                               random.Random(seed))
        report = validate_output(problem, Vehicle.POINT,
                                 format_plan(result.trajectory, result.tree), strict=True)
        assert report.valid and not report.warnings, report.first_failure
        length = sum(map(math.dist, result.trajectory, result.trajectory[1:]))
        assert length >= optimum * (1 - 1e-12)


def test_lengths_by_problem_name_skip_unknown_ones_and_maps_of_too_many_corners():
    """random-d20-500 has 115,092 corners (the search would take many minutes): left
    out, as an unknown name is."""
    lengths = shortest_lengths(["course-space-1", "maze-10", "no-such-problem",
                                "random-d20-500"])
    assert set(lengths) == {"course-space-1", "maze-10"}
    assert lengths["maze-10"] == shortest_path(
        parse_problem((PROBLEMS_DIR / "maze-10.sw").read_text())).length
