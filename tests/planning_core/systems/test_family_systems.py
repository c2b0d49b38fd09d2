"""The six systems of SPEC 5.2 (pendulum, car2, unicycle, car1, arm2, rigid2).

Dynamics pinned by hand (one euler and one rk4 slice of SPEC's equations, typed
here independently of the modules), angles wrapped, K slices as K applications,
purity, control sampling and its bounds, footprints and arm joints at exact
angles, validity in a world, geometric motions, and every example problem.
"""

from __future__ import annotations

import filecmp
import math
import pickle
import random
from math import cos, sin, tan
from pathlib import Path

import pytest

from planning_core.kinoplan import invalid_reason, state_valid, state_validator
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.systems import load
from planning_core.systems.arm2 import Arm2
from planning_core.systems.car1 import Car1
from planning_core.systems.car2 import Car2
from planning_core.systems.pendulum import Pendulum
from planning_core.systems.rigid2 import Rigid2
from planning_core.systems.unicycle import Unicycle
from planning_core.worlds.continuous import ContinuousWorld
from planning_core.worlds.shapes import Disc, Rect, body_polygon

ROOT = Path(__file__).resolve().parents[3]
FAMILY_DIR = ROOT / "benchmarks" / "problems" / "family"
SHARED_DIR = ROOT.parent / "shared" / "problems" / "family"
EXAMPLES = sorted(FAMILY_DIR.glob("*.kp"))
KINODYNAMIC = ("pendulum", "car2", "unicycle", "car1")
PI = math.pi

# SPEC 5.2's right-hand sides, typed from the table: f(state, held control).
SPEC_RATES = {
    "pendulum": lambda s, u: (s[1], -9.81 * cos(s[0]) + u[0]),
    "car2": lambda s, u: (s[3] * cos(s[2]), s[3] * sin(s[2]), u[0], u[1]),
    "unicycle": lambda s, u: (s[3] * cos(s[2]), s[3] * sin(s[2]), s[4], u[0], u[1]),
    "car1": lambda s, u: (u[0] * cos(s[2]), u[0] * sin(s[2]), u[0] / 0.2 * tan(u[1])),
}
# A non-trivial state and control per system (theta is index 0 for the pendulum, else 2).
CASES = {
    "pendulum": ((0.7, -1.3), (2.0,)),
    "car2": ((1.0, -2.0, 2.5, 1.5), (0.8, -1.2)),
    "unicycle": ((3.0, 4.0, -0.4, 2.0, 0.6), (1.0, -0.3)),
    "car1": ((0.5, 0.25, 1.0), (0.4, 0.3)),
}
THETA = {"pendulum": 0, "car2": 2, "unicycle": 2, "car1": 2}


def _by_hand(name: str, scheme: str, dt: float):
    """One slice written out: s + dt f(s), or RK4's four stages; theta wrapped."""
    f = SPEC_RATES[name]
    s, u = CASES[name]
    k1 = f(s, u)
    if scheme == "euler":
        out = [si + dt * a for si, a in zip(s, k1)]
    else:
        k2 = f([si + dt / 2 * a for si, a in zip(s, k1)], u)
        k3 = f([si + dt / 2 * a for si, a in zip(s, k2)], u)
        k4 = f([si + dt * a for si, a in zip(s, k3)], u)
        out = [si + dt / 6 * (a + 2 * b + 2 * c + d) for si, a, b, c, d in zip(s, k1, k2, k3, k4)]
    i = THETA[name]
    out[i] = math.remainder(out[i], 2 * PI)
    return tuple(out)


@pytest.mark.parametrize("scheme", ["euler", "rk4"])
@pytest.mark.parametrize("name", KINODYNAMIC)
def test_one_slice_by_hand(name, scheme):
    system = type(load(name)).configure(integrate=(scheme, 0.05))
    state, control = CASES[name]
    got = system.propagate(state, (*control, 1))
    assert got == pytest.approx(_by_hand(name, scheme, 0.05), abs=1e-14)
    # Not the other scheme's answer: the scheme really is the one named.
    other = _by_hand(name, "rk4" if scheme == "euler" else "euler", 0.05)
    assert got != pytest.approx(other, abs=1e-9)


