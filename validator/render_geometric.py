"""The family's PDF pages for the geometric systems (SPEC 5.5).

arm2: the workspace with the obstacles, the arm at poses evenly spaced (in the
metric) along the path and the path its tip draws; then the configuration-space
square (theta1, theta2) in [-pi, pi]^2 with the obstacle region shaded (the
system's validity test at the centre of each cell of a fine grid), the tree or
roadmap and the path, segments that wrap split at the square's edges. rigid2:
the workspace with the tree projected on (x, y), the path, and the body at poses
along it. Both mark the start, the goal region and the first failure.
"""

from __future__ import annotations

import math
from typing import Sequence

from reportlab.pdfgen.canvas import Canvas

from planning_core.kinoplan import state_validator
from validator.render_geometry import (cell_runs, invalid_cells, poses_along, thinning,
                                       tree_note)
from validator.render_page import (FAILURE_RGB, GOAL_RGB, OBSTACLE_GRAY, POSE_RGB, SOLUTION_RGB,
                                   START_FILL_RGB, START_RGB, TREE_RGB, FamilyOptions,
                                   RenderOptions, RenderSummary, family_legend_items, stroke_ops)
from validator.render_plot import (TAU, Frame, PageText, clip_to, draw_axes, draw_bodies,
                                   draw_dot, draw_failure, draw_goal, draw_headings,
                                   draw_obstacles, draw_page_text, draw_polygons, draw_start,
                                   new_page, no_answer, polyline_ops)

ARM_SQUARE = (-math.pi, -math.pi, math.pi, math.pi)


def geometric_pages(canvas: Canvas, problem, report, text: PageText, options: RenderOptions,
                    family: FamilyOptions) -> RenderSummary:
    """arm2's workspace and configuration-space pages, or rigid2's workspace page."""
    plan = report.plan if report is not None else None
    path = []
    if plan is not None:
        rows = plan.trajectory_rows()
        path = [row for _, row in zip(range(options.max_solution_points), rows)]
    failure = report.first_failure if report is not None else None
    where = failure.where if failure is not None else None
    if problem.system.occupies == "links":
        _arm_page(canvas, problem, report, path, where, text, family)
        return _cspace_page(canvas, problem, report, path, where, text, options, family)
    return _rigid_page(canvas, problem, report, path, where, text, options, family)


def _what(report, path: Sequence, tree: str) -> str:
    length = (f"; path length {report.path_length:.4g}"
              if report is not None and report.path_length is not None else "")
    total = report.trajectory_count if report is not None and report.plan else 0
    lines = f"{total} configurations" + (f" (first {len(path)} drawn)" if len(path) < total
                                          else "")
    return f"{tree}; path of {lines}{length}"


# ----- arm2: the workspace ----------------------------------------------------------------

def _arm_ops(frame: Frame, system, configurations) -> list[str]:
    ops: list[str] = []
    for q in configurations:
        polyline_ops(frame, system.joints(q), ops, 0.0)
    return ops


def _arm_page(canvas: Canvas, problem, report, path, where, text: PageText,
              family: FamilyOptions) -> None:
    system, world = problem.system, problem.world
    box = world.box
    page, frame = new_page(canvas, (box.x0, box.y0, box.x1, box.y1))
    clip_to(canvas, frame)
    draw_obstacles(canvas, frame, world)
    stroke_ops(canvas, _arm_ops(frame, system, poses_along(system, path, family.poses)[1:-1]),
               POSE_RGB, 1.6)
    tips: list[str] = []
    polyline_ops(frame, [system.joints(q)[2] for q in poses_along(system, path, 400)], tips)
    stroke_ops(canvas, tips, SOLUTION_RGB, 1.0)
    goal = problem.goal
    if path:
        stroke_ops(canvas, _arm_ops(frame, system, [path[-1]]), SOLUTION_RGB, 2.4)
    stroke_ops(canvas, _arm_ops(frame, system, [problem.start]), START_RGB, 2.4)
    if goal.full:  # dashed, over the last pose that ends near it
        stroke_ops(canvas, _arm_ops(frame, system, [goal.target]), GOAL_RGB, 1.4,
                   dash=(4.0, 3.0))
    if where is not None:
        stroke_ops(canvas, _arm_ops(frame, system, [where]), FAILURE_RGB, 2.0)
    draw_dot(canvas, frame, system.joints(problem.start)[0], (0.0, 0.0, 0.0), 3.5)
    no_answer(canvas, frame, report, text)
    canvas.restoreState()
    draw_axes(canvas, frame, "x", "y")
    what = (f"Workspace: the arm at {max(0, family.poses - 2)} poses evenly spaced along the "
            f"path (pink), its last configuration (thick red) and the path of its tip (red)")
    legend = [("solution", "red: tip path, last pose"), ("pose", "pink: arm along the path"),
              ("start", "green: start pose")]
    if goal.full:
        legend.append(("goalpose", "blue dashes: goal pose"))
    if where is not None:
        legend.append(("failure", "magenta: the arm at the first failure"))
    if world.obstacles:
        legend.append(("obstacle", "grey: obstacle"))
    draw_page_text(canvas, text, what, legend, page)
    canvas.showPage()


# ----- arm2: the configuration-space square ----------------------------------------------

