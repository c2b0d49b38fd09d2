"""The validator's picture in the format ``-o``'s extension names: ``.pdf`` (the pages,
render_pdf; also a name without an extension), ``.html`` (the browser view,
render_html), ``.svg`` (the same drawing as the view, still, render_svg) or ``.png``
(the PDF's pages as one image, render_png).

Each format's writer is imported only to draw one, and what it needs is found before
the planner runs (missing_tool): the PDF and the PNG need reportlab (the PNG also
pypdfium2); the view and the SVG need nothing beyond the standard library. Every
picture is written whole or not at all (render_file).
"""

from __future__ import annotations

import os
from importlib.util import find_spec
from typing import Sequence

FORMATS = {".pdf": "PDF", ".html": "HTML view", ".svg": "SVG", ".png": "PNG"}
"""The extensions ``-o`` knows and what each writes."""
_NEEDS = {".pdf": ("reportlab",), ".png": ("reportlab", "pypdfium2")}


def picture_format(path: str) -> str | None:
    """The format of ``path`` by its extension (lower case), None for one we do not
    write; a name without one (``/dev/stdout``) is a PDF, as it always was."""
    extension = os.path.splitext(path)[1].lower() or ".pdf"
    return extension if extension in FORMATS else None


def known_formats() -> str:
    return ", ".join(FORMATS)


def missing_tool(extension: str) -> str | None:
    """Why this machine cannot draw the format, in one line, or None."""
    missing = [name for name in _NEEDS.get(extension, ()) if find_spec(name) is None]
    if not missing:
        return None
    what = " and ".join(missing)
    setup = "./make.sh validator" if missing == ["reportlab"] else "./make.sh"
    return (f"drawing the {FORMATS[extension]} needs {what}: run {setup} (or pip install "
            f"{' '.join(missing)}), or pass -noviz")


def write_picture(path: str, extension: str, problem, vehicle, report, verdict: str,
                  notes: Sequence[str], label: str) -> None:
    """Draw the report into ``path`` in the format of ``extension``."""
    if extension == ".pdf":
        from validator.render_pdf import render_pdf
        render_pdf(path, problem, vehicle, report, verdict, notes, label)
    elif extension == ".png":
        from validator.render_png import render_png
        render_png(path, problem, vehicle, report, verdict, notes, label)
    else:
        from validator.render_scene import build_scene
        scene = build_scene(problem, vehicle, report, verdict, notes, label)
        if extension == ".html":
            from validator.render_html import write_html
            write_html(path, scene)
        else:
            from validator.render_svg import write_svg
            write_svg(path, scene)