def test_car2_rk4_slice_in_closed_form():
    # omega and a are constant over a slice, so RK4's stages have theta and v at t,
    # t + h/2 (twice) and t + h, and x, y weight v cos(theta), v sin(theta) 1-2-2-1.
    (x, y, theta, v), (omega, a), h = CASES["car2"][0], CASES["car2"][1], 0.05
    mid_theta, mid_v = theta + h / 2 * omega, v + h / 2 * a
    end_theta, end_v = theta + h * omega, v + h * a
    got = Car2().propagate((x, y, theta, v), (omega, a, 1))
    assert got == pytest.approx((
        x + h / 6 * (v * cos(theta) + 4 * mid_v * cos(mid_theta) + end_v * cos(end_theta)),
        y + h / 6 * (v * sin(theta) + 4 * mid_v * sin(mid_theta) + end_v * sin(end_theta)),
        2.54, 1.44), abs=1e-14)


def test_defaults_are_spec_table_5_2():
    p, c2, u, c1 = Pendulum(), Car2(), Unicycle(), Car1()
    assert (p.g, p.controls, p.scheme, p.dt, p.kmin, p.kmax) == (9.81, ((-3, 3),), "rk4", 0.05, 1, 10)
    assert p.bounds[1] == (-10, 10) and p.metric == ((("theta",), 1.0), (("omega",), 1.0))
    assert (c2.controls, c2.scheme, c2.dt, c2.kmin, c2.kmax) == (((-2, 2), (-3, 3)), "rk4", 0.05, 1, 20)
    assert c2.bounds[3] == (-5, 5) and c2.body == body_polygon("square", [1.5])
    assert c2.metric == ((("x", "y"), 1.0), (("theta",), 0.5), (("v",), 0.3))
    assert u.controls == ((-2, 2), (-PI / 2, PI / 2)) and (u.scheme, u.dt) == ("euler", 0.1)
    assert u.bounds[3:] == ((-5, 5), (-PI / 2, PI / 2)) and u.body == body_polygon("rect", [2, 1])
    assert u.metric == ((("x", "y"), 1.0), (("theta",), 0.5))
    assert (c1.L, c1.controls, c1.scheme, c1.dt, c1.kmax) == (0.2, ((-0.5, 0.5), (-PI / 4, PI / 4)), "euler", 0.01, 250)
    assert c1.body == body_polygon("rect", [0.2, 0.1])
    a = Arm2()
    assert (a.base_x, a.base_y, a.l1, a.l2, a.check) == (0, 0, 1, 1, 0.01)
    assert a.metric == ((("theta1", "theta2"), 1.0),)
    assert Rigid2().metric == ((("x", "y"), 0.7), (("theta",), 0.3)) and Rigid2().body is None


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_angles_wrap_after_every_slice(name):
    system = load(name)
    i = THETA[name]
    state = list(CASES[name][0])
    state[i] = 3.1
    # A fast turn: the pendulum by its omega, the others by their controls or rates.
    if name == "pendulum":
        state[1] = 9.0
    control = {"pendulum": (0.0,), "car2": (2.0, 0.0), "unicycle": (0.0, 0.0),
               "car1": (0.5, 0.7)}[name]
    if name == "unicycle":
        state[4] = 1.5
    slices = system.slice_states(tuple(state), (*control, system.kmax))
    thetas = [s[i] for s in slices]
    assert all(-PI <= t <= PI for t in thetas)
    assert any(t < 0 for t in thetas)      # crossed pi and came back as a negative angle


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_k_slices_are_k_applications(name):
    system = load(name)
    state, control = CASES[name]
    one = state
    for _ in range(7):
        one = system.propagate(one, (*control, 1))
    assert system.propagate(state, (*control, 7)) == one
    assert system.slice_states(state, (*control, 7))[-1] == one
    assert len(system.slice_states(state, (*control, 7))) == 7


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_propagate_is_pure(name):
    system = load(name)
    state, control = CASES[name]
    s, u = list(state), [*control, 3]
    first = system.propagate(s, u)
    assert s == list(state) and u == [*control, 3]
    assert system.propagate(tuple(state), (*control, 3)) == first


