"""Semantics of the checks that the corpus does not pin down: tolerances, angles,
limits, warnings, the report's numbers."""

from __future__ import annotations

import math

import pytest

from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.systems import spaceship
from planning_core.vehicles import Vehicle
from validator import checks
from validator.checks import Limits, validate_output


def open_map(width=6, height=4, start=(1.0, 1.5), goal=(2.0, 1.5), blocked=()):
    cells = bytearray(width * height)
    for column, row in blocked:
        cells[row * width + column] = 1
    return Problem(width, height, bytes(cells), start, goal)


def fly(start, controls):
    state = (start[0], start[1], 0.0, 0.0)
    rows = []
    for control in controls:
        rows.append(state + tuple(control))
        state = spaceship.SYSTEM.propagate(state, control)
    return rows, state


def ship_problem(rows_end, **kw):
    return open_map(goal=(rows_end[0], rows_end[1]), **kw)


@pytest.mark.parametrize("offset, valid", [(0.0999, True), (0.1001, False)])
def test_point_goal_tolerance(offset, valid):
    problem = open_map()
    text = format_plan([(1.0, 1.5), (2.0 + offset, 1.5)], [])
    report = validate_output(problem, Vehicle.POINT, text)
    assert report.valid is valid
    if not valid:
        assert report.first_failure.message == checks.NOT_AT_GOAL


@pytest.mark.parametrize("theta", [0.0, -0.0, math.pi, 2 * math.pi + 0.5, 1.0 - 2 * math.pi,
                                   5 * math.pi])
def test_left_angles_that_are_legal_modulo_two_pi(theta):
    rows, end = fly((1.0, 1.5), [(0.0, 0.3), (theta, 0.2), (math.pi, 0.1)])
    report = validate_output(ship_problem(end), Vehicle.LEFT_SPACESHIP, format_plan(rows, []))
    assert report.valid, report.first_failure


@pytest.mark.parametrize("theta", [-0.01, 2 * math.pi - 0.01, 3 * math.pi / 2, math.pi + 1e-9])
def test_left_angles_that_thrust_right(theta):
    rows, end = fly((1.0, 1.5), [(0.0, 0.3), (theta, 0.2), (math.pi, 0.1)])
    text = format_plan(rows, [])
    assert validate_output(ship_problem(end), Vehicle.SPACESHIP, text).valid
    report = validate_output(ship_problem(end), Vehicle.LEFT_SPACESHIP, text)
    failure = report.first_failure
    assert (failure.number, failure.message, failure.line) == (3, checks.OUT_OF_BOUNDS, 3)


def test_spec_check_value_rounded_to_six_places_is_within_tolerance():
    # SPEC 2: from (0.1, 1.54, 0, 0), control (0.25, 0.5) gives (0.279372, 1.720952, ...).
    # Line 2 coasts on for one step: to (0.580595, 2.103947).
    problem = open_map(4, 3, start=(0.1, 1.54), goal=(0.58, 2.1))
    text = "2\n0.1 1.54 0 0 0.25 0.5\n0.279372 1.720952 0.301223 0.382995 0 0\n0\n"
    report = validate_output(problem, Vehicle.SPACESHIP, text)
    assert report.valid, report.first_failure
    wrong = text.replace("0.279372", "0.299372")
    failure = validate_output(problem, Vehicle.SPACESHIP, wrong).first_failure
    assert failure.number == 7 and failure.line == 3
    assert failure.message == ("Trajectory claims that control <0.25, 0.5> at state "
                               "<0.1, 1.54, 0, 0> gives state <0.299372, 1.72095, 0.301223, "
                               "0.382995> but I get state <0.279372, 1.72095, 0.301223, "
                               "0.382995>!")


def test_negative_zero_velocity_is_not_the_same_motion():
    # atan2(0, -0.0) = pi: line 3 thrusts left, out of the map, though it == line 2.
    problem = open_map(start=(0.1, 1.5), goal=(0.1, 1.5))
    text = ("3\n0.1 1.5 0.0 0.0 0.0 0.5\n0.1 1.5 -0.0 0.0 0.0 0.5\n"
            "0.1 1.5 0.0 0.0 0.0 0.0\n0\n")
    failure = validate_output(problem, Vehicle.SPACESHIP, text).first_failure
    assert (failure.number, failure.message, failure.line) == (6, checks.SPACESHIP_COLLISION, 3)


