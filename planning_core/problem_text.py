"""Read and write the `.sw` grid problem format (SPEC section 1).

Lenient where the course files vary (whitespace, CRLF, trailing blanks, the
vacuum-world cells ``*`` and ``@``), strict everywhere else: every rejection is a
:class:`ProblemFormatError` that names the line and column. Numbers are plain
ASCII decimals.

Two readers give the same answer. The reference walks the text by position with
regular expressions that cannot backtrack badly, so time is linear and memory is the
text itself, whatever the text (a hostile file is at most the CLIs' stdin cap); it
reads every layout and places every error. The plain reader takes the layout
:func:`format_problem` writes (and the course files use) with ``str`` methods alone,
so a run on such a file never imports ``re`` (start-up); anything else it leaves to
the reference.
"""

from __future__ import annotations

import math

from planning_core.problem import Problem

FREE_CELLS = frozenset("_*@")
BLOCKED_CELL = "#"
_CELLS = "_*@#"
_INTEGER = r"[+-]?[0-9]+"
# No nested quantifiers that can trade digits: a long digit run fails in linear time.
_NUMBER = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_NUMBER_CHARS = "0123456789+-.eE"  # over these, float() takes what _NUMBER matches
_NON_FINITE = r"(?i)[+-]?(?:nan|inf|infinity)"
_TOKEN = r"\S+"
_BLANK_LINES = r"(?:[^\S\n]*\n)*"
_BLANK_REST = r"[^\S\n]*"
_NOT_A_CELL = r"[^_*@#]"
_BLOCKED_BYTES = bytes(1 if chr(b) == BLOCKED_CELL else 0 for b in range(256))
# Generous, but keeps a hostile header from asking for gigabytes.
MAX_CELLS = 50_000_000
_MAX_SIZE_DIGITS = 18   # a longer size is certainly over MAX_CELLS: no int() of it
_ROW_BLOCK_CHARS = 1 << 16  # about this much of the grid is matched at a time


class ProblemFormatError(ValueError):
    """A problem text that cannot be read; ``line``/``column`` are 1-based."""

    def __init__(self, line: int, column: int, message: str):
        super().__init__(f"line {line}, column {column}: {message}")
        self.line = line
        self.column = column
        self.message = message


def _pattern(source: str):
    """``source`` compiled (``re`` caches it): the reference reader's only way to ``re``,
    imported when it first runs."""
    import re
    return re.compile(source)


def _show(text: str) -> str:
    """A token as messages quote it: repr, cut to 40 characters."""
    return repr(text if len(text) <= 40 else text[:37] + "...")


def _line_end(text: str, pos: int) -> int:
    end = text.find("\n", pos)
    return len(text) if end < 0 else end


class _Cursor:
    """Walks the text by position (lines end at ``\\n``; a line's final ``\\r`` is a blank),
    keeping the 1-based line number of ``pos``."""

    def __init__(self, text: str):
        self.text = text
        self.pos = 0
        self.line = 1

    def column_of(self, pos: int) -> int:
        return pos - (self.text.rfind("\n", 0, pos) + 1) + 1

    def move_to(self, pos: int) -> None:
        self.line += self.text.count("\n", self.pos, pos)
        self.pos = pos

    def next_token(self) -> tuple[str, int, int] | None:
        match = _pattern(_TOKEN).search(self.text, self.pos)
        if match is None:
            return None
        self.move_to(match.start())
        self.pos = match.end()
        return match.group(), self.line, self.column_of(match.start())

    def end_position(self) -> tuple[int, int]:
        """Just past the last non-blank line (line 1 if every line is blank)."""
        text, end = self.text, len(self.text)
        while end > 0:  # the last non-space character, a chunk at a time
            start = max(0, end - 65536)
            kept = text[start:end].rstrip()
            if kept:
                end = start + len(kept)
                break
            end = start
        line_start = text.rfind("\n", 0, max(end - 1, 0)) + 1 if end else 0
        line_text = text[line_start:_line_end(text, line_start)].rstrip("\r")
        return text.count("\n", 0, line_start) + 1, len(line_text) + 1

    def skip_to_next_line(self) -> None:
        """Rows start on a fresh line after the size tokens."""
        end = _line_end(self.text, self.pos)
        rest = self.text[self.pos:end]
        if rest.strip():
            raise ProblemFormatError(self.line, self.column_of(self.pos),
                                     f"unexpected text {_show(rest.strip())} after the map size")
        self.move_to(min(end + 1, len(self.text)))

    def next_row(self) -> tuple[str, int] | None:
        """The next non-blank line (without its ``\\r`` and trailing blanks) and its
        line number, moving past it; None when only blank lines are left."""
        text = self.text
        self.move_to(_pattern(_BLANK_LINES).match(text, self.pos).end())
        if _pattern(_BLANK_REST).match(text, self.pos).end() == len(text):
            return None
        end, line = _line_end(text, self.pos), self.line
        row = text[self.pos:end].rstrip("\r").rstrip(" \t")
        self.move_to(min(end + 1, len(text)))
        return row, line


