"""RRT, RRT-Connect, PRM, PRM*, RRT* and Informed RRT* on the geometric family (arm2, rigid2; SPEC 5,
issue 15): answers pass the validator's own checks (SPEC 5.5), motions are
checked at exactly the validator's samples, -seed reproduces, -smooth shortens."""

import random

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from rrt_cli.planners import PLANNERS, prmstar
from rrt_cli.planners.base import StopCondition
from rrt_cli.planners.paths import path_length
from rrt_cli.planners.steering import StraightLineSteering
from planning_core.worlds.link_tests import LinkTests
from tests.conftest import ROOT, plan_in_process, run_planner
from tests.planning_core.worlds.test_link_tests import count_calls
from validator.checks import validate_plan

FAMILY = ROOT / "benchmarks" / "problems" / "family"
GEOMETRIC_PLANNERS = ("rrt", "rrtconnect", "prm", "prmstar", "rrtstar", "informed")

# Small problems: a circle in the arm's way, a wall in the body's.
ARM = """kinoplan 1
system arm2
world -2.2 -2.2 2.2 2.2
circle 0.0 1.5 0.3
start theta1 0 theta2 0
goal theta1 pi theta2 0 within 0.05
"""
BODY = """kinoplan 1
system rigid2
body rect 0.3 0.1
world 0 0 2 2
rect 0.9 0 1.1 1.4
start x 0.3 y 0.3 theta 0
goal x 1.7 y 0.3 theta 0 within 0.05
"""
# Every obstacle kind, close to the arm's reach, for the clearance skips of its motion check.
ARM_SHAPES = """kinoplan 1
system arm2
param base_x 0.1
world -2.2 -2.2 2.05 2.2
rect 0.6 0.6 1.3 1.3
circle -1.3 0.5 0.25
polygon -0.5 -1.9 0.4 -1.6 0.1 -1.2
start theta1 -0.5 theta2 -0.5
goal theta1 1.5 theta2 1.5 within 0.01
"""
SMALL = {"arm": ARM, "body": BODY, "arm-shapes": ARM_SHAPES}


def geometric_setup(text: str):
    return kinoplan_setup(parse_kinoplan(text))


def solve(planner: str, setup, seed: int, time_limit: float = 30.0, params=None):
    module = PLANNERS[planner].load()
    return module.solve(setup.si, setup.pdef, StopCondition(time_limit=time_limit),
                        random.Random(seed), params or module.Params())


def assert_solved_and_valid(setup, result):
    assert result.solved, (result.status, result.message)
    n = setup.si.space.dimension
    assert all(len(row) == n for row in result.trajectory)
    assert all(len(row) == 2 * n for row in result.tree)
    start, goal = setup.pdef.start, setup.pdef.goal
    assert result.trajectory[0] == start and goal.accepts(result.trajectory[-1])
    report = validate_plan(setup, format_plan(result.trajectory, result.tree))
    assert report.valid, report.first_failure


@pytest.mark.parametrize("planner", GEOMETRIC_PLANNERS)
@pytest.mark.parametrize("problem", sorted(SMALL))
def test_planner_solves_a_small_geometric_problem_and_the_validator_accepts(planner, problem):
    setup = geometric_setup(SMALL[problem])
    si = setup.si
    # PRM*'s refinement on a smaller scale: the default runs for seconds.
    small = prmstar.Params(min_refined_vertices=32, max_refined_vertices=128)
    result = solve(planner, setup, seed=1, params=small if planner == "prmstar" else None)
    assert_solved_and_valid(setup, result)
    assert len(result.trajectory) > 2  # the obstacle is in the straight line's way


@pytest.mark.parametrize("problem", sorted(SMALL))
def test_first_hit_is_the_first_invalid_sample_the_validator_would_test(problem, monkeypatch):
    setup = geometric_setup(SMALL[problem])
    si = setup.si
    rng = random.Random(5)
    blocked = tested = samples_total = 0
    valid = si.is_valid
    # The arm's samples are counted in its native loop (LinkTests, interpreted here).
    tests = count_calls(monkeypatch, LinkTests, "in_bounds")

    def counted(state):
        nonlocal tested
        tested += 1
        return valid(state)
    for _ in range(300):
        a, b = si.free_sampler(rng)(), si.sample_target(rng)
        samples = si.system.motion_samples(a, b)
        first_bad = next((k for k in range(1, len(samples)) if not valid(samples[k])), None)
        si.is_valid, before = counted, tests[0]
        hit = si.first_hit(a, b)
        si.is_valid, tested = valid, tested + tests[0] - before
        samples_total += len(samples) - 1
        if first_bad is None:
            assert hit is None
        else:
            blocked += 1
            assert hit is not None and hit.fraction == first_bad / (len(samples) - 1)
    assert 10 < blocked < 290
    if problem.startswith("arm"):  # the clearance skips most samples
        assert 0 < tested < samples_total / 3


def test_a_partial_extension_ends_on_a_motion_that_is_free_at_its_own_samples():
    setup = geometric_setup(BODY)
    si = setup.si
    steering = StraightLineSteering(si, True, si.check, 1.0)
    rng = random.Random(2)
    partial = 0
    for _ in range(300):
        a, target = si.free_sampler(rng)(), si.sample_target(rng)
        step = steering.extend(a, target, rng)
        if step is not None and step[0] != tuple(target):
            partial += 1
            assert si.is_valid(step[0]) and si.first_hit(a, step[0]) is None
            assert si.distance(a, step[0]) < si.distance(a, target)
    assert partial > 10


