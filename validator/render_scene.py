"""The browser view's and the SVG's drawing (the scene), built from the same report the
PDF draws, with render_geometry's geometry, headings and budgets; no drawing library.

A scene is a dict: the verdict, heading, counts, notes and first failure, the tree's
counts (the view's growth slider runs over its printed edges), and views, each a list
of plots. A plot is a data box (the map, the workspace, the phase plane, the torus's
square, a variable against time) with its axes and its layers, by id: ``grid``,
``obstacles``, ``tree``, ``footprints``, ``answer``, ``marks`` (start and goal) and
``failure`` (the first failure, corner cuts). Items are plain values; many points are
``array.array`` of float32 (x, y, x, y, ...), which render_html sends as base64 and
render_svg writes as paths. Angle axes: each polyline is unwrapped along its points
and drawn once per listed turn (``turns``), clipped to the plot.
"""

from __future__ import annotations

import math
from array import array
from dataclasses import dataclass
from typing import Iterable, Sequence

from planning_core.kinoplan import KinoplanProblem, state_validator
from planning_core.worlds.shapes import ConvexPolygon, Disc, Rect
from validator.render_geometry import (BLOCKED_GRAY, CORNER_RGB, FAILURE_RGB, FOOTPRINT_FILL_RGB,
                                       FOOTPRINT_RGB, GOAL_RGB, HEADING_RGB, OBSTACLE_GRAY,
                                       POSE_RGB, SHIP_POINTS, SOLUTION_RGB, START_RGB, TREE_RGB,
                                       Flown, FamilyOptions, body_note,
                                       caption_lines, duration_note, family_heading, fly,
                                       footprint_states, footprint_step, front_mark, goal_shape,
                                       grid_heading, grid_solution, grid_tree_edge,
                                       invalid_cells, lines_note, panel_range, phase_box,
                                       poses_along, rows_in_budget, thinning, tree_cost,
                                       tree_note, tree_polylines, turns, unwrapped, wrapped)

_MAX_TURNS = 4  # a polyline reaching over more turns than this of an angle is not drawn
_NO_LIMIT = 1 << 62


@dataclass(frozen=True)
class SceneOptions:
    """Budgets of the view and the SVG (time and size stay bounded for any answer)."""

    max_tree_points: int = 2_500_000
    """Tree vertices kept (8 bytes each in the view): a million point edges whole."""
    max_tree_slices: int = 1_000_000
    """Slices simulated to draw a spaceship's or a kinodynamic system's tree."""
    max_edge_points: int = 24
    """A tree edge's curve is kept through at most this many of its states."""
    max_solution_points: int = 500_000
    """Vertices of the solution (1 a point line, 21 a spaceship line, K + 1 a family line)."""
    family: FamilyOptions = FamilyOptions()
    """Footprints, poses, the C-space grid and the goal outline, as the PDF's."""


def hex_colour(rgb) -> str:
    """``#rrggbb`` of an RGB triple (0 to 1) or a grey level."""
    rgb = (rgb, rgb, rgb) if isinstance(rgb, (int, float)) else rgb
    return "#" + "".join(f"{round(255 * c):02x}" for c in rgb)


# ----- polylines --------------------------------------------------------------------------

