"""benchmarks/ompl_cpp_programs.py: the flat inputs of the C++ OMPL programs, and (with g++
and libompl-dev, slow) the answers of family_ompl and grid_ompl, every planner, passing the
validator's checks; benchmarks/ompl_cpp_planner.py, their peer command line."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from benchmarks.family import FAMILY_DIR
from benchmarks.harness import parse_progress, parse_stats
from benchmarks.ompl_cpp_programs import binary, family_input, grid_input
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.problem_text import parse_problem
from planning_core.setups import kinoplan_setup
from planning_core.vehicles import Vehicle
from validator.checks import validate_output, validate_plan

COURSE = FAMILY_DIR.parent / "course"


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


def test_a_kinodynamic_problem_gives_its_dynamics_controls_sst_radii_and_kpiece_grid():
    lines = family_input((FAMILY_DIR / "pendulum-t3.kp").read_text()).decode().splitlines()
    assert lines[5:] == ["1.0 1 0", "1.0 1 1", "dynamics rk4 0.05 1 10 9.81",
                         "controls 1 -3.0 3.0",
                         "sst 0.23141592653589793 0.11570796326794897",  # 1 % and 0.5 %
                         f"kpiece 2 0 {-math.pi!r} {64 / (2 * math.pi)!r} 1 -10.0 3.2",
                         "body 0 ", "box 0", "obstacles 0", "start -1.5707963267948966 0.0",
                         "goal 0.1 2 0 1.5707963267948966 1 0.0"]
    car = family_input((FAMILY_DIR / "car1-scene1.kp").read_text()).decode().splitlines()
    assert car[8] == "dynamics euler 0.01 1 250 0.2"  # car1's L
    assert car[11] == "kpiece 2 0 0.0 32.0 1 0.0 32.0"  # x and y, 64 cells over 0..2
    assert car[12] == "body 4 -0.1 -0.05 0.1 -0.05 0.1 0.05 -0.1 0.05"


def test_the_peer_refuses_what_the_programs_do_not_plan(tmp_path):
    run = lambda *args, problem: subprocess.run(  # noqa: E731
        [sys.executable, "-m", "benchmarks.ompl_cpp_planner", *args],
        stdin=open(problem), capture_output=True, text=True)
    done = run("-planner", "sst", problem=COURSE / "space-1.sw")
    assert (done.returncode, done.stdout) == (2, "")
    assert done.stderr == ("ompl_cpp_planner: error: planner 'sst' does not plan for the "
                           "point vehicle\n")
    done = run("-planner", "rrtstar", problem=FAMILY_DIR / "pendulum-t3.kp")
    assert done.returncode == 2 and done.stderr.endswith("for the pendulum system\n")
    done = run("-planner", "rrt", "-optimize", problem=COURSE / "space-1.sw")
    assert done.returncode == 2 and done.stderr.splitlines()[-1].endswith(
        "-optimize works with -planner rrtstar, informed, sst")
    bad = tmp_path / "bad.sw"
    bad.write_text("3\n")
    done = run(problem=bad)
    assert done.returncode == 2 and done.stderr.startswith("ompl_cpp_planner: bad problem: ")


CASES = [("rigid2-scene1.kp", "rrt"), ("variants/rigid2-discs.kp", "rrtconnect"),
         ("arm2-pair1.kp", "rrtconnect"), ("variants/arm2-elsewhere.kp", "rrt"),
         ("arm2-pair2.kp", "rrtstar"), ("rigid2-scene1.kp", "informed"),
         ("pendulum-t3.kp", "sst"), ("car1-scene1.kp", "sst"), ("car2-corridors.kp", "sst"),
         ("variants/unicycle-rects.kp", "sst"), ("pendulum-t5.kp", "rrt")]


@pytest.mark.slow
@pytest.mark.parametrize("name,planner", CASES)
def test_family_ompl_answers_pass_the_validator(name, planner):
    program = _program("family_ompl")
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
    problem = parse_kinoplan(text)
    if problem.system.kinodynamic:  # our slice in C++: each line's state, bit for bit
        rows = [[float(v) for v in line.split()] for line in
                runs[0].stdout.decode().splitlines()[1:report.trajectory_count + 1]]
        for row, after in zip(rows, rows[1:]):
            n = len(problem.start)
            assert problem.system.propagate(row[:n], (*row[n:-1], int(row[-1]))) == tuple(after[:n])


@pytest.mark.slow
@pytest.mark.parametrize("name,planner", [("arm2-pair1.kp", "prm"), ("rigid2-scene1.kp", "prmstar"),
                                          ("car1-scene1.kp", "kpiece"),
                                          ("pendulum-t3.kp", "kpiece")])
def test_family_ompl_roadmaps_and_kpiece_pass_the_validator(name, planner):
    """PRM's answer may differ run to run with one seed (OMPL checks its roadmap for a
    path in a thread of its own, every millisecond), so only its validity is checked."""
    text = (FAMILY_DIR / name).read_text()
    done = subprocess.run([str(_program("family_ompl")), planner, "30", "7"],
                          input=family_input(text), capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    stats = parse_stats(done.stderr.decode())
    assert stats["status"] == "solved" and int(stats["iterations"]) >= 0
    report = validate_plan(kinoplan_setup(parse_kinoplan(text)), done.stdout.decode())
    assert report.valid, report.first_failure


@pytest.mark.slow
@pytest.mark.parametrize("mode,vehicle,name", [("prm", Vehicle.POINT, "space-2"),
                                               ("prmstar", Vehicle.POINT, "space-1"),
                                               ("kpiece", Vehicle.SPACESHIP, "space-1"),
                                               ("kpiece-left", Vehicle.LEFT_SPACESHIP,
                                                "simple-0")])
def test_grid_ompl_roadmaps_and_kpiece_pass_the_validator(mode, vehicle, name):
    """KPIECE1 holds a control for 1 to 10 steps; the answer is one line a step (SPEC 2)."""
    text = (COURSE / f"{name}.sw").read_text()
    done = subprocess.run([str(_program("grid_ompl")), mode, "30", "5"], input=grid_input(text),
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    report = validate_output(parse_problem(text), vehicle, done.stdout.decode())
    assert report.valid, report.first_failure


def _program(name: str):
    program = binary(name)
    if program is None:
        pytest.skip("no g++ or OMPL headers (apt-get install libompl-dev)")
    return program


def _optimized(program, mode: str, flat: bytes, seconds: int = 5) -> tuple[str, dict, tuple]:
    """One optimize run (seed 3): its answer, stats and progress."""
    done = subprocess.run([str(program), mode, str(seconds), "3", "optimize"], input=flat,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    stderr = done.stderr.decode()
    return done.stdout.decode(), parse_stats(stderr), parse_progress(stderr)


@pytest.mark.slow
@pytest.mark.parametrize("mode,vehicle,name", [("rrtstar", Vehicle.POINT, "space-1"),
                                               ("informed", Vehicle.POINT, "space-1"),
                                               ("sst", Vehicle.SPACESHIP, "space-1"),
                                               ("sst-left", Vehicle.LEFT_SPACESHIP, "simple-0")])
def test_grid_ompl_optimizers_report_our_cost_and_pass_the_validator(mode, vehicle, name):
    text = (COURSE / f"{name}.sw").read_text()
    answer, stats, progress = _optimized(_program("grid_ompl"), mode, grid_input(text), 2)
    report = validate_output(parse_problem(text), vehicle, answer)
    assert report.valid, report.first_failure
    assert progress and [c for _, c in progress] == sorted((c for _, c in progress),
                                                           reverse=True)
    assert progress[-1][1] == pytest.approx(report.cost, rel=1e-8)  # OMPL's cost is ours
    assert float(stats["first_solution_seconds"]) == progress[0][0]


@pytest.mark.slow
@pytest.mark.parametrize("name,planner", [("arm2-pair1", "informed"),
                                          ("rigid2-scene1", "rrtstar"),
                                          ("car1-scene2", "sst")])
def test_family_ompl_optimizers_report_our_cost(name, planner):
    text = (FAMILY_DIR / f"{name}.kp").read_text()
    answer, stats, progress = _optimized(_program("family_ompl"), planner, family_input(text))
    report = validate_plan(kinoplan_setup(parse_kinoplan(text)), answer)
    assert report.valid, report.first_failure
    assert progress[-1][1] == pytest.approx(report.cost, rel=1e-8)
    assert stats["cost"] == f"{progress[-1][1]:.9g}"
