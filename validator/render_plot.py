"""Plot pieces for the family's PDF pages (render_kinodynamic, render_geometric).

A :class:`Frame` maps a data box (the workspace, the phase plane, the torus's
square, time against a variable) into a rectangle of the page; everything is
drawn clipped to it. Angle axes wrap: a polyline is unwrapped along its points
and drawn once per turn it reaches into the frame, so a segment that crosses
pi shows split at the frame's edges. The page's text bands, legend, tick steps
and polyline writer are render_page's, so the grid's and the family's PDFs read
alike.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, Sequence

from reportlab.lib.pagesizes import landscape, letter, portrait
from reportlab.pdfgen.canvas import Canvas

from planning_core.worlds.shapes import ConvexPolygon, Disc, Rect
from validator.render_geometry import (TAU, axis_ticks, caption_lines, front_mark, goal_shape,
                                       turns, unwrapped, wrapped)
from validator.render_page import (AXIS_LEFT, BOTTOM_SPACE, FOOTPRINT_FILL_RGB, FOOTPRINT_RGB,
                                   GOAL_RGB, HEADING_RGB, MARGIN, OBSTACLE_GRAY, TOP_SPACE,
                                   PageLayout, draw_captions, draw_legend, draw_line,
                                   draw_no_answer, draw_title, failure_cross,
                                   layout_polyline_ops, start_mark, stroke, stroke_ops)

PAGE = landscape(letter)
_IDENTITY = PageLayout(0.0, 0.0, 0.0, 0.0, 1.0)
_MAX_TURNS = 4  # a polyline reaching over more turns than this of an angle is not drawn
_NAME_ROOM = 28.0  # right of the plot area: the x axis's name
_PLOT_TOP = 12.0   # above the plot area: the y axis's name
_SIDE_SPACE = MARGIN + AXIS_LEFT + 6.0 + MARGIN + _NAME_ROOM
_MIN_PAGE_WIDTH = 432.0  # 6 in: room for the text lines beside a narrow plot


@dataclass(frozen=True)
class Frame:
    """The data box ``[x0, x1] x [y0, y1]`` drawn in the page rectangle at
    ``(left, bottom)`` of ``width`` x ``height`` points; angle axes wrap."""

    x0: float
    y0: float
    x1: float
    y1: float
    left: float
    bottom: float
    width: float
    height: float
    angle_x: bool = False
    angle_y: bool = False

    @property
    def sx(self) -> float:
        return self.width / (self.x1 - self.x0)

    @property
    def sy(self) -> float:
        return self.height / (self.y1 - self.y0)

    def to_page(self, x: float, y: float) -> tuple[float, float]:
        return self.left + (x - self.x0) * self.sx, self.bottom + (y - self.y0) * self.sy

    def clamped(self, x: float, y: float) -> tuple[float, float]:
        """A data point on the page, pulled into the frame when it is outside it."""
        px, py = self.to_page(x if math.isfinite(x) else self.x0,
                              y if math.isfinite(y) else self.y0)
        return (min(max(px, self.left), self.left + self.width),
                min(max(py, self.bottom), self.bottom + self.height))


def plot_area(page: tuple[float, float] = PAGE) -> tuple[float, float, float, float]:
    """``(left, bottom, width, height)`` of the page's room for plots."""
    left = MARGIN + AXIS_LEFT + 6.0
    return (left, BOTTOM_SPACE, page[0] - left - MARGIN - _NAME_ROOM,
            page[1] - TOP_SPACE - BOTTOM_SPACE - _PLOT_TOP)


