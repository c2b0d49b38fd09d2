"""The tree-viz PDF (SPEC 3): one vector page, the map scaled to fit.

Drawn bottom to top: the grid with blocked cells filled, every tree edge
(spaceship edges as their 20-slice curves), the solution in red, the start, the
goal circle (radius 0.1), segments that cut a blocked cell's corner, and the
first failure. Title: the problem, the vehicle and the verdict.

The only module that imports reportlab. Big maps and trees stay fast and small
because the blocked cells (merged into row runs) and the tree are written as a
few long PDF paths, not one object per cell or edge, with coordinates in page
points to two decimals, and a curve's vertices closer than half a point to the
previous one skipped (invisible at any sane zoom).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import BinaryIO, Iterable, Sequence

from reportlab import rl_config
from reportlab.lib.pagesizes import landscape, letter, portrait
from reportlab.pdfgen.canvas import Canvas

from planning_core.problem import Problem
from planning_core.vehicles import Vehicle, spaceship
from validator.checks import ValidationReport

SOLUTION_RGB = (0.85, 0.05, 0.05)
TREE_RGB = (0.50, 0.62, 0.82)
BLOCKED_GRAY = 0.30
GRID_GRAY = 0.82
START_RGB = (0.0, 0.60, 0.0)
GOAL_RGB = (0.10, 0.20, 0.95)
CORNER_RGB = (1.0, 0.55, 0.0)
FAILURE_RGB = (0.85, 0.0, 0.85)
VALID_RGB = (0.0, 0.50, 0.0)

_LEGEND = ("red: solution   blue-grey: tree edges   green dot: start   blue circle: goal "
           "(radius 0.1)   magenta cross: first failure   orange circle: corner cut")
_MARGIN = 36.0
_TITLE_BAND = 48.0
_CAPTION_BAND = 40.0
_EDGES_PER_PATH = 10_000
_FAR = 30_000.0  # page coordinates are clamped here: PDF readers dislike huge numbers


@dataclass(frozen=True)
class RenderOptions:
    max_tree_edges_drawn: int = 250_000
    """Edges past this many are counted in the title, not drawn (keeps huge trees fast)."""
    min_vertex_spacing: float = 0.5
    """Points: a curve vertex closer than this to the previous one is skipped."""
    tree_line_width: float = 0.4
    solution_line_width: float = 1.8
    page_size: tuple[float, float] = letter


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


def page_layout(problem: Problem, page_size: tuple[float, float] = letter) -> PageLayout:
    """Landscape for wide maps, portrait otherwise; the map as large as fits."""
    size = landscape(page_size) if problem.width > problem.height else portrait(page_size)
    page_w, page_h = size
    avail_w = page_w - 2 * _MARGIN
    avail_h = page_h - 2 * _MARGIN - _TITLE_BAND - _CAPTION_BAND
    scale = min(avail_w / problem.width, avail_h / problem.height)
    origin_x = (page_w - scale * problem.width) / 2
    origin_y = _MARGIN + _CAPTION_BAND + (avail_h - scale * problem.height) / 2
    return PageLayout(page_w, page_h, origin_x, origin_y, scale)


@dataclass(frozen=True)
class RenderSummary:
    tree_edges_drawn: int
    tree_edges_total: int


def _polyline_ops(points: Iterable[tuple[float, float]], layout: PageLayout,
                  spacing: float, out: list[str]) -> None:
    """Append ``m``/``l`` operators for one polyline; skip near-duplicate vertices.

    Non-finite points end the polyline; far points are clamped to +-_FAR.
    """
    ox, oy, scale, far = layout.origin_x, layout.origin_y, layout.scale, _FAR
    last_x = last_y = None
    pending = None
    for x, y in points:
        px, py = ox + scale * x, oy + scale * y
        if not (-far <= px <= far and -far <= py <= far):
            if not (math.isfinite(px) and math.isfinite(py)):
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


def _stroke(canvas: Canvas, ops: list[str], rgb: tuple[float, float, float],
            width: float) -> None:
    if not ops:
        return
    canvas.saveState()
    canvas.setStrokeColorRGB(*rgb)
    canvas.setLineWidth(width)
    canvas.setLineJoin(1)
    canvas.setLineCap(1)
    canvas.addLiteral("\n".join(ops) + "\nS")
    canvas.restoreState()


def _draw_grid(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    w, h, s = problem.width, problem.height, layout.scale
    ox, oy = layout.origin_x, layout.origin_y
    runs = []
    for row in range(h):
        cells = problem.blocked[row * w:(row + 1) * w]
        column = cells.find(1)
        while column >= 0:
            end = cells.find(0, column)
            end = w if end < 0 else end
            runs.append(f"{ox + s * column:.2f} {oy + s * row:.2f} "
                        f"{s * (end - column):.2f} {s:.2f} re")
            column = cells.find(1, end)
    if runs:
        canvas.saveState()
        canvas.setFillGray(BLOCKED_GRAY)
        for start in range(0, len(runs), _EDGES_PER_PATH):
            canvas.addLiteral("\n".join(runs[start:start + _EDGES_PER_PATH]) + "\nf")
        canvas.restoreState()
    if s >= 3.0:  # grid lines only where cells are big enough to tell apart
        lines = [f"{ox + s * i:.2f} {oy:.2f} m {ox + s * i:.2f} {oy + s * h:.2f} l"
                 for i in range(1, w)]
        lines += [f"{ox:.2f} {oy + s * j:.2f} m {ox + s * w:.2f} {oy + s * j:.2f} l"
                  for j in range(1, h)]
        _stroke(canvas, lines, (GRID_GRAY,) * 3, 0.25)
    canvas.saveState()
    canvas.setLineWidth(0.8)
    canvas.rect(ox, oy, s * w, s * h, stroke=1, fill=0)
    canvas.restoreState()


def _draw_tree(canvas: Canvas, rows: Iterable[Sequence[float]], vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions, limit: int) -> int:
    ops: list[str] = []
    drawn = 0
    slice_states = spaceship.slice_states
    spacing = options.min_vertex_spacing
    for row in rows:
        if drawn >= limit:
            break
        drawn += 1
        if vehicle.is_spaceship:
            if not all(map(math.isfinite, row)):
                continue
            points = [(row[0], row[1])]
            points.extend((s[0], s[1]) for s in slice_states(row[:4], row[4:]))
        else:
            points = [(row[0], row[1]), (row[2], row[3])]
        _polyline_ops(points, layout, spacing, ops)
        if drawn % _EDGES_PER_PATH == 0:
            _stroke(canvas, ops, TREE_RGB, options.tree_line_width)
            ops = []
    _stroke(canvas, ops, TREE_RGB, options.tree_line_width)
    return drawn


def solution_points(report: ValidationReport) -> list[tuple[float, float]]:
    """The solution as flown: the printed points (point vehicle), or every slice of
    every line's control (spaceship), the last line's included."""
    plan = report.plan
    if plan is None:
        return []
    rows = list(plan.trajectory_rows())
    if not report.vehicle.is_spaceship:
        return [(r[0], r[1]) for r in rows]
    points: list[tuple[float, float]] = []
    for row in rows:
        points.append((row[0], row[1]))
        if all(map(math.isfinite, row)):
            points.extend((s[0], s[1]) for s in spaceship.slice_states(row[:4], row[4:]))
    return points


def _marker_position(layout: PageLayout, x: float, y: float) -> tuple[float, float]:
    """A world point on the page, pulled back onto the page if it is far outside."""
    px, py = layout.to_page(x if math.isfinite(x) else 0.0, y if math.isfinite(y) else 0.0)
    return (min(max(px, 6.0), layout.page_width - 6.0),
            min(max(py, 6.0), layout.page_height - 6.0))


def _fit(canvas: Canvas, text: str, font: str, size: float, width: float) -> str:
    if canvas.stringWidth(text, font, size) <= width:
        return text
    while text and canvas.stringWidth(text + "...", font, size) > width:
        text = text[:-1]
    return text + "..."


def render_pdf(out: BinaryIO | str, problem: Problem, vehicle: Vehicle,
               report: ValidationReport | None, verdict: str, notes: Sequence[str] = (),
               problem_label: str = "", options: RenderOptions = RenderOptions()
               ) -> RenderSummary:
    """Write the page to ``out`` (a path or a binary file).

    ``report`` is None when there is nothing to validate (the planner timed out or
    could not start): the page then shows the problem, ``verdict`` and ``notes``.
    """
    # Binary (zlib only) streams: reportlab's ASCII85 step is pure Python, slower
    # than all the drawing, and makes the file a quarter bigger.
    saved_a85, rl_config.useA85 = rl_config.useA85, 0
    try:
        return _render(out, problem, vehicle, report, verdict, notes, problem_label, options)
    finally:
        rl_config.useA85 = saved_a85


def _render(out, problem: Problem, vehicle: Vehicle, report: ValidationReport | None,
            verdict: str, notes: Sequence[str], problem_label: str,
            options: RenderOptions) -> RenderSummary:
    layout = page_layout(problem, options.page_size)
    canvas = Canvas(out, pagesize=(layout.page_width, layout.page_height),
                    pageCompression=1, invariant=1)
    canvas.setTitle(f"rrt-validator: {problem_label or 'problem'} ({vehicle.value})")
    canvas.setCreator("rrt-validator")

    _draw_grid(canvas, problem, layout)
    plan = report.plan if report is not None else None
    total_edges = plan.tree_count if plan is not None else 0
    drawn = 0
    if plan is not None:
        drawn = _draw_plan(canvas, report, vehicle, layout, options)
    _draw_start_and_goal(canvas, problem, layout)
    if report is not None:
        _draw_corner_cuts(canvas, report, layout)
    failure = report.first_failure if report is not None else None
    if failure is not None and failure.where is not None:
        _draw_failure_mark(canvas, layout, *failure.where)

    _draw_title(canvas, layout, verdict, _heading(problem, vehicle, report, problem_label),
                valid=report is not None and report.valid)
    if plan is not None:
        _draw_line(canvas, layout, layout.page_height - _MARGIN - 41, _counts(report, drawn),
                   "Helvetica", 9.5)
    _draw_captions(canvas, layout, _captions(report, notes), failure is not None)
    canvas.showPage()
    canvas.save()
    return RenderSummary(drawn, total_edges)


def _draw_plan(canvas: Canvas, report: ValidationReport, vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions) -> int:
    """The tree, then the solution over it; returns how many tree edges were drawn."""
    canvas.saveState()
    # Anything far outside the map (bad output) is cut at the page's edge.
    path = canvas.beginPath()
    path.rect(0, 0, layout.page_width, layout.page_height)
    canvas.clipPath(path, stroke=0, fill=0)
    drawn = _draw_tree(canvas, report.plan.tree_rows(), vehicle, layout, options,
                       options.max_tree_edges_drawn)
    ops: list[str] = []
    _polyline_ops(solution_points(report), layout, 0.05, ops)
    _stroke(canvas, ops, SOLUTION_RGB, options.solution_line_width)
    canvas.restoreState()
    return drawn


def _draw_start_and_goal(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    s = layout.scale
    sx, sy = layout.to_page(*problem.start)
    canvas.setFillColorRGB(*START_RGB)
    canvas.circle(sx, sy, 3.0, stroke=0, fill=1)
    gx, gy = layout.to_page(*problem.goal)
    canvas.setStrokeColorRGB(*GOAL_RGB)
    canvas.setLineWidth(1.0)
    canvas.circle(gx, gy, 0.1 * s, stroke=1, fill=0)
    if 0.1 * s < 4.0:  # the true circle is too small to see: add a crosshair
        canvas.line(gx - 5, gy, gx + 5, gy)
        canvas.line(gx, gy - 5, gx, gy + 5)


def _draw_corner_cuts(canvas: Canvas, report: ValidationReport, layout: PageLayout) -> None:
    canvas.setStrokeColorRGB(*CORNER_RGB)
    canvas.setLineWidth(1.2)
    for cut in report.corner_cuts[:1000]:
        cx, cy = _marker_position(layout, *cut.where)
        canvas.circle(cx, cy, 4.0, stroke=1, fill=0)


def _draw_failure_mark(canvas: Canvas, layout: PageLayout, x: float, y: float) -> None:
    fx, fy = _marker_position(layout, x, y)
    canvas.setStrokeColorRGB(*FAILURE_RGB)
    canvas.setLineWidth(1.6)
    canvas.line(fx - 6, fy - 6, fx + 6, fy + 6)
    canvas.line(fx - 6, fy + 6, fx + 6, fy - 6)
    canvas.circle(fx, fy, 8.0, stroke=1, fill=0)


def _heading(problem: Problem, vehicle: Vehicle, report: ValidationReport | None,
             problem_label: str) -> str:
    """The line under the verdict: the problem, the vehicle, and -strict if so."""
    return (f"{problem_label or 'problem'}: {problem.width} x {problem.height} map, start "
            f"({problem.start[0]:g}, {problem.start[1]:g}), goal ({problem.goal[0]:g}, "
            f"{problem.goal[1]:g})   vehicle: {vehicle.value}"
            + ("   -strict" if report is not None and report.strict else ""))


def _counts(report: ValidationReport, drawn: int) -> str:
    """The line under the heading: what the output held, and the path length."""
    total_edges = report.plan.tree_count
    counts = f"{report.plan.trajectory_count} trajectory lines, {total_edges} tree edges"
    if drawn < total_edges:
        counts += f" (first {drawn} drawn)"
    if report.path_length is not None:
        counts += f", path length {report.path_length:.4g}"
    return counts


def _draw_line(canvas: Canvas, layout: PageLayout, y: float, text: str, font: str,
               size: float) -> None:
    """One line of text at the left margin, cut to the page's text width."""
    width = layout.page_width - 2 * _MARGIN
    canvas.drawString(_MARGIN, y, _fit(canvas, text, font, size, width))


