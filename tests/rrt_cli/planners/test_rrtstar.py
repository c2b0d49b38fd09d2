"""RRT* and Informed RRT* (point vehicle, arm2, rigid2): every answer passes the
validator's own checks and every printed tree edge is free; rewiring never raises a
cost-to-come and each node's cost is its parent's plus the motion's; with an
objective the cost only falls; informed targets lie in the informed set and pruning
keeps exactly what may still improve the answer; -seed reproduces bit for bit."""

from __future__ import annotations

import random
import subprocess
import sys

import pytest

from planning_core.costs import path_cost
from planning_core.informed_sampling import InformedSampler
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.problem_definition import Objective
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup, kinoplan_setup
from rrt_cli.planners import PLANNERS, informed, rrtstar
from rrt_cli.planners.base import PlanStatus, StopCondition
from tests.conftest import (COURSE_DIR, COURSE_PROBLEMS, ROOT, plan_in_process, seed_sweep,
                            unit_sample)
from validator.checks import validate_plan

SUITE = ROOT / "benchmarks" / "problems"
FAMILY = SUITE / "family"
MODULES = {"rrtstar": rrtstar, "informed": informed}


def setup_of(name: str):
    """A grid map's point setup, a course map's (``space-2``) or the suite's
    (``maze-50``), or a family problem's (``arm2-pair1``)."""
    for folder in (COURSE_DIR, SUITE):
        if (folder / f"{name}.sw").exists():
            return grid_setup(parse_problem((folder / f"{name}.sw").read_text()), "point")
    return kinoplan_setup(parse_kinoplan((FAMILY / f"{name}.kp").read_text()))


def optimizing(setup, threshold: float = 0.0):
    return setup.pdef.with_objective(Objective(threshold))


def assert_valid(setup, result):
    """The validator's checks pass, every tree edge is free in the direction it was
    grown and every node may be printed; the report (for its cost)."""
    assert result.solved, (result.status, result.message)
    report = validate_plan(setup, format_plan(result.trajectory, result.tree))
    assert report.valid, report.first_failure
    si = setup.si
    for parent, _, child in result.edges:
        assert si.first_hit(parent, child) is None
        assert si.can_end_at(child)
    return report


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("path", COURSE_PROBLEMS, ids=lambda p: p.stem)
@pytest.mark.parametrize("seed", seed_sweep(range(20), fast=(0, 1)))
def test_first_solutions_on_the_course_maps_are_valid(name, path, seed):
    setup = grid_setup(parse_problem(path.read_text()), "point")
    result = MODULES[name].solve(setup.si, setup.pdef, StopCondition(30), random.Random(seed))
    report = assert_valid(setup, result)
    stats = result.stats
    assert len(stats.improvements) <= 1  # stops at the first (none: start in the goal)
    if stats.improvements:
        assert stats.first_solution_seconds == stats.improvements[0][0]
        assert report.cost == pytest.approx(stats.improvements[0][1], rel=1e-12)


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("problem", ["arm2-pair1", "rigid2-scene3", "space-1", "space-2",
                                     "space-3"])
@pytest.mark.parametrize("seed", seed_sweep(range(20), fast=(0,)))
def test_optimized_answers_are_valid_and_their_cost_only_falls(name, problem, seed):
    setup, module = setup_of(problem), MODULES[name]
    first = module.solve(setup.si, setup.pdef, StopCondition(60), random.Random(seed))
    iterations = first.stats.iterations + 400  # the same run, 400 iterations further
    result = module.solve(setup.si, optimizing(setup),
                          StopCondition(60, max_iterations=iterations), random.Random(seed))
    report = assert_valid(setup, result)
    assert result.stats.iterations == iterations  # went on past the first solution
    seconds, costs = zip(*result.stats.improvements)
    assert list(costs) == sorted(set(costs), reverse=True)  # each strictly cheaper
    assert costs[0] == first.stats.improvements[0][1]  # the first answer, improved on
    assert list(seconds) == sorted(seconds)
    assert result.stats.first_solution_seconds == seconds[0]
    assert report.cost == pytest.approx(costs[-1], rel=1e-12) and costs[-1] <= costs[0]


@pytest.mark.parametrize("name", sorted(MODULES))
def test_a_cost_threshold_ends_the_search_once_met(name):
    setup = setup_of("space-2")
    module = MODULES[name]
    full = module.solve(setup.si, optimizing(setup), StopCondition(60, max_iterations=1500),
                        random.Random(2))
    costs = [cost for _, cost in full.stats.improvements]
    assert len(costs) >= 3
    met = module.solve(setup.si, optimizing(setup, costs[1]),
                       StopCondition(60, max_iterations=1500), random.Random(2))
    assert met.solved and met.stats.improvements == met.stats.improvements[:2]
    assert path_cost(setup.si, met.path) == pytest.approx(costs[1])
    assert met.stats.iterations < full.stats.iterations


