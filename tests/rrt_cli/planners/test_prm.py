"""PRM and PRM* (point vehicle): every course problem x 20 seeds and small
generated maps, each output checked by the validator with -strict; the answer
is a shortest path of the printed roadmap; PRM*'s k; A* against Dijkstra."""

import heapq
import math
import random
import statistics

import pytest

from benchmarks.generator import maze, narrow_passage, random_field
from planning_core.setups import grid_setup
from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from rrt_cli.graph_search import astar
from rrt_cli.planners import prm, prmstar, rrt
from rrt_cli.planners.base import PlanStatus, StopCondition
from rrt_cli.planners.paths import path_length
from tests.conftest import COURSE_PROBLEMS, run_planner, seed_sweep, solve_on, unit_sample
from validator.checks import validate_output

PLANNERS = {"prm": prm, "prmstar": prmstar}
SEEDS = range(20)


def dijkstra_length(edges, source, target) -> float:
    """Shortest distance over undirected edges given as (x1, y1, x2, y2) rows."""
    graph: dict[tuple, list] = {}
    for x1, y1, x2, y2 in edges:
        cost = math.hypot(x2 - x1, y2 - y1)
        graph.setdefault((x1, y1), []).append(((x2, y2), cost))
        graph.setdefault((x2, y2), []).append(((x1, y1), cost))
    best = {source: 0.0}
    frontier = [(0.0, source)]
    while frontier:
        cost, node = heapq.heappop(frontier)
        if node == target:
            return cost
        if cost > best[node]:
            continue
        for neighbour, step in graph.get(node, ()):
            if cost + step < best.get(neighbour, math.inf):
                best[neighbour] = cost + step
                heapq.heappush(frontier, (cost + step, neighbour))
    return math.inf


def assert_valid_roadmap_answer(problem: Problem, result) -> None:
    assert result.solved, result.status
    report = validate_output(problem, Vehicle.POINT,
                             format_plan(result.trajectory, result.tree), strict=True)
    assert report.valid, report.first_failure
    assert not report.warnings
    assert result.trajectory[0] == problem.start
    assert result.trajectory[-1] == problem.goal  # the goal is a roadmap vertex
    # The path runs along printed roadmap edges and is a shortest one among them.
    edges = {(row[:2], row[2:]) for row in result.tree}
    for a, b in zip(result.trajectory, result.trajectory[1:]):
        assert (a, b) in edges or (b, a) in edges
    shortest = dijkstra_length(result.tree, problem.start, problem.goal)
    assert path_length(result.trajectory, math.dist) == pytest.approx(shortest, rel=1e-12)


# PRM* is the slow half of this 20-seed sweep (seconds per map), and space-3 the slow
# map, whose walls the other maps share: marked slow.
@pytest.mark.parametrize("name", ["prm", pytest.param("prmstar", marks=pytest.mark.slow)])
@pytest.mark.parametrize("path", [pytest.param(path, id=path.stem, marks=pytest.mark.slow
                                               if path.stem == "space-3" else ())
                                  for path in COURSE_PROBLEMS])
def test_course_problems_20_seeds_all_valid(path, name):
    problem = parse_problem(path.read_text())
    for seed in SEEDS:
        result = solve_on(PLANNERS[name], grid_setup(problem, Vehicle.POINT), StopCondition(time_limit=30),
                                      random.Random(seed))
        assert_valid_roadmap_answer(problem, result)


@pytest.mark.parametrize("name", sorted(PLANNERS))
@pytest.mark.parametrize("problem", [
    maze(11, random.Random(5)), random_field(15, 0.3, random.Random(3)),
    narrow_passage(14, random.Random(2)),
], ids=["maze-11", "random-15", "narrow-14"])
@pytest.mark.parametrize("seed", seed_sweep(range(4)))
def test_generated_maps_valid(problem, name, seed):
    result = solve_on(PLANNERS[name], grid_setup(problem, Vehicle.POINT),
                      StopCondition(time_limit=30), random.Random(seed))
    assert_valid_roadmap_answer(problem, result)