def test_repeated_lines_are_checked_once_but_counted_fully():
    problem = open_map(goal=(1.0, 1.5))
    text = "1000\n" + "1.0 1.5 0.0 0.0 0.0 0.0\n" * 1000 + "0\n"
    report = validate_output(problem, Vehicle.SPACESHIP, text)
    assert report.valid and report.trajectory_count == 1000 and report.path_length == 0.0


def test_spaceship_path_length_follows_the_slices():
    rows, end = fly((1.0, 1.5), [(0.0, 0.5), (1.0, 0.5), (math.pi, 0.5)])
    report = validate_output(ship_problem(end), Vehicle.SPACESHIP, format_plan(rows, []))
    points = [(1.0, 1.5)]
    for row in rows:
        points += [(s[0], s[1]) for s in spaceship.SYSTEM.slice_states(row[:4], row[4:])]
    expected = sum(math.dist(a, b) for a, b in zip(points, points[1:]))
    assert report.path_length == pytest.approx(expected, rel=1e-12)
    assert report.final_state == end


def test_point_path_length_and_single_point_trajectory():
    problem = open_map(goal=(1.05, 1.5))
    report = validate_output(problem, Vehicle.POINT, "1\n1.0 1.5\n0\n")
    assert report.valid and report.path_length == 0.0
    problem = open_map(goal=(4.0, 3.5))
    report = validate_output(problem, Vehicle.POINT, "3\n1.0 1.5\n4.0 1.5\n4.0 3.5\n0\n")
    assert report.valid and report.path_length == pytest.approx(5.0)


def test_limits_keep_hostile_answers_cheap():
    problem = open_map(goal=(1.0, 1.5))
    zigzag = "5\n1.0 1.5\n5.0 1.5\n1.0 1.5\n5.0 1.5\n1.0 1.5\n0\n"
    failure = validate_output(problem, Vehicle.POINT, zigzag,
                              limits=Limits(max_point_path_length=10)).first_failure
    assert (failure.number, failure.message) == (6, checks.TOO_LONG)
    assert validate_output(problem, Vehicle.POINT, zigzag).valid
    failure = validate_output(problem, Vehicle.POINT, zigzag,
                              limits=Limits(max_trajectory_lines=4)).first_failure
    assert (failure.number, failure.message, failure.line) == (1, checks.PARSE_ERROR, 1)


def test_output_over_the_cap_fails_parsing():
    problem = open_map(goal=(1.0, 1.5))
    failure = validate_output(problem, Vehicle.POINT, "1\n1.0 1.5\n0\n0 0\n0 0",
                              output_cap_exceeded=1024).first_failure
    assert (failure.number, failure.message, failure.line) == (1, checks.PARSE_ERROR, 5)
    assert "1024 bytes" in failure.detail


def test_many_corner_cuts_are_summed_up():
    # Back and forth across the corner of blocked cell (2, 1), 30 segments.
    problem = open_map(6, 4, start=(1.0, 0.99), goal=(1.0, 0.99), blocked=[(2, 1)])
    rows = [(1.0, 0.99), (3.0, 2.99)] * 15 + [(1.0, 0.99)]
    report = validate_output(problem, Vehicle.POINT, format_plan(rows, []))
    assert report.valid
    assert len(report.corner_cuts) == 30
    assert [c.line for c in report.corner_cuts] == list(range(2, 32))
    assert len(report.warnings) == Limits().max_warnings_listed + 1
    assert report.warnings[-1].startswith("... and ")
    strict = validate_output(problem, Vehicle.POINT, format_plan(rows, []), strict=True)
    assert strict.first_failure.line == 2 and strict.first_failure.where is not None


def test_trailing_text_is_a_warning_only():
    problem = open_map(goal=(1.0, 1.5))
    report = validate_output(problem, Vehicle.POINT, "1\n1.0 1.5\n0\n\nelapsed 3ms\n")
    assert report.valid and report.warnings == ["line 5: text after the tree is ignored"]


def test_failures_carry_a_world_point_for_the_pdf():
    problem = open_map(4, 3, start=(0.1, 1.54), goal=(3.8, 1.1), blocked=[(2, 1)])
    report = validate_output(problem, Vehicle.POINT, "2\n0.1 1.54\n3.8 1.1\n0\n")
    x, y = report.first_failure.where
    assert problem.point_in_collision(x, y) and (int(x), int(y)) == (2, 1)