def _shade_invalid(canvas: Canvas, frame: Frame, invalid: bytes, cells: int) -> None:
    """Fill each cell of the ``cells`` x ``cells`` grid over the square that is
    ``invalid`` (runs along a row merged into one rectangle)."""
    step = TAU / cells
    width, height = step * frame.sx, step * frame.sy
    runs = [f"{x:.2f} {y:.2f} {(end - c) * width:.2f} {height:.2f} re"
            for r, c, end in cell_runs(invalid, cells, cells)
            for x, y in [frame.to_page(-math.pi + c * step, -math.pi + r * step)]]
    if runs:
        canvas.saveState()
        canvas.setFillGray(OBSTACLE_GRAY)
        canvas.setStrokeGray(OBSTACLE_GRAY)
        canvas.setLineWidth(0.3)
        for start in range(0, len(runs), 10_000):
            canvas.addLiteral("\n".join(runs[start:start + 10_000]) + "\nB")
        canvas.restoreState()


def _tree_ops(frame: Frame, plan, n: int, i: int, j: int, stride: int) -> list[str]:
    """Every ``stride``-th tree edge (from, to) as a straight segment on variables
    ``i`` and ``j`` (angles the shorter way)."""
    ops: list[str] = []
    for index, row in enumerate(plan.tree_rows()):
        if index % stride == 0:
            polyline_ops(frame, [(row[i], row[j]), (row[n + i], row[n + j])], ops, 0.0)
    return ops


def _plan_layer(canvas: Canvas, frame: Frame, problem, report, path, where,
                options: RenderOptions, family: FamilyOptions) -> tuple[str, bool, RenderSummary]:
    """Tree, path, start, goal region and failure on variables 0 and 1 of the plan;
    ``(what the tree is, the goal was drawn, the counts)``."""
    plan = report.plan if report is not None else None
    n = len(problem.system.state_names)
    total = kept = 0
    stride = 1
    if plan is not None and plan.tree_count:
        total, kept = plan.tree_count, plan.tree_rows_kept
        stride = thinning(kept, 2 * kept, options.max_tree_points, options.max_tree_edges_drawn)
        stroke_ops(canvas, _tree_ops(frame, plan, n, 0, 1, stride), TREE_RGB,
                   options.tree_line_width)
    ops: list[str] = []
    polyline_ops(frame, [(q[0], q[1]) for q in path], ops)
    stroke_ops(canvas, ops, SOLUTION_RGB, options.solution_line_width)
    goal_drawn = draw_goal(canvas, frame, problem.goal, 0, 1, family.goal_rays)
    draw_start(canvas, frame, problem.start[:2])
    draw_failure(canvas, frame, where)
    summary = RenderSummary(len(range(0, kept, stride)), total, len(path),
                            plan.trajectory_count if plan is not None else 0)
    return tree_note(total, kept, stride), goal_drawn, summary


def _cspace_page(canvas: Canvas, problem, report, path, where, text: PageText,
                 options: RenderOptions, family: FamilyOptions) -> RenderSummary:
    page, frame = new_page(canvas, ARM_SQUARE, angle_x=True, angle_y=True)
    clip_to(canvas, frame)
    _shade_invalid(canvas, frame, invalid_cells(state_validator(problem.system, problem.world),
                                                family.cspace_cells), family.cspace_cells)
    tree, goal_drawn, summary = _plan_layer(canvas, frame, problem, report, path, where, options,
                                            family)
    no_answer(canvas, frame, report, text)
    canvas.restoreState()
    draw_axes(canvas, frame, "theta1", "theta2")
    what = (f"Configuration space (theta1, theta2), wrapping at +-pi; grey: invalid "
            f"({family.cspace_cells} x {family.cspace_cells} cells tested); "
            + _what(report, path, tree))
    legend = family_legend_items(bool(path), "tree edges" in tree, goal_drawn,
                                 where is not None, False, None, "tree or roadmap edges")
    legend.append(("obstacle", "grey: arm touches an obstacle or leaves the world"))
    draw_page_text(canvas, text, what, legend, page)
    canvas.showPage()
    return summary


# ----- rigid2 -----------------------------------------------------------------------------

def _rigid_page(canvas: Canvas, problem, report, path, where, text: PageText,
                options: RenderOptions, family: FamilyOptions) -> RenderSummary:
    system, world = problem.system, problem.world
    box = world.box
    page, frame = new_page(canvas, (box.x0, box.y0, box.x1, box.y1))
    clip_to(canvas, frame)
    draw_obstacles(canvas, frame, world)
    poses = poses_along(system, path, 2 * family.poses)
    draw_bodies(canvas, frame, system, poses)
    if problem.goal.full:
        draw_polygons(canvas, frame, [system.footprint(problem.goal.target)], GOAL_RGB, 1.2,
                      dash=(4.0, 3.0))
    draw_bodies(canvas, frame, system, [problem.start], START_RGB, START_FILL_RGB, 1.4)
    tree, goal_drawn, summary = _plan_layer(canvas, frame, problem, report, path, where, options,
                                            family)
    draw_headings(canvas, frame, system, [problem.start, *poses])
    no_answer(canvas, frame, report, text)
    canvas.restoreState()
    draw_axes(canvas, frame, "x", "y")
    what = (f"Workspace (x, y): the body at {len(poses)} poses along the path; "
            + _what(report, path, tree))
    legend = family_legend_items(bool(path), "tree edges" in tree, goal_drawn,
                                 where is not None, bool(poses), world)
    draw_page_text(canvas, text, what, legend, page)
    canvas.showPage()
    return summary
