"""OMPL on the kinoplan family (benchmarks/ompl_family.py), through the peer planner and
the harness: its answers, converted to our format, pass the validator's checks
(skipped without ompl)."""

import os
import random
import subprocess
import sys

import pytest

pytest.importorskip("ompl")

from benchmarks import catalog  # noqa: E402
from benchmarks.family import FAMILY_DIR  # noqa: E402
from benchmarks.harness import RunSpec, run_one  # noqa: E402
from benchmarks.ompl_family import Layout, control_space_information  # noqa: E402
from planning_core.kinoplan_text import parse_kinoplan  # noqa: E402
from planning_core.setups import kinoplan_setup  # noqa: E402
from validator.checks import validate_plan  # noqa: E402


def peer(args, stdin: bytes, timeout=120) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(catalog.ROOT))
    return subprocess.run([sys.executable, "-m", "benchmarks.ompl_planner", *args],
                          input=stdin, capture_output=True, timeout=timeout, env=env,
                          cwd=catalog.ROOT)


def _validated(name: str, planner: str, seed: int = 3):
    text = (FAMILY_DIR / f"{name}.kp").read_bytes()
    done = peer(["-planner", planner, "-seed", str(seed), "-time", "60", "-stats"], text)
    assert done.returncode == 0, done.stderr
    assert done.stderr.decode().startswith("ompl_planner stats: status=solved")
    problem = parse_kinoplan(text.decode())
    report = validate_plan(kinoplan_setup(problem), done.stdout.decode())
    assert report.valid, report.first_failure
    return done, report


FAST = [("pendulum-t10", "rrt"), ("arm2-pair1", "prm"), ("rigid2-scene1", "rrtconnect")]
SLOW = [("pendulum-t5", "kpiece1"), ("car2-corridors", "rrt"), ("unicycle-circles", "rrt"),
        ("car1-scene1", "rrt"), ("car1-scene2", "kpiece1"), ("rigid2-scene3", "prm"),
        ("arm2-pair2", "rrt"), ("arm2-pair3", "rrtconnect")]


@pytest.mark.parametrize("name,planner", FAST)
def test_ompl_answers_converted_to_our_format_pass_the_validator(name, planner):
    done, report = _validated(name, planner)
    assert report.trajectory_count >= 2
    if planner == "rrt":  # the same seed gives the same answer, byte for byte
        again = peer(["-planner", planner, "-seed", "3", "-time", "60"],
                     (FAMILY_DIR / f"{name}.kp").read_bytes())
        assert again.stdout == done.stdout


@pytest.mark.slow
@pytest.mark.parametrize("name,planner", SLOW)
def test_longer_ompl_runs_pass_the_validator_too(name, planner):
    _validated(name, planner, seed=1)


@pytest.mark.parametrize("name", ["pendulum-t3", "car2-corridors", "unicycle-circles",
                                  "car1-scene3"])
def test_ompl_steps_of_dt_are_our_slices_bit_for_bit(name):
    from ompl import base as ob, control as oc
    problem = parse_kinoplan((FAMILY_DIR / f"{name}.kp").read_text())
    system, layout = problem.system, Layout(ob, problem.system.space)
    info = control_space_information(ob, oc, problem, layout)
    info.setup()
    rng = random.Random(7)
    begin, end, control = layout.space.allocState(), layout.space.allocState(), \
        info.allocControl()
    for _ in range(20):
        held = system.sample_control(rng)
        for i, value in enumerate(held[:-1]):
            control[i] = value
        layout.put(begin, problem.start)
        info.propagate(begin, control, held[-1], end)
        assert layout.get(end) == system.propagate(problem.start, held)


def test_the_harness_runs_ompl_on_a_family_problem():
    ompl_rrt = next(p for p in catalog.family_planners() if p.id == "ompl-rrt")
    row = run_one(RunSpec(ompl_rrt, None, FAMILY_DIR / "pendulum-t10.kp", 2, 30))
    assert row.solved and row.valid and row.vehicle == "pendulum"
    assert row.implementation == "ompl" and row.family == "pendulum"
    assert row.path_duration > 0 and row.path_length > 0 and row.tree_nodes > 1


def test_the_peer_planner_refuses_a_planner_the_system_has_not_in_one_line():
    done = peer(["-planner", "prm"], (FAMILY_DIR / "pendulum-t3.kp").read_bytes())
    assert done.returncode == 2 and done.stdout == b""
    assert done.stderr.decode().count("\n") == 1 and "pendulum system" in done.stderr.decode()
    flags = peer(["-grad"], (FAMILY_DIR / "arm2-pair1.kp").read_bytes())
    assert flags.returncode == 2 and "names its own system" in flags.stderr.decode()