class Polylines:
    """Polylines packed for a picture: float32 x, y pairs and where each one starts;
    on angle axes each is unwrapped, and ``turns`` lists the turns to draw it at."""

    def __init__(self, angle_x: bool = False, angle_y: bool = False):
        self.angle_x, self.angle_y = angle_x, angle_y
        self.points = array("f")
        self.starts = array("I", [0])
        self.low = [math.inf, math.inf]
        self.high = [-math.inf, -math.inf]

    def add(self, points: Iterable[tuple[float, float]]) -> None:
        """One polyline (an empty one when it cannot be drawn: the k-th added stays
        the k-th drawn, for the growth slider)."""
        kept = unwrapped(points, self.angle_x, self.angle_y)
        if kept and len(self._turns(kept)[0]) <= _MAX_TURNS and len(self._turns(kept)[1]) <= \
                _MAX_TURNS:
            for axis in (0, 1):
                values = [p[axis] for p in kept]
                self.low[axis] = min(self.low[axis], min(values))
                self.high[axis] = max(self.high[axis], max(values))
            for x, y in kept:
                self.points.append(x)
                self.points.append(y)
        self.starts.append(len(self.points) // 2)

    def _turns(self, points) -> tuple[range, range]:
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        return (turns(min(xs), max(xs), self.angle_x), turns(min(ys), max(ys), self.angle_y))

    @property
    def count(self) -> int:
        return len(self.starts) - 1

    def item(self, rgb, width: float, growth: bool = False, dash: Sequence[float] = ()) -> dict:
        """The ``lines`` item: ``width`` in CSS pixels; ``growth``: the tree's edges, in
        the order printed (the view's slider shows the first so many)."""
        tx = ty = range(0, 1)
        if self.points:
            tx = turns(self.low[0], self.high[0], self.angle_x)
            ty = turns(self.low[1], self.high[1], self.angle_y)
        return {"kind": "lines", "points": self.points, "starts": self.starts, "per": 0,
                "colour": hex_colour(rgb), "width": width, "growth": growth, "dash": list(dash),
                "turns": [[kx, ky] for kx in tx for ky in ty]}


def segments_item(values: array, rgb, width: float) -> dict:
    """Straight edges from flat float32 ``x1 y1 x2 y2`` (no unwrapping), as grown."""
    return {"kind": "lines", "points": values, "starts": None, "per": 2,
            "colour": hex_colour(rgb), "width": width, "growth": True, "dash": [],
            "turns": [[0, 0]]}


def polylines_in(item: dict) -> int:
    """How many polylines a ``lines`` item holds."""
    if item["per"]:
        return len(item["points"]) // (2 * item["per"])
    return len(item["starts"]) - 1


def _thin(points: Sequence, most: int) -> Sequence:
    """At most ``most`` of ``points``, evenly spaced, the first and last kept."""
    if len(points) <= most:
        return points
    step = (len(points) - 1) / (most - 1)
    return [points[round(k * step)] for k in range(most)]


# ----- the scene's frame: plots, marks, text ------------------------------------------------

def plot(box, x_name: str, y_name: str, layers: dict, equal: bool = True,
         angle_x: bool = False, angle_y: bool = False, title: str = "", zoom: str = "xy",
         link: str = "", grid: tuple[int, int] | None = None) -> dict:
    """A plot of ``box`` (x0, y0, x1, y1) with its layers (id -> items)."""
    return {"box": [float(v) for v in box], "equal": equal, "title": title, "zoom": zoom,
            "link": link, "x": {"name": x_name, "angle": angle_x},
            "y": {"name": y_name, "angle": angle_y}, "grid": list(grid) if grid else None,
            "layers": [{"id": key, "items": items} for key, items in layers.items() if items]}


def inside(box, x: float, y: float, angle_x: bool = False, angle_y: bool = False
           ) -> list[float]:
    """A point for a mark: angles wrapped, not finite or far out pulled onto the box."""
    x, y = wrapped(x, angle_x), wrapped(y, angle_y)
    x = x if math.isfinite(x) else box[0]
    y = y if math.isfinite(y) else box[1]
    return [min(max(x, box[0]), box[2]), min(max(y, box[1]), box[3])]


def start_dot(at) -> dict:
    return {"kind": "dot", "at": at, "radius": 4.5, "colour": hex_colour(START_RGB),
            "halo": True}


def failure_cross(at) -> dict:
    return {"kind": "cross", "at": at, "size": 7.0, "colour": hex_colour(FAILURE_RGB)}


def failure_info(report) -> dict | None:
    failure = report.first_failure if report is not None else None
    if failure is None:
        return None
    return {"check": failure.number, "name": failure.name, "line": failure.line,
            "message": failure.message, "detail": failure.detail}


def scene_frame(verdict: str, valid: bool, heading: str, counts: str, notes: Sequence[str],
                report, tree: dict, views: list[dict], title: str) -> dict:
    """The scene: its text, the tree's counts and the views."""
    return {"title": title, "verdict": verdict, "valid": valid, "heading": heading,
            "counts": counts, "notes": list(notes), "failure": failure_info(report),
            "warnings": list(report.warnings) if report is not None else [],
            "captions": caption_lines(report, notes), "answer": report is not None,
            "tree": tree, "views": views}


def tree_info(plan, stride: int, drawn: int) -> dict:
    total = plan.tree_count if plan is not None else 0
    kept = plan.tree_rows_kept if plan is not None else 0
    return {"total": total, "kept": kept, "stride": stride, "drawn": drawn,
            "note": tree_note(total, kept, stride)}


def build_scene(problem, vehicle, report, verdict: str, notes: Sequence[str] = (),
                label: str = "", options: SceneOptions = SceneOptions()) -> dict:
    """The scene of ``report`` (None: the planner did not run to the end) on ``problem``."""
    if not isinstance(problem, KinoplanProblem):
        return grid_scene(problem, vehicle, report, verdict, notes, label, options)
    heading = family_heading(problem, report, label)
    title = f"rrt-validator: {label or 'problem'} ({problem.system_name})"
    if problem.system.kinodynamic:
        views, tree, counts = kinodynamic_views(problem, report, options)
    else:
        views, tree, counts = geometric_views(problem, report, options)
    return scene_frame(verdict, report is not None and report.valid, heading, counts, notes,
                       report, tree, views, title)


# ----- the grid -----------------------------------------------------------------------------

def grid_tree(plan, ship: bool, options: SceneOptions) -> tuple[dict | None, int]:
    """The grid's tree item and its stride: point edges straight from the plan's numbers,
    a spaceship's each as its state and 20 slices."""
    kept = plan.tree_rows_kept if plan is not None else 0
    if not kept:
        return None, 1
    if not ship:
        stride = thinning(kept, 2 * kept, options.max_tree_points, _NO_LIMIT)
        values = plan.tree if stride == 1 else array("d", (
            v for start in range(0, 4 * kept, 4 * stride) for v in plan.tree[start:start + 4]))
        return segments_item(array("f", values), TREE_RGB, 0.8), stride
    stride = thinning(kept, SHIP_POINTS * kept, min(options.max_tree_slices,
                                                    options.max_tree_points), _NO_LIMIT)
    lines = Polylines()
    for index, row in enumerate(plan.tree_rows()):
        if index % stride == 0:
            lines.add(_thin(grid_tree_edge(row, True), options.max_edge_points))
    return lines.item(TREE_RGB, 0.8, growth=True), stride


def grid_layers(problem, report, ship: bool, options: SceneOptions) -> tuple[dict, int, int]:
    """The map's layers, the tree's stride and the solution lines drawn."""
    plan = report.plan if report is not None else None
    box = (0, 0, problem.width, problem.height)
    layers = {"grid": [{"kind": "gridlines", "cols": problem.width, "rows": problem.height}],
              "obstacles": [{"kind": "cells", "cols": problem.width, "rows": problem.height,
                             "box": list(box), "cells": bytes(problem.blocked),
                             "colour": hex_colour(BLOCKED_GRAY)}] if any(problem.blocked)
              else []}
    tree, stride = grid_tree(plan, ship, options)
    layers["tree"] = [tree] if tree else []
    lines = 0
    if plan is not None:
        lines = rows_in_budget(plan.trajectory_count, options.max_solution_points,
                               SHIP_POINTS if ship else 1)
        answer = Polylines()
        answer.add(grid_solution(report, lines))
        layers["answer"] = [answer.item(SOLUTION_RGB, 2.5)]
    layers["marks"] = [start_dot(list(problem.start)),
                       {"kind": "circle", "at": list(problem.goal), "radius": 0.1,
                        "cross": 7.0, "colour": hex_colour(GOAL_RGB)}]
    layers["failure"] = _grid_failure(report, box)
    return layers, stride, lines


def _grid_failure(report, box) -> list[dict]:
    if report is None:
        return []
    items = [{"kind": "rings", "points": [inside(box, *c.where) for c in report.corner_cuts[:1000]],
              "radius": 5.0, "colour": hex_colour(CORNER_RGB)}] if report.corner_cuts else []
    failure = report.first_failure
    if failure is not None and failure.where is not None:
        items.append(failure_cross(inside(box, *failure.where)))
    return items


def grid_scene(problem, vehicle, report, verdict: str, notes: Sequence[str], label: str,
               options: SceneOptions) -> dict:
    ship = vehicle.is_spaceship
    layers, stride, lines = grid_layers(problem, report, ship, options)
    plan = report.plan if report is not None else None
    tree = tree_info(plan, stride, polylines_in(layers["tree"][0]) if layers["tree"] else 0)
    counts = ""
    if plan is not None:
        shown = "" if lines == plan.trajectory_count else f" (first {lines} drawn)"
        counts = f"{plan.trajectory_count} trajectory lines{shown}, {tree['note']}"
        if report.path_length is not None:
            counts += f", path length {report.path_length:.4g}"
    view = {"name": "Map", "what": f"{problem.width} x {problem.height} map",
            "plots": [plot((0, 0, problem.width, problem.height), "x", "y", layers,
                           grid=(problem.width, problem.height))]}
    return scene_frame(verdict, report is not None and report.valid,
                       grid_heading(problem, vehicle, report, label), counts, notes, report,
                       tree, [view], f"rrt-validator: {label or 'problem'} ({vehicle.value})")


# ----- the family: world, goal, bodies -------------------------------------------------------

def obstacle_items(world) -> list[dict]:
    """The world's obstacles filled grey and its box outlined."""
    rects, discs, polygons = [], [], []
    for obstacle in world.obstacles:
        if isinstance(obstacle, Rect):
            rects.append([obstacle.x0, obstacle.y0, obstacle.x1, obstacle.y1])
        elif isinstance(obstacle, Disc):
            discs.append([obstacle.cx, obstacle.cy, obstacle.r])
        elif isinstance(obstacle, ConvexPolygon):
            polygons.append([v for point in obstacle.points for v in point])
    items = [{"kind": "shapes", "rects": rects, "discs": discs, "polygons": polygons,
              "fill": hex_colour(OBSTACLE_GRAY)}]
    if world.box is not None:
        box = world.box
        items.append({"kind": "outline", "box": [box.x0, box.y0, box.x1, box.y1],
                      "colour": "#000000"})
    return items


def goal_items(goal, i: int, j: int, box, rays: int, angle_x: bool = False,
               angle_y: bool = False) -> list[dict]:
    """The goal region's outline (or a band's edges) on variables ``i`` and ``j``, with
    a crosshair over it when it is small on the screen."""
    lines, reach = goal_shape(goal, i, j, rays, box)
    outline = Polylines(angle_x, angle_y)
    for line in lines:
        outline.add(line)
    items = [outline.item(GOAL_RGB, 1.5)] if lines else []
    if reach is not None:
        items.append({"kind": "circle", "at": inside(box, goal.target[i], goal.target[j],
                                                     angle_x, angle_y),
                      "radius": reach, "cross": 7.0, "colour": hex_colour(GOAL_RGB),
                      "outline": False})
    return items


def body_items(system, states: Sequence, outline=FOOTPRINT_RGB, fill=FOOTPRINT_FILL_RGB,
               dash: Sequence[float] = ()) -> list[dict]:
    """The body at each state: footprints outlined (filled, half see-through, unless
    ``fill`` is None: the start and goal bodies, drawn over the answer) and the front
    edges."""
    if not states:
        return []
    return [{"kind": "bodies",
             "polygons": [[v for p in system.footprint(s).points for v in p] for s in states],
             "fronts": [[v for p in front_mark(system, s) for v in p] for s in states],
             "fill": hex_colour(fill) if fill is not None else None,
             "colour": hex_colour(outline),
             "front": hex_colour(HEADING_RGB), "dash": list(dash)}]


# ----- the family: kinodynamic systems --------------------------------------------------------

def family_tree(system, plan, i: int, j: int, angle_x: bool, options: SceneOptions
                ) -> tuple[dict | None, int]:
    """The tree projected on variables ``i`` and ``j``, each edge its parent state and
    slices (thinned to ``max_edge_points``), and its stride within the budgets."""
    kept = plan.tree_rows_kept if plan is not None else 0
    if not kept:
        return None, 1
    cost = tree_cost(system, plan)
    stride = max(thinning(kept, cost, options.max_tree_slices, _NO_LIMIT),
                 thinning(kept, min(cost, kept * options.max_edge_points),
                          options.max_tree_points, _NO_LIMIT))
    lines = Polylines(angle_x)
    for states in tree_polylines(system, plan, stride):
        lines.add(_thin([(s[i], s[j]) for s in states], options.max_edge_points))
    return lines.item(TREE_RGB, 0.8, growth=True), stride


def plane_view(problem, report, flown: Flown, options: SceneOptions) -> tuple[dict, dict]:
    """The workspace (or the phase plane) and the tree's counts."""
    system, plan, world = problem.system, report.plan if report is not None else None, \
        problem.world
    i, j = system.position_indices
    names = system.state_names
    if world is not None and world.box is not None:
        box, angle_x, name = (world.box.x0, world.box.y0, world.box.x1, world.box.y1), False, \
            "Workspace"
    else:
        box, angle_x, name = phase_box(problem), problem.space.variables[i].angle, \
            "Phase portrait"
    tree, stride = family_tree(system, plan, i, j, angle_x, options)
    answer = Polylines(angle_x)
    answer.add((s[i], s[j]) for s in flown.states)
    body = system.occupies == "body"
    every = footprint_step(flown, options.family)
    layers = {"obstacles": obstacle_items(world) if world is not None else [],
              "tree": [tree] if tree else [],
              "footprints": body_items(system, footprint_states(flown, every)) if body else [],
              "answer": [answer.item(SOLUTION_RGB, 2.5)] if flown.states else [],
              "marks": [*(body_items(system, [problem.start], START_RGB, None) if body else []),
                        *goal_items(problem.goal, i, j, box, options.family.goal_rays, angle_x),
                        start_dot(inside(box, problem.start[i], problem.start[j], angle_x))],
              "failure": _family_failure(report, box, angle_x, False)}
    info = tree_info(plan, stride, polylines_in(tree) if tree else 0)
    what = (f"{name} ({names[i]}, {names[j]}): {info['note']}; solution re-simulated slice by "
            f"slice ({lines_note(flown)}" + (f", {body_note(every)}" if body else "") + ")"
            + duration_note(system, plan))
    return {"name": name, "what": what,
            "plots": [plot(box, names[i], names[j], layers, equal=world is not None,
                           angle_x=angle_x)]}, info


def _family_failure(report, box, angle_x: bool, angle_y: bool) -> list[dict]:
    failure = report.first_failure if report is not None else None
    if failure is None or failure.where is None:
        return []
    return [failure_cross(inside(box, *failure.where, angle_x, angle_y))]


def time_view(problem, flown: Flown) -> dict:
    """Each state variable and each held control against time along the solution."""
    system = problem.system
    end = max(flown.times[-1] if flown.times else 0.0, system.dt)
    plots = []
    for p, variable in enumerate(system.space.variables):
        values = [s[p] for s in flown.states]
        low, high = ((-math.pi, math.pi) if variable.angle
                     else panel_range(values, (variable.low, variable.high)))
        line = Polylines(False, variable.angle)
        line.add(zip(flown.times, values))
        plots.append(plot((0.0, low, end, high), "t (s)", variable.name,
                          {"answer": [line.item(SOLUTION_RGB, 1.5)] if values else []},
                          equal=False, angle_y=variable.angle, zoom="x", link="time"))
    for c, name in enumerate(system.control_names[:-1]):
        low, high = system.controls[c]
        low, high = (low, high) if low < high else (low - 1.0, high + 1.0)
        steps = Polylines()
        steps.add([q for t0, t1, u in flown.controls for q in ((t0, u[c]), (t1, u[c]))])
        plots.append(plot((0.0, low, end, high), "t (s)", f"control {name}",
                          {"answer": [steps.item(TREE_RGB, 1.5)] if flown.controls else []},
                          equal=False, zoom="x", link="time"))
    what = (f"State and control against time along the solution ({lines_note(flown)}, "
            f"{end:.4g} s; slices of {system.dt:g} s)")
    return {"name": "Against time", "what": what, "plots": plots}


def kinodynamic_views(problem, report, options: SceneOptions) -> tuple[list, dict, str]:
    """The plane view and the time view, the tree's counts and the counts line."""
    plan = report.plan if report is not None else None
    flown = fly(problem.system, plan, options.max_solution_points)
    plane, tree = plane_view(problem, report, flown, options)
    counts = (f"{lines_note(flown)}, {tree['note']}" + duration_note(problem.system, plan)
              if plan is not None else "")
    return [plane, time_view(problem, flown)], tree, counts


# ----- the family: geometric systems ----------------------------------------------------------

ARM_SQUARE = (-math.pi, -math.pi, math.pi, math.pi)


def path_of(report, options: SceneOptions) -> list:
    plan = report.plan if report is not None else None
    if plan is None:
        return []
    return [row for _, row in zip(range(options.max_solution_points), plan.trajectory_rows())]


def roadmap(plan, i: int, j: int, angles: bool, options: SceneOptions
            ) -> tuple[dict | None, int]:
    """The tree or roadmap's edges (from, to) on variables ``i`` and ``j``."""
    kept = plan.tree_rows_kept if plan is not None else 0
    if not kept:
        return None, 1
    n = plan.tree_fields // 2
    stride = thinning(kept, 2 * kept, options.max_tree_points, _NO_LIMIT)
    lines = Polylines(angles, angles)
    for index, row in enumerate(plan.tree_rows()):
        if index % stride == 0:
            lines.add([(row[i], row[j]), (row[n + i], row[n + j])])
    return lines.item(TREE_RGB, 0.8, growth=True), stride


def arm_lines(system, configurations, rgb, width: float, dash: Sequence[float] = ()) -> dict:
    arms = Polylines()
    for q in configurations:
        arms.add(system.joints(q))
    return arms.item(rgb, width, dash=dash)


def arm_workspace(problem, report, path, options: SceneOptions) -> dict:
    system, world, goal = problem.system, problem.world, problem.goal
    box = (world.box.x0, world.box.y0, world.box.x1, world.box.y1)
    poses = options.family.poses
    tips = Polylines()
    tips.add(system.joints(q)[2] for q in poses_along(system, path, 400))
    failure = report.first_failure if report is not None else None
    layers = {"obstacles": obstacle_items(world),
              "footprints": [arm_lines(system, poses_along(system, path, poses)[1:-1], POSE_RGB,
                                       2.0)] if path else [],
              "answer": [tips.item(SOLUTION_RGB, 1.2), arm_lines(system, path[-1:], SOLUTION_RGB,
                                                                  3.0)] if path else [],
              "marks": [arm_lines(system, [problem.start], START_RGB, 3.0),
                        *([arm_lines(system, [goal.target], GOAL_RGB, 1.8, (6.0, 4.0))]
                          if goal.full else []),
                        {"kind": "dot", "at": list(system.joints(problem.start)[0]),
                         "radius": 4.0, "colour": "#000000", "halo": False}],
              "failure": [arm_lines(system, [failure.where], FAILURE_RGB, 2.5)]
              if failure is not None and failure.where is not None else []}
    what = (f"Workspace: the arm at {max(0, poses - 2)} poses evenly spaced along the path "
            "(pink), its last configuration (thick red), the path of its tip (red), the goal "
            "pose (blue dashes)")
    return {"name": "Workspace", "what": what, "plots": [plot(box, "x", "y", layers)]}


def cspace_view(problem, report, path, options: SceneOptions) -> tuple[dict, dict]:
    """The arm's configuration-space square: the invalid region, tree, path, goal."""
    plan = report.plan if report is not None else None
    cells = options.family.cspace_cells
    tree, stride = roadmap(plan, 0, 1, True, options)
    answer = Polylines(True, True)
    answer.add((q[0], q[1]) for q in path)
    layers = {"obstacles": [{"kind": "cells", "cols": cells, "rows": cells, "box": list(ARM_SQUARE),
                             "cells": bytes(invalid_cells(state_validator(problem.system,
                                                                          problem.world), cells)),
                             "colour": hex_colour(OBSTACLE_GRAY)}],
              "tree": [tree] if tree else [],
              "answer": [answer.item(SOLUTION_RGB, 2.5)] if path else [],
              "marks": [*goal_items(problem.goal, 0, 1, ARM_SQUARE, options.family.goal_rays,
                                    True, True),
                        start_dot(inside(ARM_SQUARE, *problem.start[:2], True, True))],
              "failure": _family_failure(report, ARM_SQUARE, True, True)}
    info = tree_info(plan, stride, polylines_in(tree) if tree else 0)
    what = (f"Configuration space (theta1, theta2), wrapping at +-pi; grey: the arm touches "
            f"an obstacle or leaves the world ({cells} x {cells} cells tested); {info['note']}")
    return {"name": "Configuration space", "what": what,
            "plots": [plot(ARM_SQUARE, "theta1", "theta2", layers, angle_x=True,
                           angle_y=True)]}, info


def rigid_view(problem, report, path, options: SceneOptions) -> tuple[dict, dict]:
    system, world, goal = problem.system, problem.world, problem.goal
    box = (world.box.x0, world.box.y0, world.box.x1, world.box.y1)
    plan = report.plan if report is not None else None
    tree, stride = roadmap(plan, 0, 1, False, options)
    answer = Polylines()
    answer.add((q[0], q[1]) for q in path)
    poses = poses_along(system, path, 2 * options.family.poses)
    layers = {"obstacles": obstacle_items(world), "tree": [tree] if tree else [],
              "footprints": body_items(system, poses),
              "answer": [answer.item(SOLUTION_RGB, 2.5)] if path else [],
              "marks": [*body_items(system, [problem.start], START_RGB, None),
                        *(body_items(system, [goal.target], GOAL_RGB, None, (6.0, 4.0))
                          if goal.full else []),
                        *goal_items(goal, 0, 1, box, options.family.goal_rays),
                        start_dot(inside(box, *problem.start[:2]))],
              "failure": _family_failure(report, box, False, False)}
    info = tree_info(plan, stride, polylines_in(tree) if tree else 0)
    what = f"Workspace (x, y): the body at {len(poses)} poses along the path; {info['note']}"
    return {"name": "Workspace", "what": what,
            "plots": [plot(box, "x", "y", layers)]}, info


def geometric_views(problem, report, options: SceneOptions) -> tuple[list, dict, str]:
    path = path_of(report, options)
    if problem.system.occupies == "links":
        cspace, tree = cspace_view(problem, report, path, options)
        views = [arm_workspace(problem, report, path, options), cspace]
    else:
        rigid, tree = rigid_view(problem, report, path, options)
        views = [rigid]
    counts = ""
    if report is not None and report.plan is not None:
        total = report.trajectory_count
        counts = (f"{total} configurations" + (f" (first {len(path)} drawn)"
                                               if len(path) < total else "")
                  + f", {tree['note']}")
        if report.path_length is not None:
            counts += f", path length {report.path_length:.4g}"
    return views, tree, counts
