"""What every page of the validator's PDFs shares (the grid's page and the family's):
the colours, the page's bands (margins, title, counts, captions, legend), the
render budgets and summary, the polyline writer in page points, tick steps, the
text above and below the drawing and the legend's swatches; and the family pages'
legend. Imports reportlab, and of the validator only render_geometry (the colours).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, Sequence

from reportlab.lib.pagesizes import letter
from reportlab.pdfgen.canvas import Canvas

from validator.render_geometry import (BLOCKED_GRAY, CORNER_RGB, FAILURE_RGB,  # noqa: F401
                                       FOOTPRINT_FILL_RGB, FOOTPRINT_RGB, GOAL_RGB, GRID_GRAY,
                                       HEADING_RGB, OBSTACLE_GRAY, POSE_RGB, SOLUTION_RGB,
                                       START_FILL_RGB, START_RGB, TREE_RGB, VALID_RGB,
                                       FamilyOptions)

START_RADIUS = 4.5  # points: the start's dot

MARGIN = 24.0
_TITLE_BAND = 56.0      # verdict, heading, counts
AXIS_LEFT = 26.0        # tick marks and their labels left of the map
_AXIS_BOTTOM = 16.0     # ... and below it
_CAPTION_LINES = 4
_CAPTION_STEP = 11.0
_LEGEND_ROWS = 2
_LEGEND_STEP = 12.0
BOTTOM_SPACE = (MARGIN + _LEGEND_ROWS * _LEGEND_STEP + 4 + _CAPTION_LINES * _CAPTION_STEP
                + 4 + _AXIS_BOTTOM)
TOP_SPACE = MARGIN + _TITLE_BAND
_FAR = 30_000.0  # page coordinates are clamped here: PDF readers dislike huge numbers


@dataclass(frozen=True)
class RenderOptions:
    max_tree_edges_drawn: int = 250_000
    """Edges past this many are counted on the page, not drawn (keeps huge trees fast)."""
    max_tree_points: int = 1_000_000
    """Vertices computed for the tree (2 a point edge, 21 a spaceship edge); edges
    past the budget are counted, not drawn: bounds time and memory."""
    max_solution_points: int = 500_000
    """The same for the solution (1 a point line, 21 a spaceship line): far beyond any
    honest answer, which runs to hundreds of lines."""
    min_vertex_spacing: float = 0.5
    """Points: a curve vertex closer than this to the previous one is skipped."""
    tree_line_width: float = 0.4
    """Points."""
    solution_line_width: float = 1.8
    """Points: wide enough to show over the tree and blocked cells."""
    page_size: tuple[float, float] = letter
    """The largest page: the page is this (either way round) cut to the map's shape."""


@dataclass(frozen=True)
class RenderSummary:
    """What a PDF drew of the output, within the budgets."""

    tree_edges_drawn: int
    """Tree edges drawn (after the budget and any thinning)."""
    tree_edges_total: int
    """Tree edges the output held."""
    solution_lines_drawn: int = 0
    """Solution lines drawn (up to the budget)."""
    solution_lines_total: int = 0
    """Solution lines the output held."""


@dataclass(frozen=True)
class PageLayout:
    """Where the map sits on the page: page = origin + scale * world."""

    page_width: float
    page_height: float
    origin_x: float
    origin_y: float
    scale: float

    def to_page(self, x: float, y: float) -> tuple[float, float]:
        return self.origin_x + self.scale * x, self.origin_y + self.scale * y


def layout_polyline_ops(points: Iterable[tuple[float, float]], layout: PageLayout,
                        spacing: float, out: list[str]) -> bool:
    """Append ``m``/``l`` operators for one polyline; skip near-duplicate vertices.

    Far points are clamped to +-_FAR; a non-finite point ends the polyline (returns
    False: the rest is not drawn).
    """
    ox, oy, scale, far = layout.origin_x, layout.origin_y, layout.scale, _FAR
    last_x = last_y = None
    pending = None
    finite = True
    for x, y in points:
        px, py = ox + scale * x, oy + scale * y
        if not (-far <= px <= far and -far <= py <= far):
            if not (math.isfinite(px) and math.isfinite(py)):
                finite = False
                break
            px, py = min(max(px, -far), far), min(max(py, -far), far)
        if last_x is None:
            out.append(f"{px:.2f} {py:.2f} m")
            last_x, last_y = px, py
        elif -spacing < px - last_x < spacing and -spacing < py - last_y < spacing:
            pending = (px, py)
        else:
            out.append(f"{px:.2f} {py:.2f} l")
            last_x, last_y, pending = px, py, None
    if pending is not None:
        out.append(f"{pending[0]:.2f} {pending[1]:.2f} l")
    return finite


