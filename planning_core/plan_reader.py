"""Read a planner's output (the plan format of SPEC 2) in bounded memory and time.

The one reader of plans, used by the validator on whatever a planner prints (up
to the run_planner cap, 64 MiB): numbers are kept in ``array('d')`` (8 bytes
each, not the ~40x of tuples of floats), at most ``max_tree_rows`` tree rows are
kept (the rest are checked, counted and dropped), and blocks of lines are checked
with one regular expression each, reading line by line only to explain the first
bad line. Numbers are plain decimal ASCII (what C's ``%f``/``%g``/``%e`` and
Python's ``repr`` print), so ``1_000``, ``0x1p3`` and non-ASCII digits, which
Python's ``float`` would take, are refused. ``tests/plan_oracle.py`` is a simple
reference reader the tests compare this one with.
"""

from __future__ import annotations

import math
import re
from array import array
from itertools import islice
from collections.abc import Iterator

from planning_core.plan_text import PlanParseError

_SPACE = "[ \t\r\f\v]"
_NUMBER = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
# The same numbers, possessive (no backtracking) and with at most 300 digits before
# the point, so that a number matched here overflows a double only by its exponent.
_FAST_NUMBER = r"[+-]?+(?:[0-9]{1,300}+(?:\.[0-9]*+)?+|\.[0-9]++)(?:[eE][+-]?+[0-9]++)?+"
_NON_FINITE = r"(?i)[+-]?(?:nan|inf|infinity)"
_TOKEN = r"[^ \t\r\f\v]+"
_BLANK_LINES = re.compile(r"(?:[ \t\r\f\v]*\n)*+")
_BLANK_REST = re.compile(r"[ \t\r\f\v]*")
_COUNT_LINE = re.compile(r"[ \t\r\f\v]*([0-9]+)[ \t\r\f\v]*(?:\n|\Z)")
_BLOCK_CHARS = 1 << 18    # about this much text is checked per regular-expression match
_MAX_COUNT_DIGITS = 18    # longer counts are certainly larger than the text
_SHOWN_TOKENS = 100       # a garbage line is tokenised only this far


class PlanRowError(PlanParseError):
    """A row with the wrong number of numbers; ``found`` is how many it has
    (``None`` when it has more than can be worth counting)."""

    def __init__(self, line: int, message: str, found: int | None):
        super().__init__(line, message)
        self.found = found


class PlanArrays:
    """A parsed plan: rows stored flat, ``fields`` numbers per row. A plain class, not
    a dataclass: the validator imports it while the planner runs, where defining a
    dataclass is start-up time that shows (docs/setup-and-startup.md)."""

    def __init__(self, trajectory_fields: int, tree_fields: int, trajectory: array,
                 tree: array, tree_count: int, trajectory_first_line: int,
                 tree_first_line: int, trailing_line: int | None = None) -> None:
        self.trajectory_fields = trajectory_fields
        self.tree_fields = tree_fields
        self.trajectory = trajectory  # trajectory_count * trajectory_fields doubles
        self.tree = tree              # the first tree_rows_kept rows of the tree
        self.tree_count = tree_count  # rows in the output (may exceed the rows kept)
        self.trajectory_first_line = trajectory_first_line
        self.tree_first_line = tree_first_line
        self.trailing_line = trailing_line  # first non-blank line after the tree

    @property
    def trajectory_count(self) -> int:
        return len(self.trajectory) // self.trajectory_fields

    @property
    def tree_rows_kept(self) -> int:
        return len(self.tree) // self.tree_fields

    def trajectory_row(self, index: int) -> tuple[float, ...]:
        f = self.trajectory_fields
        return tuple(self.trajectory[index * f:(index + 1) * f])

    def trajectory_rows(self) -> Iterator[tuple[float, ...]]:
        values, f = self.trajectory, self.trajectory_fields
        for start in range(0, len(values), f):
            yield tuple(values[start:start + f])

    def tree_rows(self) -> Iterator[tuple[float, ...]]:
        values, f = self.tree, self.tree_fields
        for start in range(0, len(values), f):
            yield tuple(values[start:start + f])

    def trajectory_line(self, index: int) -> int:
        """Output line number of trajectory row ``index`` (rows are contiguous)."""
        return self.trajectory_first_line + index


