"""The family's PDF pages for the kinodynamic systems (SPEC 5.5).

car2, unicycle, car1: the workspace (obstacles, the tree projected on (x, y), the
solution re-simulated slice by slice, the body's footprint every few slices,
start and goal region, the first failure), then state and control against time.
The pendulum: its phase portrait (theta across, wrapping; omega up) with tree,
solution and goal region, then state and control against time.

Bounded as the grid page is: the tree and the solution each get a budget of
computed vertices (render_page.RenderOptions). A tree over its budget is thinned,
every k-th edge drawn, and the page says so; a solution over it is drawn up to
the budget.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

from reportlab.pdfgen.canvas import Canvas

from validator.render_page import (FOOTPRINT_RGB, SOLUTION_RGB, START_RGB, TREE_RGB,
                                   FamilyOptions, RenderOptions, RenderSummary,
                                   family_legend_items, thinning, tree_note)
from validator.render_plot import (Frame, PageText, clip_to, draw_axes, draw_dot, draw_failure,
                                   draw_goal, draw_obstacles, draw_page_text, draw_polygons,
                                   frame_in, plot_area, polyline_ops, stroke_ops)


def kinodynamic_pages(canvas: Canvas, problem, report, text: PageText, options: RenderOptions,
                      family: FamilyOptions) -> RenderSummary:
    """The plane page (workspace or phase portrait), then state and control against
    time, for ``problem`` (a KinoplanProblem of a kinodynamic system)."""
    plan = report.plan if report is not None else None
    flown = fly(problem.system, plan, options.max_solution_points)
    summary = _plane_page(canvas, problem, report, flown, text, options, family)
    _time_page(canvas, problem, flown, text)
    return summary


# ----- the solution and the tree, flown slice by slice -------------------------------------

@dataclass
class Flown:
    """The solution as flown: each drawn line's state and slices, with times."""

    states: list = field(default_factory=list)
    times: list = field(default_factory=list)
    controls: list = field(default_factory=list)
    """(start time, end time, held values) per drawn line."""
    lines: int = 0
    total: int = 0


def _drawable(system, row) -> bool:
    n = len(system.state_names)
    return all(map(math.isfinite, row)) and system.control_violation(row[n:]) is None


def fly(system, plan, budget: int) -> Flown:
    """Each line re-simulated from its own printed state (as check 7 does), until a
    line that cannot be (bad control) or the vertex budget."""
    flown = Flown(total=plan.trajectory_count if plan is not None else 0)
    if plan is None:
        return flown
    n, dt, t = len(system.state_names), system.dt, 0.0
    for row in plan.trajectory_rows():
        state, control = row[:n], row[n:]
        if not _drawable(system, row):
            flown.states.append(state)
            flown.times.append(t)
            break
        k = int(control[-1])
        if len(flown.states) + k + 1 > budget:
            break
        flown.states.append(state)
        flown.times.append(t)
        slices = system.slice_states(state, control)
        flown.states.extend(slices)
        flown.times.extend(t + dt * (i + 1) for i in range(len(slices)))
        flown.controls.append((t, t + dt * k, control[:-1]))
        t += dt * k
        flown.lines += 1
    return flown


def tree_polylines(system, plan, options: RenderOptions):
    """``(stride, polylines)``: every ``stride``-th tree edge as its parent state and
    slices (edges with a bad control are skipped)."""
    if plan is None or plan.tree_count == 0:
        return 1, iter(())
    kmax = system.kmax
    cost = sum(min(max(int(k), 1), kmax) + 1 if math.isfinite(k) else 1
               for k in plan.tree[plan.tree_fields - 1::plan.tree_fields])
    stride = thinning(plan.tree_rows_kept, cost, options)
    n = len(system.state_names)

    def polylines():
        for index, row in enumerate(plan.tree_rows()):
            if index % stride == 0 and _drawable(system, row):
                yield [row[:n], *system.slice_states(row[:n], row[n:])]
    return stride, polylines()


def draw_states(canvas: Canvas, frame: Frame, polylines, i: int, j: int, rgb,
                width: float) -> None:
    """Polylines of states projected on variables ``i`` and ``j``."""
    ops: list[str] = []
    for states in polylines:
        polyline_ops(frame, [(s[i], s[j]) for s in states], ops)
    stroke_ops(canvas, ops, rgb, width)


# ----- pages ------------------------------------------------------------------------------

def _plane_frame(problem) -> Frame:
    """The workspace box, or for a system without a world (the pendulum) its phase
    plane: the first variable (an angle) across, the second's bounds up."""
    if problem.world is not None and problem.world.box is not None:
        box = problem.world.box
        return frame_in((box.x0, box.y0, box.x1, box.y1), plot_area())
    i, j = problem.system.position_indices
    variables = problem.space.variables
    low, high = variables[j].low, variables[j].high
    if not (math.isfinite(low) and math.isfinite(high)):
        low, high = -10.0, 10.0
    return frame_in((-math.pi, low, math.pi, high), plot_area(), equal=False,
                    angle_x=variables[i].angle, angle_y=False)


