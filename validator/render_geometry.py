"""What every picture of the validator draws, in world coordinates, without a drawing
library: the solution as flown (a spaceship's or a family system's slices), the tree's
polylines, a geometric path's poses, the goal region's outline, a body's heading, the
budgets (thinning a tree, saying so) and the unwrapping of angle axes. The PDF's pages
(render_page and above) and the browser view (render_scene) both draw from here, so the
two show the same thing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import islice
from typing import Iterable, Iterator, Sequence

from planning_core.systems import spaceship
from validator.checks import ValidationReport

TAU = 2.0 * math.pi

# Every picture's colours (RGB from 0 to 1; greys one level).
SOLUTION_RGB = (0.85, 0.05, 0.05)
TREE_RGB = (0.50, 0.62, 0.82)
BLOCKED_GRAY = 0.30
GRID_GRAY = 0.82
START_RGB = (0.0, 0.60, 0.0)
GOAL_RGB = (0.10, 0.20, 0.95)
CORNER_RGB = (1.0, 0.55, 0.0)
FAILURE_RGB = (0.85, 0.0, 0.85)
VALID_RGB = (0.0, 0.50, 0.0)
FOOTPRINT_RGB = (0.90, 0.40, 0.50)  # the family's bodies along a solution: outline
FOOTPRINT_FILL_RGB = (0.99, 0.85, 0.88)  # ... and fill
HEADING_RGB = (0.45, 0.0, 0.20)    # a body's heading mark (its front edge)
START_FILL_RGB = (0.80, 0.95, 0.80)  # the body at the start
POSE_RGB = (0.95, 0.55, 0.60)      # the arm at poses along its path
OBSTACLE_GRAY = 0.55               # the family's obstacles

SHIP_POINTS = 1 + spaceship.SLICES  # a spaceship line drawn: its state and every slice


# ----- budgets ----------------------------------------------------------------------------

@dataclass(frozen=True)
class FamilyOptions:
    """What the family's pages draw, beyond RenderOptions's budgets."""

    footprints: int = 40
    """About this many body footprints along a kinodynamic solution."""
    poses: int = 12
    """The arm or rigid body drawn at about this many poses along a geometric path."""
    cspace_cells: int = 200
    """The arm's configuration-space square is shaded from this many x this many tests."""
    goal_rays: int = 72
    """Vertices of a goal region's outline (found along rays from the goal)."""



def thinning(count: int, cost: int, max_points: int, max_edges: int) -> int:
    """Draw every k-th of ``count`` tree edges costing ``cost`` vertices in all, so that
    at most ``max_points`` vertices and ``max_edges`` edges are drawn."""
    return max(1, math.ceil(cost / max_points), math.ceil(count / max_edges))


def tree_note(total: int, kept: int, stride: int) -> str:
    """``300000 tree edges (thinned: one in 63 drawn) (the first 250000 kept)``."""
    if total == 0:
        return "no tree"
    note = f"{total} tree edges"
    if stride > 1:
        note += f" (thinned: one in {stride} drawn)"
    if kept < total:
        note += f" (the first {kept} kept)"
    return note


