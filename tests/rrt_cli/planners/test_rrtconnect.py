"""RRT-Connect (point vehicle): every course problem x 20 seeds and a few small
generated maps, each output checked by the validator with -strict, with
frontier targets (the default) and without (the published algorithm); the
suite's 100x100 maze; the limits; reproducibility; the CLI's refusal of other
vehicles."""

import random
import statistics

import pytest

from benchmarks.generator import maze, narrow_passage, random_field
from planning_core.setups import grid_setup
from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from rrt_cli.planners import rrt, rrtconnect
from rrt_cli.planners.base import PlanStatus, StopCondition
from tests.conftest import COURSE_PROBLEMS, ROOT, run_planner, solve_on, unit_sample
from validator.checks import validate_output

SEEDS = range(20)
PUBLISHED = rrtconnect.Params(frontier_targets=0.0)


def assert_valid(problem: Problem, result) -> None:
    assert result.solved, result.status
    report = validate_output(problem, Vehicle.POINT,
                             format_plan(result.trajectory, result.tree), strict=True)
    assert report.valid, report.first_failure
    assert not report.warnings
    # Both trees' edges are printed: every node but the two roots has one.
    assert len(result.tree) == result.stats.tree_nodes - 2
    assert result.trajectory[0] == problem.start
    assert result.trajectory[-1] == problem.goal  # the goal tree's root


@pytest.mark.parametrize("path", COURSE_PROBLEMS, ids=lambda p: p.stem)
def test_course_problems_20_seeds_all_valid(path):
    problem = parse_problem(path.read_text())
    for seed in SEEDS:
        result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(time_limit=30),
                                  random.Random(seed))
        assert_valid(problem, result)


@pytest.mark.parametrize("name,problem", [
    ("maze-11", maze(11, random.Random(5))),
    ("random-15", random_field(15, 0.3, random.Random(3))),
    ("narrow-14", narrow_passage(14, random.Random(2))),
], ids=lambda value: value if isinstance(value, str) else "")
@pytest.mark.parametrize("params", [rrtconnect.Params(), PUBLISHED], ids=["frontier", "uniform"])
def test_generated_maps_valid(name, problem, params):
    for seed in range(5):
        result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(time_limit=30),
                                  random.Random(seed), params)
        assert_valid(problem, result)


@pytest.mark.parametrize("seed", unit_sample(range(3)))
def test_solves_the_100x100_maze(seed):
    # Uniform targets need about 80 s here (1.4 million iterations); the time
    # limit is generous so a slow machine does not fail it, the iteration
    # limit is what a regression would hit.
    problem = parse_problem((ROOT / "benchmarks" / "problems" / "maze-100.sw").read_text())
    result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT),
                      StopCondition(time_limit=120, max_iterations=100_000),
                      random.Random(seed))
    assert_valid(problem, result)


@pytest.mark.slow  # a comparison over seeds: seconds
def test_frontier_targets_grow_fewer_nodes_on_a_maze():
    # Node counts are deterministic per seed, so this is not a timing test.
    problem = maze(21, random.Random(4))
    frontier, uniform = [], []
    for seed in range(4):
        frontier.append(solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                         random.Random(seed)).stats.tree_nodes)
        uniform.append(solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                        random.Random(seed), PUBLISHED).stats.tree_nodes)
    assert statistics.median(frontier) < statistics.median(uniform) / 2


@pytest.mark.parametrize("share", [-0.1, 1.5])
def test_frontier_share_outside_0_1_is_refused(share):
    with pytest.raises(ValueError, match="frontier_targets"):
        rrtconnect.Params(frontier_targets=share)


# Comparisons over 7 seeds take seconds: marked slow.
@pytest.mark.slow
@pytest.mark.parametrize("params", [rrtconnect.Params(), PUBLISHED], ids=["frontier", "uniform"])
def test_grows_fewer_nodes_than_rrt_on_a_maze(params):
    # Node counts are deterministic per seed, so this is not a timing test.
    problem = maze(21, random.Random(7))
    ours, theirs = [], []
    for seed in range(7):
        ours.append(solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                     random.Random(seed), params).stats.tree_nodes)
        theirs.append(solve_on(rrt, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                random.Random(seed)).stats.tree_nodes)
    assert statistics.median(ours) < statistics.median(theirs)


def test_same_seed_same_result_and_seeds_differ():
    problem = parse_problem(COURSE_PROBLEMS[-1].read_text())
    runs = [solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(seed))
            for seed in (4, 4, 5)]
    assert runs[0].trajectory == runs[1].trajectory and runs[0].tree == runs[1].tree
    assert runs[0].tree != runs[2].tree


def corner_only_problem() -> Problem:
    # Free cells (0, 0) and (1, 1) touch only at the point (1, 1): 8-connected, so
    # not provably unreachable, but only a segment exactly through that point gets
    # across, and no two random points line up with it (start and goal do not).
    return Problem(2, 2, bytes([0, 1, 1, 0]), (0.3, 0.6), (1.5, 1.5))


def test_iteration_limit_ends_an_impossible_search():
    result = solve_on(rrtconnect, grid_setup(corner_only_problem(), Vehicle.POINT),
                              StopCondition(time_limit=30, max_iterations=3000),
                              random.Random(1))
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.trajectory == ()
    assert result.stats.iterations == 3000


def test_walled_off_goal_is_reported_at_once():
    problem = Problem(3, 1, bytes([0, 1, 0]), (0.5, 0.5), (2.5, 0.5))
    result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(0))
    assert result.status is PlanStatus.UNREACHABLE
    assert result.stats.iterations == 0


def test_start_within_tolerance_is_one_point():
    problem = Problem(3, 3, bytes(9), (1.5, 1.5), (1.55, 1.5))
    result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(0))
    assert result.solved and result.trajectory == ((1.5, 1.5),)


def test_max_step_limits_every_edge():
    problem = parse_problem(COURSE_PROBLEMS[-1].read_text())
    params = rrtconnect.Params(max_step=0.75)
    result = solve_on(rrtconnect, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(2), params)
    assert_valid(problem, result)
    assert max(((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
               for x0, y0, x1, y1 in result.tree) <= 0.75 + 1e-9


def test_cli_runs_it_and_refuses_the_spaceship():
    text = COURSE_PROBLEMS[0].read_text()
    done = run_planner(["-planner", "rrtconnect", "-seed", "3"], text)
    assert done.returncode == 0, done.stderr
    report = validate_output(parse_problem(text), Vehicle.POINT, done.stdout.decode(), strict=True)
    assert report.valid
    refused = run_planner(["-grad", "-planner", "rrtconnect"], text)
    assert refused.returncode == 2
    assert refused.stdout == b""
    assert len(refused.stderr.decode().strip().splitlines()) == 1
