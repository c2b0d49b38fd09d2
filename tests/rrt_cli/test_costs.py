"""A path's cost (planning_core.costs): the same number in the planner's -stats line
and in the validator's report, per kind of system; -optimize and -cost with a
planner that stops at its first solution are a usage error."""

from __future__ import annotations

import json
import math
import re
import sys

import pytest

from planning_core.costs import path_cost
from planning_core.problem_definition import Objective
from planning_core.setups import grid_setup, kinoplan_setup
from cli_common import parse_any_problem
from tests.conftest import COURSE_DIR, ROOT, plan_in_process
from validator.checks import validate_plan

FAMILY = ROOT / "benchmarks" / "problems" / "family"
CASES = [  # (problem, flags, cost kind)
    (COURSE_DIR / "space-1.sw", [], "length"),
    (COURSE_DIR / "simple-0.sw", ["-grad"], "length"),
    (COURSE_DIR / "simple-0.sw", ["-grad", "-left"], "length"),
    (FAMILY / "pendulum-t5.kp", [], "duration"),
    (FAMILY / "arm2-pair1.kp", ["-planner", "rrtconnect"], "length"),
]


def _setup(path, flags):
    problem = parse_any_problem(path.read_text())
    if path.suffix == ".kp":
        return kinoplan_setup(problem)
    vehicle = "left" if "-left" in flags else "spaceship" if "-grad" in flags else "point"
    return grid_setup(problem, vehicle)


@pytest.mark.parametrize("path, flags, kind", CASES,
                         ids=[f"{p.stem}{''.join(f)}" for p, f, _ in CASES])
def test_the_stats_cost_is_the_validators(monkeypatch, path, flags, kind):
    status, out, err = plan_in_process(monkeypatch, [*flags, "-seed", "1", "-stats"],
                                       path.read_text())
    assert status == 0, err
    stats = re.search(r"cost=(\S+) first_solution_seconds=(\S+)", err)
    report = validate_plan(_setup(path, flags), out)
    assert report.valid and report.cost_kind == kind
    assert float(stats.group(1)) == pytest.approx(report.cost, rel=1e-8)
    assert float(stats.group(2)) > 0


def test_costs_by_kind():
    ship = grid_setup(parse_any_problem((COURSE_DIR / "space-1.sw").read_text()), "spaceship")
    a, b, c = (1.0, 1.0, 0.0, 0.0), (4.0, 5.0, 1.0, 0.0), (4.0, 6.0, 0.0, 0.0)
    assert path_cost(ship.si, [a, b, c], [(0.0, 0.0)] * 2) == 6.0  # positions: 5 + 1
    family = kinoplan_setup(parse_any_problem((FAMILY / "pendulum-t5.kp").read_text()))
    start = family.pdef.start
    controls = [(0.0, 7), (1.0, 3)]
    assert path_cost(family.si, [start, start, start], controls) == pytest.approx(
        10 * family.system.dt)
    point = grid_setup(parse_any_problem((COURSE_DIR / "space-1.sw").read_text()), "point")
    assert path_cost(point.si, [(1.0, 1.0), (4.0, 5.0), (4.0, 6.0)]) == 6.0
    assert path_cost(point.si, [(1.0, 1.0)]) == 0.0


def test_an_objective_is_met_at_its_threshold():
    assert Objective(2.0).satisfied(2.0) and not Objective(2.0).satisfied(2.0 + 1e-12)
    assert not Objective().satisfied(math.ulp(0.0))


@pytest.mark.parametrize("flags", [["-optimize"], ["-cost", "3"]])
def test_optimizing_flags_need_an_optimizing_planner(monkeypatch, flags):
    status, out, err = plan_in_process(monkeypatch, [*flags, "-seed", "1"],
                                       (COURSE_DIR / "space-1.sw").read_text())
    assert (status, out) == (2, "")
    assert err.count("\n") == 1 and "stops at its first solution" in err


def test_the_validators_json_reports_the_cost_of_a_valid_answer_only(tmp_path):
    from tests.validator.validator_testlib import run_validator
    text = (FAMILY / "pendulum-t5.kp").read_text()
    planner = [str(ROOT / "run.sh"), "-seed", "1"]
    done = run_validator(["-json", "--", *planner], text, tmp_path)
    report = json.loads(done.stdout)
    assert report["valid"] and report["cost_kind"] == "duration" and report["cost"] > 0
    done = run_validator(["-json", "--", sys.executable, "-c", "print(1)"], text, tmp_path)
    report = json.loads(done.stdout)
    assert not report["valid"] and report["cost"] is None and report["cost_kind"] is None
