"""OMPL's adapters and the peer command-line planner (skipped without ompl)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("ompl")

from benchmarks import catalog, ompl_adapters  # noqa: E402
from benchmarks.harness import RunSpec, run_one  # noqa: E402
from planning_core.problem_text import parse_problem  # noqa: E402
from planning_core.systems import spaceship  # noqa: E402
from planning_core.vehicles import Vehicle  # noqa: E402
from tests.conftest import unit_sample  # noqa: E402
from validator.checks import validate_output  # noqa: E402

PROBLEMS = Path(catalog.ROOT) / "benchmarks" / "problems"
FLAGS = {Vehicle.POINT: [], Vehicle.SPACESHIP: ["-grad"], Vehicle.LEFT_SPACESHIP: ["-left"]}


def peer(args, stdin: bytes, timeout=60) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(catalog.ROOT))
    return subprocess.run([sys.executable, str(catalog.ROOT / "benchmarks" / "ompl_planner.py"),
                           *args], input=stdin, capture_output=True, timeout=timeout, env=env)


CASES = unit_sample([(Vehicle.POINT, "rrt", "course-space-2"),
                     (Vehicle.SPACESHIP, "kpiece1", "course-space-0"),
                     (Vehicle.LEFT_SPACESHIP, "rrt", "course-simple-0"),
                     (Vehicle.POINT, "rrtconnect", "maze-10"),
                     (Vehicle.SPACESHIP, "rrt", "course-space-1")], keep=3)
"""One case per vehicle in the unit run; every case in the full suite."""


@pytest.mark.parametrize("vehicle,planner,name", CASES)
def test_peer_planner_answers_pass_the_validator(vehicle, planner, name):
    path = PROBLEMS / "course" / f"{name[len('course-'):]}.sw" if name.startswith("course-") \
        else PROBLEMS / f"{name}.sw"
    text = path.read_bytes()
    done = peer([*FLAGS[vehicle], "-planner", planner, "-seed", "4", "-time", "20", "-stats"],
                text)
    assert done.returncode == 0, done.stderr
    stderr = done.stderr.decode()
    assert stderr.startswith("ompl_planner stats: status=solved") and stderr.count("\n") == 1
    report = validate_output(parse_problem(text.decode()), vehicle, done.stdout.decode())
    assert report.valid, report.first_failure
    if vehicle.is_spaceship:
        # Lines were re-propagated from the start: each state is its predecessor's step.
        rows = [tuple(map(float, line.split()))
                for line in done.stdout.decode().splitlines()[1:report.trajectory_count + 1]]
        for before, after in zip(rows, rows[1:]):
            assert spaceship.SYSTEM.propagate(before[:4], before[4:]) == after[:4]
        if vehicle is Vehicle.LEFT_SPACESHIP:
            assert all(0.0 <= row[4] <= 3.141592653589793 for row in rows)
    # The same seed gives the same output, byte for byte.
    again = peer([*FLAGS[vehicle], "-planner", planner, "-seed", "4", "-time", "20"], text)
    assert again.stdout == done.stdout


def test_peer_planner_refuses_bad_input_in_one_line():
    bad = peer([], b"4\n3\n____\n__x_\n____\n0.5\n0.5\n3.5\n2.5\n")
    assert bad.returncode == 2 and bad.stdout == b""
    assert bad.stderr.decode().count("\n") == 1 and "line 4" in bad.stderr.decode()
    wrong = peer(["-planner", "kpiece1"], (PROBLEMS / "course" / "simple-0.sw").read_bytes())
    assert wrong.returncode == 2 and "does not support" in wrong.stderr.decode()


def test_peer_planner_gives_up_at_its_time_limit():
    # A wall with no gap: unsolvable, so OMPL must stop at the limit.
    walled = b"5\n3\n__#__\n__#__\n__#__\n0.5\n0.5\n4.5\n2.5\n"
    done = peer(["-time", "0.3", "-stats"], walled)
    assert done.returncode == 3 and done.stdout == b""
    assert "status=time_limit" in done.stderr.decode()


def test_harness_runs_ompl_like_our_planners():
    ompl_rrt = next(p for p in catalog.ompl_planners() if p.id == "ompl-rrt")
    row = run_one(RunSpec(ompl_rrt, Vehicle.SPACESHIP, PROBLEMS / "course" / "space-0.sw", 2, 20))
    assert row.solved and row.valid and row.implementation == "ompl"
    assert row.tree_nodes > 1 and row.iterations >= 1 and row.planning_seconds > 0


def test_adapter_rejects_a_planner_for_the_wrong_vehicle():
    problem = parse_problem((PROBLEMS / "course" / "simple-0.sw").read_text())
    with pytest.raises(ValueError):
        ompl_adapters.solve(problem, Vehicle.POINT, "kpiece1", 1.0, 1)
