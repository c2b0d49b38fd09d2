"""SPEC 5.5's checks on kinoplan 1 answers (issue 14): a hand-made car2 answer is
accepted, and each fault is rejected by its own check with its own message."""

import json
import math
import os
import subprocess
import sys

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from tests.conftest import ROOT
from validator.checks import (LAST_EDGE_COLLISION, NOT_AT_GOAL, NOT_AT_START, OUT_OF_BOUNDS,
                              PARSE_ERROR, SPACESHIP_COLLISION, VALID_VERDICT, validate_plan)

PROBLEM = """kinoplan 1
system car2
world 0 0 20 20
start x 2 y 10 theta 0 v 0
goal x 9.5 y 10 within 0.5
"""
# Straight along y = 10: accelerate for 1 s (x 2 -> 3.5, v 0 -> 3), then coast 2 s.
CONTROLS = [(0.0, 3.0, 20), (0.0, 0.0, 20), (0.0, 0.0, 20)]


def answer(problem_text: str = PROBLEM, controls=CONTROLS):
    """The rows (state + control) of ``controls`` from the start, exactly simulated."""
    problem = parse_kinoplan(problem_text)
    state, rows = problem.start, []
    for control in controls:
        rows.append(tuple(state) + tuple(control))
        state = problem.system.propagate(state, control)
    return rows, state


def check(rows, problem_text: str = PROBLEM, strict: bool = False):
    setup = kinoplan_setup(parse_kinoplan(problem_text))
    return validate_plan(setup, format_plan(rows, rows[:1]), strict=strict)


def failure(rows, problem_text: str = PROBLEM):
    report = check(rows, problem_text)
    assert not report.valid
    return report.first_failure


def test_the_hand_made_answer_is_valid_and_ends_where_simulated():
    rows, end = answer()
    assert end[0] == pytest.approx(9.5) and end[3] == pytest.approx(3.0)
    for strict in (False, True):
        report = check(rows, strict=strict)
        assert report.valid, report.first_failure
        assert report.verdict == VALID_VERDICT
        assert len(report.checks) == 7
        assert report.final_state == end


def test_angles_compare_modulo_two_pi_at_the_start_and_between_lines():
    rows, _ = answer()
    turned = [row[:2] + (row[2] + 2 * math.pi,) + row[3:] for row in rows]
    assert check(turned).valid


def test_a_wrong_k_within_the_duration_fails_check_7():
    rows, _ = answer()
    rows[0] = rows[0][:-1] + (19,)
    fault = failure(rows)
    assert fault.number == 7 and fault.line == 3
    assert fault.message.startswith("Trajectory claims that control <0, 3, 19> at state")
    assert "tolerance 1e-06" in fault.detail


def test_a_k_outside_the_duration_fails_check_3():
    rows, _ = answer()
    rows[1] = rows[1][:-1] + (21,)
    fault = failure(rows)
    assert (fault.number, fault.message, fault.line) == (3, OUT_OF_BOUNDS, 3)
    assert "K = 21 is outside the duration [1, 20]" in fault.detail


def test_a_k_of_1e308_is_named_in_a_few_digits_not_309():
    rows, _ = answer()
    rows[1] = rows[1][:-1] + (1e308,)
    fault = failure(rows)
    assert (fault.number, fault.message, fault.line) == (3, OUT_OF_BOUNDS, 3)
    assert fault.detail == "line 3: K = 1e+308 is outside the duration [1, 20]"


@pytest.mark.parametrize("k", [2.5, 0, -3])
def test_a_k_that_is_no_positive_integer_fails_check_1(k):
    rows, _ = answer()
    rows[1] = rows[1][:-1] + (k,)
    fault = failure(rows)
    assert (fault.number, fault.message, fault.line) == (1, PARSE_ERROR, 3)
    assert "is not a positive integer" in fault.detail


def test_a_control_out_of_bounds_fails_check_3():
    rows, _ = answer()
    rows[1] = rows[1][:4] + (2.5, 0.0, 20)
    fault = failure(rows)
    assert (fault.number, fault.message, fault.line) == (3, OUT_OF_BOUNDS, 3)
    assert "control omega = 2.5 is outside [-2, 2]" in fault.detail


def test_a_state_out_of_bounds_fails_check_3():
    rows, _ = answer()
    rows[1] = rows[1][:3] + (5.5,) + rows[1][4:]
    fault = failure(rows)
    assert (fault.number, fault.message) == (3, OUT_OF_BOUNDS)
    assert "v = 5.5 is outside its bound [-5, 5]" in fault.detail


@pytest.mark.parametrize("variable", [0, 1, 2, 3])
def test_a_state_1e_4_off_its_re_simulation_fails_check_7(variable):
    rows, _ = answer()
    row = list(rows[2])
    row[variable] += 1e-4
    rows[2] = tuple(row)
    fault = failure(rows)
    assert fault.number == 7 and fault.line == 4
    assert fault.message.startswith("Trajectory claims that control <0, 0, 20> at state")
    row[variable] -= 1e-4 - 5e-7  # half the tolerance off: accepted
    rows[2] = tuple(row)
    assert check(rows).valid