@pytest.mark.slow  # a comparison over seeds and maps: seconds
def test_prmstar_paths_are_at_least_20_percent_shorter_than_rrt():
    problem = random_field(25, 0.25, random.Random(3))
    star, tree = [], []
    for seed in range(8):
        star.append(path_length(solve_on(prmstar, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                              random.Random(seed)).trajectory, math.dist))
        tree.append(path_length(solve_on(rrt, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                          random.Random(seed)).trajectory, math.dist))
    assert statistics.median(star) <= 0.8 * statistics.median(tree)


ONE_GROWTH = prmstar.PRMStarParams(min_improvement=1.0, min_refined_vertices=0)


@pytest.mark.parametrize("seed", unit_sample(range(6), keep=2))
def test_prmstar_refinement_only_ever_shortens_the_path(seed):
    # Same seed, same roadmap up to the first growth; refinement grows it further
    # while a growth gains 3%, so the answer is no longer and its roadmap no smaller.
    problem = random_field(15, 0.3, random.Random(3))
    once = solve_on(prmstar, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(seed),
                         ONE_GROWTH)
    refined = solve_on(prmstar, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(seed))
    assert_valid_roadmap_answer(problem, refined)
    assert path_length(refined.trajectory, math.dist) <= path_length(once.trajectory, math.dist)
    assert refined.stats.tree_nodes >= once.stats.tree_nodes
    assert refined.tree[:len(once.tree)] == once.tree
    # -stats' first solution is the first answer's time, not the refined one's.
    first, total = refined.stats.first_solution_seconds, refined.stats.planning_seconds
    assert first is not None and 0 < first <= total
    if refined.stats.tree_nodes > once.stats.tree_nodes:
        assert first < total


@pytest.mark.parametrize("seed", range(3))
def test_prmstar_vertex_cap_binds_the_first_growth_too(seed):
    # A first answer whose doubled roadmap would pass the cap is final (a big map
    # must not spend as long again growing); a cap the doubled roadmap just fits
    # allows exactly that one growth.
    problem = random_field(15, 0.3, random.Random(3))

    def solve(cap, **rules):
        return solve_on(prmstar, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(seed),
                             prmstar.PRMStarParams(max_refined_vertices=cap, **rules))

    first = solve(0)
    assert_valid_roadmap_answer(problem, first)
    assert len(first.trajectory) > 2  # not the straight line, which is final anyway
    first_size = first.stats.tree_nodes
    once = solve(2 * first_size, min_improvement=1.0, min_refined_vertices=0)
    assert once.stats.tree_nodes == 2 * first_size
    assert once.tree[:len(first.tree)] == first.tree
    fits = solve(2 * first_size)
    assert (fits.trajectory, fits.tree) == (once.trajectory, once.tree)
    below = solve(2 * first_size - 1)
    assert (below.trajectory, below.tree) == (first.trajectory, first.tree)


def test_prmstar_refines_where_it_pays():
    # An open map: the first answer is the straight line, so it stops there. The
    # course's walled maze: it grows past the first growth.
    open_map = Problem(20, 20, bytes(400), (0.5, 0.5), (19.5, 19.5))
    course = parse_problem(next(p for p in COURSE_PROBLEMS if p.stem == "space-2").read_text())
    for problem, grows in ((open_map, False), (course, True)):
        grown = [solve_on(prmstar, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(seed),
                               params).stats.tree_nodes
                 for seed in range(4) for params in (ONE_GROWTH, prmstar.PRMStarParams())]
        assert any(refined > once for once, refined in zip(grown[::2], grown[1::2])) == grows
    straight = solve_on(prmstar, grid_setup(open_map, Vehicle.POINT), StopCondition(30), random.Random(0))
    assert straight.trajectory == (open_map.start, open_map.goal)
    assert straight.stats.tree_nodes == 2