def rows_in_budget(count: int, budget: int, points_per_row: int) -> int:
    return max(0, min(count, budget // points_per_row))


# ----- the grid's solution and tree --------------------------------------------------------

def grid_solution(report: ValidationReport, lines: int) -> Iterator[tuple[float, float]]:
    """The first ``lines`` lines of a grid answer as flown: the printed points (point
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
    """A grid answer as flown (see grid_solution), its first ``max_lines`` lines or all."""
    count = report.plan.trajectory_count if report.plan is not None else 0
    return list(grid_solution(report, count if max_lines is None else max_lines))


def grid_tree_edge(row: Sequence[float], ship: bool) -> list[tuple[float, float]]:
    """A grid tree edge's points: its two ends, or a spaceship's state and slices
    (nothing when a number is not finite)."""
    if not ship:
        return [(row[0], row[1]), (row[2], row[3])]
    if not all(map(math.isfinite, row)):
        return []
    return [(row[0], row[1]), *((s[0], s[1]) for s in
                                spaceship.SYSTEM.slice_states(row[:4], row[4:]))]


# ----- the family's kinodynamic answers, flown slice by slice ------------------------------

@dataclass
class Flown:
    """The solution as flown: each drawn line's state and slices, with times."""

    states: list = field(default_factory=list)
    times: list = field(default_factory=list)
    controls: list = field(default_factory=list)
    """(start time, end time, held values) per drawn line."""
    lines: int = 0
    total: int = 0


def drawable(system, row) -> bool:
    """A kinodynamic row whose numbers are finite and control within bounds."""
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
        if not drawable(system, row):
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


def phase_box(problem) -> tuple[float, float, float, float]:
    """The phase plane of a system without a world (the pendulum): the first
    variable (an angle) across, the second's bounds up."""
    j = problem.system.position_indices[1]
    variable = problem.space.variables[j]
    low, high = variable.low, variable.high
    if not (math.isfinite(low) and math.isfinite(high)):
        low, high = -10.0, 10.0
    return -math.pi, low, math.pi, high


def footprint_step(flown: Flown, family: FamilyOptions) -> int:
    """The body is drawn every this many states along the flown solution."""
    return max(1, len(flown.states) // family.footprints)


def footprint_states(flown: Flown, every: int) -> list:
    """Every ``every``-th state of the flown solution and its last."""
    if not flown.states or not flown.lines:
        return []
    return [*flown.states[::every], flown.states[-1]]


def panel_range(values: Sequence[float], bounds: tuple[float, float]) -> tuple[float, float]:
    low, high = bounds
    if math.isfinite(low) and math.isfinite(high) and low < high:
        return low, high
    finite = [v for v in values if math.isfinite(v)] or [0.0]
    low, high = min(finite), max(finite)
    pad = 0.05 * (high - low) or 1.0
    return low - pad, high + pad


def duration(system, plan) -> float | None:
    """Seconds the whole answer lasts (K slices of dt a line), or None."""
    if plan is None or not plan.trajectory_count:
        return None
    ks = plan.trajectory[plan.trajectory_fields - 1::plan.trajectory_fields]
    total = math.fsum(k for k in ks if math.isfinite(k) and k > 0) * system.dt
    return total if math.isfinite(total) else None


def tree_cost(system, plan) -> int:
    """Vertices the kept tree edges would take, each its parent and K slices."""
    kmax = system.kmax
    return sum(min(max(int(k), 1), kmax) + 1 if math.isfinite(k) else 1
               for k in plan.tree[plan.tree_fields - 1::plan.tree_fields])


def tree_polylines(system, plan, stride: int) -> Iterator[list]:
    """Every ``stride``-th kept tree edge as its parent state and slices (an empty
    list for an edge with a bad control, so that the k-th item is the k-th edge drawn)."""
    n = len(system.state_names)
    for index, row in enumerate(plan.tree_rows()):
        if index % stride == 0:
            yield ([row[:n], *system.slice_states(row[:n], row[n:])]
                   if drawable(system, row) else [])


# ----- the family's geometric answers --------------------------------------------------------

def poses_along(system, path: Sequence, count: int) -> list:
    """``count`` configurations evenly spaced (in the metric) along the path, both
    ends included (the path itself when it is one configuration)."""
    if len(path) < 2 or count < 2:
        return list(path[:1])
    lengths = [system.distance(a, b) for a, b in zip(path, path[1:])]
    total = math.fsum(lengths)
    if not (total > 0.0 and math.isfinite(total)):
        return [path[0], path[-1]]
    poses, segment, walked = [], 0, 0.0
    for k in range(count):
        at = total * k / (count - 1)
        while segment < len(lengths) - 1 and walked + lengths[segment] < at:
            walked += lengths[segment]
            segment += 1
        d = lengths[segment]
        t = min(1.0, (at - walked) / d) if d > 0 else 1.0
        poses.append(system.interpolate(path[segment], path[segment + 1], t))
    return poses


def cell_runs(cells: bytes, cols: int, rows: int) -> Iterator[tuple[int, int, int]]:
    """``(row, first, end)`` of each run of filled cells (1) along each row of a grid
    stored row by row from the bottom: how the pictures draw cells, a rectangle a run."""
    for r in range(rows):
        row = cells[r * cols:(r + 1) * cols]
        c = row.find(1)
        while c >= 0:
            end = row.find(0, c)
            end = cols if end < 0 else end
            yield r, c, end
            c = row.find(1, end)


def invalid_cells(valid, cells: int) -> bytearray:
    """A ``cells`` x ``cells`` grid over the square [-pi, pi]^2, row by row from the
    bottom: 1 where the configuration at the cell's centre is not ``valid``."""
    step = TAU / cells
    centres = [-math.pi + (k + 0.5) * step for k in range(cells)]
    return bytearray(0 if valid((t1, t2)) else 1 for t2 in centres for t1 in centres)


def front_mark(system, state) -> tuple[tuple[float, float], tuple[float, float]]:
    """A body's heading mark, placed at ``state``: its front edge (the side farthest
    along the body's x axis), or from its reference point to its nose when the front
    is one vertex."""
    points = system.body.points
    front = max(p[0] for p in points)
    ahead = sorted((p for p in points if p[0] >= front - 1e-9 * (1.0 + abs(front))),
                   key=lambda p: p[1])
    ends = (ahead[0], ahead[-1]) if len(ahead) > 1 else ((0.0, 0.0), ahead[0])
    x, y, theta = state[0], state[1], state[2]
    c, s = math.cos(theta), math.sin(theta)
    return tuple((x + c * px - s * py, y + s * px + c * py) for px, py in ends)


# ----- angle axes ---------------------------------------------------------------------------

def unwrapped(points: Iterable[tuple[float, float]], angle_x: bool, angle_y: bool
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


def turns(low: float, high: float, angle: bool) -> range:
    """The turns k for which values in [low, high], shifted by k turns, reach [-pi, pi]."""
    if not angle:
        return range(0, 1)
    return range(math.ceil((-math.pi - high) / TAU), math.floor((math.pi - low) / TAU) + 1)


def wrapped(value: float, angle: bool) -> float:
    return math.remainder(value, TAU) if angle and math.isfinite(value) else value


# ----- the goal region -------------------------------------------------------------------

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


def goal_shape(goal, i: int, j: int, rays: int, box: tuple[float, float, float, float]
               ) -> tuple[list[list[tuple[float, float]]], float | None]:
    """The goal region projected on variables ``i`` (across) and ``j`` (up), as
    polylines in data units: its outline when the goal names both, a band's two edges
    across ``box`` when it names one, else none; and its reach along ``i`` when it
    names both (None otherwise: no crosshair)."""
    names = set(goal.names)
    variables = goal.space.variables
    has_i, has_j = variables[i].name in names, variables[j].name in names
    gx, gy = goal.target[i], goal.target[j]
    if has_i and has_j:
        outline = []
        for k in range(rays + 1):
            c, s = math.cos(TAU * k / rays), math.sin(TAU * k / rays)
            r = _reach(goal, ((i, c), (j, s)))
            outline.append((gx + r * c, gy + r * s))
        return [outline], _reach(goal, ((i, 1.0),))
    lines = []
    if has_i or has_j:
        x0, y0, x1, y1 = box
        index, centre = (i, gx) if has_i else (j, gy)
        for sign in (1.0, -1.0):
            edge = centre + sign * _reach(goal, ((index, sign),))
            lines.append([(edge, y0), (edge, y1)] if has_i else [(x0, edge), (x1, edge)])
    return lines, None


# ----- what the pictures say: headings, captions, notes, tick labels -------------------------

_MIN_TICK_GAP = 30.0  # points between labelled ticks, at least


def caption_lines(report: ValidationReport | None, notes: Sequence[str]) -> list[str]:
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


def grid_heading(problem, vehicle, report: ValidationReport | None, problem_label: str) -> str:
    """The line under the verdict: the problem, the vehicle, and -strict if so."""
    return (f"{problem_label or 'problem'}: {problem.width} x {problem.height} map, start "
            f"({problem.start[0]:g}, {problem.start[1]:g}), goal ({problem.goal[0]:g}, "
            f"{problem.goal[1]:g})   vehicle: {vehicle.value}"
            + ("   -strict" if report is not None and report.strict else ""))


def _values(names: Sequence[str], values: Sequence[float]) -> str:
    return " ".join(f"{n} {v:.4g}" for n, v in zip(names, values))


def family_heading(problem, report, label: str) -> str:
    """The line under the verdict: problem, system, start, goal, -strict."""
    goal = problem.goal
    return (f"{label or 'problem'}: system {problem.system_name}, start "
            f"{_values(problem.system.state_names, problem.start)}, goal "
            f"{_values(goal.names, [v for _, v in goal.values])} within {goal.tolerance:g}"
            + ("   -strict" if report is not None and report.strict else ""))


def lines_note(flown: Flown) -> str:
    if flown.lines < flown.total:
        return f"{flown.lines} of {flown.total} lines drawn"
    return f"{flown.total} lines"


def duration_note(system, plan) -> str:
    """How long the answer lasts (a kinodynamic answer's measure, not a length)."""
    seconds = duration(system, plan)
    return "" if seconds is None else f"; duration {seconds:.4g} s"


def body_note(every: int) -> str:
    return "the body at every slice" if every == 1 else f"the body every {every} slices"


def tick_steps(scale: float) -> tuple[float, float | None]:
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


def tick_label(value: float) -> str:
    return f"{round(value, 9):g}"


def _angle_label(value: float) -> str:
    quarter = round(value / (math.pi / 2))
    return {0: "0", 1: "pi/2", -1: "-pi/2", 2: "pi", -2: "-pi"}.get(quarter, f"{quarter}pi/2")


_LABEL_ROOM = 9.0  # points between labelled ticks along y, at least (7.5 pt labels)


def _multiples(low: float, high: float, step: float) -> range:
    return range(math.ceil(low / step - 1e-9), math.floor(high / step + 1e-9) + 1)


def axis_ticks(low: float, high: float, scale: float, angle: bool, gap: float
                ) -> list[tuple[float, str]]:
    """Labelled ticks about ``gap`` points apart, at least three where they fit
    _LABEL_ROOM apart; an angle's at multiples of pi/2, or of pi when that is crowded."""
    if angle:
        step = math.pi / 2 if (high - low) * scale >= 4 * gap else math.pi
        return [(k * step, _angle_label(k * step)) for k in _multiples(low, high, step)]
    step, _ = tick_steps(scale * 30.0 / gap)
    while len(_multiples(low, high, step)) < 3:
        mantissa = round(step / 10 ** math.floor(math.log10(step)))
        smaller = step / (2.5 if mantissa == 5 else 2.0)
        if smaller * scale < _LABEL_ROOM:
            break
        step = smaller
    return [(k * step, tick_label(k * step)) for k in _multiples(low, high, step)]