def test_a_start_off_by_1e_5_fails_check_4():
    rows, _ = answer()
    rows[0] = (rows[0][0] + 1e-5,) + rows[0][1:]
    fault = failure(rows)
    assert (fault.number, fault.message, fault.line) == (4, NOT_AT_START, 2)
    assert "x is 1e-05 off" in fault.detail


def test_a_slice_in_collision_fails_check_6():
    # A small disc on the second line's path, 1.5 from every printed state (the body
    # is a 1.5 square): only slices between the printed states touch it.
    problem = PROBLEM + "circle 5 10 0.01\n"
    rows, _ = answer(problem)
    fault = failure(rows, problem)
    assert (fault.number, fault.message, fault.line) == (6, SPACESHIP_COLLISION, 3)
    assert "slice" in fault.detail and "touches obstacle 1 (line 6)" in fault.detail


# The last line's body (a 1.5 square) runs from x = 6.5 to 9.5, its front edge at 10.1
# one slice before the end and at 10.25 at the end: a disc at x = 8 is met mid-line,
# one across [10.19, 10.21] by the last slice only (whose state no line prints).
@pytest.mark.parametrize("disc, slice_", [("circle 8 10 0.01", 5), ("circle 10.2 10 0.01", 20)])
def test_a_slice_of_the_last_line_in_collision_fails_check_5(disc, slice_):
    problem = PROBLEM + disc + "\n"
    rows, _ = answer(problem)
    fault = failure(rows, problem)
    assert (fault.number, fault.message, fault.line) == (5, LAST_EDGE_COLLISION, 4)
    assert f"slice {slice_} of 20" in fault.detail
    assert check(rows, problem.replace(disc, "circle 10.3 10 0.01")).valid


def test_an_end_outside_the_goal_fails_check_5():
    rows, _ = answer()
    fault = failure(rows[:2])
    assert (fault.number, fault.message, fault.line) == (5, NOT_AT_GOAL, 3)
    assert "from the goal (x, y within 0.5)" in fault.detail


def test_rows_of_the_wrong_width_fail_check_1():
    rows, _ = answer()
    fault = failure([row[:-1] for row in rows])
    assert (fault.number, fault.message) == (1, PARSE_ERROR)
    assert "(car2: 7 numbers a line, x y theta v omega a K)" in fault.detail


def test_an_empty_trajectory_fails_check_2():
    fault = validate_plan(kinoplan_setup(parse_kinoplan(PROBLEM)), "0\n0\n").first_failure
    assert fault.number == 2


# ----- rrt-validator ------------------------------------------------------------------


def validator(args, stdin: str, timeout: float = 120):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "validator", *args], input=stdin.encode(),
                          capture_output=True, timeout=timeout, cwd=ROOT, env=env)


def printing(tmp_path, rows):
    """A planner command that prints ``rows`` as its answer."""
    path = tmp_path / "answer.txt"
    path.write_text(format_plan(rows, rows[:1]))
    return ["sh", "-c", f"cat > /dev/null; cat '{path}'"]


def test_cli_accepts_the_answer(tmp_path):
    rows, _ = answer()
    done = validator(["-noviz", "--", *printing(tmp_path, rows)], PROBLEM)
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode() == VALID_VERDICT + "\n"


def test_cli_rejects_a_bad_answer_with_exit_1_and_json(tmp_path):
    rows, _ = answer()
    done = validator(["-noviz", "-json", "--", *printing(tmp_path, rows[:2])], PROBLEM)
    assert done.returncode == 1
    report = json.loads(done.stdout)
    assert report["vehicle"] == "car2" and report["verdict"] == "invalid"
    assert report["first_failure"]["message"] == NOT_AT_GOAL
    assert [c["status"] for c in report["checks"]] == ["passed"] * 4 + ["failed", "not run",
                                                                        "not run", "not applicable"]


def test_cli_runs_our_planner_on_the_pendulum():
    text = (ROOT / "benchmarks" / "problems" / "family" / "pendulum-t3.kp").read_text()
    done = validator(["-noviz", "--", sys.executable, "-m", "rrt_cli", "-seed", "2"], text)
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode() == VALID_VERDICT + "\n"


@pytest.mark.parametrize("flags", [["-grad"], ["-ugrad"], ["-left"]])
def test_cli_vehicle_flags_with_a_kinoplan_problem_are_usage_errors(flags, tmp_path):
    done = validator([*flags, "-noviz", "--", "true"], PROBLEM)
    assert done.returncode == 2 and done.stdout == b""
    assert b"kinoplan problem names its own system" in done.stderr


def test_cli_bad_kinoplan_problem_is_one_line_exit_2():
    done = validator(["-noviz", "--", "true"], PROBLEM.replace("car2", "car9"))
    assert done.returncode == 2 and done.stdout == b""
    err = done.stderr.decode()
    assert err.count("\n") == 1 and "bad problem: line 2, column 8" in err
