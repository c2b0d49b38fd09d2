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

from reportlab.lib.pagesizes import landscape, letter
from reportlab.pdfgen.canvas import Canvas

from planning_core.worlds.shapes import ConvexPolygon, Disc, Rect
from validator.render_page import (AXIS_LEFT, BOTTOM_SPACE, GOAL_RGB, MARGIN, OBSTACLE_GRAY,
                                   TOP_SPACE, PageLayout, caption_lines, draw_captions,
                                   draw_legend, draw_line, draw_title, failure_cross,
                                   layout_polyline_ops, stroke, tick_label, tick_steps)

TAU = 2.0 * math.pi
PAGE = landscape(letter)
_IDENTITY = PageLayout(0.0, 0.0, 0.0, 0.0, 1.0)
_MAX_TURNS = 4  # a polyline reaching over more turns than this of an angle is not drawn
_NAME_ROOM = 28.0  # right of the plot area: the x axis's name


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


def plot_area() -> tuple[float, float, float, float]:
    """``(left, bottom, width, height)`` of the page's room for plots."""
    left = MARGIN + AXIS_LEFT + 6.0
    return (left, BOTTOM_SPACE, PAGE[0] - left - MARGIN - _NAME_ROOM,
            PAGE[1] - TOP_SPACE - BOTTOM_SPACE - 12.0)


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


def _values(names: Sequence[str], values: Sequence[float]) -> str:
    return " ".join(f"{n} {v:.4g}" for n, v in zip(names, values))


def family_heading(problem, report, label: str) -> str:
    """The line under the verdict: problem, system, start, goal, -strict."""
    goal = problem.goal
    return (f"{label or 'problem'}: system {problem.system_name}, start "
            f"{_values(problem.system.state_names, problem.start)}, goal "
            f"{_values(goal.names, [v for _, v in goal.values])} within {goal.tolerance:g}"
            + ("   -strict" if report is not None and report.strict else ""))


def page_text(report, verdict: str, heading: str, notes: Sequence[str]) -> PageText:
    failure = report.first_failure if report is not None else None
    return PageText(verdict, heading, report is not None and report.valid,
                    tuple(caption_lines(report, notes)), failure is not None)


def draw_page_text(canvas: Canvas, text: PageText, what: str,
                   legend: list[tuple[str, str]]) -> None:
    """Verdict, heading and ``what`` this page shows above; failure and legend below."""
    layout = PageLayout(PAGE[0], PAGE[1], 0.0, BOTTOM_SPACE, 1.0)
    draw_title(canvas, layout, text.verdict, text.heading, text.valid)
    canvas.setFillGray(0.0)
    canvas.setFont("Helvetica", 9.5)
    draw_line(canvas, layout, PAGE[1] - MARGIN - 41, what, "Helvetica", 9.5)
    draw_captions(canvas, layout, text.captions, text.failed)
    draw_legend(canvas, layout, legend)


def clip_to(canvas: Canvas, frame: Frame) -> None:
    """Clip what follows to the frame (the caller restores the state)."""
    canvas.saveState()
    path = canvas.beginPath()
    path.rect(frame.left, frame.bottom, frame.width, frame.height)
    canvas.clipPath(path, stroke=0, fill=0)


def _angle_label(value: float) -> str:
    quarter = round(value / (math.pi / 2))
    return {0: "0", 1: "pi/2", -1: "-pi/2", 2: "pi", -2: "-pi"}.get(quarter, f"{quarter}pi/2")


def _axis_ticks(low: float, high: float, scale: float, angle: bool, gap: float
                ) -> list[tuple[float, str]]:
    if angle and (high - low) * scale >= 4 * gap:
        step = math.pi / 2
        return [(k * step, _angle_label(k * step))
                for k in range(math.ceil(low / step - 1e-9), math.floor(high / step + 1e-9) + 1)]
    step, _ = tick_steps(scale * 30.0 / gap)
    first = math.ceil(low / step - 1e-9)
    return [(k * step, tick_label(k * step))
            for k in range(first, math.floor(high / step + 1e-9) + 1)]


def draw_axes(canvas: Canvas, frame: Frame, x_name: str, y_name: str,
              x_labels: bool = True, y_gap: float = 30.0) -> None:
    """The frame's border; ticks out of its bottom and left edges, labelled in data
    units (angles at multiples of pi/2); the axes' names at their ends."""
    canvas.saveState()
    canvas.setLineWidth(0.8)
    canvas.setStrokeGray(0.0)
    canvas.rect(frame.left, frame.bottom, frame.width, frame.height, stroke=1, fill=0)
    xs = _axis_ticks(frame.x0, frame.x1, frame.sx, frame.angle_x, 30.0)
    ys = _axis_ticks(frame.y0, frame.y1, frame.sy, frame.angle_y, y_gap)
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

def _unwrapped(points: Iterable[tuple[float, float]], angle_x: bool, angle_y: bool
               ) -> list[tuple[float, float]] | None:
    """The points with each angle coordinate continued from the previous point's
    (the shorter way), the first one wrapped; None if any is not finite."""
    out: list[tuple[float, float]] = []
    px = py = 0.0
    for x, y in points:
        if not (math.isfinite(x) and math.isfinite(y)):
            return None
        if angle_x:
            x = px + math.remainder(x - px, TAU)
        if angle_y:
            y = py + math.remainder(y - py, TAU)
        out.append((x, y))
        px, py = x, y
    return out


def _turns(values: Iterable[float], angle: bool) -> range:
    if not angle:
        return range(0, 1)
    values = list(values)
    low, high = min(values), max(values)
    return range(math.ceil((-math.pi - high) / TAU), math.floor((math.pi - low) / TAU) + 1)


