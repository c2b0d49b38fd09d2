"""Planner output pinned byte for byte: each run's stdout hashes to what
``golden.json`` recorded before the core was reshaped (issue 13), and passes the
validator's checks (with ``strict``). Replayed interpreted and, when the compiled
hot modules are built and fresh (``./make.sh``), compiled: the same hashes."""

from __future__ import annotations

import hashlib
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from golden_cases import (PROBLEM_DIR, SEEDS, argv, case_id, cases,  # noqa: E402
                          compiled_quick, unit_interpreted)

from planning_core.kinoplan_text import parse_kinoplan  # noqa: E402
from planning_core.problem_text import parse_problem  # noqa: E402
from planning_core.setups import kinoplan_setup  # noqa: E402
from tests.conftest import run_planner  # noqa: E402
from tests.test_compiled import run_planner_compiled  # noqa: E402
from validator.checks import validate_output, validate_plan  # noqa: E402

# golden_cases' vehicle names -> the validator's (the names the -grad/-left flags give).
VALIDATOR_VEHICLE = {"point": "point", "grad": "spaceship", "left": "left"}

GOLDEN = json.loads((Path(__file__).resolve().parent / "golden.json").read_text())


def _params():
    # The unit run (-m "not slow") replays a sample with the first seed: every planner
    # on every vehicle and system interpreted, on every vehicle and a system of each kind
    # compiled (golden_cases); the rest is marked slow.
    sample = {"interpreted": unit_interpreted, "compiled": compiled_quick}
    for mode in ("interpreted", "compiled"):
        for case in cases():
            quick = case[3] == SEEDS[0] and sample[mode](case)
            marks = [] if quick else [pytest.mark.slow]
            yield pytest.param(mode, case, id=f"{mode}/{case_id(*case)}", marks=marks)


def test_every_case_is_recorded():
    assert sorted(GOLDEN) == sorted(case_id(*case) for case in cases())


@pytest.mark.parametrize("mode, case", list(_params()))
def test_output_matches_golden(mode, case):
    vehicle, planner, problem, seed = case
    stdin = (PROBLEM_DIR / problem).read_text()
    if mode == "interpreted":
        done = run_planner(argv(vehicle, planner, seed), stdin, timeout=900, interpreted=True)
    else:
        done = run_planner_compiled(argv(vehicle, planner, seed), stdin, timeout=900)
    expected = GOLDEN[case_id(*case)]
    assert done.returncode == expected["exit"], done.stderr.decode()
    assert len(done.stdout) == expected["bytes"]
    assert hashlib.sha256(done.stdout).hexdigest() == expected["sha256"]
    assert _validated(vehicle, (PROBLEM_DIR / problem).read_text(), done.stdout.decode())


def _validated(vehicle: str, problem_text: str, output: str) -> bool:
    """The answer passes the validator's checks (strict)."""
    if vehicle.startswith("family"):
        report = validate_plan(kinoplan_setup(parse_kinoplan(problem_text)), output)  # the family's -strict is ten times denser than planned
    else:
        report = validate_output(parse_problem(problem_text), VALIDATOR_VEHICLE[vehicle],
                                 output, strict=True)
    assert report.valid, report.first_failure
    return True