@pytest.mark.parametrize("name", KINODYNAMIC)
def test_sampled_controls_are_within_bounds_and_cover_the_duration(name):
    system = type(load(name)).configure(duration=(2, 5))
    ks = set()
    for seed in range(2000):
        control = system.sample_control(random.Random(seed))
        assert system.control_violation(control) is None, control
        for value, (lo, hi) in zip(control, system.controls):
            assert lo <= value < hi
        ks.add(control[-1])
    assert ks == {2, 3, 4, 5}


def test_sample_control_draws_in_the_documented_order():
    system = Car2()
    rng, mirror = random.Random(7), random.Random(7)
    control = system.sample_control(rng)
    omega = -2.0 + 4.0 * mirror.random()
    a = -3.0 + 6.0 * mirror.random()
    assert control == (omega, a, mirror.randint(1, 20))


@pytest.mark.parametrize("control, message", [
    ((2.5, 0.0, 3), "control omega = 2.5 is outside [-2, 2]"),
    ((0.0, -3.5, 3), "control a = -3.5 is outside [-3, 3]"),
    ((0.0, 0.0, 0), "K = 0 is outside the duration [1, 20]"),
    ((0.0, 0.0, 21), "K = 21 is outside the duration [1, 20]"),
    ((0.0, 0.0, 2.5), "K = 2.5 is not a whole number of slices"),
    ((0.0, 0.0), "2 control values, expected 3 (omega a K)"),
    ((math.nan, 0.0, 3), "control omega = nan is outside"),
])
def test_control_violation_names_what_is_wrong(control, message):
    assert message in Car2().control_violation(control)


def test_control_violation_accepts_the_bounds_themselves():
    assert Car2().control_violation((-2.0, 3.0, 20)) is None
    assert Car2().control_violation((2.0, -3.0, 1.0)) is None


@pytest.mark.parametrize("system, half", [
    (Car2(), (0.75, 0.75)), (Unicycle(), (1.0, 0.5)), (Car1(), (0.1, 0.05)),
    (Rigid2(body=body_polygon("rect", [0.3, 0.15])), (0.15, 0.075)),
])
def test_footprints_at_zero_and_a_quarter_turn_have_exact_corners(system, half):
    hx, hy = half
    at_zero = system.footprint((3.0, 2.0, 0.0) + (0.0,) * (len(system.state_names) - 3))
    assert set(at_zero.points) == {(3 + sx * hx, 2 + sy * hy) for sx in (-1, 1) for sy in (-1, 1)}
    quarter = system.footprint((3.0, 2.0, PI / 2) + (0.0,) * (len(system.state_names) - 3))
    assert set(quarter.points) == {(3 + sx * hy, 2 + sy * hx) for sx in (-1, 1) for sy in (-1, 1)}


def test_arm_joints_at_known_angles():
    arm = Arm2()
    assert arm.joints((0.0, 0.0)) == ((0, 0), (1, 0), (2, 0))
    assert arm.joints((PI / 2, 0.0)) == ((0, 0), (0, 1), (0, 2))
    assert arm.joints((PI / 2, PI / 2)) == ((0, 0), (0, 1), (-1, 1))
    assert arm.joints((PI, -PI / 2)) == ((0, 0), (-1, 0), (-1, 1))
    moved = Arm2(base_x=1.0, base_y=-1.0, l1=2.0, l2=0.5)
    assert moved.joints((0.0, PI / 2)) == ((1, -1), (3, -1), (3, -0.5))
    base_elbow, elbow_tip = moved.links((0.0, PI / 2))
    assert (base_elbow.x0, base_elbow.y0, base_elbow.x1, base_elbow.y1) == (1, -1, 3, -1)
    assert (elbow_tip.x0, elbow_tip.y0, elbow_tip.x1, elbow_tip.y1) == (3, -1, 3, -0.5)
    _, elbow, tip = Arm2().joints((0.3, 0.4))
    assert elbow == pytest.approx((cos(0.3), sin(0.3)), abs=1e-15)
    assert tip == pytest.approx((cos(0.3) + cos(0.7), sin(0.3) + sin(0.7)), abs=1e-15)