class Recorder:
    """Snapshots a search's tree after each iteration and checks the invariants."""

    def __init__(self, search, si):
        self.search, self.si = search, si
        self.costs = list(search.tree.costs)

    def check(self):
        tree, si = self.search.tree, self.si
        for node, old in enumerate(self.costs):  # rewiring never raises a cost-to-come
            if tree.alive[node]:
                assert tree.costs[node] <= old
        for node in range(1, len(tree.states)):
            if tree.alive[node]:
                parent = tree.parents[node]
                assert tree.alive[parent] and node in tree.children[parent]
                step = si.distance(tree.states[parent], tree.states[node])
                assert tree.costs[node] == tree.costs[parent] + step
        assert self.search.index_nodes == [n for n, live in enumerate(tree.alive) if live]
        self.costs = list(tree.costs)


@pytest.mark.parametrize("problem, iterations", [("space-2", 400), ("arm2-pair1", 400),
                                                 ("rigid2-scene3", 4000)])
def test_rewiring_never_raises_a_cost_and_costs_follow_the_tree(problem, iterations):
    setup = setup_of(problem)
    si, rng = setup.si, random.Random(3)
    search = rrtstar.StarSearch(si, setup.pdef, rng, rrtstar.Params(),
                                lambda best: si.sample_target(rng))
    recorder, rewired = Recorder(search, si), 0
    for _ in range(iterations):
        before = list(search.tree.parents)
        search.iterate()
        rewired += sum(a != b for a, b in zip(before, search.tree.parents))
        recorder.check()
    assert rewired > 20  # the property was put to the test


def test_informed_targets_lie_in_the_informed_set_and_pruning_keeps_what_may_improve():
    setup = setup_of("space-2")
    si, pdef, rng = setup.si, setup.pdef, random.Random(4)
    sampler = InformedSampler(si, pdef, rng)
    drawn = []

    def draw(best):
        state = sampler.sample(best)
        drawn.append((best, state))
        return state
    search = rrtstar.StarSearch(si, pdef, rng, informed.Params(), draw)
    pruning, recorder, pruned = informed.Pruning(sampler.heuristic, 0.05), Recorder(search, si), 0
    for _ in range(600):  # the first solution near 100, one pruning, 500 informed draws
        if search.iterate():
            size, last = search.tree.size, pruning.pruned_at
            pruning(search)
            pruned += size - search.tree.size
            if pruning.pruned_at != last:  # it pruned (on a fall of over 5%)
                assert_only_hopeless_nodes_were_dropped(search, sampler.heuristic)
        recorder.check()
    informed_draws = [(best, s) for best, s in drawn if best < float("inf") and s is not None]
    assert len(informed_draws) > 100 and pruned > 0
    assert all(sampler.heuristic(state) <= best for best, state in informed_draws)


def assert_only_hopeless_nodes_were_dropped(search, heuristic):
    """A live node lies within the pruning's bound or leads to one that does; the best
    path is whole."""
    tree, bound = search.tree, search.best_cost
    hopeful = {n for n in range(len(tree.states))
               if tree.alive[n] and heuristic(tree.states[n]) <= bound}
    for node in range(len(tree.states)):
        if tree.alive[node]:
            stack, found = [node], False
            while stack and not found:
                here = stack.pop()
                found = here in hopeful or here == search.best
                stack.extend(tree.children[here])
            assert found or node == 0
    assert all(tree.alive[n] for n in tree.path_to(search.best))


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("problem", ["space-2.sw", "arm2-pair1.kp"])
def test_cli_seed_reproduces_an_optimized_answer_bit_for_bit(monkeypatch, name, problem):
    path = COURSE_DIR / problem if problem.endswith(".sw") else FAMILY / problem
    # 500 iterations: past the first solution, where Informed RRT* draws its own targets
    argv = ["-planner", name, "-seed", "3", "-optimize", "-iterations", "500"]
    status, out, err = plan_in_process(monkeypatch, argv, path.read_text())
    assert status == 0 and err == "", err
    assert plan_in_process(monkeypatch, argv, path.read_text())[1] == out
    other = plan_in_process(monkeypatch, [*argv[:3], "4", *argv[4:]], path.read_text())[1]
    assert other != out