def _show(text: str, limit: int = 60) -> str:
    return repr(text if len(text) <= limit else text[:limit] + "...")


_ROW_PATTERNS: dict[int, re.Pattern] = {}


def _rows_pattern(fields: int) -> re.Pattern:
    """Any number of complete rows of ``fields`` numbers (possessive: no backtracking)."""
    pattern = _ROW_PATTERNS.get(fields)
    if pattern is None:
        row = f"{_SPACE}*+{_FAST_NUMBER}(?:{_SPACE}++{_FAST_NUMBER}){{{fields - 1}}}{_SPACE}*+"
        pattern = _ROW_PATTERNS[fields] = re.compile(f"(?:{row}(?:\n|\\Z))*+")
    return pattern


def compile_row_patterns(*widths: int) -> None:
    """Compile the patterns :func:`read_plan` uses for rows of these widths now (the
    validator does while the planner runs, so that reading the answer does not)."""
    for fields in widths:
        _rows_pattern(fields)


def row_error(line: str, fields: int, what: str) -> tuple[str, int | None] | None:
    """Why ``line`` is not a row of ``fields`` finite numbers, or None if it is one.

    Returns the message and the number of tokens found (None: too many to count).
    """
    # (Compiled here, from re's cache after the first time: only a bad answer needs them.)
    tokens = [m.group() for m in islice(re.finditer(_TOKEN, line), _SHOWN_TOKENS + 1)]
    if len(tokens) != fields:
        if len(tokens) > _SHOWN_TOKENS:
            return (f"expected {fields} numbers on a {what} line, got more than "
                    f"{_SHOWN_TOKENS} tokens: {_show(line.strip())}", None)
        shown = _show(line.strip()) if tokens else "a blank line"
        return f"expected {fields} numbers on a {what} line, got {len(tokens)}: {shown}", \
            len(tokens)
    for token in tokens:
        if re.fullmatch(_NON_FINITE, token):
            return f"{_show(token)} is not a finite number", fields
        if not re.fullmatch(_NUMBER, token):
            return f"{_show(token)} is not a number", fields
        if not math.isfinite(float(token)):
            return f"{_show(token)} is not a finite number (too large for a double)", fields
    return None


