"""What submissions and planners wrote (names, messages, details), shown as text
wherever it goes: a spreadsheet cell, a terminal, Markdown (HTML: grading.html_report)."""

from __future__ import annotations

import html
import os
from pathlib import Path
from urllib.parse import quote


def spreadsheet_text(value: str) -> str:
    """A submission's name as a spreadsheet cell that stays text: a leading ``=``,
    ``+``, ``-``, ``@``, tab or carriage return would start a formula, so it gets a
    ``'`` before it (as OWASP advises for CSV)."""
    return "'" + value if value[:1] in ("=", "+", "-", "@", "\t", "\r") else value


def terminal_text(value) -> str:
    """What a submission named, for a terminal: control characters (escape
    sequences among them) shown as ``\\xNN``, not sent."""
    return "".join(char if char.isprintable() else f"\\x{ord(char):02x}"
                   for char in str(value))


_MARKDOWN = str.maketrans({char: "\\" + char for char in "\\`*_[]|~"})


def text(value) -> str:
    """What a submission, a planner or a file name gave, shown as text in Markdown: one
    line, HTML's ``& < >`` as entities, Markdown's emphasis, code, link and table marks
    escaped."""
    return html.escape(" ".join(str(value).split()), quote=False).translate(_MARKDOWN)


def relative_url(path: str | Path, base: Path) -> str:
    """``path`` relative to the folder ``base``, as a URL's path (every character that is
    not a plain path character percent-encoded: a name stays one name)."""
    return quote(os.path.relpath(path, base))


def link(label: str, path: str, out: Path) -> str:
    """A Markdown link to ``path`` relative to ``out`` (``label`` already text)."""
    return f"[{label}]({relative_url(path, out)})"
