"""The corpus of hand-made planner outputs: every check fails where it should, for
both vehicles, and the valid outputs pass (in-process and through the command)."""

from __future__ import annotations

import pytest

from validator.checks import INVALID_VERDICT, VALID_VERDICT, validate_output
from validator.cli import decode_output
from validator_testlib import load_cases, load_problem, run_validator

CASES = load_cases()


def _report(case):
    text = decode_output(case.output_path.read_bytes())
    return validate_output(load_problem(case.problem), case.vehicle, text,
                           strict="-strict" in case.flags)


def test_corpus_covers_every_check_for_each_vehicle():
    for vehicles, checks in ((("point",), range(1, 7)), (("spaceship",), range(1, 8))):
        failing = {c.check for c in CASES if not c.valid and c.output.split("/")[0] in vehicles}
        assert set(checks) <= failing, f"{vehicles}: no failing case for {set(checks) - failing}"
        assert any(c.valid for c in CASES if c.output.split("/")[0] in vehicles)


def test_corpus_has_the_required_special_cases():
    # The same output, valid with a warning, invalid with -strict.
    corner = [c for c in CASES if c.problem == "corner.sw"]
    assert {(c.valid, "-strict" in c.flags) for c in corner} == {(True, False), (False, True)}
    assert len({c.output_path.read_bytes() for c in corner}) == 1
    # The same spaceship output, valid with -grad, invalid with -grad -left.
    right = [c for c in CASES if c.problem == "open-right.sw"]
    assert {(c.valid, "-left" in c.flags) for c in right} == {(True, False), (False, True)}
    assert len({c.output_path.read_bytes() for c in right}) == 1
    assert len({c.id for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_case_in_process(case):
    report = _report(case)
    assert report.valid is case.valid, report.first_failure
    if case.valid:
        assert report.first_failure is None
        assert report.verdict == VALID_VERDICT
        assert report.path_length is not None and report.path_length >= 0
    else:
        failure = report.first_failure
        assert failure.number == case.check
        assert failure.message.startswith(case.message)
        assert failure.line == case.line
        assert f"line {case.line}" in failure.detail or failure.number == 7
        assert report.verdict == INVALID_VERDICT
        # Checks run in order and stop at the first failure.
        assert [c.number for c in report.checks] == list(range(1, case.check + 1))
        assert all(c.passed for c in report.checks[:-1])
    if case.warning:
        assert any(case.warning in w for w in report.warnings), report.warnings
    elif case.valid:
        assert report.warnings == []


def _through_the_command() -> list:
    """Every case; in the unit run, the first valid and the first invalid one of each
    vehicle, warning and flags, the first of check 7 (its detail names no line), and the
    binary outputs: each case's verdict is test_case_in_process's business."""
    seen, params = set(), []
    for case in CASES:
        key = (case.output.split("/")[0], case.valid, case.check == 7, bool(case.warning),
               case.flags)
        quick = key not in seen or "binary" in case.id
        seen.add(key)
        params.append(pytest.param(case, id=case.id, marks=() if quick else pytest.mark.slow))
    return params


@pytest.mark.parametrize("case", _through_the_command())
def test_case_through_the_command(case, tmp_path):
    done = run_validator([*case.flags, "-noviz", "--", "cat", str(case.output_path)],
                         case.problem_path.read_text(), tmp_path)
    out = done.stdout.decode()
    lines = out.splitlines()
    assert done.returncode == (0 if case.valid else 1), (out, done.stderr)
    assert lines[-1] == (VALID_VERDICT if case.valid else INVALID_VERDICT)
    assert sum(line in (VALID_VERDICT, INVALID_VERDICT) for line in lines) == 1
    if not case.valid:
        message_at = next(k for k, line in enumerate(lines) if line.startswith(case.message))
        # The message, then the detail naming the line at fault, then the verdict.
        assert f"line {case.line}" in lines[message_at + 1] or case.check == 7
        assert message_at + 2 == len(lines) - 1
    if case.warning:
        assert any(line.startswith("Warning: ") and case.warning in line for line in lines)
    assert not (tmp_path / "tree-viz.pdf").exists()
    assert b"Traceback" not in done.stderr
