"""benchmarks/ompl_cpp_programs.py: the flat inputs of the C++ OMPL programs, and (with g++
and libompl-dev, slow) family_ompl's answers passing the validator's checks."""

from __future__ import annotations

import subprocess

import pytest

from benchmarks.family import FAMILY_DIR
from benchmarks.ompl_cpp_programs import binary, family_input
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.setups import kinoplan_setup
from validator.checks import validate_plan


def test_a_rigid_body_problem_is_written_flat_with_its_defaults():
    lines = family_input((FAMILY_DIR / "rigid2-scene1.kp").read_text()).decode().splitlines()
    assert lines[:4] == ["system rigid2", "vars 3", "0 0.0 2.0", "0 0.0 2.0"]
    assert lines[4].startswith("1 ")  # theta: an angle
    assert lines[5:9] == ["groups 2", "0.7 2 0 1", "0.3 1 2", "check 0.01"]
    assert lines[9] == "body 4 -0.15 -0.075 0.15 -0.075 0.15 0.075 -0.15 0.075"
    assert lines[10:12] == ["box 1 0.0 0.0 2.0 2.0", "obstacles 3"]
    assert lines[14] == "P 3 0.2 1.5 0.6 1.5 0.4 1.8"
    assert lines[15:] == ["start 0.5 0.25 0.0", "goal 0.02 3 0 1.75 1 1.5 2 0.0"]


def test_an_arm_problem_gives_its_links_and_every_obstacle_kind():
    text = (FAMILY_DIR / "variants" / "arm2-elsewhere.kp").read_text()
    lines = family_input(text).decode().splitlines()
    assert "arm 0.0 0.0 1.0 1.0" in lines and "groups 1" in lines and "1.0 2 0 1" in lines
    kinds = [line.split()[0] for line in lines[lines.index("obstacles 4") + 1:][:4]]
    assert kinds == ["R", "C", "P", "C"]
    assert lines[-1] == "goal 0.01 2 0 2.5 1 0.5"


def test_a_kinodynamic_problem_is_refused():
    with pytest.raises(ValueError, match="not pendulum"):
        family_input((FAMILY_DIR / "pendulum-t3.kp").read_text())


CASES = [("rigid2-scene1.kp", "rrt"), ("variants/rigid2-discs.kp", "rrtconnect"),
         ("arm2-pair1.kp", "rrtconnect"), ("variants/arm2-elsewhere.kp", "rrt")]


@pytest.mark.slow
@pytest.mark.parametrize("name,planner", CASES)
def test_family_ompl_answers_pass_the_validator(name, planner):
    program = binary("family_ompl")
    if program is None:
        pytest.skip("no g++ or OMPL headers (apt-get install libompl-dev)")
    text = (FAMILY_DIR / name).read_text()
    runs = [subprocess.run([str(program), planner, "30", "7"], input=family_input(text),
                           capture_output=True, timeout=120) for _ in range(2)]
    assert runs[0].returncode == 0, runs[0].stderr
    assert runs[0].stderr.decode().startswith("ompl_cpp stats: status=solved planning_seconds=")
    report = validate_plan(kinoplan_setup(parse_kinoplan(text)),
                           runs[0].stdout.decode())
    assert report.valid, report.first_failure
    assert report.trajectory_count >= 2
    assert runs[1].stdout == runs[0].stdout  # -seed reproduces the run
