"""The substrate test: a planner new to both substrates is one file
(toy_expansive.py, written against the protocols of planning_core.space_information
only) and one registry line; it plans for the grid's ships and the family's
kinodynamic systems through the command line, and the validator accepts its answers."""

from __future__ import annotations

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.problem_text import parse_problem
from planning_core.setups import kinoplan_setup
from rrt_cli.planners import KINODYNAMIC, PLANNERS, PlannerEntry
from tests.conftest import COURSE_DIR, ROOT, plan_in_process
from validator.checks import validate_output, validate_plan

ENTRY = PlannerEntry("tests.rrt_cli.planners.toy_expansive", KINODYNAMIC,
                     "a random tree of random motions")
PENDULUM = (ROOT / "benchmarks" / "problems" / "family" / "pendulum-t3.kp").read_text()


@pytest.fixture
def registered(monkeypatch):
    monkeypatch.setitem(PLANNERS, "toy", ENTRY)


@pytest.mark.parametrize("flags,vehicle", [(["-grad"], "spaceship"),
                                           (["-grad", "-left"], "left")])
def test_a_new_planner_plans_for_the_grid_ships(registered, monkeypatch, flags, vehicle):
    text = (COURSE_DIR / "space-0.sw").read_text()
    status, out, err = plan_in_process(monkeypatch, [*flags, "-planner", "toy", "-seed", "2"],
                                       text)
    assert status == 0, err
    report = validate_output(parse_problem(text), vehicle, out, strict=True)
    assert report.valid, report.first_failure


def test_a_new_planner_plans_for_the_family(registered, monkeypatch):
    status, out, err = plan_in_process(monkeypatch, ["-planner", "toy", "-seed", "2"], PENDULUM)
    assert status == 0, err
    report = validate_plan(kinoplan_setup(parse_kinoplan(PENDULUM)), out)
    assert report.valid, report.first_failure
