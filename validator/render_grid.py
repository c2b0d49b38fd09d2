"""The grid's tree-viz page (SPEC 3): one vector page cut to the map's shape.

Drawn bottom to top: the grid with blocked cells filled, the tree's edges
(spaceship edges as their 20-slice curves), the solution in red, the start, the
goal circle (radius 0.1), segments that cut a blocked cell's corner, the first
failure; around the map, tick marks labelled in map units (bottom and left
edges); above it the verdict, the problem and the counts; below it the failure's
message and a legend of what the page shows, with a swatch each.

Big maps and trees stay fast and small because the blocked cells (merged into row
runs) and the tree are written as a few long PDF paths, not one object per cell or
edge, with coordinates in page points to two decimals, and a curve's vertices
closer than half a point to the previous one skipped. Time and memory are bounded
whatever the planner printed: the tree and the solution each get a budget of
computed vertices (a point edge costs 2, a spaceship line 21); rows past it are
counted, not drawn, and the counts line says how many were drawn.
"""

from __future__ import annotations

import math
from itertools import islice
from typing import BinaryIO, Iterable, Iterator, Sequence

from reportlab.lib.pagesizes import landscape, letter, portrait
from reportlab.pdfgen.canvas import Canvas

from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from validator.checks import ValidationReport
from validator.render_geometry import (SHIP_POINTS, caption_lines, cell_runs, grid_heading,
                                       grid_solution, grid_tree_edge, rows_in_budget, tick_label,
                                       tick_steps)
from validator.render_page import (AXIS_LEFT, BLOCKED_GRAY, BOTTOM_SPACE, CORNER_RGB, GOAL_RGB,
                                   GRID_GRAY, MARGIN, SOLUTION_RGB, TOP_SPACE, TREE_RGB,
                                   PageLayout, RenderOptions, RenderSummary, draw_captions,
                                   draw_legend, draw_line, draw_no_answer, draw_title,
                                   failure_cross, layout_polyline_ops, start_mark, stroke)

_SIDE_SPACE = 2 * MARGIN + AXIS_LEFT
_MIN_PAGE_WIDTH = 432.0  # 6 in: room for the text lines beside a narrow map
_EDGES_PER_PATH = 10_000
_POINTS_PER_PATH = 50_000
_GOAL_MARK = 7.0  # points: the goal's crosshair arm, when its circle is smaller


def page_layout(problem: Problem, page_size: tuple[float, float] = letter) -> PageLayout:
    """The map as large as ``page_size`` allows in either orientation; the page then
    shrinks to the map plus its bands (never narrower than _MIN_PAGE_WIDTH)."""
    w, h = problem.width, problem.height
    scale = max(min((box_w - _SIDE_SPACE) / w, (box_h - TOP_SPACE - BOTTOM_SPACE) / h)
                for box_w, box_h in (portrait(page_size), landscape(page_size)))
    page_w = max(_MIN_PAGE_WIDTH, scale * w + _SIDE_SPACE)
    page_h = scale * h + TOP_SPACE + BOTTOM_SPACE
    origin_x = MARGIN + AXIS_LEFT + (page_w - _SIDE_SPACE - scale * w) / 2
    return PageLayout(page_w, page_h, origin_x, BOTTOM_SPACE, scale)


def render_grid(out: BinaryIO, problem: Problem, vehicle: Vehicle,
                report: ValidationReport | None, verdict: str, notes: Sequence[str],
                problem_label: str, options: RenderOptions) -> RenderSummary:
    """Write the page into the binary file ``out``; ``report`` None: the problem
    alone, with ``verdict`` and ``notes``."""
    layout = page_layout(problem, options.page_size)
    canvas = Canvas(out, pagesize=(layout.page_width, layout.page_height),
                    pageCompression=1, invariant=1)
    canvas.setTitle(f"rrt-validator: {problem_label or 'problem'} ({vehicle.value})")
    canvas.setCreator("rrt-validator")

    _draw_grid(canvas, problem, layout)
    plan = report.plan if report is not None else None
    summary = RenderSummary(0, 0)
    if plan is not None:
        summary = _draw_plan(canvas, problem, report, vehicle, layout, options)
    else:
        _draw_start_and_goal(canvas, problem, layout)
    if report is not None:
        _draw_corner_cuts(canvas, report, layout)
    failure = report.first_failure if report is not None else None
    marked = failure is not None and failure.where is not None
    if marked:
        _draw_failure_mark(canvas, layout, *failure.where)

    draw_title(canvas, layout, verdict, grid_heading(problem, vehicle, report, problem_label),
               valid=report is not None and report.valid)
    if plan is not None:
        draw_line(canvas, layout, layout.page_height - MARGIN - 41, _counts(report, summary),
                  "Helvetica", 9.5)
    draw_captions(canvas, layout, caption_lines(report, notes), failure is not None)
    draw_legend(canvas, layout, _legend_items(problem, report, summary, marked))
    _draw_axes(canvas, problem, layout)
    if report is None:
        draw_no_answer(canvas, layout.origin_x + layout.scale * problem.width / 2,
                       layout.origin_y + layout.scale * problem.height / 2,
                       min(layout.scale * problem.width, 420.0), notes)
    canvas.showPage()
    canvas.save()
    return summary