def test_prmstar_k_follows_the_formula():
    # k = ceil(e (1 + 1/d) log n), d = 2: 4.077 * log n.
    assert prmstar.star_neighbor_count(1) == 1
    assert prmstar.star_neighbor_count(2) == 3      # 4.077 * 0.693 = 2.83
    assert prmstar.star_neighbor_count(100) == 19    # 4.077 * 4.605 = 18.78
    assert prmstar.star_neighbor_count(10_000) == 38  # 4.077 * 9.210 = 37.55


def test_prm_tries_k_nearest_only():
    # On an open map every k-nearest attempt succeeds: each new vertex adds at
    # most k edges, so edges <= k * vertices.
    problem = Problem(30, 30, bytes(900), (0.5, 0.5), (29.5, 29.5))
    params = prm.Params(neighbors=4, min_vertices=300)
    result = solve_on(prm, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(0), params)
    assert_valid_roadmap_answer(problem, result)
    assert result.stats.tree_nodes >= 300
    assert len(result.tree) <= 4 * result.stats.tree_nodes


@pytest.mark.parametrize("seed", range(6))
def test_astar_equals_dijkstra_on_random_graphs(seed):
    rng = random.Random(seed)
    n = 60
    xs = [rng.random() * 10 for _ in range(n)]
    ys = [rng.random() * 10 for _ in range(n)]
    adjacency = [[] for _ in range(n)]
    rows = []
    for _ in range(150):
        a, b = rng.randrange(n), rng.randrange(n)
        if a != b:
            cost = math.hypot(xs[a] - xs[b], ys[a] - ys[b])
            adjacency[a].append((b, cost))
            adjacency[b].append((a, cost))
            rows.append((xs[a], ys[a], xs[b], ys[b]))
    path = astar(adjacency, xs, ys, 0, n - 1)
    expected = dijkstra_length(rows, (xs[0], ys[0]), (xs[-1], ys[-1]))
    if path is None:
        assert expected == math.inf
    else:
        assert path[0] == 0 and path[-1] == n - 1
        length = sum(math.hypot(xs[a] - xs[b], ys[a] - ys[b]) for a, b in zip(path, path[1:]))
        assert length == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_limits_end_an_impossible_search(name):
    # Free cells (0, 0) and (1, 1) touch only at the point (1, 1): not provably
    # unreachable, but only a segment exactly through that point gets across.
    problem = Problem(2, 2, bytes([0, 1, 1, 0]), (0.3, 0.6), (1.5, 1.5))
    result = solve_on(PLANNERS[name], grid_setup(problem, Vehicle.POINT),
                                  StopCondition(time_limit=30, max_iterations=500),
                                  random.Random(1))
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.trajectory == ()
    walled = Problem(3, 1, bytes([0, 1, 0]), (0.5, 0.5), (2.5, 0.5))
    result = solve_on(PLANNERS[name], grid_setup(walled, Vehicle.POINT), StopCondition(30), random.Random(0))
    assert result.status is PlanStatus.UNREACHABLE


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_goal_on_the_maps_edge_is_nudged_inside(name):
    problem = Problem(4, 3, bytes(12), (2.5, 1.5), (0.0, 0.0))
    result = solve_on(PLANNERS[name], grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(0))
    assert result.solved
    report = validate_output(problem, Vehicle.POINT,
                             format_plan(result.trajectory, result.tree), strict=True)
    assert report.valid, report.first_failure
    assert math.dist(result.trajectory[-1], problem.goal) < 1e-5


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_cli_runs_it_reproducibly_and_refuses_the_spaceship(name):
    text = next(p for p in COURSE_PROBLEMS if p.stem == "space-1").read_text()
    first = run_planner(["-planner", name, "-seed", "9"], text)
    second = run_planner(["-planner", name, "-seed", "9"], text)
    assert first.returncode == 0, first.stderr
    assert first.stdout == second.stdout
    report = validate_output(parse_problem(text), Vehicle.POINT, first.stdout.decode(),
                             strict=True)
    assert report.valid
    refused = run_planner(["-left", "-planner", name], text)
    assert refused.returncode == 2 and refused.stdout == b""
