"""SST (rrt_cli/planners/sst.py): every answer passes the validator's own checks, on
the family's kinodynamic systems and both grid ships; with an objective the cost only
falls; the witnesses keep at most one active node each, and what is inactive or pruned
is found by no query; a seed fixes the output."""

from __future__ import annotations

import math
import random

import pytest

from cli_common import parse_any_problem
from planning_core.costs import path_cost
from planning_core.plan_text import format_plan
from planning_core.problem_definition import Objective
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup, kinoplan_setup
from planning_core.vehicles import Vehicle
from rrt_cli.planners import PLANNERS, sst
from rrt_cli.planners.base import PlanStatus, StopCondition
from tests.conftest import COURSE_PROBLEMS, ROOT, run_planner, unit_sample
from tests.rrt_cli.planners.ship_planner_testlib import GAP_WALL, SHIPS, ZIGZAG
from tests.rrt_cli.test_family_kinodynamic_planners import KINODYNAMIC_PROBLEMS, SMALL
from validator.checks import validate_plan

FAMILY = ROOT / "benchmarks" / "problems" / "family"
SST_DEFAULTS = sst.SSTParams()


def _setup(text: str, vehicle: Vehicle | None = None):
    if vehicle is None:
        return kinoplan_setup(parse_any_problem(text))
    return grid_setup(parse_problem(text), vehicle)


def solve_and_validate(text: str, vehicle: Vehicle | None, seed: int,
                       stop: StopCondition | None = None, objective: Objective | None = None):
    """SST's answer, which must be solved and valid by the validator's own checks."""
    setup = _setup(text, vehicle)
    pdef = setup.pdef if objective is None else setup.pdef.__class__(
        setup.pdef.start, setup.pdef.goal, objective)
    result = sst.solve(setup.si, pdef, stop or StopCondition(time_limit=60), random.Random(seed))
    assert result.solved, (result.status, result.stats)
    report = validate_plan(setup, format_plan(result.trajectory, result.tree))
    assert report.valid, report.first_failure
    assert len(result.tree) == result.stats.tree_nodes - 1
    return setup, result, report


SMALL_CASES = ([(name, None) for name in sorted(SMALL)]
               + [(name, ship) for name in ("gap-wall", "zigzag") for ship in SHIPS])
MAPS = {"gap-wall": GAP_WALL, "zigzag": ZIGZAG}


# The left ship on gap-wall (the slow case) is CI only: zigzag-left plans for it too.
@pytest.mark.parametrize("name, vehicle", [
    pytest.param(n, v, id=f"{n}-{v.value if v else 'family'}",
                 marks=pytest.mark.slow if (n, v) == ("gap-wall", Vehicle.LEFT_SPACESHIP) else ())
    for n, v in SMALL_CASES])
def test_small_problems_solved_and_valid(name, vehicle):
    text = SMALL[name] if vehicle is None else MAPS[name]
    _, result, _ = solve_and_validate(text, vehicle, 1)
    assert result.stats.first_solution_seconds == result.stats.improvements[0][0]


BENCHMARK_CASES = ([(FAMILY / f"{name}.kp", None) for name in KINODYNAMIC_PROBLEMS]
                   + [(path, ship) for path in COURSE_PROBLEMS for ship in SHIPS])


@pytest.mark.slow  # seconds each (the left ship on space-3: tens)
@pytest.mark.parametrize("path, vehicle", BENCHMARK_CASES,
                         ids=[f"{p.stem}-{v.value if v else 'family'}" for p, v in BENCHMARK_CASES])
def test_benchmark_problems_seed_1_solved_and_valid(path, vehicle):
    solve_and_validate(path.read_text(), vehicle, 1, StopCondition(time_limit=120))


@pytest.mark.parametrize("text, vehicle, seed, more", [(SMALL["pendulum"], None, 2, 2000),
                                                       (GAP_WALL, Vehicle.SPACESHIP, 7, 2000)],
                         ids=["pendulum", "spaceship"])
def test_with_an_objective_the_cost_only_falls(text, vehicle, seed, more):
    """The same seed run longer: its answer costs at most the first solution, every
    improvement is cheaper and later than the one before, and the answer is valid."""
    first = solve_and_validate(text, vehicle, seed)[1]
    setup, longer, report = solve_and_validate(text, vehicle, seed, StopCondition(
        max_iterations=first.stats.iterations + more), Objective())
    steps = longer.stats.improvements
    assert steps[0][1] == pytest.approx(path_cost(setup.si, first.path, first.path_controls),
                                        rel=1e-12)
    assert len(steps) > 1, f"no improvement in {more} iterations"
    assert all(a[0] < b[0] and a[1] > b[1] for a, b in zip(steps, steps[1:]))
    assert report.cost == pytest.approx(steps[-1][1], rel=1e-9) and report.cost < steps[0][1]
    assert longer.stats.iterations == first.stats.iterations + more