def _draw_plan(canvas: Canvas, problem: Problem, report: ValidationReport, vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions) -> RenderSummary:
    """The tree, the start and goal over it, then the solution over them, each within
    its budget."""
    plan = report.plan
    per_edge = SHIP_POINTS if vehicle.is_spaceship else 2
    edges = min(options.max_tree_edges_drawn,
                rows_in_budget(plan.tree_count, options.max_tree_points, per_edge))
    lines = rows_in_budget(plan.trajectory_count, options.max_solution_points,
                           SHIP_POINTS if vehicle.is_spaceship else 1)
    canvas.saveState()
    # Anything far outside the map (bad output) is cut at the page's edge.
    path = canvas.beginPath()
    path.rect(0, 0, layout.page_width, layout.page_height)
    canvas.clipPath(path, stroke=0, fill=0)
    drawn = _draw_tree(canvas, plan.tree_rows(), vehicle, layout, options, edges)
    _draw_start_and_goal(canvas, problem, layout)  # over the tree, under the solution
    _stroke_long_polyline(canvas, grid_solution(report, lines), layout, 0.05, SOLUTION_RGB,
                          options.solution_line_width)
    canvas.restoreState()
    return RenderSummary(drawn, plan.tree_count, lines, plan.trajectory_count)


def _stroke_long_polyline(canvas: Canvas, points: Iterator[tuple[float, float]],
                          layout: PageLayout, spacing: float, rgb: tuple[float, float, float],
                          width: float) -> None:
    """One polyline of any length, written as paths of _POINTS_PER_PATH vertices
    (each starting where the last ended), so no list holds all of it."""
    last: list[tuple[float, float]] = []
    while True:
        chunk = last + list(islice(points, _POINTS_PER_PATH))
        if len(chunk) <= len(last):
            return
        ops: list[str] = []
        finite = layout_polyline_ops(chunk, layout, spacing, ops)
        stroke(canvas, ops, rgb, width)
        if not finite:
            return
        last = chunk[-1:]