def _read_size(cursor: _Cursor, what: str) -> int:
    token = cursor.next_token()
    if token is None:
        raise ProblemFormatError(*cursor.end_position(), f"missing map {what}")
    text, line, column = token
    if not _pattern(_INTEGER).fullmatch(text):
        raise ProblemFormatError(line, column, f"map {what} {_show(text)} is not an integer")
    digits = text.lstrip("+-").lstrip("0")
    if len(digits) > _MAX_SIZE_DIGITS:
        raise ProblemFormatError(line, column, f"map {what} {_show(text)} is too large "
                                               f"(a map has at most {MAX_CELLS} cells)")
    value = -int(digits or "0") if text.startswith("-") else int(digits or "0")
    if value <= 0:
        raise ProblemFormatError(line, column, f"map {what} must be positive, got {value}")
    return value


def _is_non_finite(text: str) -> bool:
    return _pattern(_NON_FINITE).fullmatch(text) is not None


def _read_coordinate(cursor: _Cursor, what: str) -> tuple[float, int, int]:
    token = cursor.next_token()
    if token is None:
        raise ProblemFormatError(*cursor.end_position(), f"missing {what}")
    text, line, column = token
    if not _pattern(_NUMBER).fullmatch(text):
        if _is_non_finite(text):
            raise ProblemFormatError(line, column, f"{what} {_show(text)} is not a finite number")
        raise ProblemFormatError(line, column, f"{what} {_show(text)} is not a number")
    value = float(text)
    if not math.isfinite(value):
        raise ProblemFormatError(line, column, f"{what} {_show(text)} is not a finite number")
    return value, line, column


def _checked_row(cursor: _Cursor, width: int, height: int, rows_read: int) -> str:
    """The next row, read line by line: the slow path, which explains a bad row."""
    found = cursor.next_row()
    if found is None:
        raise ProblemFormatError(cursor.text.count("\n") + 1, 1, f"too few rows: expected "
                                 f"{height}, found {rows_read}")
    row_text, line = found
    stripped = row_text.strip()
    if _pattern(_NUMBER).fullmatch(stripped) or _is_non_finite(stripped):
        raise ProblemFormatError(line, 1, f"too few rows: expected {height}, found {rows_read}")
    if len(row_text) != width:
        raise ProblemFormatError(line, min(len(row_text), width) + 1, f"row {rows_read + 1} "
                                 f"has {len(row_text)} cells, expected {width}")
    bad = _pattern(_NOT_A_CELL).search(row_text)
    if bad is not None:
        raise ProblemFormatError(line, bad.start() + 1, f"unknown cell character "
                                 f"{bad.group()!r} (expected '_', '#', '*' or '@')")
    return row_text


def _place_rows(blocked: bytearray, cells: bytes, width: int, top: int) -> None:
    """Text rows (top first) into ``blocked`` (bottom row first), the first at row top-1."""
    rows = len(cells) // width
    if width == 1:
        blocked[top - rows:top] = cells[::-1]
        return
    for i in range(rows):
        row = top - 1 - i
        blocked[row * width:(row + 1) * width] = cells[i * width:(i + 1) * width]


