"""SPEC 5.5's checks on geometric kinoplan 1 answers (issue 15): hand-written arm2
and rigid2 paths, each fault rejected by its own check with its own message."""

import json
import math

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from tests.validator.test_family_checks import validator
from validator.checks import (EMPTY_TRAJECTORY, NOT_AT_GOAL, NOT_AT_START, OUT_OF_BOUNDS,
                              PARSE_ERROR, POINT_COLLISION, TOO_LONG, VALID_VERDICT, Limits,
                              validate_plan)

# A small disc straight above the shoulder, 1.5 out: the stretched arm (links
# along one line, tip at 2) touches it for theta1 within 0.0333 of pi/2.
ARM = """kinoplan 1
system arm2
world -2.2 -2.2 2.2 2.2
circle 0 1.5 0.05
start theta1 0 theta2 0
goal theta1 {goal} theta2 0 within 0.01
"""
DISC_HALF_WIDTH = math.asin(0.05 / 1.5)  # the angles around pi/2 where the arm touches it

RIGID = """kinoplan 1
system rigid2
body rect 0.3 0.15
world 0 0 2 2
rect 0.9 0.0 1.1 0.8
start x 0.5 y 0.5 theta 0
goal x 1.5 y 0.5 theta 0 within 0.02
"""


def answer(rows) -> str:
    """The output for a path: its configurations, its segments as the tree."""
    return format_plan(rows, [tuple(a) + tuple(b) for a, b in zip(rows, rows[1:])])


def check(problem_text: str, rows, strict: bool = False, limits: Limits = Limits()):
    setup = kinoplan_setup(parse_kinoplan(problem_text))
    return validate_plan(setup, answer(rows), strict=strict, limits=limits)


def failure(problem_text: str, rows, strict: bool = False):
    report = check(problem_text, rows, strict)
    assert not report.valid
    return report.first_failure


def test_a_short_free_arm_move_is_valid_with_six_checks():
    text = ARM.replace("goal theta1 {goal} theta2 0", "goal theta1 -1 theta2 0.5")
    rows = [(0.0, 0.0), (-0.5, 0.2), (-1.0, 0.5)]
    for strict in (False, True):
        report = check(text, rows, strict)
        assert report.valid, report.first_failure
        assert report.verdict == VALID_VERDICT and len(report.checks) == 6
    assert report.path_length == pytest.approx(math.hypot(0.5, 0.2) + math.hypot(0.5, 0.3))
    assert "ten times denser" in report.checks[-1].detail


def test_a_sweep_through_the_disc_between_valid_ends_is_caught_naming_link_and_obstacle():
    text = ARM.format(goal=3)
    si = kinoplan_setup(parse_kinoplan(text)).si
    assert si.is_valid((0.0, 0.0)) and si.is_valid((3.0, 0.0))
    fault = failure(text, [(0.0, 0.0), (3.0, 0.0)])
    assert (fault.number, fault.message, fault.line) == (6, POINT_COLLISION, 2)
    assert "segment from line 2 <0, 0> to line 3 <3, 0>: sample" in fault.detail
    assert "of 300" in fault.detail
    assert "link 2 (elbow to tip) touches obstacle 1 (line 4)" in fault.detail
    assert abs(fault.where[0] - math.pi / 2) <= DISC_HALF_WIDTH  # (theta1, theta2)


def test_a_coarse_check_misses_the_disc_and_strict_catches_it():
    text = ARM.format(goal=3).replace("circle", "check 0.5\ncircle")
    rows = [(0.0, 0.0), (3.0, 0.0)]  # samples 0.5 apart: 1.5 and 2.0 straddle the disc
    assert check(text, rows).valid
    fault = failure(text, rows, strict=True)  # samples 0.05 apart
    assert (fault.number, fault.message) == (6, POINT_COLLISION)
    assert "of 60" in fault.detail and "touches obstacle 1" in fault.detail


def test_an_angle_path_goes_across_pi_the_short_way_in_any_printed_turn():
    # Along theta1 3 -> -3 the long way (through pi/2) meets the disc; the short way
    # (through pi) is free.
    text = ARM.format(goal=-3).replace("start theta1 0", "start theta1 3")
    assert check(text, [(3.0, 0.0), (-3.0, 0.0)]).valid
    assert check(text, [(3.0 - 2 * math.pi, 0.0), (-3.0 + 4 * math.pi, 2 * math.pi)]).valid
    # A disc at pi instead: now the short way is caught.
    at_pi = text.replace("circle 0 1.5 0.05", "circle -1.5 0 0.05")
    fault = failure(at_pi, [(3.0, 0.0), (-3.0, 0.0)])
    assert fault.number == 6 and "of 29" in fault.detail
    assert abs(abs(fault.where[0]) - math.pi) <= DISC_HALF_WIDTH


