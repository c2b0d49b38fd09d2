"""The plan format round-trips bit for bit (through the test oracle reader; the
validator's bounded reader is compared with it in tests/validator)."""

import random

import pytest

from planning_core.plan_text import PlanParseError, format_plan
from tests.plan_oracle import parse_plan


def test_round_trip_is_bit_exact():
    rng = random.Random(5)
    trajectory = [tuple(rng.uniform(-10, 10) for _ in range(6)) for _ in range(30)]
    tree = [tuple(rng.random() / 3 for _ in range(6)) for _ in range(50)]
    parsed = parse_plan(format_plan(trajectory, tree), 6, 6)
    assert list(parsed.trajectory) == trajectory and list(parsed.tree) == tree
    assert parsed.trajectory_first_line == 2 and parsed.tree_first_line == 33
    assert parsed.trailing_line is None


@pytest.mark.parametrize("text,line,words", [
    ("", 1, "empty"),
    ("\n\n", 1, "empty"),
    ("-1\n", 1, "non-negative integer"),
    ("2\n1 2\n", 1, "only 1 lines follow"),
    ("1\n1 2 3\n0\n", 2, "expected 2 numbers"),
    ("1\n1 x\n0\n", 2, "is not a number"),
    ("1\n1 inf\n0\n", 2, "not a finite number"),
    ("1\n1 2\n", 3, "before the tree count"),
    ("1\n1 2\n1\n1 2 3\n", 4, "expected 4 numbers"),
    ("99999999999999999999\n", 1, "only 0 lines follow"),
])
def test_damaged_output_names_the_line(text, line, words):
    with pytest.raises(PlanParseError) as caught:
        parse_plan(text, 2, 4)
    assert caught.value.line == line and words in caught.value.message


def test_trailing_text_is_reported_not_fatal():
    parsed = parse_plan("1\n1 2\n0\nDEBUG done\n", 2, 4)
    assert parsed.trailing_line == 4 and parsed.trajectory == ((1.0, 2.0),)


def test_a_kinodynamic_row_ends_in_k_as_an_integer_and_reads_back():
    rows = [(-1.5, 0.25, 2.0, 8)]
    text = format_plan(rows, rows, ends_in_count=True)
    assert text.splitlines()[1] == "-1.5 0.25 2.0 8"
    assert format_plan(rows, []).splitlines()[1] == "-1.5 0.25 2.0 8.0"
    parsed = parse_plan(text, 4, 4)
    assert list(parsed.trajectory) == [(-1.5, 0.25, 2.0, 8.0)]