class _Reader:
    def __init__(self, text: str):
        self.text = text
        self.pos = 0
        self.line_no = 1
        # Lines as the plan format counts them: split on "\n", minus a blank last piece.
        last_start = text.rfind("\n") + 1
        self.total_lines = text.count("\n") + 1
        if _BLANK_REST.fullmatch(text, last_start) is not None:
            self.total_lines -= 1

    def skip_blank_lines(self) -> None:
        end = _BLANK_LINES.match(self.text, self.pos).end()
        self.line_no += self.text.count("\n", self.pos, end)
        self.pos = end

    def line_preview(self) -> str:
        end = self.text.find("\n", self.pos, self.pos + 200)
        return self.text[self.pos:end if end >= 0 else self.pos + 200].strip()

    def count(self, what: str, limit: int | None) -> int:
        self.skip_blank_lines()
        if self.line_no > self.total_lines:
            if what == "trajectory":
                raise PlanParseError(self.line_no, "output is empty: expected the trajectory count")
            raise PlanParseError(self.line_no, "output ended before the tree count")
        match = _COUNT_LINE.match(self.text, self.pos)
        if match is None:
            raise PlanParseError(self.line_no, f"expected the {what} count (a non-negative "
                                               f"integer), got {_show(self.line_preview())}")
        digits = match.group(1)
        lines_left = self.total_lines - self.line_no
        significant = digits.lstrip("0") or "0"  # leading zeros are no reason to refuse
        count = int(significant) if len(significant) <= _MAX_COUNT_DIGITS else None
        if count is None or count > lines_left:
            raise PlanParseError(self.line_no, f"{what} count {_show(digits, 30)[1:-1]} but "
                                               f"only {lines_left} lines follow")
        if limit is not None and count > limit:
            raise PlanParseError(self.line_no, f"{what} count {count} is over the validator's "
                                               f"limit of {limit} lines")
        self.pos = match.end()
        self.line_no += 1
        return count

    def _advance(self, lines: int) -> int:
        """Position just after the next ``lines`` lines."""
        text, position = self.text, self.pos
        for _ in range(lines):
            newline = text.find("\n", position)
            if newline < 0:
                return len(text)
            position = newline + 1
        return position

    def _next_block(self, remaining: int) -> tuple[int, int]:
        """End position and line count of the next block: about _BLOCK_CHARS of
        whole lines, never more than ``remaining`` lines."""
        text, pos = self.text, self.pos
        end = pos + _BLOCK_CHARS
        newline = text.find("\n", end) if end < len(text) else -1
        end = len(text) if newline < 0 else newline + 1
        lines = text.count("\n", pos, end)
        if end == len(text) and not text.endswith("\n"):
            lines += 1  # the last line, without its newline
        if lines > remaining:
            return self._advance(remaining), remaining
        return end, lines

    def rows(self, count: int, fields: int, what: str, keep: int | None = None) -> array:
        """Read ``count`` rows; convert and return the first ``keep`` (all if None)."""
        values = array("d")
        pattern = _rows_pattern(fields)
        keep = count if keep is None else min(keep, count)
        remaining = count
        while remaining:
            end, block_lines = self._next_block(remaining)
            fast = pattern.fullmatch(self.text, self.pos, end) is not None
            if not fast:
                # Raises on the first bad line; returns if all are good (a number
                # with over 300 digits before its point is left to this slow path).
                self._explain(end, fields, what)
            kept_rows = min(block_lines, max(0, keep - (count - remaining)))
            # A number too big for a double needs an exponent or 309 digits (checked
            # by _explain): only blocks with an "e" need converting just to check.
            overflow_possible = fast and (self.text.find("e", self.pos, end) >= 0
                                          or self.text.find("E", self.pos, end) >= 0)
            if kept_rows or overflow_possible:
                block = array("d", map(float, self.text[self.pos:end].split()))
                if overflow_possible and not math.isfinite(sum(block)) \
                        and not all(map(math.isfinite, block)):
                    bad = next(k for k, v in enumerate(block) if not math.isfinite(v))
                    self.line_no += bad // fields
                    self.pos = self._advance(bad // fields)
                    self._explain(self._advance(1), fields, what)
                if kept_rows:
                    values.extend(block if kept_rows == block_lines
                                  else block[:kept_rows * fields])
            self.pos = end
            self.line_no += block_lines
            remaining -= block_lines
        return values

    def _explain(self, end: int, fields: int, what: str) -> None:
        """Raise the error of the first bad row in ``[pos, end)``; return if none is bad."""
        text, position, line_no = self.text, self.pos, self.line_no
        while position < end:
            newline = text.find("\n", position, end)
            line_end = newline if newline >= 0 else end
            problem = row_error(text[position:line_end], fields, what)
            if problem is not None:
                raise PlanRowError(line_no, problem[0], problem[1])
            position, line_no = line_end + 1, line_no + 1

    def trailing_line(self) -> int | None:
        self.skip_blank_lines()
        return self.line_no if self.line_no <= self.total_lines else None


def read_plan(text: str, trajectory_fields: int, tree_fields: int,
              max_trajectory_rows: int | None = None,
              max_tree_rows_kept: int | None = None) -> PlanArrays:
    """Parse a plan; raise :class:`PlanParseError` (with the 1-based line) if it is malformed.

    ``max_trajectory_rows``: a larger trajectory count is an error. ``max_tree_rows_kept``:
    tree rows past this many are still checked but not stored.
    """
    reader = _Reader(text)
    n = reader.count("trajectory", max_trajectory_rows)
    trajectory_first = reader.line_no
    trajectory = reader.rows(n, trajectory_fields, "trajectory")
    m = reader.count("tree", None)
    tree_first = reader.line_no
    tree = reader.rows(m, tree_fields, "tree", keep=max_tree_rows_kept)
    return PlanArrays(trajectory_fields, tree_fields, trajectory, tree, m,
                      trajectory_first, tree_first, reader.trailing_line())