def stroke(canvas: Canvas, ops: list[str], rgb: tuple[float, float, float],
           width: float, dash: Sequence[float] = ()) -> None:
    """One path of ``ops`` (its first one a move) stroked in ``rgb``."""
    if not ops:
        return
    canvas.saveState()
    canvas.setStrokeColorRGB(*rgb)
    canvas.setLineWidth(width)
    canvas.setLineJoin(1)
    canvas.setLineCap(1)
    if dash:
        canvas.setDash(list(dash))
    canvas.addLiteral("\n".join(ops) + "\nS")
    canvas.restoreState()


def stroke_ops(canvas: Canvas, ops: list[str], rgb, width: float, every: int = 10_000,
               dash: Sequence[float] = ()) -> None:
    """Stroke ``ops`` as paths of at most ``every`` operators each. A path cut inside a
    polyline starts with a move to where the previous one ended: a path that began with
    a line-to would have no current point (strict readers drop it)."""
    for start in range(0, len(ops), every):
        chunk = ops[start:start + every]
        if start and not chunk[0].endswith(" m"):
            x, y = ops[start - 1].split()[-3:-1]
            chunk.insert(0, f"{x} {y} m")
        stroke(canvas, chunk, rgb, width, dash)


def failure_cross(canvas: Canvas, x: float, y: float, arm: float) -> None:
    canvas.saveState()
    canvas.setStrokeColorRGB(*FAILURE_RGB)
    canvas.setLineWidth(1.6 * arm / 6.0)
    canvas.line(x - arm, y - arm, x + arm, y + arm)
    canvas.line(x - arm, y + arm, x + arm, y - arm)
    canvas.circle(x, y, arm * 4 / 3, stroke=1, fill=0)
    canvas.restoreState()


def _fit(canvas: Canvas, text: str, font: str, size: float, width: float) -> str:
    if canvas.stringWidth(text, font, size) <= width:
        return text
    while text and canvas.stringWidth(text + "...", font, size) > width:
        text = text[:-1]
    return text + "..."


def draw_line(canvas: Canvas, layout: PageLayout, y: float, text: str, font: str,
              size: float) -> None:
    """One line of text at the left margin, cut to the page's text width."""
    width = layout.page_width - 2 * MARGIN
    canvas.drawString(MARGIN, y, _fit(canvas, text, font, size, width))


def draw_title(canvas: Canvas, layout: PageLayout, verdict: str, heading: str,
               valid: bool) -> None:
    """The verdict (green when valid, red otherwise) and the heading under it."""
    top = layout.page_height - MARGIN
    canvas.setFillColorRGB(*(VALID_RGB if valid else SOLUTION_RGB))
    canvas.setFont("Helvetica-Bold", 13)
    draw_line(canvas, layout, top - 13, verdict, "Helvetica-Bold", 13)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 9.5)
    draw_line(canvas, layout, top - 28, heading, "Helvetica", 9.5)


def draw_captions(canvas: Canvas, layout: PageLayout, captions: Sequence[str],
                  failed: bool) -> None:
    """Up to _CAPTION_LINES lines (magenta after a failure) under the map's labels."""
    canvas.setFont("Helvetica", 8.5)
    canvas.setFillColorRGB(*(FAILURE_RGB if failed else (0.0, 0.0, 0.0)))
    top = layout.origin_y - _AXIS_BOTTOM - 4 - 8.5
    for k, caption in enumerate(captions[:_CAPTION_LINES]):
        draw_line(canvas, layout, top - _CAPTION_STEP * k, caption, "Helvetica", 8.5)


