"""The bounded-memory plan reader agrees with planning_core.plan_text where both accept
the text, and names the right line when it refuses it."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planning_core.plan_text import PlanParseError, format_plan
from tests.plan_oracle import parse_plan
from planning_core.plan_reader import read_plan

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)


@settings(max_examples=60, deadline=None)
@given(fields=st.sampled_from([(2, 4), (6, 6)]), data=st.data())
def test_agrees_with_parse_plan_on_formatted_plans(fields, data):
    n_fields, t_fields = fields
    trajectory = data.draw(st.lists(st.tuples(*[finite] * n_fields), max_size=8))
    tree = data.draw(st.lists(st.tuples(*[finite] * t_fields), max_size=8))
    text = format_plan(trajectory, tree)
    expected = parse_plan(text, n_fields, t_fields)
    got = read_plan(text, n_fields, t_fields)
    assert list(got.trajectory_rows()) == list(expected.trajectory)
    assert list(got.tree_rows()) == list(expected.tree)
    assert got.tree_count == len(expected.tree)
    assert got.trajectory_first_line == expected.trajectory_first_line
    assert got.tree_first_line == expected.tree_first_line
    # Bit for bit, signs of zeros included.
    for a, b in zip(got.trajectory, [v for row in trajectory for v in row]):
        assert math.copysign(1, a) == math.copysign(1, b) and a == b


LINE_MUTATIONS = ["", "x", "1 2 3 4 5 6 7", "nan 1", "1e999 1", "1_0 2", "0x10 1", "١ 2",
                  "1\xa02", "--1 2", "1.2.3 4"]


@settings(max_examples=80, deadline=None)
@given(n=st.integers(1, 6), m=st.integers(0, 6), victim=st.integers(0, 20),
       mutation=st.sampled_from(LINE_MUTATIONS), crlf=st.booleans())
def test_refusals_name_the_same_line_as_parse_plan(n, m, victim, mutation, crlf):
    lines = format_plan([(1.5, 2.5)] * n, [(0.5, 0.5, 1.0, 1.0)] * m).splitlines()
    victim %= len(lines)
    lines[victim] = mutation
    text = ("\r\n" if crlf else "\n").join(lines) + "\n"
    with pytest.raises(PlanParseError) as ours:
        read_plan(text, 2, 4)
    # plan_text's float() takes some tokens we refuse (1_0, Arabic digits, \xa0 as a
    # space); on the others the two readers must fail on the same line.
    lenient_only = mutation in ("1_0 2", "١ 2", "1\xa02")
    try:
        parse_plan(text, 2, 4)
    except PlanParseError as theirs:
        assert ours.value.line == theirs.line
    else:
        assert lenient_only


def test_blocks_longer_than_one_regex_match():
    rows = [(float(k % 97) + 0.25, float(k % 89) + 0.5) for k in range(10_000)]
    text = format_plan(rows, [(1.0, 2.0, 3.0, 4.0)] * 9_000)
    plan = read_plan(text, 2, 4)
    assert plan.trajectory_count == 10_000 and plan.tree_count == 9_000
    assert plan.trajectory_row(9_999) == rows[9_999]
    lines = text.splitlines()
    lines[1 + 9_000] = "1.0 inf"           # trajectory row 9000, deep in the third block
    with pytest.raises(PlanParseError) as error:
        read_plan("\n".join(lines) + "\n", 2, 4)
    assert error.value.line == 9_002
    lines[1 + 9_000] = "1.0 1e400"         # parses as a regex number, overflows to inf
    with pytest.raises(PlanParseError) as error:
        read_plan("\n".join(lines) + "\n", 2, 4)
    assert error.value.line == 9_002 and "finite" in error.value.message


def test_tree_rows_past_the_limit_are_counted_not_kept():
    text = format_plan([(1.0, 1.0)], [(1.0, 1.0, 2.0, 2.0)] * 50)
    plan = read_plan(text, 2, 4, max_tree_rows_kept=20)
    assert plan.tree_count == 50 and plan.tree_rows_kept == 20
    bad = text.rstrip("\n") + "\n"
    bad = bad.replace("1.0 1.0 2.0 2.0\n", "1.0 1.0 2.0\n", 50)  # last tree row broken
    with pytest.raises(PlanParseError) as error:
        read_plan(bad, 2, 4, max_tree_rows_kept=20)
    assert error.value.line == 4  # the first tree row


def test_with_no_tree_row_kept_every_row_is_still_judged():
    """The validator's -noviz keeps no tree row: each one is still read and checked."""
    rows = [(1.0, 1.0, 2.0, 2.0)] * 20_000
    text = format_plan([(1.0, 1.0)], rows)
    plan = read_plan(text, 2, 4, max_tree_rows_kept=0)
    assert plan.tree_count == 20_000 and plan.tree_rows_kept == 0
    lines = text.split("\n")
    for bad, message in (("1.0 1.0 2.0 1e400", "finite"), ("1.0 1.0 2.0", ""),
                         ("1.0 1.0 2.0 nan", "")):
        broken = lines.copy()
        broken[3 + 15_000] = bad  # tree row 15000, past the first blocks
        with pytest.raises(PlanParseError) as error:
            read_plan("\n".join(broken), 2, 4, max_tree_rows_kept=0)
        assert error.value.line == 3 + 15_000 + 1 and message in error.value.message


def test_trajectory_count_over_the_limit_is_refused_before_reading():
    text = format_plan([(1.0, 1.0)] * 30, [])
    with pytest.raises(PlanParseError) as error:
        read_plan(text, 2, 4, max_trajectory_rows=10)
    assert error.value.line == 1 and "limit" in error.value.message


def test_trailing_line_and_blank_lines():
    plan = read_plan("\n\n1\n1 1\n\n0\n\n  \n", 2, 4)
    assert plan.trajectory_first_line == 4 and plan.trailing_line is None
    plan = read_plan("1\n1 1\n0\n\nextra words\n", 2, 4)
    assert plan.trailing_line == 5


def test_numbers_with_hundreds_of_digits_take_the_slow_path_correctly():
    plan = read_plan("1\n1 1\n2\n" + "1" * 305 + " 1 1 1\n1e5 2 3 4\n", 2, 4)
    assert [row[0] for row in plan.tree_rows()] == [float("1" * 305), 1e5]
    with pytest.raises(PlanParseError) as error:
        read_plan("1\n1 1\n2\n1 1 1 1\n" + "9" * 400 + " 1 1 1\n", 2, 4)
    assert error.value.line == 5 and "finite" in error.value.message
