"""A placed body (a car's footprint) against a world's obstacles, on plain floats.

Placing a body's points, the polygon-against-disc test and a point's distance to
a rect or disc (a polygon's: ``segment_tests.polygon_distance``) live here as
plain-float functions that :mod:`planning_core.worlds.shapes` imports (one copy),
with :class:`BodyTest`, the per-slice collision test of every family car (compiled,
mypyc), and :func:`clearance`, a point's distance to a world's
:class:`~planning_core.worlds.segment_tests.Obstacles`.

The full test, whether the placed body leaves the box or meets an obstacle, has
one reference, the shapes' (``ContinuousWorld.polygon_free(place(...))``), and one
fast version, the C kernel ``body_kernel.c`` (the same floats; built with the
compiled modules and used with them); :class:`BodyTest` is given the one to call.
"""

from __future__ import annotations

import math
from typing import Any, Final

from planning_core.worlds.segment_tests import DISC, RECT, Obstacles, near_segment, polygon_distance

BBox = tuple[float, float, float, float]  # xmin, ymin, xmax, ymax (closed)

SNAP: Final = 1e-12
"""place(): |cos| or |sin| below this is 0, so quarter turns are exact."""


def placed_coordinates(pxs: list[float], pys: list[float], x: float, y: float,
                       theta: float) -> tuple[list[float], list[float]]:
    """The x and the y coordinates of the points (pxs, pys) rotated by ``theta``
    about the origin, then translated by ``(x, y)`` (``shapes.place``; SNAP applied)."""
    try:
        c, s = math.cos(theta), math.sin(theta)
    except ValueError:  # an infinite angle: every vertex NaN, which no world accepts
        c = s = math.nan
    if abs(c) < SNAP:
        c = 0.0
    if abs(s) < SNAP:
        s = 0.0
    xs: list[float] = []
    ys: list[float] = []
    for px, py in zip(pxs, pys):  # one pass: compiled, cheaper than two comprehensions
        xs.append(x + c * px - s * py)
        ys.append(y + s * px + c * py)
    return xs, ys


def poly_disc(xs: list[float], ys: list[float], cx: float, cy: float, r: float) -> bool:
    """Closed polygon (its points' coordinates xs, ys) and closed disc meet: centre
    inside, or a boundary point within r."""
    r2 = r * r
    inside = True
    ax, ay = xs[-1], ys[-1]
    for bx, by in zip(xs, ys):
        ex, ey = bx - ax, by - ay
        cr = ex * (cy - ay) - ey * (cx - ax)
        if cr < 0.0:  # centre strictly outside this edge's line
            inside = False
            if cr * cr > r2 * (ex * ex + ey * ey):
                return False  # the whole disc is strictly beyond the line
            if near_segment(ax, ay, bx, by, cx, cy, r2):
                return True
        ax, ay = bx, by
    return inside


# Two-argument min()/max() below compare as the builtins with more arguments do
# (the next value replaces the one so far when strictly less/greater), so NaNs and
# signed zeros come out the same; mypyc compiles only the two-argument form natively.


def disc_distance(cx: float, cy: float, r: float, x: float, y: float) -> float:
    """Distance from the point to the closed disc (0 inside or on it)."""
    return max(0.0, math.hypot(x - cx, y - cy) - r)


def rect_distance(rect: BBox, x: float, y: float) -> float:
    """Distance from the point to the closed rect (0 inside or on it)."""
    x0, y0, x1, y1 = rect
    return math.hypot(max(max(x0 - x, 0.0), x - x1), max(max(y0 - y, 0.0), y - y1))


def clearance(world: Obstacles, x: float, y: float) -> float:
    """Distance from the point to the world's nearest obstacle or box side (0 when
    it is in an obstacle or outside the box)."""
    box = world.box
    gap = math.inf
    if world.has_box:  # min() of the four, as the builtin compares them
        gap = max(0.0, min(min(min(x - box[0], box[2] - x), y - box[1]), box[3] - y))
    for i in range(len(world.kinds)):
        ox0, oy0, ox1, oy1 = world.boxes[i]
        # The gap so far is a lower bound: an obstacle that cannot be nearer is skipped.
        if max(ox0 - x, x - ox1) < gap and max(oy0 - y, y - oy1) < gap:
            gap = min(gap, obstacle_distance(world, i, x, y))
    return gap


