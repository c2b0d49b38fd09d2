"""Shortcut smoothing (-smooth): the path stays exactly collision-free, keeps its
ends, never gets longer, and validates with -strict; the CLI flag."""

import math
import random

import pytest

from benchmarks.generator import maze, random_field
from planning_core.setups import grid_setup
from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from planning_core.worlds.grid import GridWorld
from rrt_cli.planners import rrt, rrtconnect
from rrt_cli.planners.base import StopCondition
from rrt_cli.planners.paths import first_blocked_segment, path_length
from rrt_cli.smoothing import SmoothingParams, prune_vertices, smooth_path
from tests.conftest import COURSE_PROBLEMS, run_planner, solve_on
from validator.checks import validate_output

PROBLEMS = [parse_problem(p.read_text()) for p in COURSE_PROBLEMS] + [
    maze(11, random.Random(5)), random_field(15, 0.3, random.Random(3))]


def assert_smoothed(problem: Problem, before, after) -> None:
    world = GridWorld(problem)
    si = grid_setup(problem, Vehicle.POINT).si
    assert after[0] == tuple(before[0]) and after[-1] == tuple(before[-1])
    assert path_length(after, math.dist) <= path_length(before, math.dist) + 1e-9
    assert first_blocked_segment(si, after) is None
    assert all(world.point_strictly_inside(x, y) for x, y in after)
    report = validate_output(problem, Vehicle.POINT, format_plan(after, ()), strict=True)
    assert report.valid, report.first_failure
    assert not report.warnings


@pytest.mark.parametrize("problem", PROBLEMS, ids=lambda p: f"{p.width}x{p.height}")
def test_smoothed_planner_paths_stay_valid_and_get_shorter(problem):
    shortened = 0
    for seed in range(6):
        for planner in (rrt, rrtconnect):
            raw = solve_on(planner, grid_setup(problem, Vehicle.POINT), StopCondition(30),
                                random.Random(seed)).trajectory
            smooth = smooth_path(grid_setup(problem, Vehicle.POINT).si, raw, random.Random(seed))
            assert_smoothed(problem, raw, smooth)
            shortened += path_length(smooth, math.dist) < path_length(raw, math.dist) - 1e-9
    if len(problem.blocked) > 12:  # beyond the 4x3 course map, RRT paths zigzag
        assert shortened >= 10


def test_visible_ends_become_one_segment():
    problem = Problem(5, 5, bytes(25), (0.5, 0.5), (4.5, 4.5))
    zigzag = [(0.5, 0.5), (2.0, 0.7), (1.0, 3.0), (4.0, 2.0), (4.5, 4.5)]
    assert smooth_path(grid_setup(problem, Vehicle.POINT).si, zigzag, random.Random(0)) == ((0.5, 0.5), (4.5, 4.5))


def test_corner_around_a_wall_is_cut_but_not_through_it():
    # A wall at column 2, rows 0-3: the path must go over its top (y >= 4).
    blocked = bytearray(25)
    for row in range(4):
        blocked[row * 5 + 2] = 1
    problem = Problem(5, 5, bytes(blocked), (0.5, 0.5), (4.5, 0.5))
    detour = [(0.5, 0.5), (0.5, 2.0), (0.5, 4.5), (1.5, 4.5), (2.5, 4.5), (3.5, 4.5),
              (4.5, 4.5), (4.5, 2.0), (4.5, 0.5)]
    world = grid_setup(problem, Vehicle.POINT).si
    pruned = prune_vertices(world, detour)
    assert len(pruned) < len(detour)
    smooth = smooth_path(world, detour, random.Random(3), SmoothingParams(shortcut_attempts=400))
    assert_smoothed(problem, detour, smooth)
    # The best path bends at the wall's top corners (2, 4) and (3, 4): length ~ 8.3.
    assert path_length(smooth, math.dist) < path_length(detour, math.dist) - 2.0
    assert path_length(smooth, math.dist) >= 2 * math.dist((0.5, 0.5), (2, 4)) + 1 - 1e-9


def test_same_rng_same_result():
    problem = PROBLEMS[-1]
    raw = solve_on(rrt, grid_setup(problem, Vehicle.POINT), StopCondition(30), random.Random(1)).trajectory
    world = grid_setup(problem, Vehicle.POINT).si
    assert smooth_path(world, raw, random.Random(8)) == smooth_path(world, raw, random.Random(8))


def test_short_paths_are_returned_as_they_are():
    world = grid_setup(Problem(3, 3, bytes(9), (0.5, 0.5), (2.5, 2.5)), Vehicle.POINT).si
    assert smooth_path(world, [(0.5, 0.5)], random.Random(0)) == ((0.5, 0.5),)
    assert smooth_path(world, [(0.5, 0.5), (2.5, 2.5)], random.Random(0)) == (
        (0.5, 0.5), (2.5, 2.5))


def test_cli_smooth_flag():
    text = COURSE_PROBLEMS[-1].read_text()
    problem = parse_problem(text)
    plain = run_planner(["-seed", "5"], text)
    smooth = run_planner(["-seed", "5", "-smooth"], text)
    assert plain.returncode == smooth.returncode == 0
    reports = [validate_output(problem, Vehicle.POINT, done.stdout.decode(), strict=True)
               for done in (plain, smooth)]
    assert all(report.valid for report in reports)
    # Same seed, same search: smoothing only shortens the trajectory; the tree is unchanged.
    assert reports[1].path_length < reports[0].path_length
    assert plain.stdout.decode().split("\n")[-2] == smooth.stdout.decode().split("\n")[-2]
    refused = run_planner(["-grad", "-smooth"], text)
    assert refused.returncode == 2 and refused.stdout == b""
