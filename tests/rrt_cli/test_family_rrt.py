"""RRT on kinoplan 1 problems (SPEC 5, issue 14): `-planner rrt` plans for every
kinodynamic family system, its answers pass SPEC 5.5's checks, and the CLI tells
the two formats apart by the first word."""

import random

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from rrt_cli.planners import PLANNERS, rrt
from rrt_cli.planners.base import StopCondition
from tests.conftest import ROOT, run_planner
from validator.checks import validate_plan

FAMILY = ROOT / "benchmarks" / "problems" / "family"
SLOW = pytest.mark.slow


def plan(text: str, seed: int, time_limit: float = 60.0):
    setup = kinoplan_setup(parse_kinoplan(text))
    result = rrt.solve(setup.si, setup.pdef, StopCondition(time_limit=time_limit),
                       random.Random(seed), rrt.Params())
    return setup, result


def assert_solved_and_valid(setup, result):
    assert result.solved, (result.status, result.message)
    system = setup.system
    n, m = len(system.state_names), len(system.control_names)
    for row in result.trajectory + result.tree:
        assert len(row) == n + m  # s.. u.. K (control_names ends with K)
        assert system.control_violation(row[n:]) is None
    report = validate_plan(setup, format_plan(result.trajectory, result.tree))
    assert report.valid, report.first_failure


# pendulum: a fraction of a second a seed, seed 2 in the unit run; the cars: seconds (see
# the report's medians).
CASES = [pytest.param(name, seed, marks=() if fast and seed == 2 else SLOW, id=f"{name}-{seed}")
         for name, fast in (("pendulum-t3", True), ("pendulum-t5", True),
                            ("pendulum-t10", True), ("car2-corridors", False),
                            ("unicycle-circles", False), ("car1-scene1", False),
                            ("car1-scene2", False), ("car1-scene3", False))
         for seed in (1, 2, 3)]


@pytest.mark.parametrize("name,seed", CASES)
def test_rrt_solves_family_problem_and_validator_accepts(name, seed):
    setup, result = plan((FAMILY / f"{name}.kp").read_text(), seed)
    assert_solved_and_valid(setup, result)


OPEN_CAR2 = """kinoplan 1
system car2
world 0 0 20 20
start x 3 y 10 theta 0 v 0
goal x 9 y 10 within 1.5
"""


def test_rrt_on_an_open_car2_problem_is_valid_and_reproducible():
    setup, first = plan(OPEN_CAR2, 5)
    assert_solved_and_valid(setup, first)
    _, again = plan(OPEN_CAR2, 5)
    assert format_plan(first.trajectory, first.tree) == format_plan(again.trajectory, again.tree)


AT_REST_IN_GOAL = """kinoplan 1
system pendulum
start theta -pi/2 omega 0
goal theta -pi/2 omega 0 within 0.1
"""
# In the goal (theta only, 0.095 from it) but falling: zero torque for KMIN = 1 slice
# leaves the goal region, so a one-line "rest" answer would be wrong.
DRIFTS_OUT_OF_GOAL = """kinoplan 1
system pendulum
start theta -0.045 omega 0
goal theta 0.05 within 0.1
"""


def test_start_at_rest_in_goal_is_one_line_with_zero_torque_for_kmin():
    setup, result = plan(AT_REST_IN_GOAL, 1)
    assert result.trajectory == ((setup.pdef.start[0], 0.0, 0.0, 1),)
    assert_solved_and_valid(setup, result)


def test_start_in_goal_that_drifts_out_plans_instead():
    setup, result = plan(DRIFTS_OUT_OF_GOAL, 1)
    start, goal = setup.pdef.start, setup.pdef.goal
    assert goal.reached(start)
    assert setup.si.stay_controls(start, goal) is None
    assert_solved_and_valid(setup, result)


def test_goal_target_fills_unnamed_variables_from_a_uniform_sample():
    setup = kinoplan_setup(parse_kinoplan((FAMILY / "unicycle-circles.kp").read_text()))
    si, rng = setup.si, random.Random(4)
    targets = [si.goal_target(setup.pdef.goal, rng) for _ in range(20)]
    assert {t[:2] for t in targets} == {(42.0, 42.0)}
    assert len({t[2:] for t in targets}) == 20  # theta, v, omega drawn each time
    assert all(si.space.satisfies_bounds(t) for t in targets)
    full = kinoplan_setup(parse_kinoplan(AT_REST_IN_GOAL))
    rng = random.Random(4)
    assert full.si.goal_target(full.pdef.goal, rng) == full.pdef.goal.target
    assert rng.random() == random.Random(4).random()  # a full goal draws nothing


