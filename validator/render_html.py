"""The validator's view for the browser: one self-contained HTML file (no network, no
server) that draws a scene (render_scene) with validator/view/view.js on a canvas.

The page holds the scene as JSON in a ``<script type="application/json">`` element,
its many numbers as base64 typed arrays (float32 points, uint32 starts; cells
zlib-compressed), and the script and style inline, read from validator/view/ when the
page is written. A Content-Security-Policy allows that script and style only (by their
hashes) and no connection. What the planner wrote reaches the page as JSON strings,
which the script shows as text: ``<``, ``>`` and ``&`` are escaped in them, so the
element cannot end early.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import sys
import zlib
from array import array
from pathlib import Path

from validator.render_file import write_atomically

VIEW = Path(__file__).resolve().parent / "view"


def _typed(value):
    """JSON for the scene's arrays: little-endian base64, cells compressed."""
    if isinstance(value, array):
        if sys.byteorder != "little":
            value = array(value.typecode, value)
            value.byteswap()
        kind = {"f": "f32", "I": "u32"}[value.typecode]
        if value.typecode == "I" and value.itemsize != 4:
            raise TypeError("uint32 arrays need a 4-byte 'I'")
        return {"$": kind, "b64": base64.b64encode(value.tobytes()).decode("ascii")}
    if isinstance(value, (bytes, bytearray)):
        return {"$": "u8z", "b64": base64.b64encode(zlib.compress(bytes(value), 6)).decode()}
    raise TypeError(f"not in a scene: {type(value).__name__}")


def _hash(text: str) -> str:
    return "sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode()


def html_text(scene: dict) -> str:
    """The page of ``scene``."""
    data = json.dumps(scene, default=_typed, allow_nan=False, separators=(",", ":"))
    for char, escaped in (("<", "\\u003c"), (">", "\\u003e"), ("&", "\\u0026")):
        data = data.replace(char, escaped)  # only inside strings: the element cannot end
    script = (VIEW / "view.js").read_text(encoding="utf-8")
    style = (VIEW / "view.css").read_text(encoding="utf-8")
    policy = (f"default-src 'none'; script-src '{_hash(script)}'; style-src '{_hash(style)}'; "
              "img-src data: blob:")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{policy}\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<title>{html.escape(scene['title'])}</title>\n<style>{style}</style>\n</head>\n"
            f"<body>\n<script type=\"application/json\" id=\"scene\">{data}</script>\n"
            f"<noscript>This view needs JavaScript.</noscript>\n<script>{script}</script>\n"
            "</body></html>\n")


def write_html(path: str, scene: dict) -> None:
    """Write the page of ``scene`` to ``path``, whole or not at all."""
    page = html_text(scene).encode("utf-8")
    write_atomically(path, lambda out: out.write(page))
