"""The ``kinoplan 1`` reader (planning_core.kinoplan_text, SPEC 5.1).

A table of bad problems, each with its own message at its line and column; then
what must be accepted: pi forms, comments, whitespace, CRLF, items in any
order, defaults filled in, and params, bounds, controls and the rest overriding
them.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import strategies as st

from planning_core import kinoplan_text
from planning_core.kinoplan import state_valid
from planning_core.kinoplan_text import Token, looks_like_kinoplan, number, parse_kinoplan
from planning_core.problem_text import ProblemFormatError
from planning_core.systems import pendulum
from planning_core.systems.family import Defaults
from planning_core.worlds.shapes import Disc, Rect, body_polygon
from tests.conftest import property_pair

PI = math.pi
CAR2 = ["kinoplan 1", "system car2", "world 0 0 10 10", "rect 4 4 6 6",
        "start x 1 y 1 theta 0 v 0", "goal x 9 y 9 within 0.5"]
PENDULUM = ["kinoplan 1", "system pendulum", "start theta -pi/2 omega 0",
            "goal theta pi/2 omega 0 within 0.1"]
ARM = ["kinoplan 1", "system arm2", "world -2.2 -2.2 2.2 2.2", "start theta1 0 theta2 0",
       "goal theta1 1.5 theta2 1.5 within 0.01"]
RIGID = ["kinoplan 1", "system rigid2", "body rect 0.3 0.15", "world 0 0 2 2",
         "start x 0.5 y 0.25 theta 0", "goal x 1.75 y 1.5 theta 0 within 0.02"]
CAR1 = ["kinoplan 1", "system car1", "world 0 0 2 2", "polygon 0.7 0 0.9 0 0.9 1.2 0.7 1.3",
        "start x 0.5 y 0.25 theta 0", "goal x 1.75 y 1.5 theta 0 within 0.1"]
UNICYCLE = ["kinoplan 1", "system unicycle", "world -50 -50 50 50",
            "start x -45 y -45 theta 0 v 0 omega 0", "goal x 42 y 42 within 2.0"]


def text(lines, replace=None, insert=None):
    """``lines`` with line ``i`` (1-based) replaced or new lines inserted before it."""
    out = list(lines)
    for i, line in (replace or {}).items():
        out[i - 1] = line
    for i, new in sorted((insert or {}).items(), reverse=True):
        out[i - 1:i - 1] = [new] if isinstance(new, str) else new
    return "\n".join(out) + "\n"


# (id, problem text, line, column, message fragment)
BAD = [
    ("empty", "", 1, 1, "the first line must be 'kinoplan 1'"),
    ("comment first", "# hi\n" + text(CAR2), 1, 1, "the first line must be 'kinoplan 1'"),
    ("blank first", "\n" + text(CAR2), 1, 1, "the first line must be 'kinoplan 1'"),
    ("grid text", "4 3\n____\n", 1, 1, "the first line must be 'kinoplan 1'"),
    ("no version", text(CAR2, {1: "kinoplan"}), 1, 9, "kinoplan: missing the version"),
    ("version 2", text(CAR2, {1: "kinoplan 2"}), 1, 10, "unsupported version '2'"),
    ("after version", text(CAR2, {1: "kinoplan 1 x"}), 1, 12, "unexpected 'x' after 'kinoplan 1'"),
    ("kinoplan again", text(CAR2, insert={3: "kinoplan 1"}), 3, 1, "first line only"),
    ("non-ascii", text(CAR2, {2: "system car2 # caf\u00e9"}), 2, 18, "'\u00e9' is not allowed"),
    ("nul byte", text(CAR2, {4: "rect 4 4 6\x006"}), 4, 11, "'\\x00' is not allowed"),
    ("no system", text(CAR2[:1] + CAR2[2:]), 5, 24, "missing 'system NAME'"),
    ("unknown system", text(CAR2, {2: "system boat"}), 2, 8, "unknown system 'boat'"),
    ("system twice", text(CAR2, insert={4: "system car2"}), 4, 1, "system given twice"),
    ("system arity", text(CAR2, {2: "system car2 car1"}), 2, 13, "system: unexpected 'car1'"),
    ("unknown keyword", text(CAR2, insert={3: "speed 3"}), 3, 1, "unknown keyword 'speed'"),
    ("param none", text(CAR2, insert={3: "param L 1"}), 3, 7,
     "car2 has no parameter 'L' (its parameters: none)"),
    ("param unknown", text(CAR1, insert={3: "param M 1"}), 3, 7,
     "car1 has no parameter 'M' (its parameters: L)"),
    ("param not > 0", text(CAR1, insert={3: "param L 0"}), 3, 9, "param L must be > 0"),
    ("param twice", text(CAR1, insert={3: ["param L 1", "param L 2"]}), 4, 1,
     "param L given twice (first on line 3)"),
    ("param arity", text(CAR1, insert={3: "param L"}), 3, 8, "param: missing VALUE"),
    ("bound angle", text(CAR2, insert={3: "bound theta -1 1"}), 3, 7,
     "theta is an angle: angles wrap and take no bound"),
    ("bound unknown", text(CAR2, insert={3: "bound w -1 1"}), 3, 7,
     "bound: car2 has no state variable 'w'"),
    ("bound lo > hi", text(CAR2, insert={3: "bound v 3 1"}), 3, 9, "bound v: LO 3 is greater than HI 1"),
    ("bound twice", text(CAR2, insert={3: ["bound v -1 1", "bound v -2 2"]}), 4, 1,
     "bound v given twice"),
    ("control K", text(CAR2, insert={3: "control K 1 5"}), 3, 9, "bounded by 'duration KMIN KMAX'"),
    ("control unknown", text(CAR2, insert={3: "control tau -1 1"}), 3, 9,
     "car2 has no control 'tau' (its controls: omega, a)"),
    ("control lo > hi", text(CAR2, insert={3: "control a 1 -1"}), 3, 11, "control a: LO 1 is greater"),
    ("control twice", text(CAR2, insert={3: ["control a -1 1", "control a -1 1"]}), 4, 1,
     "control a given twice"),
    ("control geometric", text(ARM, insert={3: "control v 0 1"}), 3, 1,
     "arm2 is geometric: it takes no control"),
    ("integrate geometric", text(RIGID, insert={3: "integrate rk4 0.1"}), 3, 1,
     "rigid2 is geometric: it takes no integrate"),
    ("duration geometric", text(ARM, insert={3: "duration 1 5"}), 3, 1,
     "arm2 is geometric: it takes no duration"),
    ("check kinodynamic", text(CAR2, insert={3: "check 0.1"}), 3, 1,
     "car2 is kinodynamic: it takes no check"),
    ("integrate scheme", text(CAR2, insert={3: "integrate midpoint 0.1"}), 3, 11,
     "unknown scheme 'midpoint'"),
    ("integrate dt", text(CAR2, insert={3: "integrate rk4 0"}), 3, 15, "integrate DT must be > 0"),
    ("integrate twice", text(CAR2, insert={3: ["integrate rk4 0.1", "integrate euler 0.1"]}), 4, 1,
     "integrate given twice"),
    ("kmin > kmax", text(CAR2, insert={3: "duration 5 2"}), 3, 10, "KMIN 5 is greater than KMAX 2"),
    ("kmin 0", text(CAR2, insert={3: "duration 0 3"}), 3, 10, "KMIN must be at least 1"),
    ("kmax not integer", text(CAR2, insert={3: "duration 1 2.5"}), 3, 12,
     "duration KMAX: '2.5' is not an integer"),
    ("kmax huge", text(CAR2, insert={3: "duration 1 2000000"}), 3, 12, "more than 1000000 slices"),
    ("kmax digits", text(CAR2, insert={3: "duration 1 9999999999999999999"}), 3, 12, "is too large"),
    ("check 0", text(ARM, insert={3: "check 0"}), 3, 7, "check STEP must be > 0"),
    ("check too fine", text(ARM, insert={3: "check 1e-9"}), 3, 7, "too fine for this space"),
    ("body pendulum", text(PENDULUM, insert={3: "body square 1"}), 3, 1, "pendulum has no body"),
    ("body arm", text(ARM, insert={3: "body square 1"}), 3, 1, "arm2 has no body"),
    ("body kind", text(RIGID, {3: "body hexagon 1"}), 3, 6, "unknown kind 'hexagon'"),
    ("body missing kind", text(RIGID, {3: "body"}), 3, 5, "body: missing KIND"),
    ("body dims", text(RIGID, {3: "body square 1 2"}), 3, 13, "takes SIDE, got 2 numbers"),
    ("body not convex", text(RIGID, {3: "body polygon 0 0 1 0 0.2 0.2 0 1"}), 3, 14, "not convex"),
    ("no body", text(RIGID[:2] + RIGID[3:]), 5, 38, "missing 'body KIND ...' (rigid2"),
    ("no world", text(CAR2[:2] + CAR2[3:4] + CAR2[4:]), 5, 24, "missing 'world X0 Y0 X1 Y1'"),
    ("world pendulum", text(PENDULUM, insert={3: "world 0 0 1 1"}), 3, 1,
     "pendulum has no workspace: it takes no world"),
    ("rect pendulum", text(PENDULUM, insert={3: "rect 0 0 1 1"}), 3, 1, "it takes no rect"),
    ("world corners", text(CAR2, {3: "world 10 0 0 10"}), 3, 1, "world: needs X0 < X1"),
    ("world arity", text(CAR2, {3: "world 0 0 10"}), 3, 13, "world: missing Y1"),
    ("world twice", text(CAR2, insert={4: "world 0 0 10 10"}), 4, 1, "world given twice"),
    ("rect corners", text(CAR2, {4: "rect 6 4 4 6"}), 4, 1, "rect: needs X0 < X1"),
    ("rect extra", text(CAR2, {4: "rect 4 4 6 6 7"}), 4, 14, "rect: unexpected '7'"),
    ("circle radius", text(CAR2, {4: "circle 5 5 -1"}), 4, 12, "circle R must be > 0"),
    ("polygon not convex", text(CAR2, {4: "polygon 4 4 6 4 5 4.5 6 6 4 6"}), 4, 9, "not convex"),
    ("polygon odd", text(CAR2, {4: "polygon 4 4 6 4 5"}), 4, 17, "needs X Y pairs"),
    ("polygon two vertices", text(CAR2, {4: "polygon 4 4 6 4"}), 4, 16, "needs X Y pairs"),
    ("metric unknown", text(CAR2, insert={3: "metric x,q 1"}), 3, 8,
     "metric: car2 has no state variable 'q'"),
    ("metric twice", text(CAR2, insert={3: "metric x,y 1 x 2"}), 3, 14, "metric: x is named twice"),
    ("metric weight", text(CAR2, insert={3: "metric x,y 0"}), 3, 12, "metric weight of x,y must be > 0"),
    ("metric odd", text(CAR2, insert={3: "metric x,y"}), 3, 11, "metric: needs GROUP W pairs"),
    ("start missing", text(CAR2, {5: "start x 1 y 1 theta 0"}), 5, 1,
     "start: missing v (the start names every state variable)"),
    ("start twice var", text(CAR2, {5: "start x 1 y 1 x 2 theta 0 v 0"}), 5, 15, "start: x is named twice"),
    ("start unknown", text(CAR2, {5: "start x 1 y 1 z 0 theta 0 v 0"}), 5, 15,
     "start: car2 has no state variable 'z'"),
    ("start no value", text(CAR2, {5: "start x 1 y 1 theta 0 v"}), 5, 24, "start: v has no value"),
    ("start line twice", text(CAR2, insert={6: "start x 1 y 1 theta 0 v 0"}), 6, 1, "start given twice"),
    ("start bound", text(CAR2, {5: "start x 1 y 1 theta 0 v 7"}), 5, 25,
     "start: v = 7 is outside its bound [-5, 5]"),
    ("start in world bound", text(CAR2, {5: "start x 11 y 1 theta 0 v 0"}), 5, 9,
     "start: x = 11 is outside its bound [0, 10]"),
    ("start collision", text(CAR2, {5: "start x 3.25 y 5 theta 0 v 0"}), 5, 1,
     "start is not valid: the body touches obstacle 1 (line 4)"),
    ("start box", text(CAR2, {5: "start x 0.5 y 5 theta 0 v 0"}), 5, 1,
     "start is not valid: the body is not inside the world box"),
    ("start omega", text(PENDULUM, {3: "start theta 0 omega 11"}), 3, 21,
     "start: omega = 11 is outside its bound [-10, 10]"),
    ("start arm link", text(ARM, insert={3: "circle 1.5 0 0.1"}), 5, 1,
     "start is not valid: link 2 (elbow to tip) touches obstacle 1 (line 3)"),
    ("no start", text(CAR2[:4] + CAR2[5:]), 5, 24, "missing 'start VAR VALUE ...'"),
    ("no goal", text(CAR2[:5]), 5, 26, "missing 'goal VAR VALUE ... within TOL'"),
    ("goal no within", text(CAR2, {6: "goal x 9 y 9"}), 6, 13, "goal: missing 'within TOL'"),
    ("goal no tol", text(CAR2, {6: "goal x 9 y 9 within"}), 6, 20, "goal: missing TOL after 'within'"),
    ("goal two tols", text(CAR2, {6: "goal x 9 y 9 within 1 2"}), 6, 23,
     "goal: unexpected '2' after the tolerance"),
    ("goal no var", text(CAR2, {6: "goal within 1"}), 6, 6, "goal: names no variable"),
    ("goal tol 0", text(CAR2, {6: "goal x 9 y 9 within 0"}), 6, 21, "goal TOL must be > 0"),
    ("goal no value", text(CAR2, {6: "goal x 9 y within 1"}), 6, 12, "goal: y has no value"),
    ("goal var twice", text(CAR2, {6: "goal x 9 x 8 within 1"}), 6, 10, "goal: x is named twice"),
    ("goal no group", text(UNICYCLE, {5: "goal x 42 y 42 v 0 within 2"}), 5, 16,
     "goal: v is in no metric group"),
    ("goal invalid", text(CAR1, {6: "goal x 0.8 y 0.5 theta 0 within 0.1"}), 6, 1,
     "goal is not valid: the body touches obstacle 1 (line 4)"),
    ("goal bound", text(PENDULUM, {4: "goal theta 0 omega -12 within 0.1"}), 4, 1,
     "goal is not valid: omega = -12.0 is outside its bound [-10, 10]"),
    ("nan", text(CAR2, {4: "rect 4 nan 6 6"}), 4, 8, "rect: 'nan' is not a finite number"),
    ("inf", text(CAR2, {4: "circle 5 -inf 1"}), 4, 10, "circle CY: '-inf' is not a finite number"),
    ("overflow", text(CAR2, {4: "rect 4 4 6 1e999"}), 4, 12, "rect: '1e999' is not a finite number"),
    ("not a number", text(CAR2, {4: "rect 4 4 6 1.2.3"}), 4, 12, "rect: '1.2.3' is not a number"),
    ("pi over zero", text(CAR2, {5: "start x 1 y 1 theta pi/0 v 0"}), 5, 21,
     "start theta: 'pi/0' divides by zero"),
    ("pi plus", text(CAR2, {5: "start x 1 y 1 theta +pi v 0"}), 5, 21, "'+pi' is not a number"),
    ("long line", text(CAR2, {4: "polygon" + " 1" * 20_002}), 4, 1, "more than 20002 words"),
    # Finite values no arithmetic can use: over 1e9 in magnitude, or a positive one under 1e-9.
    ("omega bound 1e308", text(PENDULUM, insert={3: "bound omega -1e308 1e308"}), 3, 13,
     "bound omega LO: '-1e308' is larger than 1e+09 in magnitude"),
    ("world 1e308", text(CAR1, {3: "world -1e308 -1e308 1e308 1e308"}), 3, 7,
     "world: '-1e308' is larger than 1e+09 in magnitude"),
    ("tau 1e308", text(PENDULUM, insert={3: "control tau -1e308 1e308"}), 3, 13,
     "control tau LO: '-1e308' is larger than 1e+09 in magnitude"),
    ("rk4 step 1e300", text(PENDULUM, insert={3: "integrate rk4 1e300"}), 3, 15,
     "integrate DT: '1e300' is larger than 1e+09 in magnitude"),
    ("L subnormal", text(CAR1, insert={3: "param L 1e-320"}), 3, 9,
     "param L must be at least 1e-09, got 1e-320"),
    ("rigid2 world 1e200", text(RIGID, {4: "world -1e200 -1e200 1e200 1e200"}), 4, 7,
     "world: '-1e200' is larger than 1e+09 in magnitude"),
    ("step tiny", text(PENDULUM, insert={3: "integrate euler 5e-324"}), 3, 17,
     "integrate DT must be at least 1e-09, got 5e-324"),
    ("pi form huge", text(CAR2, {5: "start x 1 y 1 theta 1e9*pi v 0"}), 5, 21,
     "start theta: '1e9*pi' is larger than 1e+09 in magnitude"),
    # Odd counts of polygon numbers past the first (5 numbers is also too few vertices).
    ("polygon 7 numbers", text(CAR2, {4: "polygon 4 4 6 4 6 6 4"}), 4, 21,
     "polygon: needs X Y pairs of at least 3 vertices, got 7 numbers"),
    ("polygon 9 numbers", text(CAR2, {4: "polygon 4 4 6 4 6 6 4 6 5"}), 4, 25,
     "polygon: needs X Y pairs of at least 3 vertices, got 9 numbers"),
    ("body polygon 7 numbers", text(RIGID, {3: "body polygon 0 0 1 0 1 1 0"}), 3, 14,
     "body polygon: needs X Y pairs for at least 3 vertices, got 7 numbers"),
]


@pytest.mark.parametrize("problem, line, column, fragment",
                         [case[1:] for case in BAD], ids=[case[0] for case in BAD])
def test_bad_problem_names_line_column_and_what(problem, line, column, fragment):
    with pytest.raises(ProblemFormatError) as info:
        parse_kinoplan(problem)
    error = info.value
    assert fragment in error.message
    assert (error.line, error.column) == (line, column), error.message
    assert "\n" not in str(error)
    assert str(error) == f"line {line}, column {column}: {error.message}"


def test_each_error_has_its_own_message():
    messages = {}
    for name, problem, *_ in BAD:
        with pytest.raises(ProblemFormatError) as info:
            parse_kinoplan(problem)
        messages.setdefault(info.value.message, []).append(name)
    shared = {m: names for m, names in messages.items() if len(names) > 1}
    # The first-line message is one message for every way the first line is wrong.
    assert list(shared.values()) == [["empty", "comment first", "blank first", "grid text"]]


def test_a_long_token_is_shortened_in_the_message():
    with pytest.raises(ProblemFormatError) as info:
        parse_kinoplan(text(CAR2, {4: "rect 4 4 6 " + "9" * 100 + "x"}))
    assert len(info.value.message) < 120 and "..." in info.value.message


def test_unbounded_variable_is_reported(monkeypatch):
    # Every non-angle variable of SPEC's table has a default bound or the world's, so
    # this guard needs a system without one.
    monkeypatch.setattr(pendulum.Pendulum, "DEFAULTS", Defaults(
        bounds={}, metric=(("theta", 1.0), ("omega", 1.0)), controls={"tau": (-3, 3)}))
    with pytest.raises(ProblemFormatError) as info:
        parse_kinoplan(text(PENDULUM))
    assert (info.value.line, info.value.column) == (2, 1)
    assert "state variable omega has no bound (give 'bound omega LO HI')" in info.value.message
    problem = parse_kinoplan(text(PENDULUM, insert={3: "bound omega -4 4"}))
    assert problem.system.bounds[1] == (-4, 4)


def test_obstacle_vertex_cap(monkeypatch):
    monkeypatch.setattr(kinoplan_text, "MAX_OBSTACLE_VERTICES", 9)
    lines = text(CAR2, insert={4: ["rect 7 7 8 8", "circle 1 9 0.2"]})
    assert len(parse_kinoplan(lines).world.obstacles) == 3          # 4 + 4 + 1 vertices
    with pytest.raises(ProblemFormatError, match="more than 9 obstacle vertices"):
        parse_kinoplan(text(CAR2, insert={4: ["rect 7 7 8 8", "circle 1 9 0.2", "circle 9 1 .1"]}))


# ----- what must be accepted -------------------------------------------------------------


@pytest.mark.parametrize("token, value", [
    ("pi", PI), ("-pi", -PI), ("pi/2", PI / 2), ("-pi/2", -(PI / 2)), ("2*pi", 2 * PI),
    ("-3*pi/4", -(3 * PI / 4)), ("0.5*pi/0.25", 0.5 * PI / 0.25), ("1e0*pi", PI),
    ("-0.5", -0.5), ("2e-3", 0.002), (".5", 0.5), ("5.", 5.0), ("+1", 1.0), ("1E+2", 100.0),
])
def test_numbers_and_pi_forms(token, value):
    assert number(Token(token, 1, 1), "x") == value


@pytest.mark.parametrize("token", ["pi*2", "2pi", "2*-pi", "pi/-2", "--1", "1e", "e1", "0x10",
                                   "1_000", "PI", "pi/2/2", "2**pi"])
def test_not_numbers(token):
    with pytest.raises(ProblemFormatError, match="is not a number"):
        number(Token(token, 1, 1), "x")


def test_comments_whitespace_crlf_and_any_order():
    messy = ("kinoplan 1   # the format\r\n"
             "\r\n"
             "# a whole-line comment\r\n"
             "  goal\tx 9  y 9 within 0.5 # near the corner\r\n"
             "\tstart x 2 y 2 theta -pi/4 v 0\r\n"
             "\f\v\r\n"
             "rect 4 4 6 6#touching comment\r\n"
             "world 0 0 10 10\r\n"
             "system car2")
    problem = parse_kinoplan(messy)
    assert problem.system_name == "car2"
    assert problem.start == (2.0, 2.0, -PI / 4, 0.0)
    assert problem.world.obstacles == (Rect(4, 4, 6, 6),)
    assert problem.obstacle_lines == (7,)
    assert problem.goal.values == (("x", 9.0), ("y", 9.0)) and problem.goal.tolerance == 0.5
    tidy = parse_kinoplan(text(CAR2[:4] + ["start x 2 y 2 theta -pi/4 v 0"] + CAR2[5:]))
    assert (problem.system, problem.world, problem.goal) == (tidy.system, tidy.world, tidy.goal)


def test_error_columns_count_from_the_line_start_after_crlf_lines():
    with pytest.raises(ProblemFormatError) as info:
        parse_kinoplan("kinoplan 1\r\nsystem car2\r\n\r\n   world 0 0 x 10\r\n")
    assert (info.value.line, info.value.column) == (4, 14)


def test_defaults_are_filled_in():
    problem = parse_kinoplan(text(PENDULUM))
    system = problem.system
    assert problem.world is None and problem.system_name == "pendulum"
    assert system.g == 9.81 and problem.control_bounds == ((-3.0, 3.0),)
    assert problem.integrator == ("rk4", 0.05) and problem.duration == (1, 10)
    assert system.metric == ((("theta",), 1.0), (("omega",), 1.0))
    assert problem.space.variables[1].low == -10 and problem.check is None
    car = parse_kinoplan(text(CAR2))
    assert car.system.body == body_polygon("square", [1.5])
    assert car.system.bounds[:2] == ((0, 10), (0, 10))          # x, y from the world box
    assert car.control_bounds == ((-2, 2), (-3, 3)) and car.duration == (1, 20)
    arm = parse_kinoplan(text(ARM))
    assert arm.check == 0.01 and arm.integrator is None and arm.duration is None
    assert (arm.system.l1, arm.system.l2, arm.system.base_x) == (1, 1, 0)


def test_items_override_the_defaults():
    problem = parse_kinoplan(text(PENDULUM, insert={3: [
        "param g 1.62", "bound omega -4 4", "control tau -5 5", "integrate euler 0.01",
        "duration 2 7", "metric theta 2 omega 0.5"]}))
    system = problem.system
    assert system.g == 1.62 and system.bounds[1] == (-4, 4) and system.controls == ((-5, 5),)
    assert (system.scheme, system.dt, system.kmin, system.kmax) == ("euler", 0.01, 2, 7)
    assert system.metric == ((("theta",), 2.0), (("omega",), 0.5))
    # The parameter reaches the dynamics: one euler slice at rest, hanging level.
    assert system.propagate((0.0, 0.0), (0.0, 1)) == (0.0, -0.01 * 1.62)
    car = parse_kinoplan(text(CAR2, {5: "start x 2 y 2 theta 0 v 0"},
                              insert={3: ["body rect 3 1", "bound x 1 9"]}))
    assert car.system.body == body_polygon("rect", [3, 1])
    assert car.system.bounds[:2] == ((1, 9), (0, 10))
    arm = parse_kinoplan(text(ARM, insert={3: ["param l1 0.5", "param base_x 0.1", "check 0.05"]}))
    assert (arm.system.l1, arm.system.base_x, arm.check) == (0.5, 0.1, 0.05)
    car1 = parse_kinoplan(text(CAR1, insert={3: "param L 0.3"}))
    assert car1.system.L == 0.3


def test_obstacles_in_order_and_the_world():
    problem = parse_kinoplan(text(CAR2, insert={5: ["circle 8 2 1", "polygon 1 8 2 8 1.5 9"]}))
    world = problem.world
    assert world.box == Rect(0, 0, 10, 10)
    assert world.obstacles[:2] == (Rect(4, 4, 6, 6), Disc(8, 2, 1))
    assert set(world.obstacles[2].points) == {(1, 8), (2, 8), (1.5, 9)}
    assert problem.obstacle_lines == (4, 5, 6)


def test_start_angles_are_wrapped_and_the_goal_is_the_restricted_metric():
    problem = parse_kinoplan(text(CAR2, {5: "start x 2 y 2 theta 4 v 0",
                                         6: "goal x 9 y 9 theta pi within 0.5"}))
    assert problem.start[2] == math.remainder(4.0, 2 * PI)
    goal = problem.goal
    assert not goal.full and goal.names == ("x", "y", "theta")
    # x,y weight 1, theta 0.5; v is not in the goal so it does not count.
    assert goal.distance((9.0, 9.3, -PI, 4.0)) == pytest.approx(0.3)
    assert goal.distance((9.0, 9.0, PI - 0.2, -4.0)) == pytest.approx(0.1)
    assert goal.accepts((9.0, 9.5, PI, 0.0)) and not goal.accepts((9.0, 9.5000001, PI, 0.0))
    assert not goal.reached((9.0, 9.5, PI, 0.0))          # the planners stop a hair inside
    assert goal.complete((1.0, 2.0, 3.0, 4.0)) == (9.0, 9.0, goal.target[2], 4.0)


def test_looks_like_kinoplan():
    assert looks_like_kinoplan("kinoplan 1\n") and looks_like_kinoplan("  \n# c\nkinoplan 1")
    assert looks_like_kinoplan("kinoplan2")                  # the reader then says what is wrong
    assert not looks_like_kinoplan("4\n3\n____\n") and not looks_like_kinoplan("")


EXAMPLE_TEXTS = [text(lines) for lines in (CAR2, PENDULUM, ARM, RIGID, CAR1, UNICYCLE)]
VOCABULARY = ["", "0", "-1", "1e999", "nan", "pi/0", "-pi/2", "3*pi", "x", "y", "theta", "v",
              "within", "K", "2.5", "#", "\t", "\r", "system", "start", "goal", "body", "world",
              "rect", "circle", "polygon", "metric", "x,y", "duration", "check", "integrate",
              "rk4", "control", "bound", "param", "1000001", "9" * 30]


def check_any_edit(base, edits):
    """Any edit of a good problem gives a problem or one format error."""
    words = base.replace("\n", " \n ").split(" ")
    for position, edit, word in edits:
        i = position % len(words)
        if edit == "replace":
            words[i] = word
        elif edit == "insert":
            words.insert(i, word)
        elif edit == "delete" and len(words) > 1:
            del words[i]
        else:
            words.insert(i, " ".join(words[i:i + 3]))
    try:
        problem = parse_kinoplan(" ".join(words))
    except ProblemFormatError as error:
        assert error.line >= 1 and error.column >= 1 and "\n" not in error.message
    else:
        assert state_valid(problem.system, problem.world, problem.start)


EDITS = st.lists(st.tuples(st.integers(0, 10_000), st.sampled_from(
    ["replace", "insert", "delete", "dup"]), st.sampled_from(VOCABULARY)), min_size=1, max_size=4)
test_any_edit_gives_a_problem_or_one_format_error, \
    test_any_edit_gives_a_problem_or_one_format_error_full = property_pair(
        check_any_edit, st.sampled_from(EXAMPLE_TEXTS), EDITS, unit=130, full=400)


def test_a_long_digit_run_is_refused_in_linear_time():
    """200 000 digits and a bad character: one error line; a backtracking number
    pattern took 40 s on a tenth of this (quadratic), so a hang fails the timeout."""
    import subprocess
    import sys
    code = ("from planning_core.kinoplan_text import parse_kinoplan\n"
            "from planning_core.problem_text import ProblemFormatError\n"
            "text = 'kinoplan 1\\nsystem pendulum\\nstart theta ' + '1' * 200000 + 'x omega 0\\n'\n"
            "try:\n    parse_kinoplan(text)\nexcept ProblemFormatError as error:\n"
            "    print(error)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=30)
    assert "line 3, column 13" in done.stdout and "is not a number" in done.stdout