def page_for(box: tuple[float, float, float, float]) -> tuple[float, float]:
    """The page for one plot of ``box`` at one scale for both axes: as large as letter
    allows in either orientation, then cut to the plot's shape (a square workspace on
    a page of its own shape, not in the middle of a landscape page)."""
    w, h = box[2] - box[0], box[3] - box[1]
    vertical = TOP_SPACE + BOTTOM_SPACE + _PLOT_TOP
    scale = max(min((page_w - _SIDE_SPACE) / w, (page_h - vertical) / h)
                for page_w, page_h in (portrait(letter), landscape(letter)))
    return max(_MIN_PAGE_WIDTH, scale * w + _SIDE_SPACE), scale * h + vertical


def frame_in(box: tuple[float, float, float, float], area, equal: bool = True,
             angle_x: bool = False, angle_y: bool = False) -> Frame:
    """``box`` fitted into ``area`` (centred; one scale for both axes if ``equal``)."""
    x0, y0, x1, y1 = box
    left, bottom, width, height = area
    if equal:
        scale = min(width / (x1 - x0), height / (y1 - y0))
        w, h = scale * (x1 - x0), scale * (y1 - y0)
        left, bottom, width, height = left + (width - w) / 2, bottom + (height - h) / 2, w, h
    return Frame(x0, y0, x1, y1, left, bottom, width, height, angle_x, angle_y)


# ----- the page: text bands, clipping, axes ----------------------------------------------

@dataclass(frozen=True)
class PageText:
    """What every page of one PDF says around its plots."""

    verdict: str
    heading: str
    valid: bool
    captions: tuple[str, ...]
    failed: bool


def page_text(report, verdict: str, heading: str, notes: Sequence[str]) -> PageText:
    failure = report.first_failure if report is not None else None
    return PageText(verdict, heading, report is not None and report.valid,
                    tuple(caption_lines(report, notes)), failure is not None)


def draw_page_text(canvas: Canvas, text: PageText, what: str,
                   legend: list[tuple[str, str]], page: tuple[float, float] = PAGE) -> None:
    """Verdict, heading and ``what`` this page shows above; failure and legend below."""
    layout = PageLayout(page[0], page[1], 0.0, BOTTOM_SPACE, 1.0)
    draw_title(canvas, layout, text.verdict, text.heading, text.valid)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 8.5)
    draw_line(canvas, layout, page[1] - MARGIN - 41, what, "Helvetica", 8.5)
    draw_captions(canvas, layout, text.captions, text.failed)
    draw_legend(canvas, layout, legend)


def new_page(canvas: Canvas, box: tuple[float, float, float, float], **angles: bool
             ) -> tuple[tuple[float, float], Frame]:
    """Start a page shaped to ``box`` (page_for); the page size and the box's frame."""
    page = page_for(box)
    canvas.setPageSize(page)
    return page, frame_in(box, plot_area(page), **angles)


def no_answer(canvas: Canvas, frame: Frame, report, text: PageText) -> None:
    """Over the plot of a run with nothing to draw: why (the notes)."""
    if report is None:
        draw_no_answer(canvas, frame.left + frame.width / 2, frame.bottom + frame.height / 2,
                       min(frame.width, 420.0), text.captions)


def clip_to(canvas: Canvas, frame: Frame) -> None:
    """Clip what follows to the frame (the caller restores the state)."""
    canvas.saveState()
    path = canvas.beginPath()
    path.rect(frame.left, frame.bottom, frame.width, frame.height)
    canvas.clipPath(path, stroke=0, fill=0)