def _plane_page(canvas, problem, report, flown: Flown, text: PageText,
                options: RenderOptions, family: FamilyOptions) -> RenderSummary:
    """The workspace (or phase plane): obstacles, tree, footprints, solution, start,
    goal region, first failure."""
    system, plan = problem.system, report.plan if report is not None else None
    i, j = system.position_indices
    frame = _plane_frame(problem)
    footprints = system.occupies == "body"
    clip_to(canvas, frame)
    if problem.world is not None:
        draw_obstacles(canvas, frame, problem.world)
    stride, polylines = tree_polylines(system, plan, options)
    draw_states(canvas, frame, polylines, i, j, TREE_RGB, options.tree_line_width)
    every = max(1, len(flown.states) // family.footprints)
    if footprints and flown.states:
        draw_polygons(canvas, frame, [system.footprint(s) for s in
                                      (*flown.states[::every], flown.states[-1])],
                      FOOTPRINT_RGB, 0.6)
    draw_states(canvas, frame, [flown.states], i, j, SOLUTION_RGB, options.solution_line_width)
    if footprints:
        draw_polygons(canvas, frame, [system.footprint(problem.start)], START_RGB, 1.2)
    goal_drawn = draw_goal(canvas, frame, problem.goal, i, j, family.goal_rays)
    draw_dot(canvas, frame, (problem.start[i], problem.start[j]), START_RGB)
    failure = report.first_failure if report is not None else None
    draw_failure(canvas, frame, failure.where if failure else None)
    canvas.restoreState()
    names = system.state_names
    draw_axes(canvas, frame, names[i], names[j])
    total = plan.tree_count if plan is not None else 0
    kept = plan.tree_rows_kept if plan is not None else 0
    what = (f"{'Workspace' if problem.world is not None else 'Phase portrait'} "
            f"({names[i]}, {names[j]}): {tree_note(total, kept, stride)}; solution "
            f"re-simulated slice by slice ({_lines_note(flown)})"
            + (f", footprint every {every} slices" if footprints else "")
            + _length_note(report))
    legend = family_legend_items(flown.lines > 0, total > 0, goal_drawn,
                                 failure is not None and failure.where is not None,
                                 footprints and flown.lines > 0, problem.world)
    draw_page_text(canvas, text, what, legend)
    canvas.showPage()
    return RenderSummary(len(range(0, kept, stride)), total, flown.lines, flown.total)


def _lines_note(flown: Flown) -> str:
    if flown.lines < flown.total:
        return f"{flown.lines} of {flown.total} lines drawn"
    return f"{flown.total} lines"


def _length_note(report) -> str:
    if report is None or report.path_length is None:
        return ""
    return f"; path length {report.path_length:.4g}"


def _panel_range(values: Sequence[float], bounds: tuple[float, float]) -> tuple[float, float]:
    low, high = bounds
    if math.isfinite(low) and math.isfinite(high) and low < high:
        return low, high
    finite = [v for v in values if math.isfinite(v)] or [0.0]
    low, high = min(finite), max(finite)
    pad = 0.05 * (high - low) or 1.0
    return low - pad, high + pad


def _time_page(canvas, problem, flown: Flown, text: PageText) -> None:
    """Each state variable and each held control against time along the solution,
    one panel each, stacked; angles in [-pi, pi], split where they wrap."""
    system = problem.system
    n, held = len(system.state_names), system.control_names[:-1]
    end = max(flown.times[-1] if flown.times else 0.0, system.dt)
    left, bottom, width, height = plot_area()
    panels = n + len(held)
    gap = 16.0
    step = (height + gap) / panels
    for p in range(panels):
        top = bottom + height - p * step
        area = (left, top - (step - gap), width, step - gap)
        if p < n:
            variable = system.space.variables[p]
            values = [s[p] for s in flown.states]
            low, high = ((-math.pi, math.pi) if variable.angle
                         else _panel_range(values, (variable.low, variable.high)))
            frame = frame_in((0.0, low, end, high), area, equal=False, angle_y=variable.angle)
            points = list(zip(flown.times, values))
            name, rgb = variable.name, SOLUTION_RGB
        else:
            c = p - n
            low, high = system.controls[c]
            if not low < high:
                low, high = low - 1.0, high + 1.0
            frame = frame_in((0.0, low, end, high), area, equal=False)
            points = [q for t0, t1, u in flown.controls for q in ((t0, u[c]), (t1, u[c]))]
            name, rgb = f"control {held[c]}", TREE_RGB
        clip_to(canvas, frame)
        draw_states(canvas, frame, [points] if points else [], 0, 1, rgb, 1.2)
        canvas.restoreState()
        draw_axes(canvas, frame, "t (s)", name, x_labels=p == panels - 1, y_gap=14.0)
    what = (f"State and control against time along the solution ({_lines_note(flown)}, "
            f"{end:.4g} s; slices of {system.dt:g} s)")
    draw_page_text(canvas, text, what, [("solution", "red: state"),
                                        ("tree", "blue-grey: held control")])
    canvas.showPage()
