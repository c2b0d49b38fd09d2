"""Property-based tests: no input crashes the validator, and every answer of our
planner validates."""

from __future__ import annotations

import json
import random
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planning_core.problem import Problem
from planning_core.problem_text import format_problem
from planning_core.vehicles import Vehicle
from validator.checks import INVALID_VERDICT, VALID_VERDICT, validate_output
from validator.cli import decode_output
from validator_testlib import ROOT, load_problem, run_validator

from tests.conftest import unit_sample

SPACE0 = load_problem("space-0.sw")   # start (0.1, 1.54), goal (3.8, 1.1)
VEHICLES = list(Vehicle)

# Tokens that steer random streams into every check: counts, the start, the goal,
# numbers in and out of the map, legal and illegal thrusts, garbage.
TOKENS = ["0", "1", "2", "3", "6", "-1", "0.1", "1.54", "3.8", "1.1", "0.5", "0.25", "4",
          "1e999", "nan", "-inf", "3.14159", "1e-300", "99999999999999999999", "x", "#",
          "\x00", "é", "0x1p3", "1_000"]
SEPARATORS = [" ", " ", " ", "\n", "\n", "\t", "\r\n", "  "]


def _check_report(report):
    assert isinstance(report.valid, bool)
    assert report.verdict in (VALID_VERDICT, INVALID_VERDICT)
    if not report.valid:
        assert report.first_failure is not None and report.first_failure.message


@settings(max_examples=150, deadline=None)
@given(data=st.binary(max_size=400), vehicle=st.sampled_from(VEHICLES), strict=st.booleans())
def test_random_bytes_never_crash_the_checks(data, vehicle, strict):
    _check_report(validate_output(SPACE0, vehicle, decode_output(data), strict=strict))


token_streams = st.lists(st.tuples(st.sampled_from(TOKENS), st.sampled_from(SEPARATORS)),
                         max_size=60).map(lambda pairs: "".join(t + s for t, s in pairs))


@settings(max_examples=250, deadline=None)
@given(body=token_streams, head=st.sampled_from(["", "1\n0.1 1.54", "2\n0.1 1.54 0 0 ",
                                                 "1\n0.1 1.54 0 0 0.25 0.5\n"]),
       vehicle=st.sampled_from(VEHICLES))
def test_random_token_streams_never_crash_the_checks(body, head, vehicle):
    _check_report(validate_output(SPACE0, vehicle, head + body))


@settings(max_examples=6, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.one_of(st.binary(max_size=300), token_streams.map(str.encode)),
       flags=st.sampled_from([[], ["-grad"], ["-left", "-strict"], ["-json"]]))
def test_random_output_through_the_command_exits_0_or_1(data, flags, tmp_path):
    output = tmp_path / "out.bin"
    output.write_bytes(data)
    done = run_validator([*flags, "-noviz", "--", "cat", str(output)],
                         format_problem(SPACE0), tmp_path)
    assert done.returncode in (0, 1), done.stderr
    assert b"Traceback" not in done.stderr
    if "-json" in flags:
        assert json.loads(done.stdout)["valid"] is (done.returncode == 0)
    else:
        assert done.stdout.decode().splitlines()[-1] in (VALID_VERDICT, INVALID_VERDICT)


@st.composite
def grid_problems(draw):
    width, height = draw(st.integers(3, 9)), draw(st.integers(3, 9))
    rng = random.Random(draw(st.integers(0, 2 ** 32)))
    density = draw(st.sampled_from([0.0, 0.1, 0.25]))
    blocked = bytearray(1 if rng.random() < density else 0 for _ in range(width * height))
    free = [k for k, cell in enumerate(blocked) if not cell]
    if len(free) < 2:
        blocked[0] = blocked[-1] = 0
        free = [0, width * height - 1]
    start_cell, goal_cell = rng.sample(free, 2)

    def point_in(cell):
        row, column = divmod(cell, width)
        return (column + rng.uniform(0.05, 0.95), row + rng.uniform(0.05, 0.95))
    return Problem(width, height, bytes(blocked), point_in(start_cell), point_in(goal_cell))


VEHICLE_FLAGS = {Vehicle.POINT: [], Vehicle.SPACESHIP: ["-grad"],
                 Vehicle.LEFT_SPACESHIP: ["-grad", "-left"], Vehicle.DUBINS: ["-dubins"]}


@pytest.mark.slow  # 24 planner processes of up to 1.5 s each
@settings(max_examples=24, deadline=None)
@given(problem=grid_problems(), seed=st.integers(0, 2 ** 31),
       vehicle=st.sampled_from(VEHICLES))
def test_every_answer_of_our_planner_validates(problem, seed, vehicle):
    done = subprocess.run([sys.executable, "-m", "rrt_cli", *VEHICLE_FLAGS[vehicle],
                           "-seed", str(seed), "-time", "1.5"],
                          input=format_problem(problem).encode(), capture_output=True,
                          timeout=60, cwd=ROOT)
    assert done.returncode in (0, 3), done.stderr  # 3: no solution within the limit
    if done.returncode == 3:
        assert done.stdout == b""
        return
    # Our planner checks segments exactly, so even -strict must pass.
    report = validate_output(problem, vehicle, done.stdout.decode(), strict=True)
    assert report.valid, (report.first_failure, format_problem(problem), seed)
    assert report.warnings == []


# One vehicle in the unit run: the corpus takes every vehicle through the command there.
@pytest.mark.parametrize("name, flags", unit_sample([
    pytest.param("space-1.sw", [], id="point"), pytest.param("space-2.sw", ["-grad"], id="grad"),
    pytest.param("space-0.sw", ["-left"], id="left")]))
def test_our_planner_through_the_command_on_the_course_maps(tmp_path, name, flags):
    done = run_validator([*flags, "-strict", "-json", "--", str(ROOT / "run.sh"), *flags,
                          "-seed", "11"],
                         (ROOT / "tests/validator/corpus/problems" / name).read_text(),
                         tmp_path)
    report = json.loads(done.stdout)
    assert done.returncode == 0 and report["valid"], report
    assert report["planner"]["exit_code"] == 0
    assert (tmp_path / "tree-viz.pdf").stat().st_size > 1000
