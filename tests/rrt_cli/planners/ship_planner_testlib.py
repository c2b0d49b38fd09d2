"""What the spaceship planners' tests share: small maps made for them, and a run
that must solve and pass the validator's checks."""

from __future__ import annotations

import random
from pathlib import Path

from planning_core.setups import grid_setup
from planning_core.plan_text import format_plan
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from rrt_cli.planners.base import StopCondition
from validator.checks import validate_output

SHIPS = [Vehicle.SPACESHIP, Vehicle.LEFT_SPACESHIP]
# Far above what either planner needed on these maps in a 20-seed sweep (kpiece
# 25 025, rgrrt 79 895), so a regression fails instead of hanging.
ITERATION_CAP = 200_000

# A wall with a one-cell gap, and a zigzag of two-cell corridors.
GAP_WALL = """8
5
___#____
___#____
________
___#____
___#____
1.5 1.5
6.5 3.5
"""
ZIGZAG = """6
6
______
_####_
______
_####_
______
______
0.5 0.5
0.5 5.5
"""
# The goal's cell is walled in: nothing can reach it.
WALLED_GOAL = """5
5
_____
_###_
_#_#_
_###_
_____
0.5 0.5
2.5 2.5
"""


# The suite's 20x20 maze (1-cell corridors): the straight line to the goal
# misleads there, which the default goal_distance="cells" is for.
PROBLEMS_DIR = Path(__file__).resolve().parents[3] / "benchmarks" / "problems"
MAZE_20 = (PROBLEMS_DIR / "maze-20.sw").read_text()
MAZE_50 = (PROBLEMS_DIR / "maze-50.sw").read_text()


def solve_and_validate(planner, problem_text: str, vehicle: Vehicle, seed: int, params,
                       options=None):
    """Run ``planner.solve`` (the ship's ``GridControlOptions``: ``options``); it must
    solve, and its output must validate."""
    problem = parse_problem(problem_text)
    stop = StopCondition(time_limit=120, max_iterations=ITERATION_CAP)
    setup = grid_setup(problem, vehicle, options)
    result = planner.solve(setup.si, setup.pdef, stop, random.Random(seed), params)
    assert result.solved, (result.status, result.stats)
    output = format_plan(result.trajectory, result.tree)
    report = validate_output(problem, vehicle, output)
    assert report.valid, report.first_failure
    assert len(result.tree) == result.stats.tree_nodes - 1
    return result, output