def obstacle_distance(world: Obstacles, i: int, x: float, y: float) -> float:
    """Distance from the point to the world's obstacle ``i``."""
    kind = world.kinds[i]
    if kind == DISC:
        cx, cy, r = world.discs[i]
        return disc_distance(cx, cy, r, x, y)
    if kind == RECT:
        return rect_distance(world.boxes[i], x, y)
    return polygon_distance(world.xs[i], world.ys[i], x, y)


def native_kernel(world: Obstacles, body_xs: list[float], body_ys: list[float]) -> Any:
    """The C kernel (``planning_core/worlds/body_kernel.c``) for this body and world:
    only the compiled build holds it, else None."""
    try:
        from planning_core.worlds._body_kernel import BodyKernel
    except ImportError:
        return None
    return BodyKernel(body_xs, body_ys, world.has_box, world.box, world.kinds, world.boxes,
                      world.xs, world.ys, world.discs)


class BodyTest:
    """A body's points bound to a world (:class:`Obstacles`): :meth:`free` is the
    per-slice collision test of a car, with the free disc it remembers."""

    def __init__(self, world: Obstacles, body_xs: list[float], body_ys: list[float],
                 margin: float, meets: Any):
        self.world = world
        self.body_xs = body_xs
        self.body_ys = body_ys
        """The x and the y coordinates of the body's points in its own frame (CCW)."""
        self.margin = margin
        """The body's radius plus a margin far above rounding."""
        self.disc_x = math.nan
        self.disc_y = math.nan
        self.disc_r2 = -1.0
        """The free disc: centre and squared radius (none yet)."""
        self.last_x = math.nan
        self.last_y = math.nan
        self.last_gap = 0.0
        """Where the clearance was last measured, and it."""
        kernel = native_kernel(world, body_xs, body_ys)
        self.native = kernel is not None
        """The C kernel is in use (the compiled build is)."""
        self.meets: Any = meets if kernel is None else kernel.meets
        """``meets(x, y, theta)``: the body placed there leaves the box or meets an
        obstacle. The C kernel's where the compiled build is in use, else ``meets``,
        the reference."""
        self.native_clearance: Any = None if kernel is None else kernel.clearance
        """The C kernel's :func:`clearance` where the compiled build is in use, else None."""

    def free(self, x: float, y: float, theta: float) -> bool:
        """``not meets(x, y, theta)``, or True at once inside the free disc (see
        ``ContinuousWorld.body_test``) for a finite angle; a free pose at an infinite
        (x, y) (no box) leaves no disc."""
        dx, dy = x - self.disc_x, y - self.disc_y
        if dx * dx + dy * dy <= self.disc_r2 and theta - theta == 0.0:  # a finite angle
            return True
        if self.meets(x, y, theta):
            return False
        if not (abs(x) < math.inf and abs(y) < math.inf):
            return True  # free far out (no box): no disc centred there
        margin, moved_x, moved_y = self.margin, x - self.last_x, y - self.last_y
        # No room for a free disc here yet? The hypot is never below the larger leg,
        # so where the leg leaves room the hypot, taken only otherwise, does too.
        if (self.last_gap + max(abs(moved_x), abs(moved_y)) <= margin
                and self.last_gap + math.hypot(moved_x, moved_y) <= margin):
            return True
        native = self.native_clearance
        gap = clearance(self.world, x, y) if native is None else native(x, y)
        self.last_x, self.last_y, self.last_gap = x, y, gap
        if gap > margin:
            self.disc_x, self.disc_y, self.disc_r2 = x, y, (gap - margin) ** 2
        return True
