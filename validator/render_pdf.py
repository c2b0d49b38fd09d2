"""The tree-viz PDF (SPEC 3): one vector page cut to the map's shape.

Drawn bottom to top: the grid with blocked cells filled, the tree's edges
(spaceship edges as their 20-slice curves), the solution in red, the start, the
goal circle (radius 0.1), segments that cut a blocked cell's corner, the first
failure; around the map, tick marks labelled in map units (bottom and left
edges); above it the verdict, the problem and the counts; below it the failure's
message and a legend of what the page shows, with a swatch each.

A ``kinoplan 1`` problem gets the family's pages instead (render_family). The
rendering modules (this one, render_family, render_geometric, render_plot) are
the only ones that import reportlab. Big maps and trees stay fast and small
because the blocked cells (merged into row runs) and the tree are written as a
few long PDF paths, not one object per cell or edge, with coordinates in page
points to two decimals, and a curve's vertices closer than half a point to the
previous one skipped. Time and memory are bounded whatever the planner printed:
the tree and the solution each get a budget of computed vertices (a point edge
costs 2, a spaceship line 21); rows past it are counted, not drawn, and the
counts line says how many were drawn.

Given a path, the page is written to a temporary file in the same folder and
renamed over the path only when complete: a reader (or a second validator
writing the same path) never sees half a file, and a failed render leaves none.
"""

from __future__ import annotations

import math
import os
import stat
import tempfile
from dataclasses import dataclass
from itertools import islice
from typing import BinaryIO, Iterable, Iterator, Sequence

from reportlab import rl_config
from reportlab.lib.pagesizes import landscape, letter, portrait
from reportlab.pdfgen.canvas import Canvas

from planning_core.kinoplan import KinoplanProblem
from planning_core.problem import Problem
from planning_core.systems import spaceship
from planning_core.vehicles import Vehicle
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
FOOTPRINT_RGB = (0.95, 0.55, 0.60)  # the family's bodies along a solution
OBSTACLE_GRAY = 0.55               # the family's obstacles

_MARGIN = 24.0
_TITLE_BAND = 56.0      # verdict, heading, counts
_AXIS_LEFT = 26.0       # tick marks and their labels left of the map
_AXIS_BOTTOM = 16.0     # ... and below it
_CAPTION_LINES = 3
_CAPTION_STEP = 11.0
_LEGEND_ROWS = 2
_LEGEND_STEP = 12.0
_BOTTOM_SPACE = (_MARGIN + _LEGEND_ROWS * _LEGEND_STEP + 4 + _CAPTION_LINES * _CAPTION_STEP
                 + 4 + _AXIS_BOTTOM)
_TOP_SPACE = _MARGIN + _TITLE_BAND
_SIDE_SPACE = 2 * _MARGIN + _AXIS_LEFT
_MIN_PAGE_WIDTH = 432.0  # 6 in: room for the text lines beside a narrow map
_MIN_TICK_GAP = 30.0     # points between labelled ticks, at least
_EDGES_PER_PATH = 10_000
_POINTS_PER_PATH = 50_000
_FAR = 30_000.0  # page coordinates are clamped here: PDF readers dislike huge numbers
_SHIP_POINTS = 1 + spaceship.SLICES  # a spaceship line drawn: its state and every slice


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
    """The map as large as ``page_size`` allows in either orientation; the page then
    shrinks to the map plus its bands (never narrower than _MIN_PAGE_WIDTH)."""
    w, h = problem.width, problem.height
    scale = max(min((box_w - _SIDE_SPACE) / w, (box_h - _TOP_SPACE - _BOTTOM_SPACE) / h)
                for box_w, box_h in (portrait(page_size), landscape(page_size)))
    page_w = max(_MIN_PAGE_WIDTH, scale * w + _SIDE_SPACE)
    page_h = scale * h + _TOP_SPACE + _BOTTOM_SPACE
    origin_x = _MARGIN + _AXIS_LEFT + (page_w - _SIDE_SPACE - scale * w) / 2
    return PageLayout(page_w, page_h, origin_x, _BOTTOM_SPACE, scale)


@dataclass(frozen=True)
class RenderSummary:
    tree_edges_drawn: int
    tree_edges_total: int
    solution_lines_drawn: int = 0
    solution_lines_total: int = 0