def test_the_objective_threshold_stops_the_search():
    setup = _setup(SMALL["pendulum"])
    free = sst.solve(setup.si, setup.pdef.__class__(setup.pdef.start, setup.pdef.goal,
                                                    Objective()),
                     StopCondition(max_iterations=4000), random.Random(2))
    costs = [cost for _, cost in free.stats.improvements]
    threshold = costs[1]  # the second solution is good enough
    _, met, _ = solve_and_validate(SMALL["pendulum"], None, 2, objective=Objective(threshold))
    assert [cost for _, cost in met.stats.improvements] == costs[:2]
    assert met.stats.iterations < free.stats.iterations


@pytest.mark.parametrize("text, vehicle, iterations", unit_sample([  # >= 10 replaced nodes
    pytest.param(SMALL["car2"], None, 6000, id="car2"),
    pytest.param(ZIGZAG, Vehicle.SPACESHIP, 1000, id="spaceship"),
    pytest.param(GAP_WALL, Vehicle.LEFT_SPACESHIP, 3000, id="left")], keep=2))
def test_each_witness_keeps_one_active_node_and_the_rest_is_never_found(text, vehicle,
                                                                         iterations):
    setup = _setup(text, vehicle)
    pdef = setup.pdef.__class__(setup.pdef.start, setup.pdef.goal, Objective())
    search = sst._Search(setup.si, pdef, random.Random(4), sst.SSTParams())
    before: list[float] = []
    for iteration in range(iterations):
        goal_node = search.iterate()
        if goal_node is not None:
            search.accept(goal_node)
        if iteration % 10 == 0:  # a witness's representative only gets cheaper
            now = [search.costs[rep] for rep in search.reps]
            assert all(b >= a for a, b in zip(now, before)), "a costlier node replaced one"
            before = now
    active = [k for k, is_active in enumerate(search.active) if is_active]
    reps = [rep for rep in search.reps if rep >= 0]
    assert len(reps) == len(set(reps)), "a node represents two witnesses"
    assert sorted(reps) == active, "the active nodes are not exactly the representatives"
    state_distance, states = setup.si.state_distance, search.tree.states
    for witness, rep in enumerate(search.reps):
        if rep >= 0:
            assert state_distance(search.witnesses[witness], states[rep]) \
                <= search.pruning_radius
    inactive = len(states) - len(active)
    assert inactive >= 10, "too few replaced nodes to test anything"
    everything = search.nodes.within(pdef.start, math.inf)
    assert sorted(everything) == active
    for k in range(len(states)):  # no query finds an inactive node, a pruned one included
        assert search.active[search.nodes.nearest(states[k])]
    # The tree: pruned nodes are inactive leaves of the tree as it was; what is left
    # is connected to the start and holds the best path.
    in_tree, parents = search.in_tree, search.tree.parents
    assert not all(in_tree) and all(in_tree[parents[k]] for k in range(1, len(states))
                                    if in_tree[k])
    assert all(in_tree[k] for k in search.tree.path_to(search.best))
    assert all(search.active[k] or search.children[k] > 0 or search.pinned[k]
               for k in range(len(states)) if in_tree[k])


def test_seed_reproduces_the_output_bit_for_bit():
    text = COURSE_PROBLEMS[1].read_text()
    runs = [run_planner(["-grad", "-planner", "sst", "-seed", seed, *more], text)
            for seed, more in [("3", []), ("3", []), ("4", []),
                               ("3", ["-optimize", "-iterations", "1500"]),
                               ("3", ["-optimize", "-iterations", "1500"])]]
    assert all(run.returncode == 0 for run in runs), [run.stderr for run in runs]
    first, again, other, optimized, optimized_again = (run.stdout for run in runs)
    assert first == again and first != other
    assert optimized == optimized_again and optimized != first


def test_registered_as_optimizing_for_kinodynamic_systems_only():
    entry = PLANNERS["sst"]
    assert entry.optimizing
    assert {v for v in Vehicle if entry.plans_for(v.system)} == set(SHIPS)
    refused = run_planner(["-planner", "sst"], COURSE_PROBLEMS[1].read_text())
    assert (refused.returncode, refused.stdout) == (2, b"")
    with pytest.raises(ValueError):
        setup = grid_setup(parse_problem(GAP_WALL), Vehicle.POINT)
        sst.solve(setup.si, setup.pdef, StopCondition(), random.Random(0))


def test_a_walled_in_goal_ends_at_the_limit_with_no_path():
    text = "5\n5\n_____\n_###_\n_#_#_\n_###_\n_____\n0.5 0.5\n2.5 2.5\n"
    setup = _setup(text, Vehicle.SPACESHIP)
    result = sst.solve(setup.si, setup.pdef, StopCondition(max_iterations=500),
                       random.Random(0))
    assert result.status is PlanStatus.ITERATION_LIMIT and result.path == ()
    assert result.stats.first_solution_seconds is None and result.stats.improvements == ()


