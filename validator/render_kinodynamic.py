"""The family's PDF pages for the kinodynamic systems (SPEC 5.5).

car2, unicycle, car1: the workspace on a page of its shape (obstacles, the tree
projected on (x, y), the solution re-simulated slice by slice, the body's footprint
and heading every few slices, start and goal region, the first failure), then state
and control against time.
The pendulum: its phase portrait (theta across, wrapping; omega up) with tree,
solution and goal region, then state and control against time.

Bounded as the grid page is: the tree and the solution each get a budget of
computed vertices (render_page.RenderOptions). A tree over its budget is thinned,
every k-th edge drawn, and the page says so; a solution over it is drawn up to
the budget.
"""

from __future__ import annotations

import math

from reportlab.pdfgen.canvas import Canvas

from validator.render_geometry import (Flown, body_note, duration_note, fly, footprint_states,
                                       footprint_step, lines_note, panel_range, phase_box,
                                       thinning, tree_cost, tree_note, tree_polylines)
from validator.render_page import (SOLUTION_RGB, START_FILL_RGB, START_RGB, TREE_RGB,
                                   FamilyOptions, RenderOptions, RenderSummary,
                                   family_legend_items, stroke_ops)
from validator.render_plot import (PAGE, Frame, PageText, clip_to, draw_axes, draw_bodies,
                                   draw_failure, draw_goal, draw_headings, draw_obstacles,
                                   draw_page_text, draw_start, frame_in, new_page, no_answer,
                                   plot_area, polyline_ops)


def kinodynamic_pages(canvas: Canvas, problem, report, text: PageText, options: RenderOptions,
                      family: FamilyOptions) -> RenderSummary:
    """The plane page (workspace or phase portrait), then state and control against
    time, for ``problem`` (a KinoplanProblem of a kinodynamic system)."""
    plan = report.plan if report is not None else None
    flown = fly(problem.system, plan, options.max_solution_points)
    summary = _plane_page(canvas, problem, report, flown, text, options, family)
    _time_page(canvas, problem, report, flown, text)
    return summary


def tree_stride(system, plan, options: RenderOptions) -> int:
    """Every how many tree edges one is drawn, within the budgets."""
    if plan is None or plan.tree_count == 0:
        return 1
    return thinning(plan.tree_rows_kept, tree_cost(system, plan), options.max_tree_points,
                    options.max_tree_edges_drawn)


def draw_states(canvas: Canvas, frame: Frame, polylines, i: int, j: int, rgb,
                width: float) -> None:
    """Polylines of states projected on variables ``i`` and ``j``."""
    ops: list[str] = []
    for states in polylines:
        if states:
            polyline_ops(frame, [(s[i], s[j]) for s in states], ops)
    stroke_ops(canvas, ops, rgb, width)


# ----- pages ------------------------------------------------------------------------------

def _plane_frame(canvas: Canvas, problem) -> tuple[tuple[float, float], Frame]:
    """The page and frame of the workspace box (a page of its shape), or of the phase
    plane (landscape)."""
    if problem.world is not None and problem.world.box is not None:
        box = problem.world.box
        return new_page(canvas, (box.x0, box.y0, box.x1, box.y1))
    i = problem.system.position_indices[0]
    canvas.setPageSize(PAGE)
    return PAGE, frame_in(phase_box(problem), plot_area(), equal=False,
                          angle_x=problem.space.variables[i].angle)


def _plane_page(canvas, problem, report, flown: Flown, text: PageText,
                options: RenderOptions, family: FamilyOptions) -> RenderSummary:
    """The workspace (or phase plane): obstacles, tree, footprints, solution, start,
    goal region, first failure."""
    system, plan = problem.system, report.plan if report is not None else None
    i, j = system.position_indices
    page, frame = _plane_frame(canvas, problem)
    footprints = system.occupies == "body"
    clip_to(canvas, frame)
    if problem.world is not None:
        draw_obstacles(canvas, frame, problem.world)
    stride = tree_stride(system, plan, options)
    if plan is not None:
        draw_states(canvas, frame, tree_polylines(system, plan, stride), i, j, TREE_RGB,
                    options.tree_line_width)
    every = footprint_step(flown, family)
    bodies = footprint_states(flown, every) if footprints else []
    if footprints:
        draw_bodies(canvas, frame, system, bodies)
        draw_bodies(canvas, frame, system, [problem.start], START_RGB, START_FILL_RGB, 1.2)
    goal_drawn = draw_goal(canvas, frame, problem.goal, i, j, family.goal_rays)
    draw_start(canvas, frame, (problem.start[i], problem.start[j]))
    draw_states(canvas, frame, [flown.states], i, j, SOLUTION_RGB, options.solution_line_width)
    if footprints:
        draw_headings(canvas, frame, system, [problem.start, *bodies])
    failure = report.first_failure if report is not None else None
    draw_failure(canvas, frame, failure.where if failure else None)
    no_answer(canvas, frame, report, text)
    canvas.restoreState()
    names = system.state_names
    draw_axes(canvas, frame, names[i], names[j])
    total = plan.tree_count if plan is not None else 0
    kept = plan.tree_rows_kept if plan is not None else 0
    what = (f"{'Workspace' if problem.world is not None else 'Phase portrait'} "
            f"({names[i]}, {names[j]}): {tree_note(total, kept, stride)}; solution "
            f"re-simulated slice by slice ({lines_note(flown)}"
            + (f", {body_note(every)}" if footprints else "") + ")"
            + duration_note(system, plan))
    legend = family_legend_items(flown.lines > 0, total > 0, goal_drawn,
                                 failure is not None and failure.where is not None,
                                 footprints and flown.lines > 0, problem.world)
    draw_page_text(canvas, text, what, legend, page)
    canvas.showPage()
    return RenderSummary(len(range(0, kept, stride)), total, flown.lines, flown.total)


def _time_page(canvas, problem, report, flown: Flown, text: PageText) -> None:
    """Each state variable and each held control against time along the solution,
    one panel each, stacked; angles in [-pi, pi], split where they wrap."""
    system = problem.system
    n, held = len(system.state_names), system.control_names[:-1]
    end = max(flown.times[-1] if flown.times else 0.0, system.dt)
    canvas.setPageSize(PAGE)
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
                         else panel_range(values, (variable.low, variable.high)))
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
    if report is None:
        no_answer(canvas, frame_in((0, 0, 1, 1), (left, bottom, width, height), equal=False),
                  report, text)
    what = (f"State and control against time along the solution ({lines_note(flown)}, "
            f"{end:.4g} s; slices of {system.dt:g} s)")
    draw_page_text(canvas, text, what, [("solution", "red: state"),
                                        ("tree", "blue-grey: held control")])
    canvas.showPage()
