"""The `.sw` reader: lenient forms load, every bad form is one located error."""

import math

import pytest
from hypothesis import strategies as st

from planning_core.problem_text import ProblemFormatError, format_problem, parse_problem
from tests.conftest import COURSE_PROBLEMS, property_pair, run_planner

SPACE0 = "4\n3\n____\n__#_\n___#\n0.1\n1.54\n3.8\n1.1\n"


def test_reads_the_spec_example_with_bottom_row_first():
    problem = parse_problem(SPACE0)
    assert (problem.width, problem.height) == (4, 3)
    assert problem.start == (0.1, 1.54) and problem.goal == (3.8, 1.1)
    # Text row 3 (bottom, y in [0,1)) is "___#": cell (3, 0) blocked.
    assert problem.is_blocked_cell(3, 0)
    assert problem.is_blocked_cell(2, 1)
    assert not problem.is_blocked_cell(2, 2)
    assert problem.point_in_collision(3.5, 0.5)
    assert not problem.point_in_collision(3.5, 1.5)
    assert problem.point_in_collision(4.0, 1.0)   # x = W is outside
    assert problem.point_in_collision(-1e-9, 1.0)


@pytest.mark.parametrize("text", [
    "4 3\n____\n__#_\n___#\n0.1 1.54\n3.8 1.1\n",                       # pairs on a line
    "4 3\r\n____\r\n__#_\r\n___#\r\n0.1 1.54\r\n3.8 1.1\r\n",            # CRLF
    "4  3  \n____  \n__#_\t\n___#\n0.100000 1.540000 \n 3.800000\t1.100000\n\n\n",  # blanks, %f
    "4\n3\n_*__\n__#_\n@__#\n0.1\n1.54\n3.8\n1.1",                     # vacuum cells, no final newline
])
def test_lenient_forms_load_the_same_problem(text):
    reference = parse_problem(SPACE0)
    problem = parse_problem(text)
    assert problem == reference


@pytest.mark.parametrize("path", COURSE_PROBLEMS, ids=lambda p: p.name)
def test_course_problems_round_trip_through_the_canonical_layout(path):
    problem = parse_problem(path.read_text())
    assert parse_problem(format_problem(problem)) == problem


# (case, text, expected line, expected column, words the message must contain)
BAD_PROBLEMS = [
    ("missing size", "", 1, 1, "missing map width"),
    ("missing height", "4\n", 1, 2, "missing map height"),
    ("non-integer size", "4.5\n3\n", 1, 1, "not an integer"),
    ("non-integer height", "4\nthree\n", 2, 1, "not an integer"),
    ("zero size", "0\n3\n", 1, 1, "must be positive"),
    ("row too short", "4\n3\n____\n__#\n___#\n0.1\n1.54\n3.8\n1.1\n", 4, 4, "has 3 cells, expected 4"),
    ("row too long", "4\n3\n____\n__#__\n___#\n0.1\n1.54\n3.8\n1.1\n", 4, 5, "has 5 cells"),
    ("too few rows", "4\n3\n____\n__#_\n0.1\n1.54\n3.8\n1.1\n", 5, 1, "too few rows"),
    ("too few rows at end", "4\n3\n____\n__#_\n", 5, 1, "too few rows"),
    ("unknown cell", "4\n3\n____\n__%_\n___#\n0.1\n1.54\n3.8\n1.1\n", 4, 3, "unknown cell character '%'"),
    ("missing goal", "4\n3\n____\n__#_\n___#\n0.1\n1.54\n", 7, 5, "missing goal x"),
    ("missing start y", "4\n3\n____\n__#_\n___#\n0.1\n", 6, 4, "missing start y"),
    ("non-number coordinate", "4\n3\n____\n__#_\n___#\n0.1\nabc\n3.8\n1.1\n", 7, 1, "not a number"),
    ("nan coordinate", "4\n3\n____\n__#_\n___#\n0.1\nnan\n3.8\n1.1\n", 7, 1, "not a finite number"),
    ("inf coordinate", "4\n3\n____\n__#_\n___#\n0.1\n1.5\n-inf\n1.1\n", 8, 1, "not a finite number"),
    ("overflowing coordinate", "4\n3\n____\n__#_\n___#\n0.1\n1.5\n1e999\n1.1\n", 8, 1, "not a finite number"),
    ("start blocked", "4\n3\n____\n__#_\n___#\n2.5\n1.5\n3.8\n1.1\n", 6, 1, "start (2.5, 1.5) is in blocked cell (2, 1)"),
    ("start outside", "4\n3\n____\n__#_\n___#\n4.0\n1.5\n3.8\n1.1\n", 6, 1, "start (4.0, 1.5) is outside the map"),
    ("start negative", "4 3\n____\n__#_\n___#\n0.5 -0.1\n3.8 1.1\n", 5, 1, "start (0.5, -0.1) is outside"),
    ("goal blocked", "4\n3\n____\n__#_\n___#\n0.1\n1.54\n3.5\n0.5\n", 8, 1, "goal (3.5, 0.5) is in blocked cell (3, 0)"),
    ("goal outside", "4 3\n____\n__#_\n___#\n0.1 1.54\n3.8 3.0\n", 6, 1, "goal (3.8, 3.0) is outside the map"),
    ("trailing junk", "4 3\n____\n__#_\n___#\n0.1 1.54\n3.8 1.1 7\n", 6, 9, "unexpected text '7'"),
    ("binary", "4 3\n__\x00_\n", 2, 3, "binary data"),
]