def test_a_start_off_by_1e_5_fails_check_4():
    text = ARM.format(goal=-1)
    fault = failure(text, [(1e-5, 0.0), (-1.0, 0.0)])
    assert (fault.number, fault.message, fault.line) == (4, NOT_AT_START, 2)
    assert "theta1 is 1e-05 off" in fault.detail


def test_an_end_outside_the_goal_fails_check_5():
    fault = failure(ARM.format(goal=-1), [(0.0, 0.0), (-0.98, 0.0)])
    assert (fault.number, fault.message, fault.line) == (5, NOT_AT_GOAL, 3)
    assert "the last configuration <-0.98, 0> is 0.02 from the goal" in fault.detail


def test_rows_of_the_wrong_width_fail_check_1():
    fault = failure(ARM.format(goal=-1), [(0.0, 0.0, 0.0), (-1.0, 0.0, 0.0)])
    assert (fault.number, fault.message, fault.line) == (1, PARSE_ERROR, 2)
    assert "(arm2: 2 numbers a trajectory line, theta1 theta2; 4 a tree line)" in fault.detail


def test_an_empty_trajectory_fails_check_2():
    assert validate_plan(kinoplan_setup(parse_kinoplan(RIGID)), "0\n0\n").first_failure.message == EMPTY_TRAJECTORY


def test_a_rigid_body_out_of_bounds_fails_check_3():
    fault = failure(RIGID, [(0.5, 0.5, 0.0), (2.5, 0.5, 0.0), (1.5, 0.5, 0.0)])
    assert (fault.number, fault.message, fault.line) == (3, OUT_OF_BOUNDS, 3)
    assert "x = 2.5 is outside its bound [0, 2]" in fault.detail


def test_a_rigid_body_over_the_wall_is_valid_through_it_not():
    over = [(0.5, 0.5, 0.0), (0.5, 1.2, 0.0), (1.5, 1.2, math.pi / 2), (1.5, 0.5, 0.0)]
    report = check(RIGID, over, strict=True)
    assert report.valid, report.first_failure
    fault = failure(RIGID, [(0.5, 0.5, 0.0), (1.5, 0.5, 0.0)])
    assert (fault.number, fault.message) == (6, POINT_COLLISION)
    assert "the body touches obstacle 1 (line 5)" in fault.detail
    assert 0.7 <= fault.where[0] <= 0.9 + 1e-9  # the body's front meets the wall at x = 0.9


def test_a_path_with_too_many_samples_fails_check_6_before_testing_any():
    report = check(ARM.format(goal=3), [(0.0, 0.0), (3.0, 0.0)],
                   limits=Limits(max_motion_samples=100))
    fault = report.first_failure
    assert (fault.number, fault.message) == (6, TOO_LONG)
    assert "301 samples" in fault.detail


def test_cli_checks_a_geometric_answer_json_without_check_7(tmp_path):
    path = tmp_path / "answer.txt"
    path.write_text(answer([(0.0, 0.0), (-1.0, 0.0)]))
    planner = ["sh", "-c", f"cat > /dev/null; cat '{path}'"]
    done = validator(["-noviz", "-json", "--", *planner], ARM.format(goal=-1))
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    assert report["vehicle"] == "arm2" and report["verdict"] == "valid"
    assert [c["status"] for c in report["checks"]] == ["passed"] * 6 + ["not applicable"] * 2
    done = validator(["-noviz", "--", *planner], ARM.format(goal=-1.5))
    assert done.returncode == 1 and done.stdout.decode().startswith(NOT_AT_GOAL)


def test_angles_too_large_to_subtract_fail_check_3_not_the_validator(tmp_path):
    # From theta1 = 1.7e308 to -1.7e308 the difference overflowed: a 'math domain
    # error', exit 4 ("internal error") for what a hostile planner printed.
    rows = [(0.0, 0.0), (1.7e308, 0.0), (-1.7e308, 0.0), (-1.0, 0.0)]
    fault = failure(ARM.format(goal=-1), rows)
    assert (fault.number, fault.message, fault.line) == (3, OUT_OF_BOUNDS, 3)
    assert fault.detail == ("line 3: theta1 = 1.7e+308 is larger than 1e+09 in magnitude "
                            "(an angle may be printed in any turn within it)")
    assert check(ARM.format(goal=-1), [(0.0, 0.0), (1e9, 0.0), (-1.0, 0.0)]).checks[2].passed
    path = tmp_path / "answer.txt"
    path.write_text(answer(rows))
    done = validator(["-o", str(tmp_path / "out.pdf"), "--", "sh", "-c",
                      f"cat > /dev/null; cat '{path}'"], ARM.format(goal=-1))
    assert done.returncode == 1 and done.stdout.decode().startswith(OUT_OF_BOUNDS)
    assert b"internal error" not in done.stderr
