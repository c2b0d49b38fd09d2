"""arm2's shortest-path yardstick: valid by the validator's own checks, no longer than
rrtstar's best answers, and the straight torus distance where nothing is in the way."""

import functools
import math
import subprocess

import pytest

from benchmarks.arm2_shortest_path import arm2_shortest_path
from benchmarks.catalog import ROOT
from benchmarks.family import FAMILY_DIR
from cli_common import parse_any_problem
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from tests.conftest import unit_sample
from validator.checks import validate_plan

PAIRS = [f"arm2-pair{k}" for k in (3, 1, 2, 4, 5)]
"""The family's arm2 problems, the quickest to solve first (the unit run's one)."""


@functools.lru_cache(maxsize=None)
def solved(name: str):
    problem = parse_any_problem((FAMILY_DIR / f"{name}.kp").read_text())
    return problem, arm2_shortest_path(problem)


def _open_problem(start, goal) -> str:
    return ("kinoplan 1\nsystem arm2\nworld -2.2 -2.2 2.2 2.2\n"
            f"start theta1 {start[0]} theta2 {start[1]}\n"
            f"goal theta1 {goal[0]} theta2 {goal[1]} within 0.01\n")


@pytest.mark.parametrize("name", unit_sample(PAIRS))
def test_the_path_passes_the_validators_checks_and_costs_its_length(name):
    problem, found = solved(name)
    assert found is not None
    report = validate_plan(kinoplan_setup(problem), format_plan(found.points, []))
    assert report.valid, report.first_failure
    assert report.cost == pytest.approx(found.length, rel=1e-9)
    # The refinement's rounds never lengthen the path, and the last one falls by < 0.1%.
    assert list(found.rounds) == sorted(found.rounds, reverse=True)
    assert found.rounds[-2] - found.rounds[-1] < 1e-3 * found.rounds[-1]


@pytest.mark.parametrize("start,goal", [((-0.5, -0.5), (1.5, 1.2)),
                                        ((3.0, 0.2), (-3.0, -0.1)),   # across pi
                                        ((0.1, -3.1), (0.4, 3.1))])
def test_without_obstacles_it_is_the_straight_torus_distance(start, goal):
    problem = parse_any_problem(_open_problem(start, goal))
    found = arm2_shortest_path(problem)
    straight = math.hypot(*(math.remainder(g - s, 2 * math.pi) for s, g in zip(start, goal)))
    assert found.length == pytest.approx(straight, rel=1e-9)
    assert len(found.points) == 2
    assert validate_plan(kinoplan_setup(problem), format_plan(found.points, [])).valid


@pytest.mark.slow
@pytest.mark.parametrize("name,seed", [("arm2-pair1", 1), ("arm2-pair4", 2)])
def test_it_is_no_longer_than_rrtstars_10_second_answer(name, seed):
    problem, found = solved(name)
    text = (FAMILY_DIR / f"{name}.kp").read_text()
    done = subprocess.run([str(ROOT / "run.sh"), "-planner", "rrtstar", "-seed", str(seed),
                           "-optimize", "-time", "10"], input=text.encode(),
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr.decode()
    report = validate_plan(kinoplan_setup(problem), done.stdout.decode())
    assert report.valid, report.first_failure
    # rrtstar's answer may end within the goal's 0.01 of the goal configuration.
    assert found.length <= report.cost + problem.goal.tolerance