def test_registry_lines_are_optimizing_geometric_planners():
    for name in MODULES:
        entry = PLANNERS[name]
        assert entry.optimizing and entry.load() is MODULES[name]
        assert entry.plans_for(setup_of("space-1").si.system)


def test_a_start_in_the_goal_region_is_the_answer_alone():
    setup = grid_setup(parse_problem("4\n3\n____\n____\n____\n1.0\n1.0\n1.05\n1.0\n"), "point")
    for module in MODULES.values():
        result = module.solve(setup.si, optimizing(setup), StopCondition(5), random.Random(1))
        assert result.status is PlanStatus.SOLVED and result.path == ((1.0, 1.0),)


@pytest.mark.parametrize("problem", unit_sample(["space-3", "arm2-pair1", "rigid2-scene1"],
                                                keep=2))
def test_both_planners_draw_alike_until_the_first_solution(problem):
    # Informed RRT* differs only once a solution exists (the docs say so).
    setup = setup_of(problem)
    paths = {name: module.solve(setup.si, setup.pdef, StopCondition(30), random.Random(6)).path
             for name, module in MODULES.items()}
    assert paths["rrtstar"] == paths["informed"] and paths["rrtstar"]


def test_frontier_targets_find_a_maze_path_that_uniform_targets_miss_in_as_many_iterations():
    setup = setup_of("maze-50")
    found = [rrtstar.solve(setup.si, setup.pdef, StopCondition(60, max_iterations=3000),
                           random.Random(1),
                           rrtstar.Params(frontier_targets=share, guided_targets=0.0)).solved
             for share in (0.9, 0.0)]
    assert found == [True, False]


BENDS = {  # map: (iterations, a cost only a path through the bend points gets under)
    # space-0's shortest path passes (3, 1), where two blocked cells touch corner to
    # corner: round the cell above no path is shorter than 4.05 (3.78 through it).
    "space-0": (1000, 3.85),
    # space-3's bends round eight convex corners (47.11 to the goal point, 47.01 to the
    # goal region); with bend targets 47.15 after 3000 iterations, without 48.77.
    "space-3": (3000, 47.2),
}


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("problem", sorted(BENDS))
def test_bend_targets_take_the_corners_shortest_paths_pass(name, problem):
    setup = setup_of(problem)
    bends = setup.si.bend_points()
    assert ((3.0, 1.0) in bends) == (problem == "space-0")  # the pinch
    module = MODULES[name]
    iterations, bound = BENDS[problem]
    costs = {}
    for share in (0.05, 0.0):
        result = module.solve(setup.si, optimizing(setup),
                              StopCondition(60, max_iterations=iterations), random.Random(1),
                              module.Params(bend_targets=share))
        costs[share] = assert_valid(setup, result).cost
        assert bool(set(bends) & set(result.path)) == (share > 0.0)
    assert costs[0.05] < bound < costs[0.0], costs


@pytest.mark.parametrize("name", sorted(MODULES))
def test_rim_targets_end_the_answer_on_the_goal_regions_rim(name):
    """course-simple-0 has no blocked cell: the shortest path runs straight to the goal
    disc's rim (0.9). After 2000 iterations, seeds 1-3, each answer with rim targets
    ends on the rim and is shorter than the same seed's without, which ends inside.
    arm2-pair1's goal is a ball of the joint metric: there too the answer ends on it."""
    module = MODULES[name]
    rim = module.Params().rim_targets
    for problem, seeds, iterations in (("simple-0", (1, 2, 3), 2000), ("arm2-pair1", (1,), 500)):
        setup = setup_of(problem)
        goal = setup.pdef.goal
        costs, depths = {}, {}
        for share in (rim, 0.0):
            for seed in seeds:
                result = module.solve(setup.si, optimizing(setup),
                                      StopCondition(60, max_iterations=iterations),
                                      random.Random(seed), module.Params(rim_targets=share))
                costs[share, seed] = assert_valid(setup, result).cost
                depths[share, seed] = (goal.tolerance - goal.distance(result.path[-1])) \
                    / goal.tolerance
        for seed in seeds:
            assert 0.0 < depths[rim, seed] < 1e-8 < depths[0.0, seed], depths
            if problem == "simple-0":
                assert costs[rim, seed] < costs[0.0, seed], costs


@pytest.mark.parametrize("name", sorted(MODULES))
def test_ancestor_hops_hang_every_node_from_the_start_in_open_space(name):
    """course-simple-0 has no blocked cell: with ancestor hops every node hangs from
    the start and the answer is one straight motion; without, chains grow."""
    setup, module = setup_of("simple-0"), MODULES[name]
    for hops in (True, False):
        result = module.solve(setup.si, optimizing(setup),
                              StopCondition(60, max_iterations=1000), random.Random(2),
                              module.Params(ancestor_hops=hops))
        assert_valid(setup, result)
        from_start = {parent == setup.pdef.start for parent, _, _ in result.edges}
        assert (from_start == {True}) == hops and (len(result.path) == 2) == hops