def test_check_around_keeps_the_free_edges_at_a_vertex_and_drops_the_blocked_ones():
    from rrt_cli.planners.prm import Roadmap
    setup = geometric_setup(BODY)
    si = setup.si
    roadmap, draw = Roadmap(si), si.free_sampler(random.Random(3))
    for _ in range(60):
        roadmap.add_vertex(draw(), neighbors=12)
    vertex = max(range(len(roadmap)), key=lambda v: len(roadmap.adjacency[v]))
    before = {other for other, _ in roadmap.adjacency[vertex]}
    roadmap.check_around(vertex)
    after = {other for other, _ in roadmap.adjacency[vertex]}
    state = roadmap.states[vertex]
    assert after and after < before  # the wall blocks some
    for other in before:
        free = si.first_hit(state, roadmap.states[other]) is None
        assert (other in after) == free
        assert free == ((vertex, other) in roadmap.checked)


def test_rrtconnect_targets_the_family_with_uniform_states_valid_or_not():
    from rrt_cli.planners import rrtconnect
    setup = geometric_setup(BODY)
    si = setup.si
    si.free_sampler = None  # not asked for by default
    assert_solved_and_valid(setup, solve("rrtconnect", setup, seed=1))
    with pytest.raises(TypeError):
        solve("rrtconnect", setup, seed=1,
              params=rrtconnect.Params(free_space_targets=True))


def test_registry_geometric_kinoplan_systems_have_six_planners():
    for name in ("arm2-pair1", "rigid2-scene1"):
        system = parse_kinoplan((FAMILY / f"{name}.kp").read_text()).system
        assert {planner for planner, entry in PLANNERS.items()
                if entry.plans_for_kinoplan(system)} == set(GEOMETRIC_PLANNERS)


def test_prmstar_neighbour_rules():
    assert prmstar.star_neighbor_count(100, dimension=3) == 17  # e (4/3) 4.605 = 16.7
    assert prmstar.log_neighbor_count(100) == 5 and prmstar.log_neighbor_count(1) == 1
    setup = geometric_setup(ARM)
    si = setup.si
    assert_solved_and_valid(setup, solve("prmstar", setup, 3,
                                      params=prmstar.Params(log_neighbors=True)))


@pytest.mark.parametrize("planner", ("rrtconnect", "prm"))
def test_cli_seed_reproduces_and_smooth_shortens_a_geometric_answer(monkeypatch, planner):
    argv = ["-planner", planner, "-seed", "4"]
    status, raw, err = plan_in_process(monkeypatch, argv, BODY)
    assert status == 0 and err == "", err
    assert plan_in_process(monkeypatch, argv, BODY)[1] == raw
    status, smooth, _ = plan_in_process(monkeypatch, argv + ["-smooth"], BODY)
    assert status == 0
    setup = geometric_setup(BODY)
    si = setup.si
    lengths = []
    for text in (raw, smooth):
        report = validate_plan(setup, text)
        assert report.valid, report.first_failure
        lengths.append(report.path_length)
    assert lengths[1] <= lengths[0] + 1e-9


def test_cli_smooth_with_a_kinodynamic_family_system_is_a_usage_error():
    done = run_planner(["-smooth"], (FAMILY / "pendulum-t3.kp").read_text())
    assert done.returncode == 2 and done.stdout == b"" and b"Traceback" not in done.stderr
    last = done.stderr.decode().splitlines()[-1]
    assert last == "rrt_cli: error: -smooth works on geometric systems only"


def test_cli_a_planner_that_does_not_plan_for_the_arm_says_which_do(monkeypatch):
    status, out, err = plan_in_process(monkeypatch, ["-planner", "kpiece"], ARM)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "does not plan for kinoplan problems of the arm2 system" in err
    assert "prmstar" in err


def test_lazy_roadmap_prints_only_edges_found_free_and_gives_way_to_the_time_limit():
    setup = geometric_setup(BODY)
    si = setup.si
    result = solve("prm", setup, seed=2)
    assert_solved_and_valid(setup, result)
    for row in result.tree:
        a, b = row[:3], row[3:]
        assert si.first_hit(a, b) is None or si.first_hit(b, a) is None
    stop = StopCondition(time_limit=0.05)
    prmstar.solve(si, setup.pdef, stop, random.Random(1), prmstar.Params(min_refined_vertices=10 ** 6,
                                                             max_refined_vertices=10 ** 6))
    assert stop.time_is_up() and not stop.status(0) is None


# ----- issue 15's acceptance: every planner, every family problem, 20 seeds --------------

SWEEP = [pytest.param(planner, name, marks=pytest.mark.slow, id=f"{planner}-{name}")
         for planner in GEOMETRIC_PLANNERS
         for name in [f"arm2-pair{i}" for i in range(1, 6)]
         + [f"rigid2-scene{i}" for i in range(1, 4)]]


@pytest.mark.parametrize("planner,name", SWEEP)
def test_every_planner_solves_every_geometric_family_problem_for_20_seeds(planner, name):
    setup = geometric_setup((FAMILY / f"{name}.kp").read_text())
    si = setup.si
    for seed in range(1, 21):
        assert_solved_and_valid(setup, solve(planner, setup, seed, time_limit=30.0))


def test_path_length_helper_takes_the_metric():
    setup = geometric_setup(ARM)
    si = setup.si
    path = [(0.0, 0.0), (3.0, 0.0), (-3.0, 0.0)]  # the last motion wraps: 2 pi - 6
    assert path_length(path, si.distance) == pytest.approx(3.0 + (2 * 3.141592653589793 - 6))


def test_kdtree_bench_table_rows_compare_answers_with_the_scan():
    from benchmarks.bench_kdtree import measure_k_nearest, roadmap_spaces
    for space in roadmap_spaces().values():
        row = measure_k_nearest(space, size=60, k=5, repeats=1, n_queries=20)
        assert row["kd"] > 0.0 and row["scan"] > 0.0