def _read_rows(cursor: _Cursor, width: int, height: int) -> bytearray:
    """The grid, row-major from the bottom row (the first text row is the top).

    Blocks of well-formed rows (blank lines between them tolerated) are taken by one
    regular expression each; a row it does not take goes through :func:`_checked_row`.
    """
    blocked = bytearray(width * height)
    per_block = max(1, _ROW_BLOCK_CHARS // (width + 1))
    rows_read = 0
    while rows_read < height:
        count = min(per_block, height - rows_read)
        block = _pattern(rf"(?:(?:[^\S\n]*\n)*[_*@#]{{{width}}}[ \t]*\r*(?:\n|\Z))"
                         rf"{{1,{count}}}").match(cursor.text, cursor.pos)
        if block is None:
            cells = _checked_row(cursor, width, height, rows_read)
        else:
            cells = _pattern(_NOT_A_CELL).sub("", block.group())
            cursor.move_to(block.end())
        _place_rows(blocked, cells.encode("ascii").translate(_BLOCKED_BYTES), width,
                    height - rows_read)
        rows_read += len(cells) // width
    return blocked


def _point_error(problem: Problem, name: str) -> str | None:
    """What is wrong with the start or the goal, or None: free (SPEC 1); the start also
    off the border, as the answer's first line must lie strictly inside the map (SPEC 2)
    and is the start itself."""
    width, height = problem.width, problem.height
    x, y = problem.start if name == "start" else problem.goal
    if not (0.0 <= x < width and 0.0 <= y < height):
        return f"{name} ({x!r}, {y!r}) is outside the map [0, {width}) x [0, {height})"
    if problem.point_in_collision(x, y):
        return f"{name} ({x!r}, {y!r}) is in blocked cell ({int(x)}, {int(y)})"
    if name == "start" and (x == 0.0 or y == 0.0):
        return (f"start ({x!r}, {y!r}) is on the map's border: it must lie strictly inside "
                f"(0, {width}) x (0, {height}), as every printed point must")
    return None


def _check_points(problem: Problem, where: dict[str, tuple[int, int]]) -> None:
    for name in ("start", "goal"):
        message = _point_error(problem, name)
        if message is not None:
            raise ProblemFormatError(*where[name], message)


def _plain_sizes(text: str) -> tuple[int, int, str] | None:
    """Width and height as plain digits on the first line or the first two, and the text
    after them; None otherwise. At most 3 tokens are split off a line, however long."""
    first, _, rest = text.partition("\n")
    sizes = first.split(None, 2)
    if len(sizes) == 1:
        second, _, rest = rest.partition("\n")
        sizes += second.split(None, 1)
    if len(sizes) != 2 or not all(size.isascii() and size.isdigit() and len(size) < 10
                                  for size in sizes):
        return None
    width, height = int(sizes[0]), int(sizes[1])
    if width == 0 or height == 0 or width * height > MAX_CELLS:
        return None
    return width, height, rest


def _plain_coordinates(text: str) -> list[float] | None:
    """Exactly four finite plain decimals, blanks between and around them; None otherwise."""
    tokens = text.split(None, 4)
    if len(tokens) != 4 or any(token.strip(_NUMBER_CHARS) for token in tokens):
        return None
    try:
        values = [float(token) for token in tokens]
    except ValueError:
        return None
    return values if all(math.isfinite(value) for value in values) else None


def _read_plain(text: str) -> Problem | None:
    """The problem when ``text`` has the plain layout (sizes, then each row exactly the
    width of cells and a ``\\n``, then the four coordinates) and start and goal are
    fine; None for any other text, which :func:`_read_located` reads or explains."""
    found = _plain_sizes(text)
    if found is None:
        return None
    width, height, rest = found
    size = height * (width + 1)
    rows = rest[:size]
    if len(rows) != size or rows[width::width + 1] != "\n" * height:
        return None
    cells = rows.replace("\n", "")
    coordinates = _plain_coordinates(rest[size:])
    if len(cells) != width * height or cells.strip(_CELLS) or coordinates is None:
        return None
    blocked = bytearray(width * height)
    _place_rows(blocked, cells.encode("ascii").translate(_BLOCKED_BYTES), width, height)
    start_x, start_y, goal_x, goal_y = coordinates
    problem = Problem(width, height, bytes(blocked), (start_x, start_y), (goal_x, goal_y))
    if _point_error(problem, "start") or _point_error(problem, "goal"):
        return None
    return problem


def parse_problem(text: str) -> Problem:
    """Parse `.sw` text into a :class:`Problem`, or raise ProblemFormatError."""
    if "\x00" in text:
        index = text.index("\x00")
        line = text.count("\n", 0, index) + 1
        column = index - (text.rfind("\n", 0, index) + 1) + 1
        raise ProblemFormatError(line, column, "binary data (NUL byte) in the problem")
    problem = _read_plain(text)
    return _read_located(text) if problem is None else problem


def _read_located(text: str) -> Problem:
    """The reference reader: any layout the format admits, or the located error."""
    cursor = _Cursor(text)
    width = _read_size(cursor, "width")
    height = _read_size(cursor, "height")
    if width * height > MAX_CELLS:
        raise ProblemFormatError(1, 1, f"map of {width} x {height} cells is larger than "
                                       f"{MAX_CELLS} cells")
    cursor.skip_to_next_line()
    blocked = _read_rows(cursor, width, height)

    start_x, sx_line, sx_col = _read_coordinate(cursor, "start x")
    start_y, _, _ = _read_coordinate(cursor, "start y")
    goal_x, gx_line, gx_col = _read_coordinate(cursor, "goal x")
    goal_y, _, _ = _read_coordinate(cursor, "goal y")
    extra = cursor.next_token()
    if extra is not None:
        extra_text, line, column = extra
        raise ProblemFormatError(line, column, f"unexpected text {_show(extra_text)} "
                                               "after the goal")

    problem = Problem(width, height, bytes(blocked), (start_x, start_y), (goal_x, goal_y))
    _check_points(problem, {"start": (sx_line, sx_col), "goal": (gx_line, gx_col)})
    return problem


def format_problem(problem: Problem) -> str:
    """The canonical layout: W, H, rows top first, then start x, y, goal x, y."""
    parts = [str(problem.width), str(problem.height), *problem.text_rows(),
             repr(problem.start[0]), repr(problem.start[1]),
             repr(problem.goal[0]), repr(problem.goal[1])]
    return "\n".join(parts) + "\n"
