"""The planner as users run it: flags, exit statuses, reproducibility, limits."""

import subprocess
import time

import pytest

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from tests.conftest import COURSE_DIR, ROOT, plan_in_process, run_planner
from validator.checks import validate_output

SPACE0 = (COURSE_DIR / "space-0.sw")
# The goal cell (3, 3) is walled off by blocked cells on every side, corners included.
WALLED = "5 4\n__#_#\n__###\n_____\n_____\n0.5 0.5\n3.5 3.5\n"


@pytest.mark.parametrize("flags,vehicle", [
    ([], Vehicle.POINT), (["-ugrad"], Vehicle.POINT), (["-grad"], Vehicle.SPACESHIP),
    (["-left"], Vehicle.LEFT_SPACESHIP), (["-grad", "-left"], Vehicle.LEFT_SPACESHIP),
])
def test_course_spellings_select_the_vehicle_and_output_validates(flags, vehicle):
    text = SPACE0.read_text()
    done = run_planner(flags + ["-seed", "3"], text)
    assert done.returncode == 0, done.stderr
    assert done.stderr == b""
    report = validate_output(parse_problem(text), vehicle, done.stdout.decode())
    assert report.valid, report.first_failure


def test_same_seed_same_bytes_and_different_seeds_differ():
    text = SPACE0.read_text()
    first = run_planner(["-grad", "-seed", "7"], text)
    second = run_planner(["-grad", "-seed", "7"], text)
    other = run_planner(["-grad", "-seed", "8"], text)
    assert first.returncode == second.returncode == other.returncode == 0
    assert first.stdout == second.stdout
    assert first.stdout != other.stdout


def test_without_seed_runs_differ():
    text = SPACE0.read_text()
    outputs = {run_planner(["-grad"], text).stdout for _ in range(3)}
    assert len(outputs) > 1


def test_run_sh_passes_arguments_and_prints_only_the_answer():
    text = SPACE0.read_text()
    done = subprocess.run([str(ROOT / "run.sh"), "-grad", "-seed", "7"], input=text.encode(),
                          capture_output=True, timeout=300)
    assert done.returncode == 0, done.stderr
    direct = run_planner(["-grad", "-seed", "7"], text)
    assert done.stdout == direct.stdout


def test_every_printed_float_is_full_precision():
    done = run_planner(["-grad", "-seed", "1"], SPACE0.read_text())
    numbers = [float(tok) for line in done.stdout.decode().splitlines()[1:] for tok in line.split()]
    # repr() round-trips: re-printing gives the same text.
    tokens = done.stdout.decode().split()
    assert all(repr(float(tok)) == tok for tok in tokens if "." in tok or "e" in tok)
    assert len(numbers) > 10


def test_walled_off_goal_point_vehicle_ends_at_once_with_exit_3():
    started = time.monotonic()
    done = run_planner(["-seed", "1"], WALLED)
    assert done.returncode == 3 and done.stdout == b""
    assert b"goal unreachable" in done.stderr and done.stderr.count(b"\n") == 1
    assert time.monotonic() - started < 10


@pytest.mark.parametrize("limit_flags,words", [
    (["-time", "0.3"], b"time limit reached"),
    (["-iterations", "300"], b"iteration limit reached"),
])
def test_walled_off_goal_spaceship_ends_by_its_limit_with_exit_3(limit_flags, words):
    started = time.monotonic()
    done = run_planner(["-grad", "-seed", "1", *limit_flags], WALLED, timeout=60)
    assert done.returncode == 3 and done.stdout == b""
    assert words in done.stderr and done.stderr.count(b"\n") == 1
    assert time.monotonic() - started < 20


@pytest.mark.parametrize("args", [["-bogus"], ["-seed"], ["-seed", "x"], ["-time", "-1"],
                                  ["-time", "nan"], ["-iterations", "0"], ["-ugrad", "-grad"],
                                  ["-planner", "nope"], ["extra"]])
def test_bad_usage_gives_usage_and_exit_2(args):
    done = run_planner(args, SPACE0.read_text(), timeout=30)
    assert done.returncode == 2 and done.stdout == b""
    err = done.stderr.decode()
    assert err.startswith("usage:") and "Traceback" not in err


def test_help_lists_every_flag():
    done = run_planner(["-h"], "", timeout=30)
    assert done.returncode == 0
    for flag in ("-grad", "-left", "-ugrad", "-seed", "-time", "-iterations", "-planner", "-stats",
                 "-optimize", "-cost"):
        assert flag.encode() in done.stdout


def test_stats_line_is_key_value_on_stderr_then_the_kernels_that_ran():
    done = run_planner(["-seed", "2", "-stats"], SPACE0.read_text(), interpreted=True)
    assert done.returncode == 0
    build, line, kernels = done.stderr.decode().splitlines()
    assert build == "rrt_cli build: interpreted: RRT_INTERPRETED is set"
    assert line.startswith("rrt_cli stats: ")
    fields = dict(item.split("=", 1) for item in line.split(": ", 1)[1].split())
    assert list(fields) == ["status", "planner", "vehicle", "seed", "iterations", "tree_nodes",
                            "planning_seconds", "cost", "first_solution_seconds"]
    assert fields["status"] == "solved" and fields["seed"] == "2"
    assert float(fields["cost"]) > 0
    assert fields["first_solution_seconds"] == fields["planning_seconds"]
    assert int(fields["tree_nodes"]) >= 2 and float(fields["planning_seconds"]) >= 0
    assert kernels == "rrt_cli kernels: segment test=GridWorld's own, interpreted"


def test_start_within_goal_tolerance_is_a_one_line_trajectory():
    text = "3 3\n___\n___\n___\n1.5 1.5\n1.55 1.5\n"
    for flags, vehicle in (([], Vehicle.POINT), (["-grad"], Vehicle.SPACESHIP)):
        done = run_planner(flags + ["-seed", "1"], text)
        assert done.returncode == 0
        assert done.stdout.decode().splitlines()[0] == "1"
        assert validate_output(parse_problem(text), vehicle, done.stdout.decode()).valid


BORDER_GOAL = "3\n3\n___\n___\n___\n1.5\n1.5\n0\n1.5\n"  # the goal on the map's left edge


@pytest.mark.parametrize("planner", ["rrt", "rrtconnect", "prm", "prmstar"])
def test_a_goal_on_the_maps_edge_gets_a_valid_answer(monkeypatch, planner):
    """The reader accepts a goal at x = 0; every point planner must stop short of
    the edge, since printed points lie strictly inside the map."""
    for seed in range(1, 6):
        status, out, err = plan_in_process(monkeypatch, ["-planner", planner, "-seed", str(seed)],
                                           BORDER_GOAL)
        assert status == 0, err
        report = validate_output(parse_problem(BORDER_GOAL), Vehicle.POINT, out, strict=True)
        assert report.valid, (seed, report.first_failure)
