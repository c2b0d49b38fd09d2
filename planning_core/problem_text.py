"""Read and write the `.sw` grid problem format (SPEC section 1).

Lenient where the course files vary (whitespace, CRLF, trailing blanks, the
vacuum-world cells ``*`` and ``@``), strict everywhere else: every rejection is a
:class:`ProblemFormatError` that names the line and column.
"""

from __future__ import annotations

import math
import re

from planning_core.problem import Problem

FREE_CELLS = frozenset("_*@")
BLOCKED_CELL = "#"
_INTEGER = re.compile(r"[+-]?\d+\Z")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\Z")
_NON_FINITE = re.compile(r"[+-]?(nan|inf|infinity)\Z", re.IGNORECASE)
# Generous, but keeps a hostile header from asking for gigabytes.
MAX_CELLS = 50_000_000


class ProblemFormatError(ValueError):
    """A problem text that cannot be read; ``line``/``column`` are 1-based."""

    def __init__(self, line: int, column: int, message: str):
        super().__init__(f"line {line}, column {column}: {message}")
        self.line = line
        self.column = column
        self.message = message


def _lines(text: str) -> list[str]:
    # splitlines() also splits on \x0b, \x1c ... ; only \n and \r\n are line ends here.
    return [line.rstrip("\r") for line in text.split("\n")]


class _Cursor:
    """Walks tokens across lines, remembering where each one came from."""

    def __init__(self, lines: list[str]):
        self.lines = lines
        self.line_index = 0
        self.column = 0

    def next_token(self) -> tuple[str, int, int] | None:
        while self.line_index < len(self.lines):
            line = self.lines[self.line_index]
            while self.column < len(line) and line[self.column].isspace():
                self.column += 1
            if self.column < len(line):
                start = self.column
                while self.column < len(line) and not line[self.column].isspace():
                    self.column += 1
                return line[start:self.column], self.line_index + 1, start + 1
            self.line_index += 1
            self.column = 0
        return None

    def end_position(self) -> tuple[int, int]:
        last = len(self.lines)
        while last > 1 and not self.lines[last - 1].strip():
            last -= 1
        return last, len(self.lines[last - 1]) + 1 if self.lines else 1

    def skip_to_next_line(self) -> None:
        """Rows start on a fresh line after the size tokens."""
        if self.column:
            rest = self.lines[self.line_index][self.column:]
            if rest.strip():
                raise ProblemFormatError(self.line_index + 1, self.column + 1,
                                         f"unexpected text {rest.strip()!r} after the map size")
            self.line_index += 1
            self.column = 0


def _read_size(cursor: _Cursor, what: str) -> int:
    token = cursor.next_token()
    if token is None:
        line, column = cursor.end_position()
        raise ProblemFormatError(line, column, f"missing map {what}")
    text, line, column = token
    if not _INTEGER.match(text):
        raise ProblemFormatError(line, column, f"map {what} {text!r} is not an integer")
    value = int(text)
    if value <= 0:
        raise ProblemFormatError(line, column, f"map {what} must be positive, got {value}")
    return value


def _read_coordinate(cursor: _Cursor, what: str) -> tuple[float, int, int]:
    token = cursor.next_token()
    if token is None:
        line, column = cursor.end_position()
        raise ProblemFormatError(line, column, f"missing {what}")
    text, line, column = token
    if _NON_FINITE.match(text):
        raise ProblemFormatError(line, column, f"{what} {text!r} is not a finite number")
    if not _NUMBER.match(text):
        raise ProblemFormatError(line, column, f"{what} {text!r} is not a number")
    value = float(text)
    if not math.isfinite(value):
        raise ProblemFormatError(line, column, f"{what} {text!r} is not a finite number")
    return value, line, column


def parse_problem(text: str) -> Problem:
    """Parse `.sw` text into a :class:`Problem`, or raise ProblemFormatError."""
    if "\x00" in text:
        index = text.index("\x00")
        line = text.count("\n", 0, index) + 1
        column = index - (text.rfind("\n", 0, index) + 1) + 1
        raise ProblemFormatError(line, column, "binary data (NUL byte) in the problem")
    lines = _lines(text)
    cursor = _Cursor(lines)
    width = _read_size(cursor, "width")
    height = _read_size(cursor, "height")
    if width * height > MAX_CELLS:
        raise ProblemFormatError(1, 1, f"map of {width} x {height} cells is larger than "
                                       f"{MAX_CELLS} cells")
    cursor.skip_to_next_line()

    blocked = bytearray(width * height)
    rows_read = 0
    index = cursor.line_index
    while rows_read < height:
        # Blank lines between the header and the rows, or between rows, are tolerated.
        while index < len(lines) and not lines[index].strip():
            index += 1
        if index >= len(lines):
            raise ProblemFormatError(len(lines), 1, f"too few rows: expected {height}, "
                                                    f"found {rows_read}")
        row_text = lines[index].rstrip(" \t")
        line_number = index + 1
        if _NUMBER.match(row_text.strip()) or _NON_FINITE.match(row_text.strip()):
            raise ProblemFormatError(line_number, 1, f"too few rows: expected {height}, "
                                                     f"found {rows_read}")
        if len(row_text) != width:
            column = min(len(row_text), width) + 1
            raise ProblemFormatError(line_number, column, f"row {rows_read + 1} has "
                                     f"{len(row_text)} cells, expected {width}")
        row = height - 1 - rows_read  # the first text row is the top of the world
        base = row * width
        for column, char in enumerate(row_text):
            if char == BLOCKED_CELL:
                blocked[base + column] = 1
            elif char not in FREE_CELLS:
                raise ProblemFormatError(line_number, column + 1,
                                         f"unknown cell character {char!r} "
                                         "(expected '_', '#', '*' or '@')")
        rows_read += 1
        index += 1

    cursor.line_index, cursor.column = index, 0
    start_x, sx_line, sx_col = _read_coordinate(cursor, "start x")
    start_y, _, _ = _read_coordinate(cursor, "start y")
    goal_x, gx_line, gx_col = _read_coordinate(cursor, "goal x")
    goal_y, _, _ = _read_coordinate(cursor, "goal y")
    extra = cursor.next_token()
    if extra is not None:
        text_, line, column = extra
        raise ProblemFormatError(line, column, f"unexpected text {text_!r} after the goal")

    problem = Problem(width, height, bytes(blocked), (start_x, start_y), (goal_x, goal_y))
    for (x, y), name, line, column in (((start_x, start_y), "start", sx_line, sx_col),
                                       ((goal_x, goal_y), "goal", gx_line, gx_col)):
        if not (0.0 <= x < width and 0.0 <= y < height):
            raise ProblemFormatError(line, column, f"{name} ({x!r}, {y!r}) is outside the "
                                     f"map [0, {width}) x [0, {height})")
        if problem.point_in_collision(x, y):
            raise ProblemFormatError(line, column, f"{name} ({x!r}, {y!r}) is in blocked "
                                     f"cell ({int(x)}, {int(y)})")
    return problem


def format_problem(problem: Problem) -> str:
    """The canonical layout: W, H, rows top first, then start x, y, goal x, y."""
    parts = [str(problem.width), str(problem.height), *problem.text_rows(),
             repr(problem.start[0]), repr(problem.start[1]),
             repr(problem.goal[0]), repr(problem.goal[1])]
    return "\n".join(parts) + "\n"