def draw_axes(canvas: Canvas, frame: Frame, x_name: str, y_name: str,
              x_labels: bool = True, y_gap: float = 30.0) -> None:
    """The frame's border; ticks out of its bottom and left edges, labelled in data
    units (angles at multiples of pi/2); the axes' names at their ends."""
    canvas.saveState()
    canvas.setLineWidth(0.8)
    canvas.setStrokeGray(0.0)
    canvas.rect(frame.left, frame.bottom, frame.width, frame.height, stroke=1, fill=0)
    xs = axis_ticks(frame.x0, frame.x1, frame.sx, frame.angle_x, 30.0)
    ys = axis_ticks(frame.y0, frame.y1, frame.sy, frame.angle_y, y_gap)
    ops = [f"{frame.to_page(v, 0)[0]:.2f} {frame.bottom:.2f} m "
           f"{frame.to_page(v, 0)[0]:.2f} {frame.bottom - 4:.2f} l" for v, _ in xs]
    ops += [f"{frame.left:.2f} {frame.to_page(0, v)[1]:.2f} m "
            f"{frame.left - 4:.2f} {frame.to_page(0, v)[1]:.2f} l" for v, _ in ys]
    stroke(canvas, ops, (0.0, 0.0, 0.0), 0.5)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 7.5)
    if x_labels:
        for value, label in xs:
            canvas.drawCentredString(frame.to_page(value, 0)[0], frame.bottom - 12.5, label)
        canvas.drawString(frame.left + frame.width + 6, frame.bottom - 2.6, x_name)
    for value, label in ys:
        canvas.drawRightString(frame.left - 6, frame.to_page(0, value)[1] - 2.6, label)
    canvas.setFont("Helvetica-Bold", 8)
    canvas.drawString(frame.left + 2, frame.bottom + frame.height + 3, y_name)
    canvas.restoreState()


# ----- polylines, wrapping ----------------------------------------------------------------

def polyline_ops(frame: Frame, points: Iterable[tuple[float, float]], out: list[str],
                 spacing: float = 0.5) -> bool:
    """Append a polyline in data coordinates, once per turn of each angle axis it
    reaches into the frame; False when it is not drawn (not finite, too many turns)."""
    points = unwrapped(points, frame.angle_x, frame.angle_y)
    if not points:
        return False
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    turns_x = turns(min(xs), max(xs), frame.angle_x)
    turns_y = turns(min(ys), max(ys), frame.angle_y)
    if len(turns_x) > _MAX_TURNS or len(turns_y) > _MAX_TURNS:
        return False
    left, bottom, sx, sy = frame.left, frame.bottom, frame.sx, frame.sy
    for kx in turns_x:
        for ky in turns_y:
            dx, dy = kx * TAU - frame.x0, ky * TAU - frame.y0
            layout_polyline_ops([(left + (x + dx) * sx, bottom + (y + dy) * sy) for x, y in points],
                                _IDENTITY, spacing, out)
    return True


# ----- shapes -----------------------------------------------------------------------------

def _polygon_path(canvas: Canvas, frame: Frame, points: Sequence[tuple[float, float]]):
    path = canvas.beginPath()
    path.moveTo(*frame.to_page(*points[0]))
    for point in points[1:]:
        path.lineTo(*frame.to_page(*point))
    path.close()
    return path


def draw_obstacles(canvas: Canvas, frame: Frame, world) -> None:
    """The obstacles filled grey, the world box outlined."""
    canvas.saveState()
    canvas.setFillGray(OBSTACLE_GRAY)
    canvas.setStrokeGray(OBSTACLE_GRAY)
    canvas.setLineWidth(0.3)
    for obstacle in world.obstacles:
        if isinstance(obstacle, Rect):
            x, y = frame.to_page(obstacle.x0, obstacle.y0)
            canvas.rect(x, y, (obstacle.x1 - obstacle.x0) * frame.sx,
                        (obstacle.y1 - obstacle.y0) * frame.sy, stroke=1, fill=1)
        elif isinstance(obstacle, Disc):
            canvas.circle(*frame.to_page(obstacle.cx, obstacle.cy), obstacle.r * frame.sx,
                          stroke=1, fill=1)
        elif isinstance(obstacle, ConvexPolygon):
            canvas.drawPath(_polygon_path(canvas, frame, obstacle.points), stroke=1, fill=1)
    if world.box is not None:
        box = world.box
        canvas.setStrokeGray(0.0)
        canvas.setLineWidth(1.0)
        x, y = frame.to_page(box.x0, box.y0)
        canvas.rect(x, y, (box.x1 - box.x0) * frame.sx, (box.y1 - box.y0) * frame.sy,
                    stroke=1, fill=0)
    canvas.restoreState()