def test_arm_links_must_stay_in_the_box_and_off_obstacles():
    world = ContinuousWorld(Rect(-2, -2, 2, 2), (Rect(0.5, 0.5, 1.0, 1.0),))
    arm, valid = Arm2(), state_validator(Arm2(), world)
    assert valid((0.0, 0.0))                              # tip on (2, 0): touching the box
    assert not valid((PI / 4, 0.0))                       # the first link crosses the rect
    assert "link 1 (base to elbow) touches obstacle 1" in invalid_reason(arm, world, (PI / 4, 0.0))
    assert not valid((PI / 2, -PI / 2))                   # elbow (0, 1), tip (1, 1): rect's edge
    assert "link 2" in invalid_reason(arm, world, (PI / 2, -PI / 2))
    tight = ContinuousWorld(Rect(-1.5, -2, 2, 2))
    assert not state_valid(arm, tight, (PI, 0.0))         # tip (-2, 0): out of the box
    assert "not inside the world box" in invalid_reason(arm, tight, (PI, 0.0))
    assert not valid((math.nan, 0.0))


def test_body_validity_in_a_world():
    world = ContinuousWorld(Rect(0, 0, 10, 10), (Disc(5, 5, 1),))
    car, valid = Car2(), state_validator(Car2(), world)
    assert valid((0.75, 0.75, 0.0, 0.0))                  # touching two walls
    assert not valid((0.7, 5.0, 0.0, 0.0))                # crosses x = 0
    assert not valid((3.25, 5.0, 0.0, 0.0))               # touches the disc at (4, 5)
    assert valid((3.2499, 5.0, 0.0, 0.0))
    assert not valid((2.0, 2.0, 0.0, 5.5))                # v out of bounds
    assert "v = 5.5 is outside its bound [-5, 5]" == invalid_reason(car, world, (2, 2, 0, 5.5))
    assert "touches obstacle 1 (line 9)" in invalid_reason(car, world, (3.25, 5, 0, 0), (9,))
    assert invalid_reason(car, world, (3.2499, 5.0, 0.0, 0.0)) is None
    assert not valid((2.0, 2.0, math.inf, 0.0)) and not valid((2.0, 2.0, 0.0))
    assert state_validator(Pendulum(), None)((100.0, 10.0))
    assert not state_validator(Pendulum(), None)((0.0, 10.5))


def test_propagate_while_stops_at_the_first_invalid_slice():
    car = Car2()
    world = ContinuousWorld(Rect(0, 0, 10, 10))
    valid = state_validator(car, world)
    start, control = (5.0, 5.0, 0.0, 4.0), (0.0, 0.0, 20)     # 4 m/s east for 1 s
    assert car.propagate_while(start, control, valid) is not None
    blocked = ContinuousWorld(Rect(0, 0, 10, 10), (Rect(8.0, 0, 9, 10),))
    seen = []

    def spy(state):
        seen.append(state)
        return state_valid(car, blocked, state)

    assert car.propagate_while(start, control, spy) is None
    # Slice k is at x = 5 + 0.2 k; the front edge (x + 0.75) touches x = 8 at k = 11.25,
    # so slice 12 is the first invalid one, and nothing after it is looked at.
    assert len(seen) == 12 and seen[-1][0] == pytest.approx(7.4)