@pytest.mark.parametrize("case,text,line,column,words", BAD_PROBLEMS, ids=[c[0] for c in BAD_PROBLEMS])
def test_bad_problem_names_line_and_column(case, text, line, column, words):
    with pytest.raises(ProblemFormatError) as caught:
        parse_problem(text)
    error = caught.value
    assert (error.line, error.column) == (line, column), str(error)
    assert words in error.message


# Through the command in the unit run: one of each kind (every case's line and column
# is test_bad_problem_names_line_and_column's business); CI runs them all.
CLI_QUICK = ("missing size", "row too short", "nan coordinate", "start blocked", "binary")


@pytest.mark.parametrize("case,text,line,column,words", [
    pytest.param(*bad, id=bad[0], marks=() if bad[0] in CLI_QUICK else pytest.mark.slow)
    for bad in BAD_PROBLEMS])
def test_cli_rejects_bad_problem_with_one_line_and_exit_2(case, text, line, column, words):
    for args in ([], ["-grad"]):
        done = run_planner(args + ["-seed", "1"], text, timeout=30)
        assert done.returncode == 2
        assert done.stdout == b""
        err = done.stderr.decode()
        assert err.count("\n") == 1 and "Traceback" not in err
        assert f"line {line}, column {column}" in err and words in err


def test_undecodable_bytes_are_a_located_error_not_a_crash():
    done = run_planner([], "4 3\n__\udcff_\n".encode("utf-8", "surrogateescape").decode("latin-1"))
    assert done.returncode == 2 and b"line 2" in done.stderr and b"Traceback" not in done.stderr


def test_huge_declared_size_is_rejected_before_allocating():
    with pytest.raises(ProblemFormatError, match="larger than"):
        parse_problem("100000 100000\n")
    assert math.isfinite(parse_problem(SPACE0).start[0])


# ----- the plain reader answers as the reference -------------------------------------

def test_the_plain_reader_takes_the_canonical_layout_and_every_course_file():
    from planning_core.problem_text import _read_plain
    assert _read_plain(SPACE0) == parse_problem(SPACE0)
    # Rows of 3 and 5 cells where 4 and 4 are due: as many cells and line ends in all.
    assert _read_plain(SPACE0.replace("____\n__#_", "___\n___#_")) is None
    for path in COURSE_PROBLEMS:
        text = path.read_text()
        assert _read_plain(text) is not None, path.name
        assert _read_plain(format_problem(parse_problem(text))) is not None, path.name


_PIECES = st.sampled_from(["_", "#", "*", "@", "\n", "\r\n", " ", "\t", "\n\n", "0", "1", "4",
                           "3", ".", "5", "e", "+", "-", "x", "\u00a0", "\u0664", "nan", "1e999"])


@st.composite
def _near_plain_texts(draw):
    """The plain layout of a small map (mostly free), then a few pieces inserted,
    dropped, swapped or moved (a moved line end makes rows of the wrong widths)."""
    width, height = draw(st.integers(1, 5)), draw(st.integers(1, 4))
    rows = ["".join(draw(st.lists(st.sampled_from("____*@#"), min_size=width,
                                  max_size=width))) for _ in range(height)]
    rows[-1] = "_" + rows[-1][1:]  # start and goal in the free cell (0, 0)
    numbers = [draw(st.sampled_from(["0.5", ".5", "0.25", "5e-1", "+0.75", "7.5E-01", "0.9"]))
               for _ in range(4)]
    head = draw(st.sampled_from([f"{width} {height}", f"{width}\n{height}"]))
    text = "\n".join([head, *rows, *numbers]) + "\n"
    for _ in range(draw(st.integers(0, 3))):
        at = draw(st.integers(0, len(text)))
        edit = draw(st.sampled_from(["insert", "drop", "swap", "move"]))
        piece = draw(_PIECES)
        if edit == "move" and text[at:at + 1]:
            to = draw(st.integers(0, len(text) - 1))
            piece, text = text[at], text[:at] + text[at + 1:]
            text = text[:to] + piece + text[to:]
        elif edit == "insert":
            text = text[:at] + piece + text[at:]
        elif edit == "drop":
            text = text[:at] + text[at + len(piece):]
        else:
            text = text[:at] + piece + text[at + 1:]
    return text


def check_plain_reader(text):
    """The plain reader answers as the reference or leaves the text to it."""
    from planning_core.problem_text import _read_located, _read_plain
    plain = _read_plain(text)
    try:
        reference = _read_located(text)
    except ProblemFormatError:
        assert plain is None, text
        return
    assert plain is None or plain == reference, text


test_the_plain_reader_answers_as_the_reference_or_leaves_the_text_to_it, \
    test_the_plain_reader_answers_as_the_reference_or_leaves_the_text_to_it_full = \
    property_pair(check_plain_reader, unit=130, full=400, text=_near_plain_texts())