def hop_runs(module, setup, pdef, stop, seed=1):
    """Per ``ancestor_hops`` setting: iterations, the tree's nodes, the answer's cost."""
    runs = {}
    for hops in (True, False):
        result = module.solve(setup.si, pdef, stop, random.Random(seed),
                              module.Params(ancestor_hops=hops))
        runs[hops] = (result.stats.iterations, {edge[2] for edge in result.edges},
                      assert_valid(setup, result).cost)
    return runs


HOP_PROBLEMS = ["space-3", "random-d20-20", "arm2-pair3"]


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("problem", HOP_PROBLEMS)
def test_ancestor_hops_change_parents_only(name, problem):
    """The first solution comes at the same iteration through the same nodes, no
    longer; RRT*'s uniform draws after it are the same too, and (1500 iterations) its
    answer is shorter for most of seeds 1-5 (a seed alone may lose by a hair)."""
    setup, module = setup_of(problem), MODULES[name]
    first = hop_runs(module, setup, setup.pdef, StopCondition(60))
    assert first[True][:2] == first[False][:2] and first[True][2] <= first[False][2]
    if name == "rrtstar":
        shorter = []
        for seed in range(1, 6):
            runs = hop_runs(module, setup, optimizing(setup),
                            StopCondition(60, max_iterations=1500), seed)
            assert runs[True][:2] == runs[False][:2]
            shorter.append(runs[True][2] < runs[False][2])
        assert sum(shorter) >= 3, shorter


@pytest.mark.parametrize("name", sorted(MODULES))
def test_guided_targets_lead_down_the_free_cells(name):
    """random-d20-100, seeds 1-3, 1500 iterations: with guided targets every first
    solution comes, valid; with none, not one (uniform and frontier targets fill the
    map before they reach the far corner). The family's worlds measure no such
    distance: no guided draws there (outputs as with none)."""
    module = MODULES[name]
    setup = setup_of("random-d20-100")
    solved = []
    for share in (rrtstar.RRTStarParams().guided_targets, 0.0):
        results = [module.solve(setup.si, setup.pdef, StopCondition(60, max_iterations=1500),
                                random.Random(seed), module.Params(guided_targets=share))
                   for seed in range(1, 4)]
        for result in results:
            if result.solved:
                assert_valid(setup, result)
        solved.append(sum(result.solved for result in results))
    assert solved == [3, 0], solved
    family = setup_of("arm2-pair1")
    runs = [format_plan(*(lambda r: (r.trajectory, r.tree))(module.solve(
        family.si, family.pdef, StopCondition(60, max_iterations=300), random.Random(2),
        module.Params(guided_targets=share)))) for share in (0.5, 0.0)]
    assert runs[0] == runs[1]


FIRST_CLOCK_READ = """
import importlib, random, sys, time
sys.path.insert(0, sys.argv[1])
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup
from rrt_cli.planners.base import StopCondition
planner, vehicle = sys.argv[3], sys.argv[4]
setup = grid_setup(parse_problem(open(sys.argv[2]).read()), vehicle)
stop = StopCondition(60, max_iterations=1)
read, seen = time.perf_counter, []
def clock():
    if not seen:
        seen.append("planning_core.worlds.grid_distance" in sys.modules)
    return read()
time.perf_counter = clock
importlib.import_module("rrt_cli.planners." + planner).solve(
    setup.si, setup.pdef, stop, random.Random(1))
print(seen[0], "planning_core.worlds.grid_distance" in sys.modules)
"""


@pytest.mark.parametrize("planner, vehicle, loaded", [
    ("rrtstar", "point", "True True"), ("rrt", "dubins", "True True"),
    ("rrtconnect", "dubins", "True True"), ("rrt", "point", "False False")])
def test_guided_planners_load_the_dijkstra_before_the_clock(planner, vehicle, loaded):
    """Where iterations are guided (RRT*'s on the point, RRT's and RRT-Connect's on the
    Dubins car), the Dijkstra's module is loaded before the planner first reads its
    clock: its import (tens of microseconds in a fresh process) would otherwise count
    toward the first solution's time. Without guided iterations nothing loads it."""
    done = subprocess.run([sys.executable, "-c", FIRST_CLOCK_READ, str(ROOT),
                           str(COURSE_DIR / "simple-0.sw"), planner, vehicle],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == loaded.split()