def _draw_title(canvas: Canvas, layout: PageLayout, verdict: str, heading: str,
                valid: bool) -> None:
    """The verdict (green when valid, red otherwise) and the heading under it."""
    top = layout.page_height - _MARGIN
    canvas.setFillColorRGB(*(VALID_RGB if valid else SOLUTION_RGB))
    canvas.setFont("Helvetica-Bold", 13)
    _draw_line(canvas, layout, top - 13, verdict, "Helvetica-Bold", 13)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 9.5)
    _draw_line(canvas, layout, top - 28, heading, "Helvetica", 9.5)


def _captions(report: ValidationReport | None, notes: Sequence[str]) -> list[str]:
    """The notes, then the first failure (or else the first warning)."""
    captions = list(notes)
    failure = report.first_failure if report is not None else None
    if failure is not None:
        at = f", line {failure.line}" if failure.line is not None else ""
        captions.append(f"First failure (check {failure.number}{at}): {failure.message}")
        if failure.detail:
            captions.append(failure.detail)
    elif report is not None and report.warnings:
        captions.append(f"Warning: {report.warnings[0]}"
                        + (f" (+{len(report.warnings) - 1} more)" if len(report.warnings) > 1
                           else ""))
    return captions


def _draw_captions(canvas: Canvas, layout: PageLayout, captions: Sequence[str],
                   failed: bool) -> None:
    """Up to three caption lines (magenta after a failure), then the legend."""
    canvas.setFont("Helvetica", 8.5)
    canvas.setFillColorRGB(*(FAILURE_RGB if failed else (0.0, 0.0, 0.0)))
    for k, caption in enumerate(captions[:3]):
        _draw_line(canvas, layout, _MARGIN + _CAPTION_BAND - 12 - 11 * k, caption,
                   "Helvetica", 8.5)
    canvas.setFont("Helvetica", 7.5)
    canvas.setFillGray(0.35)
    _draw_line(canvas, layout, _MARGIN - 14, _LEGEND, "Helvetica", 7.5)