@pytest.mark.parametrize("bad", [dict(goal_bias=1.5), dict(selection_radius=-1.0),
                                 dict(pruning_radius=float("nan")), dict(frontier_targets=1.5)])
def test_bad_params_are_rejected(bad):
    with pytest.raises(ValueError):
        sst.SSTParams(**bad)


def test_the_best_path_stays_in_the_printed_tree_when_its_nodes_turn_inactive():
    """Replaced representatives on the best path are kept (pinned), so the printed
    tree holds the printed path; a later answer unpins them."""
    setup = _setup(SMALL["pendulum"])
    pdef = setup.pdef.__class__(setup.pdef.start, setup.pdef.goal, Objective())
    search = sst._Search(setup.si, pdef, random.Random(1), sst.SSTParams())
    while search.best is None:
        goal_node = search.iterate()
        if goal_node is not None:
            search.accept(goal_node)
    path = search.tree.path_to(search.best)
    for k in reversed(path[1:]):  # as if each were replaced by a cheaper node
        if search.active[k]:
            search.deactivate(k)
    assert all(search.in_tree[k] for k in path)
    result = search.result(PlanStatus.SOLVED, 0.0, [])
    report = validate_plan(setup, format_plan(result.trajectory, result.tree))
    assert report.valid, report.first_failure
    assert {edge[2] for edge in result.edges} >= set(result.path[1:])
    childless = [k for k in path[1:] if search.children[k] == 0]
    assert childless, "the old answer's last node has children: nothing to prune"
    search.accept(0)  # another answer: the old path's inactive leaves are pruned
    assert not any(search.in_tree[k] for k in childless)


def test_frontier_targets_on_the_grid_until_the_first_solution():
    """Before a solution the targets are frontier points (free cells beside a node's);
    after it none are; the family's worlds offer no frontier. A ship's target is a whole
    state: the point with a velocity within the target speed."""
    setup = _setup(GAP_WALL, Vehicle.SPACESHIP)
    search = sst._Search(setup.si, setup.pdef, random.Random(1),
                         sst.SSTParams(goal_bias=0.0, frontier_targets=1.0))
    start_cell = (int(setup.pdef.start[0]), int(setup.pdef.start[1]))
    targets = [search.target() for _ in range(50)]
    speed = setup.si.options.target_speed
    assert all(len(t) == 4 and max(abs(t[2]), abs(t[3])) <= speed for t in targets)
    assert len({t[2:] for t in targets}) == 50  # a velocity drawn for each
    cells = {(int(x), int(y)) for x, y, _, _ in targets}
    assert cells == {(start_cell[0] + dx, start_cell[1] + dy)
                     for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))}
    search.best = 0
    far = [t for t in (search.target() for _ in range(200))
           if abs(int(t[0]) - start_cell[0]) + abs(int(t[1]) - start_cell[1]) > 1]
    assert far  # uniform over the map again
    family = _setup(SMALL["pendulum"])
    assert sst._Search(family.si, family.pdef, random.Random(1), sst.SSTParams()).frontier is None


def test_refining_by_distance_changes_nothing_where_it_is_the_whole_state():
    """The family's distance is its whole-state metric: after the first solution the
    rebuilt index selects the same nodes, so the answer and tree are the same."""
    runs = []
    for refine in (True, False):
        setup = _setup(SMALL["pendulum"])
        pdef = setup.pdef.__class__(setup.pdef.start, setup.pdef.goal, Objective())
        result = sst.solve(setup.si, pdef, StopCondition(max_iterations=6000), random.Random(2),
                           sst.SSTParams(refine_by_distance=refine))
        assert len(result.stats.improvements) > 1
        runs.append(format_plan(result.trajectory, result.tree))
    assert runs[0] == runs[1]


def test_guided_iterations_take_the_active_nodes_nearest_the_goal_each_once():
    """Until the first solution a share of iterations extends the active node nearest
    the goal along the free cells (judged where braking would stop it), each node at
    most once; the family's worlds measure no such distance, and a share of 0 turns it
    off (no draw for it: OMPL's selection)."""
    setup = _setup(ZIGZAG, Vehicle.SPACESHIP)
    search = sst._Search(setup.si, setup.pdef, random.Random(3), sst.SSTParams())
    while search.iterations < 400 and search.best is None:
        search.iterate()
    assert search.best is None and len(search.guide) > 50
    key = setup.si.stopping_point_key(setup.si.distance_along_free_space(setup.pdef.goal))
    taken, keys = [], []
    while True:
        node = search.guided()
        if node < 0:
            break
        taken.append(node)
        keys.append(key(search.tree.states[node]))
    assert len(set(taken)) == len(taken) and all(search.active[k] for k in taken)
    assert keys == sorted(keys)
    inactive = [k for k, live in enumerate(search.active) if not live]
    assert inactive and not set(inactive) & set(taken)
    family = _setup(SMALL["pendulum"])
    assert sst._Search(family.si, family.pdef, random.Random(1), sst.SSTParams()).guide_key is None
    assert sst._Search(setup.si, setup.pdef, random.Random(1),
                       sst.SSTParams(guided_share=0.0)).guide_key is None