def polyline_ops(frame: Frame, points: Iterable[tuple[float, float]], out: list[str],
                 spacing: float = 0.5) -> bool:
    """Append a polyline in data coordinates, once per turn of each angle axis it
    reaches into the frame; False when it is not drawn (not finite, too many turns)."""
    points = _unwrapped(points, frame.angle_x, frame.angle_y)
    if not points:
        return False
    turns_x = _turns((p[0] for p in points), frame.angle_x)
    turns_y = _turns((p[1] for p in points), frame.angle_y)
    if len(turns_x) > _MAX_TURNS or len(turns_y) > _MAX_TURNS:
        return False
    left, bottom, sx, sy = frame.left, frame.bottom, frame.sx, frame.sy
    for kx in turns_x:
        for ky in turns_y:
            dx, dy = kx * TAU - frame.x0, ky * TAU - frame.y0
            layout_polyline_ops([(left + (x + dx) * sx, bottom + (y + dy) * sy) for x, y in points],
                          _IDENTITY, spacing, out)
    return True


def stroke_ops(canvas: Canvas, ops: list[str], rgb, width: float, every: int = 10_000) -> None:
    """Stroke ``ops`` as paths of at most ``every`` operators each."""
    for start in range(0, len(ops), every):
        stroke(canvas, ops[start:start + every], rgb, width)


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


def draw_polygons(canvas: Canvas, frame: Frame, polygons: Iterable[ConvexPolygon], rgb,
                  width: float) -> None:
    """Outlines of placed bodies (footprints), one path."""
    ops: list[str] = []
    for polygon in polygons:
        points = polygon.points
        layout_polyline_ops([frame.to_page(*p) for p in (*points, points[0])], _IDENTITY, 0.0, ops)
    stroke_ops(canvas, ops, rgb, width)


def draw_dot(canvas: Canvas, frame: Frame, point: tuple[float, float], rgb,
             radius: float = 3.0) -> None:
    canvas.saveState()
    canvas.setFillColorRGB(*rgb)
    canvas.circle(*frame.clamped(*point), radius, stroke=0, fill=1)
    canvas.restoreState()


def draw_failure(canvas: Canvas, frame: Frame, where: tuple[float, float] | None) -> None:
    if where is not None:
        x, y = where
        if frame.angle_x and math.isfinite(x):
            x = math.remainder(x, TAU)
        if frame.angle_y and math.isfinite(y):
            y = math.remainder(y, TAU)
        failure_cross(canvas, *frame.clamped(x, y), 6.0)


# ----- the goal region --------------------------------------------------------------------

def _reach(goal, direction: Sequence[tuple[int, float]]) -> float:
    """How far from the goal's target along ``direction`` the region ends."""
    target, tolerance = goal.target, goal.tolerance

    def distance(r: float) -> float:
        state = list(target)
        for index, component in direction:
            state[index] += r * component
        return goal.distance(state)
    high = max(tolerance, 1e-12)
    while distance(high) <= tolerance and high < 1e12:
        high *= 2.0
    low = 0.0
    for _ in range(50):
        middle = (low + high) / 2
        low, high = (middle, high) if distance(middle) <= tolerance else (low, middle)
    return low


def goal_ops(frame: Frame, goal, i: int, j: int, rays: int) -> list[str]:
    """The goal region projected on variables ``i`` (across) and ``j`` (up): its
    outline when the goal names both, a band's two edges when it names one, else
    nothing."""
    names = set(goal.names)
    variables = goal.space.variables
    has_i, has_j = variables[i].name in names, variables[j].name in names
    gx, gy = goal.target[i], goal.target[j]
    ops: list[str] = []
    if has_i and has_j:
        outline = []
        for k in range(rays + 1):
            c, s = math.cos(TAU * k / rays), math.sin(TAU * k / rays)
            r = _reach(goal, ((i, c), (j, s)))
            outline.append((gx + r * c, gy + r * s))
        polyline_ops(frame, outline, ops, 0.0)
    elif has_i or has_j:
        index, centre = (i, gx) if has_i else (j, gy)
        for sign in (1.0, -1.0):
            edge = centre + sign * _reach(goal, ((index, sign),))
            line = ([(edge, frame.y0), (edge, frame.y1)] if has_i
                    else [(frame.x0, edge), (frame.x1, edge)])
            polyline_ops(frame, line, ops, 0.0)
    return ops


def draw_goal(canvas: Canvas, frame: Frame, goal, i: int, j: int, rays: int) -> bool:
    """The goal region in blue (a crosshair over it when it is tiny); False when the
    goal names neither plotted variable."""
    ops = goal_ops(frame, goal, i, j, rays)
    if not ops:
        return False
    stroke_ops(canvas, ops, GOAL_RGB, 1.0)
    names = set(goal.names)
    variables = goal.space.variables
    if variables[i].name in names and variables[j].name in names:
        r = _reach(goal, ((i, 1.0),))
        if r * frame.sx < 4.0:
            x, y = frame.to_page(math.remainder(goal.target[i], TAU) if frame.angle_x
                                 else goal.target[i],
                                 math.remainder(goal.target[j], TAU) if frame.angle_y
                                 else goal.target[j])
            stroke(canvas, [f"{x - 6:.2f} {y:.2f} m {x + 6:.2f} {y:.2f} l",
                             f"{x:.2f} {y - 6:.2f} m {x:.2f} {y + 6:.2f} l"], GOAL_RGB, 1.0)
    return True