def _draw_swatch(canvas: Canvas, kind: str, x: float, y: float) -> None:
    """A 14 x 8 point sample of ``kind`` with its lower left corner at (x, y)."""
    canvas.saveState()
    cx, cy = x + 7.0, y + 4.0
    if kind in ("solution", "tree", "pose"):
        rgb, width = {"solution": (SOLUTION_RGB, 1.8), "tree": (TREE_RGB, 1.0),
                      "pose": (POSE_RGB, 1.6)}[kind]
        canvas.setStrokeColorRGB(*rgb)
        canvas.setLineWidth(width)
        canvas.setLineCap(1)
        canvas.line(x + 1, cy, x + 13, cy)
    elif kind == "goalpose":
        canvas.setStrokeColorRGB(*GOAL_RGB)
        canvas.setLineWidth(1.4)
        canvas.setDash([4.0, 3.0])
        canvas.line(x, cy, x + 14, cy)
    elif kind == "start":
        canvas.setFillColorRGB(*START_RGB)
        canvas.circle(cx, cy, 3.5, stroke=0, fill=1)
    elif kind in ("goal", "corner"):
        canvas.setStrokeColorRGB(*(GOAL_RGB if kind == "goal" else CORNER_RGB))
        canvas.setLineWidth(1.0 if kind == "goal" else 1.2)
        canvas.circle(cx, cy, 3.5, stroke=1, fill=0)
    elif kind == "failure":
        failure_cross(canvas, cx, cy, 3.0)
    elif kind in ("blocked", "obstacle"):
        canvas.setFillGray(BLOCKED_GRAY if kind == "blocked" else OBSTACLE_GRAY)
        canvas.rect(x + 3, y, 8, 8, stroke=0, fill=1)
    elif kind == "footprint":
        canvas.setFillColorRGB(*FOOTPRINT_FILL_RGB)
        canvas.setStrokeColorRGB(*FOOTPRINT_RGB)
        canvas.setLineWidth(1.0)
        canvas.rect(x + 2, y + 1, 10, 6, stroke=1, fill=1)
        canvas.setStrokeColorRGB(*HEADING_RGB)
        canvas.setLineWidth(1.6)
        canvas.line(x + 12, y + 1, x + 12, y + 7)
    canvas.restoreState()


def draw_legend(canvas: Canvas, layout: PageLayout, items: list[tuple[str, str]]) -> None:
    """The items left to right, in up to _LEGEND_ROWS rows at the bottom of the page."""
    font, size = "Helvetica", 7.5
    canvas.setFont(font, size)
    canvas.setFillGray(0.25)
    right = layout.page_width - MARGIN
    x, row = MARGIN, 0
    for kind, label in items:
        width = 17.0 + canvas.stringWidth(label, font, size)
        if x + width > right and x > MARGIN:
            x, row = MARGIN, row + 1
        if row >= _LEGEND_ROWS:
            return
        y = MARGIN + (_LEGEND_ROWS - 1 - row) * _LEGEND_STEP
        _draw_swatch(canvas, kind, x, y - 1.0)
        canvas.drawString(x + 17.0, y, label)
        x += width + 12.0


def start_mark(canvas: Canvas, x: float, y: float) -> None:
    """The start: a green dot in a white ring, visible over a dense tree."""
    canvas.saveState()
    canvas.setFillGray(1.0)
    canvas.circle(x, y, START_RADIUS + 1.6, stroke=0, fill=1)
    canvas.setFillColorRGB(*START_RGB)
    canvas.circle(x, y, START_RADIUS, stroke=0, fill=1)
    canvas.restoreState()


def draw_no_answer(canvas: Canvas, x: float, y: float, width: float,
                   lines: Sequence[str]) -> None:
    """Why there is nothing to draw (the planner timed out or did not start), in a
    white box centred at (x, y) over the picture."""
    if not lines:
        return
    size, step = 10.0, 13.0
    shown = [_fit(canvas, line, "Helvetica", size, width - 16) for line in lines[:4]]
    top = y + step * len(shown) / 2
    canvas.saveState()
    canvas.setFillGray(1.0)
    canvas.setStrokeColorRGB(*FAILURE_RGB)
    canvas.rect(x - width / 2, top - step * len(shown) - 6, width, step * len(shown) + 12,
                stroke=1, fill=1)
    canvas.setFillColorRGB(*FAILURE_RGB)
    canvas.setFont("Helvetica-Bold", size)
    for k, line in enumerate(shown):
        canvas.drawCentredString(x, top - step * (k + 1) + 3, line)
    canvas.restoreState()


# ----- the family's pages: legend ------------------------------------------------------

def family_legend_items(solution: bool, tree: bool, goal: bool, failure: bool,
                        footprint: bool, world, tree_label: str = "tree edges"
                        ) -> list[tuple[str, str]]:
    """(swatch kind, label) for what a family page shows, nothing else."""
    items = []
    if solution:
        items.append(("solution", "red: solution"))
    if tree:
        items.append(("tree", f"blue-grey: {tree_label}"))
    if footprint:
        items.append(("footprint", "pink: body along the solution (dark edge: its front)"))
    items.append(("start", "green: start"))
    if goal:
        items.append(("goal", "blue outline: goal region"))
    if failure:
        items.append(("failure", "magenta cross: first failure"))
    if world is not None and world.obstacles:
        items.append(("obstacle", "grey: obstacle"))
    return items