def test_guidance_finds_a_first_path_sooner():
    """narrow-20, the plain ship, seeds 1-6, 1500 iterations each: guided, every run
    solves; unguided, at most half (docs/optimal-planning.md has the medians)."""
    setup = _setup((ROOT / "benchmarks" / "problems" / "narrow-20.sw").read_text(),
                   Vehicle.SPACESHIP)
    solved = [_solved_and_valid(setup, sst.SSTParams(guided_share=share), range(1, 7), 1500)
              for share in (SST_DEFAULTS.guided_share, 0.0)]
    assert solved[0] == 6 and solved[1] <= 3, solved


def _solved_and_valid(setup, params: sst.SSTParams, seeds, iterations: int) -> int:
    """How many of ``seeds`` solve within ``iterations``; every answer must be valid."""
    solved = 0
    for seed in seeds:
        result = sst.solve(setup.si, setup.pdef, StopCondition(60, max_iterations=iterations),
                           random.Random(seed), params)
        if result.solved:
            report = validate_plan(setup, format_plan(result.trajectory, result.tree))
            assert report.valid, report.first_failure
            solved += 1
    return solved


def test_a_guided_node_is_extended_by_the_reachable_set():
    """A guided iteration extends its node by each control of ``si.reachable_controls``
    held one step: every node it adds is that node's child by one of those controls,
    exactly where the control leads; with ``guided_reach=False`` one random motion."""
    setup = _setup(ZIGZAG, Vehicle.LEFT_SPACESHIP)
    controls = setup.si.reachable_controls()
    search = sst._Search(setup.si, setup.pdef, random.Random(5), sst.SSTParams())
    assert search.guide_controls == tuple(controls)
    for _ in range(30):
        node, before = search.guided(), len(search.tree.states)
        assert node >= 0
        search.expand(node)
        added = range(before, len(search.tree.states))
        assert all(search.tree.parents[k] == node and search.tree.controls[k] in controls
                   and search.tree.states[k] == setup.si.propagate_valid(
                       search.tree.states[node], search.tree.controls[k]) for k in added)
    assert len(search.tree.states) > 30
    assert sst._Search(setup.si, setup.pdef, random.Random(5),
                       sst.SSTParams(guided_reach=False)).guide_controls == ()


def test_the_left_only_ship_takes_the_50_cell_maze():
    """maze-50, the left-only ship, seeds 1-3, 6000 iterations: with the reachable set
    every run solves, valid; with one random motion per guided node none does (its
    right turns need a near stop, which random controls seldom give)."""
    setup = _setup((ROOT / "benchmarks" / "problems" / "maze-50.sw").read_text(),
                   Vehicle.LEFT_SPACESHIP)
    solved = [_solved_and_valid(setup, sst.SSTParams(guided_reach=reach), range(1, 4), 6000)
              for reach in (True, False)]
    assert solved == [3, 0], solved


@pytest.mark.parametrize("name, vehicle", [("car2-corridors", None),
                                           ("gap-wall", Vehicle.SPACESHIP)])
def test_a_whole_motion_is_the_random_motion_when_no_slice_is_cut_else_none(name, vehicle):
    """``whole_motions`` (OMPL's rule): from the same draws, ``random_motion(whole=True)``
    is the cut-at-the-first-invalid-slice motion when it lasts the duration drawn, and
    None when it was cut short."""
    text = MAPS[name] if vehicle else (FAMILY / f"{name}.kp").read_text()
    setup = _setup(text, vehicle)
    si = setup.si
    grown = sst.solve(si, setup.pdef, StopCondition(max_iterations=300), random.Random(1),
                      sst.SSTParams(whole_motions=False))
    kinds = set()
    for k, (_, _, state) in enumerate(grown.edges[:150]):
        for seed in range(k * 8, k * 8 + 8):
            cut = si.random_motion(state, random.Random(seed))
            draws = random.Random(seed)
            control = si.sample_control(draws)
            if vehicle is None:
                drawn, done = control[-1], None if cut is None else cut[0][-1]
            else:
                drawn = draws.randint(si.options.min_steps, si.options.max_steps)
                done = None if cut is None else len(cut[1])
            whole = done == drawn
            kinds.add(whole)
            assert si.random_motion(state, random.Random(seed), True) == (cut if whole else None)
    assert kinds == {True, False}