def test_nearest_is_by_the_metric_with_angles_wrapping():
    si = kinoplan_setup(parse_kinoplan((FAMILY / "pendulum-t3.kp").read_text())).si
    index = si.new_nearest()
    for state in [(3.1, 0.0), (0.0, 0.5), (-1.0, 0.0)]:
        index.add(state)
    assert index.nearest((-3.1, 0.0)) == 0  # 0.08 away across the wrap
    assert si.closeness((3.1, 0.0), (-3.1, 0.0)) == pytest.approx(2 * 3.141592653589793 - 6.2)


def test_the_kinodynamic_planners_are_registered_for_kinoplan_problems():
    pendulum = parse_kinoplan((FAMILY / "pendulum-t3.kp").read_text()).system
    assert {name for name, entry in PLANNERS.items()
            if entry.plans_for_kinoplan(pendulum)} == {"blossom", "kpiece", "rgrrt", "rrt", "sst"}


# ----- the command line -------------------------------------------------------------

PENDULUM = (FAMILY / "pendulum-t3.kp").read_text()


def test_cli_plans_a_kinoplan_problem_and_the_answer_validates():
    done = run_planner(["-seed", "1"], PENDULUM)
    assert done.returncode == 0, done.stderr
    assert done.stderr == b""
    report = validate_plan(kinoplan_setup(parse_kinoplan(PENDULUM)), done.stdout.decode())
    assert report.valid, report.first_failure
    again = run_planner(["-seed", "1", "-stats"], PENDULUM)
    assert again.stdout == done.stdout
    assert b"vehicle=pendulum" in again.stderr


@pytest.mark.parametrize("flags", [["-grad"], ["-ugrad"], ["-left"], ["-grad", "-left"]])
def test_cli_vehicle_flags_with_a_kinoplan_problem_are_usage_errors(flags):
    done = run_planner(flags, PENDULUM)
    assert done.returncode == 2 and done.stdout == b""
    assert b"kinoplan problem names its own system" in done.stderr
    assert b"Traceback" not in done.stderr


@pytest.mark.parametrize("planner", ["prm", "prmstar", "rrtconnect"])
def test_cli_planners_without_kinoplan_support_refuse_in_one_line(planner):
    done = run_planner(["-planner", planner], PENDULUM)
    assert done.returncode == 2 and done.stdout == b""
    assert done.stderr.decode().count("\n") == 1
    assert "does not plan for kinoplan problems of the pendulum system" in done.stderr.decode()


@pytest.mark.parametrize("planner", ["blossom", "kpiece", "rgrrt"])
def test_cli_kinodynamic_planners_refuse_geometric_kinoplan_systems_in_one_line(planner):
    done = run_planner(["-planner", planner], (FAMILY / "arm2-pair1.kp").read_text())
    assert done.returncode == 2 and done.stdout == b""
    assert done.stderr.decode().count("\n") == 1
    assert "does not plan for kinoplan problems of the arm2 system" in done.stderr.decode()


@pytest.mark.parametrize("text,where", [
    ("kinoplan 1\nsystem pendulum\nstart theta 0 omega 0 foo\ngoal theta 1 within 0.1\n",
     "line 3, column 26"),
    ("kinoplan 2\nsystem pendulum\n", "line 1, column 10"),
    ("kinoplan 1\nsystem boat\n", "line 2, column 8"),
    ("kinoplan 1\nsystem pendulum\nstart theta 0 omega 0\ngoal theta 1 within nan\n",
     "line 4, column 21"),
    ("# nothing may come before the first line\nkinoplan 1\nsystem pendulum\n",
     "line 1, column 1: the first line must be 'kinoplan 1'"),
])
def test_cli_bad_kinoplan_problem_is_one_line_with_line_and_column(text, where):
    done = run_planner([], text)
    assert done.returncode == 2 and done.stdout == b""
    err = done.stderr.decode()
    assert err.count("\n") == 1 and err.startswith("rrt_cli: bad problem: ")
    assert where in err