def test_geometric_interpolation_goes_the_short_way_and_samples_both_ends():
    body = body_polygon("rect", [0.3, 0.15])
    rigid = Rigid2(body=body, check=0.1)
    a, b = (0.0, 0.0, 3.0), (1.0, 0.0, -3.0)
    mid = rigid.interpolate(a, b, 0.5)
    assert mid[0] == 0.5 and abs(mid[2]) == pytest.approx(PI)   # through pi, not through 0
    d = rigid.distance(a, b)
    assert d == pytest.approx(0.7 * 1.0 + 0.3 * (2 * PI - 6.0))
    samples = rigid.motion_samples(a, b)
    n = math.ceil(d / 0.1)
    assert len(samples) == n + 1 and samples[0] == a and samples[-1] == b
    assert len(rigid.motion_samples(a, b, strict=True)) == math.ceil(10 * d / 0.1) + 1
    assert len(rigid.motion_samples(a, b, 0.01)) == math.ceil(d / 0.01) + 1
    assert rigid.motion_samples(a, a) == [a, a]                 # n = max(1, 0)
    steps = [rigid.distance(p, q) for p, q in zip(samples, samples[1:])]
    assert max(steps) <= 0.1 and max(steps) == pytest.approx(min(steps))


def test_arm_motion_wraps_on_the_torus():
    arm = Arm2()
    a, b = (3.0, -3.0), (-3.0, 3.0)
    assert arm.distance(a, b) == pytest.approx(math.hypot(2 * PI - 6, 2 * PI - 6))
    samples = arm.motion_samples(a, b)
    assert all(abs(s[0]) >= 3.0 and abs(s[1]) >= 3.0 for s in samples)


def test_configure_overrides_defaults_and_takes_world_bounds():
    car = Car1.configure(params={"L": 0.5}, bounds={"y": (0.5, 1.5)}, world_box=Rect(0, 0, 2, 3),
                         controls={"v": (-1.0, 1.0)}, integrate=("rk4", 0.02), duration=(5, 9))
    assert car.L == 0.5 and car.bounds[:2] == ((0, 2), (0.5, 1.5))
    assert car.controls == ((-1, 1), (-PI / 4, PI / 4)) and (car.scheme, car.dt) == ("rk4", 0.02)
    assert (car.kmin, car.kmax) == (5, 9)
    # The new wheelbase reaches the dynamics: theta' = v / L tan(phi).
    assert car.propagate((0, 0, 0), (1.0, 0.5, 1))[2] == pytest.approx(0.02 * tan(0.5) / 0.5, rel=1e-3)
    with pytest.raises(ValueError, match="no variable or param"):
        Car1.configure(params={"g": 1.0})
    with pytest.raises(ValueError, match="no control"):
        Car1.configure(controls={"tau": (0, 1)})
    with pytest.raises(ValueError, match="takes no"):
        Arm2.configure(integrate=("rk4", 0.1))


@pytest.mark.parametrize("name", ["pendulum", "car2", "unicycle", "car1", "arm2", "rigid2"])
def test_a_configured_system_pickles_and_compares_by_its_fields(name):
    system = load(name)
    again = pickle.loads(pickle.dumps(system))
    assert again == system and hash(again) == hash(system)
    if system.kinodynamic:
        state, control = CASES[name]
        assert again.propagate(state, (*control, 4)) == system.propagate(state, (*control, 4))


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_problem_parses_with_a_valid_start_and_goal(path):
    problem = parse_kinoplan(path.read_text())
    valid = state_validator(problem.system, problem.world)
    assert valid(problem.start)
    if problem.goal.full:
        assert valid(problem.goal.target)
    assert problem.goal.accepts(problem.goal.target) or not problem.goal.full


def test_examples_cover_every_system_and_match_the_shared_folder():
    assert {parse_kinoplan(p.read_text()).system_name for p in EXAMPLES} == set(
        ("pendulum", "car2", "unicycle", "car1", "arm2", "rigid2"))
    if SHARED_DIR.is_dir():
        shared = sorted(p.name for p in SHARED_DIR.glob("*.kp"))
        assert shared == [p.name for p in EXAMPLES]
        assert all(filecmp.cmp(SHARED_DIR / n, FAMILY_DIR / n, shallow=False) for n in shared)