def _draw_grid(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    w, h, s = problem.width, problem.height, layout.scale
    ox, oy = layout.origin_x, layout.origin_y
    runs = [f"{ox + s * column:.2f} {oy + s * row:.2f} {s * (end - column):.2f} {s:.2f} re"
            for row, column, end in cell_runs(problem.blocked, w, h)]
    if s >= 3.0:  # grid lines (under the blocked cells) where cells are big enough
        lines = [f"{ox + s * i:.2f} {oy:.2f} m {ox + s * i:.2f} {oy + s * h:.2f} l"
                 for i in range(1, w)]
        lines += [f"{ox:.2f} {oy + s * j:.2f} m {ox + s * w:.2f} {oy + s * j:.2f} l"
                  for j in range(1, h)]
        stroke(canvas, lines, (GRID_GRAY,) * 3, 0.25)
    if runs:
        canvas.saveState()
        canvas.setFillGray(BLOCKED_GRAY)
        canvas.setStrokeGray(BLOCKED_GRAY)  # a hairline of the same grey: no light seams
        canvas.setLineWidth(0.3)            # between cells of neighbouring runs
        for start in range(0, len(runs), _EDGES_PER_PATH):
            canvas.addLiteral("\n".join(runs[start:start + _EDGES_PER_PATH]) + "\nB")
        canvas.restoreState()
    canvas.saveState()
    canvas.setLineWidth(0.8)
    canvas.rect(ox, oy, s * w, s * h, stroke=1, fill=0)
    canvas.restoreState()


def _draw_tree(canvas: Canvas, rows: Iterable[Sequence[float]], vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions, limit: int) -> int:
    ops: list[str] = []
    drawn = 0
    spacing = options.min_vertex_spacing
    for row in rows:
        if drawn >= limit:
            break
        drawn += 1
        layout_polyline_ops(grid_tree_edge(row, vehicle.is_spaceship), layout, spacing, ops)
        if drawn % _EDGES_PER_PATH == 0:
            stroke(canvas, ops, TREE_RGB, options.tree_line_width)
            ops = []
    stroke(canvas, ops, TREE_RGB, options.tree_line_width)
    return drawn


def _marker_position(layout: PageLayout, x: float, y: float) -> tuple[float, float]:
    """A world point on the page, pulled back onto the page if it is far outside."""
    px, py = layout.to_page(x if math.isfinite(x) else 0.0, y if math.isfinite(y) else 0.0)
    return (min(max(px, 6.0), layout.page_width - 6.0),
            min(max(py, 6.0), layout.page_height - 6.0))


def _draw_start_and_goal(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    """The goal circle (radius 0.1; a crosshair over it when that is small) and the
    start's dot, each over a white halo so that a dense tree does not hide them."""
    gx, gy = layout.to_page(*problem.goal)
    radius = 0.1 * layout.scale
    arm = _GOAL_MARK if radius < 4.0 else 0.0
    canvas.saveState()
    canvas.setLineCap(1)
    for rgb, width in (((1.0, 1.0, 1.0), 5.0), (GOAL_RGB, 1.4)):
        canvas.setStrokeColorRGB(*rgb)
        canvas.setLineWidth(width)
        canvas.circle(gx, gy, radius, stroke=1, fill=0)
        if arm:
            canvas.line(gx - arm, gy, gx + arm, gy)
            canvas.line(gx, gy - arm, gx, gy + arm)
    canvas.restoreState()
    start_mark(canvas, *layout.to_page(*problem.start))


def _draw_corner_cuts(canvas: Canvas, report: ValidationReport, layout: PageLayout) -> None:
    canvas.setStrokeColorRGB(*CORNER_RGB)
    canvas.setLineWidth(1.2)
    for cut in report.corner_cuts[:1000]:
        cx, cy = _marker_position(layout, *cut.where)
        canvas.circle(cx, cy, 4.0, stroke=1, fill=0)


def _draw_failure_mark(canvas: Canvas, layout: PageLayout, x: float, y: float) -> None:
    fx, fy = _marker_position(layout, x, y)
    failure_cross(canvas, fx, fy, 6.0)


def _ticks(limit: int, step: float) -> list[float]:
    count = int(math.floor(limit / step + 1e-9))
    return [k * step for k in range(count + 1)]


def _draw_axes(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    """Ticks out of the bottom and left edges, labelled in map units; unlabelled
    ticks between (the half-way one longer when they are tenths)."""
    step, minor = tick_steps(layout.scale)
    ox, oy, s = layout.origin_x, layout.origin_y, layout.scale
    tenths = minor is not None and math.isclose(step / minor, 10)
    ops = []
    for limit, along_x in ((problem.width, True), (problem.height, False)):
        ticks = [(value, 4.0) for value in _ticks(limit, step)]
        if minor is not None:
            ticks += [(value, 3.0 if tenths and k % 5 == 0 else 2.0)
                      for k, value in enumerate(_ticks(limit, minor)) if k % 10 or not tenths]
        for value, length in ticks:
            p = (ox if along_x else oy) + s * value
            ops.append(f"{p:.2f} {oy:.2f} m {p:.2f} {oy - length:.2f} l" if along_x
                       else f"{ox:.2f} {p:.2f} m {ox - length:.2f} {p:.2f} l")
    stroke(canvas, ops, (0.0, 0.0, 0.0), 0.5)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 7.5)
    for value in _ticks(problem.width, step):
        canvas.drawCentredString(ox + s * value, oy - 4.0 - 8.5, tick_label(value))
    for value in _ticks(problem.height, step):
        canvas.drawRightString(ox - 6.0, oy + s * value - 2.6, tick_label(value))


def _legend_items(problem: Problem, report: ValidationReport | None, summary: RenderSummary,
                  marked: bool) -> list[tuple[str, str]]:
    """(swatch kind, label) for what is on the page, nothing else."""
    items = []
    if summary.solution_lines_drawn:
        items.append(("solution", "red: solution"))
    if summary.tree_edges_drawn:
        items.append(("tree", "blue-grey: tree edges"))
    items += [("start", "green dot: start"), ("goal", "blue circle: goal (radius 0.1)")]
    if marked:
        items.append(("failure", "magenta cross: first failure"))
    if report is not None and report.corner_cuts:
        items.append(("corner", "orange circle: corner cut"))
    if any(problem.blocked):
        items.append(("blocked", "grey: blocked cell"))
    return items


def _counts(report: ValidationReport, summary: RenderSummary) -> str:
    """The line under the heading: what the output held, what of it is drawn, and
    the path length."""
    lines, edges = summary.solution_lines_total, summary.tree_edges_total
    counts = f"{lines} trajectory lines"
    if summary.solution_lines_drawn < lines:
        counts += f" (first {summary.solution_lines_drawn} drawn)"
    counts += f", {edges} tree edges"
    if summary.tree_edges_drawn < edges:
        counts += f" (first {summary.tree_edges_drawn} drawn)"
    if report.path_length is not None:
        counts += f", path length {report.path_length:.4g}"
    return counts