def _polyline_ops(points: Iterable[tuple[float, float]], layout: PageLayout,
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
        finite = _polyline_ops(chunk, layout, spacing, ops)
        _stroke(canvas, ops, rgb, width)
        if not finite:
            return
        last = chunk[-1:]


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
    if s >= 3.0:  # grid lines (under the blocked cells) where cells are big enough
        lines = [f"{ox + s * i:.2f} {oy:.2f} m {ox + s * i:.2f} {oy + s * h:.2f} l"
                 for i in range(1, w)]
        lines += [f"{ox:.2f} {oy + s * j:.2f} m {ox + s * w:.2f} {oy + s * j:.2f} l"
                  for j in range(1, h)]
        _stroke(canvas, lines, (GRID_GRAY,) * 3, 0.25)
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


def _rows_in_budget(count: int, budget: int, points_per_row: int) -> int:
    return max(0, min(count, budget // points_per_row))


def _draw_tree(canvas: Canvas, rows: Iterable[Sequence[float]], vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions, limit: int) -> int:
    ops: list[str] = []
    drawn = 0
    slice_states = spaceship.SYSTEM.slice_states
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


def _solution_iter(report: ValidationReport, lines: int) -> Iterator[tuple[float, float]]:
    """The first ``lines`` lines of the solution as flown: the printed points (point
    vehicle), or each line's state and every slice of its control (spaceship)."""
    plan = report.plan
    if plan is None:
        return
    rows = islice(plan.trajectory_rows(), lines)
    if not report.vehicle.is_spaceship:
        yield from ((r[0], r[1]) for r in rows)
        return
    slice_states = spaceship.SYSTEM.slice_states
    for row in rows:
        yield row[0], row[1]
        if all(map(math.isfinite, row)):
            yield from ((s[0], s[1]) for s in slice_states(row[:4], row[4:]))


def solution_points(report: ValidationReport, max_lines: int | None = None
                    ) -> list[tuple[float, float]]:
    """The solution as flown (see _solution_iter), its first ``max_lines`` lines or all."""
    count = report.plan.trajectory_count if report.plan is not None else 0
    return list(_solution_iter(report, count if max_lines is None else max_lines))


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


def render_pdf(out: BinaryIO | str | os.PathLike, problem: Problem, vehicle: Vehicle,
               report: ValidationReport | None, verdict: str, notes: Sequence[str] = (),
               problem_label: str = "", options: RenderOptions = RenderOptions()
               ) -> RenderSummary:
    """Write the page to ``out``: a binary file, or a path, written atomically (a
    temporary file in the same folder, renamed over it when complete; removed if
    the render fails, the exception then raised as it was).

    ``report`` is None when there is nothing to validate (the planner timed out or
    could not start): the page then shows the problem, ``verdict`` and ``notes``.
    """
    if isinstance(out, (str, os.PathLike)):
        return _render_to_path(os.fspath(out), problem, vehicle, report, verdict, notes,
                               problem_label, options)
    # Binary (zlib only) streams: reportlab's ASCII85 step is pure Python, slower
    # than all the drawing, and makes the file a quarter bigger.
    saved_a85, rl_config.useA85 = rl_config.useA85, 0
    try:
        if isinstance(problem, KinoplanProblem):  # the family's pages (``vehicle`` unused)
            from validator.render_family import render_family
            return render_family(out, problem, report, verdict, notes, problem_label, options)
        return _render(out, problem, vehicle, report, verdict, notes, problem_label, options)
    finally:
        rl_config.useA85 = saved_a85


def _render_to_path(path: str, *args) -> RenderSummary:
    """render_pdf into a temporary file beside ``path``, then os.replace; the mode is
    what ``open`` would give. A device, FIFO or /proc path, or a folder we cannot
    create a file in (the file itself may still be writable), is written directly."""
    temporary = _temporary_beside(path)
    if temporary is None:
        with open(path, "wb") as out:
            return render_pdf(out, *args)
    fd, temporary_path, target = temporary
    try:
        with os.fdopen(fd, "wb") as out:
            summary = render_pdf(out, *args)
        os.chmod(temporary_path, _new_file_mode(target))
        os.replace(temporary_path, target)
    except BaseException:
        try:
            os.unlink(temporary_path)
        except OSError:
            pass
        raise
    return summary


def _temporary_beside(path: str) -> tuple[int, str, str] | None:
    """(fd, name) of a new temporary file in the folder of ``path``'s target (through
    symlinks, as ``open`` writes) and that target; None when ``path`` is not a
    regular file (nor absent) or no file can be made there."""
    if os.path.abspath(path).startswith(("/dev/", "/proc/")):
        return None
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
    except FileNotFoundError:
        pass
    except OSError:
        return None
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    try:
        fd, temporary_path = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    except OSError:
        return None
    return fd, temporary_path, target


def _new_file_mode(target: str) -> int:
    """The existing file's permissions, or 0o666 less the umask (mkstemp gives 0o600)."""
    try:
        return os.stat(target).st_mode & 0o7777
    except OSError:
        pass
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask


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
    summary = RenderSummary(0, 0)
    if plan is not None:
        summary = _draw_plan(canvas, report, vehicle, layout, options)
    _draw_start_and_goal(canvas, problem, layout)
    if report is not None:
        _draw_corner_cuts(canvas, report, layout)
    failure = report.first_failure if report is not None else None
    marked = failure is not None and failure.where is not None
    if marked:
        _draw_failure_mark(canvas, layout, *failure.where)

    _draw_title(canvas, layout, verdict, _heading(problem, vehicle, report, problem_label),
                valid=report is not None and report.valid)
    if plan is not None:
        _draw_line(canvas, layout, layout.page_height - _MARGIN - 41, _counts(report, summary),
                   "Helvetica", 9.5)
    _draw_captions(canvas, layout, _captions(report, notes), failure is not None)
    _draw_legend(canvas, layout, _legend_items(problem, report, summary, marked))
    _draw_axes(canvas, problem, layout)
    canvas.showPage()
    canvas.save()
    return summary


def _draw_plan(canvas: Canvas, report: ValidationReport, vehicle: Vehicle,
               layout: PageLayout, options: RenderOptions) -> RenderSummary:
    """The tree, then the solution over it, each within its budget."""
    plan = report.plan
    per_edge = _SHIP_POINTS if vehicle.is_spaceship else 2
    edges = min(options.max_tree_edges_drawn,
                _rows_in_budget(plan.tree_count, options.max_tree_points, per_edge))
    lines = _rows_in_budget(plan.trajectory_count, options.max_solution_points,
                            _SHIP_POINTS if vehicle.is_spaceship else 1)
    canvas.saveState()
    # Anything far outside the map (bad output) is cut at the page's edge.
    path = canvas.beginPath()
    path.rect(0, 0, layout.page_width, layout.page_height)
    canvas.clipPath(path, stroke=0, fill=0)
    drawn = _draw_tree(canvas, plan.tree_rows(), vehicle, layout, options, edges)
    _stroke_long_polyline(canvas, _solution_iter(report, lines), layout, 0.05, SOLUTION_RGB,
                          options.solution_line_width)
    canvas.restoreState()
    return RenderSummary(drawn, plan.tree_count, lines, plan.trajectory_count)


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
    _failure_cross(canvas, fx, fy, 6.0)


def _failure_cross(canvas: Canvas, x: float, y: float, arm: float) -> None:
    canvas.saveState()
    canvas.setStrokeColorRGB(*FAILURE_RGB)
    canvas.setLineWidth(1.6 * arm / 6.0)
    canvas.line(x - arm, y - arm, x + arm, y + arm)
    canvas.line(x - arm, y + arm, x + arm, y - arm)
    canvas.circle(x, y, arm * 4 / 3, stroke=1, fill=0)
    canvas.restoreState()


def _tick_steps(scale: float) -> tuple[float, float | None]:
    """The labelled step in map units (1, 2 or 5 times a power of ten, at least
    _MIN_TICK_GAP points apart) and the unlabelled one between (None if under 4 pt)."""
    raw = _MIN_TICK_GAP / scale
    power = 10.0 ** math.floor(math.log10(raw))
    mantissa = next(m for m in (1, 2, 5, 10) if m * power >= raw * (1 - 1e-9))
    step = mantissa * power
    for divisor in ((10, 5, 2) if mantissa in (1, 5, 10) else (4, 2)):
        if step / divisor * scale >= 4.0:
            return step, step / divisor
    return step, None


def _ticks(limit: int, step: float) -> list[float]:
    count = int(math.floor(limit / step + 1e-9))
    return [k * step for k in range(count + 1)]


def _tick_label(value: float) -> str:
    return f"{round(value, 9):g}"


def _draw_axes(canvas: Canvas, problem: Problem, layout: PageLayout) -> None:
    """Ticks out of the bottom and left edges, labelled in map units; unlabelled
    ticks between (the half-way one longer when they are tenths)."""
    step, minor = _tick_steps(layout.scale)
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
    _stroke(canvas, ops, (0.0, 0.0, 0.0), 0.5)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 7.5)
    for value in _ticks(problem.width, step):
        canvas.drawCentredString(ox + s * value, oy - 4.0 - 8.5, _tick_label(value))
    for value in _ticks(problem.height, step):
        canvas.drawRightString(ox - 6.0, oy + s * value - 2.6, _tick_label(value))


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


def _draw_swatch(canvas: Canvas, kind: str, x: float, y: float) -> None:
    """A 14 x 8 point sample of ``kind`` with its lower left corner at (x, y)."""
    canvas.saveState()
    cx, cy = x + 7.0, y + 4.0
    if kind in ("solution", "tree", "pose"):
        rgb, width = {"solution": (SOLUTION_RGB, 1.8), "tree": (TREE_RGB, 1.0),
                      "pose": (FOOTPRINT_RGB, 1.6)}[kind]
        canvas.setStrokeColorRGB(*rgb)
        canvas.setLineWidth(width)
        canvas.setLineCap(1)
        canvas.line(x + 1, cy, x + 13, cy)
    elif kind == "start":
        canvas.setFillColorRGB(*START_RGB)
        canvas.circle(cx, cy, 3.0, stroke=0, fill=1)
    elif kind in ("goal", "corner"):
        canvas.setStrokeColorRGB(*(GOAL_RGB if kind == "goal" else CORNER_RGB))
        canvas.setLineWidth(1.0 if kind == "goal" else 1.2)
        canvas.circle(cx, cy, 3.5, stroke=1, fill=0)
    elif kind == "failure":
        _failure_cross(canvas, cx, cy, 3.0)
    elif kind in ("blocked", "obstacle"):
        canvas.setFillGray(BLOCKED_GRAY if kind == "blocked" else OBSTACLE_GRAY)
        canvas.rect(x + 3, y, 8, 8, stroke=0, fill=1)
    elif kind == "footprint":
        canvas.setStrokeColorRGB(*FOOTPRINT_RGB)
        canvas.setLineWidth(1.0)
        canvas.rect(x + 3, y + 1, 8, 6, stroke=1, fill=0)
    canvas.restoreState()


def _draw_legend(canvas: Canvas, layout: PageLayout, items: list[tuple[str, str]]) -> None:
    """The items left to right, in up to _LEGEND_ROWS rows at the bottom of the page."""
    font, size = "Helvetica", 7.5
    canvas.setFont(font, size)
    canvas.setFillGray(0.25)
    right = layout.page_width - _MARGIN
    x, row = _MARGIN, 0
    for kind, label in items:
        width = 17.0 + canvas.stringWidth(label, font, size)
        if x + width > right and x > _MARGIN:
            x, row = _MARGIN, row + 1
        if row >= _LEGEND_ROWS:
            return
        y = _MARGIN + (_LEGEND_ROWS - 1 - row) * _LEGEND_STEP
        _draw_swatch(canvas, kind, x, y - 1.0)
        canvas.drawString(x + 17.0, y, label)
        x += width + 12.0


def _heading(problem: Problem, vehicle: Vehicle, report: ValidationReport | None,
             problem_label: str) -> str:
    """The line under the verdict: the problem, the vehicle, and -strict if so."""
    return (f"{problem_label or 'problem'}: {problem.width} x {problem.height} map, start "
            f"({problem.start[0]:g}, {problem.start[1]:g}), goal ({problem.goal[0]:g}, "
            f"{problem.goal[1]:g})   vehicle: {vehicle.value}"
            + ("   -strict" if report is not None and report.strict else ""))


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
    """Up to _CAPTION_LINES lines (magenta after a failure) under the map's labels."""
    canvas.setFont("Helvetica", 8.5)
    canvas.setFillColorRGB(*(FAILURE_RGB if failed else (0.0, 0.0, 0.0)))
    top = layout.origin_y - _AXIS_BOTTOM - 4 - 8.5
    for k, caption in enumerate(captions[:_CAPTION_LINES]):
        _draw_line(canvas, layout, top - _CAPTION_STEP * k, caption, "Helvetica", 8.5)