def _polygon_ops(frame: Frame, polygons: Iterable[ConvexPolygon]) -> list[str]:
    ops: list[str] = []
    for polygon in polygons:
        points = polygon.points
        layout_polyline_ops([frame.to_page(*p) for p in (*points, points[0])], _IDENTITY, 0.0,
                            ops)
    return ops


def draw_polygons(canvas: Canvas, frame: Frame, polygons: Iterable[ConvexPolygon], rgb,
                  width: float, dash: Sequence[float] = ()) -> None:
    """Outlines of placed bodies (footprints), one path."""
    stroke_ops(canvas, _polygon_ops(frame, polygons), rgb, width, dash=dash)


def draw_bodies(canvas: Canvas, frame: Frame, system, states: Sequence, outline=FOOTPRINT_RGB,
                fill=FOOTPRINT_FILL_RGB, width: float = 0.8) -> None:
    """The body at each state, its footprint filled (half see-through) and outlined."""
    if not states:
        return
    ops = _polygon_ops(frame, [system.footprint(s) for s in states])
    canvas.saveState()
    canvas.setFillColorRGB(*fill)
    canvas.setFillAlpha(0.6)
    canvas.addLiteral("\n".join(ops) + "\nf")  # a few dozen bodies (FamilyOptions)
    canvas.restoreState()
    stroke_ops(canvas, ops, outline, width)


def draw_headings(canvas: Canvas, frame: Frame, system, states: Sequence,
                  width: float = 1.6) -> None:
    """Each body's front edge in a dark line: which way it faces (over the solution,
    across it)."""
    marks: list[str] = []
    for state in states:
        layout_polyline_ops([frame.to_page(*p) for p in front_mark(system, state)], _IDENTITY,
                            0.0, marks)
    stroke_ops(canvas, marks, HEADING_RGB, width)


def draw_dot(canvas: Canvas, frame: Frame, point: tuple[float, float], rgb,
             radius: float = 3.0) -> None:
    canvas.saveState()
    canvas.setFillColorRGB(*rgb)
    canvas.circle(*frame.clamped(*point), radius, stroke=0, fill=1)
    canvas.restoreState()


def draw_start(canvas: Canvas, frame: Frame, point: tuple[float, float]) -> None:
    start_mark(canvas, *frame.clamped(wrapped(point[0], frame.angle_x),
                                      wrapped(point[1], frame.angle_y)))


def draw_failure(canvas: Canvas, frame: Frame, where: tuple[float, float] | None) -> None:
    if where is not None:
        x, y = where
        failure_cross(canvas, *frame.clamped(wrapped(x, frame.angle_x),
                                             wrapped(y, frame.angle_y)), 6.0)


# ----- the goal region --------------------------------------------------------------------

def draw_goal(canvas: Canvas, frame: Frame, goal, i: int, j: int, rays: int) -> bool:
    """The goal region in blue (a crosshair over it when it is tiny); False when the
    goal names neither plotted variable."""
    lines, reach = goal_shape(goal, i, j, rays, (frame.x0, frame.y0, frame.x1, frame.y1))
    if not lines:
        return False
    ops: list[str] = []
    for line in lines:
        polyline_ops(frame, line, ops, 0.0)
    stroke_ops(canvas, ops, GOAL_RGB, 1.0)
    if reach is not None and reach * frame.sx < 4.0:
        x, y = frame.to_page(wrapped(goal.target[i], frame.angle_x),
                             wrapped(goal.target[j], frame.angle_y))
        stroke(canvas, [f"{x - 6:.2f} {y:.2f} m {x + 6:.2f} {y:.2f} l",
                        f"{x:.2f} {y - 6:.2f} m {x:.2f} {y + 6:.2f} l"], GOAL_RGB, 1.0)
    return True
