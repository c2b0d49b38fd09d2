"""Closed segments (the arm's links) against a world's obstacles, on plain floats.

The primitive predicates that :mod:`planning_core.worlds.shapes` builds its pair
tests from live here, with the segment-against-obstacle tests themselves, so
that the arm's hot path (a link free? how far from everything?) runs compiled
(mypyc, ``rrt_startup.compiled``) from the same single copy the shapes use.
:class:`SegmentTests` binds a world's box and obstacles once. A polygon (or a
rect's corners, a segment's ends, a point) is passed as two ``list[float]``, its
points' x and y coordinates, which compiled loops read natively.
"""

from __future__ import annotations

import math
from typing import Final, Optional

BBox = tuple[float, float, float, float]  # xmin, ymin, xmax, ymax (closed)

RECT: Final = 0
DISC: Final = 1
POLYGON: Final = 2
"""Obstacle kinds, as :class:`SegmentTests` stores them."""


def boxes_overlap(a: BBox, b: BBox) -> bool:
    """Closed boxes share a point (touching counts)."""
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def edge_separates(pxs: list[float], pys: list[float], qxs: list[float],
                   qys: list[float]) -> bool:
    """Some edge line of the CCW polygon p (its points' x and y coordinates) has
    every point of q strictly outside it."""
    ax, ay = pxs[-1], pys[-1]
    for bx, by in zip(pxs, pys):  # zip over lists: compiled to direct item reads
        ex, ey = bx - ax, by - ay
        separated = True
        for qx, qy in zip(qxs, qys):
            if ex * (qy - ay) - ey * (qx - ax) >= 0.0:  # on the line or inside
                separated = False
                break
        if separated:
            return True
        ax, ay = bx, by
    return False


def strictly_one_side(ax: float, ay: float, bx: float, by: float,
                      xs: list[float], ys: list[float]) -> bool:
    """Every point (x and y coordinates) is strictly on the same side of the line
    through a and b (False if a == b)."""
    ex, ey = bx - ax, by - ay
    side = 0.0
    for qx, qy in zip(xs, ys):
        cr = ex * (qy - ay) - ey * (qx - ax)
        # Opposite signs, compared directly: their product underflows to 0 below
        # about 1e-154 each (a segment 1e-199 long read as beside a polygon it is in).
        if cr == 0.0 or cr < 0.0 < side or side < 0.0 < cr:
            return False
        side = cr
    return True


def near_segment(ax: float, ay: float, bx: float, by: float,
                 cx: float, cy: float, r2: float) -> bool:
    """The point c is within distance sqrt(r2) of the closed segment ab (equal counts)."""
    ex, ey, wx, wy = bx - ax, by - ay, cx - ax, cy - ay
    t = ex * wx + ey * wy
    if t <= 0.0:
        return wx * wx + wy * wy <= r2
    l2 = ex * ex + ey * ey
    if t >= l2:
        dx, dy = cx - bx, cy - by
        return dx * dx + dy * dy <= r2
    cr = ex * wy - ey * wx
    return cr * cr <= r2 * l2


def segment_offset(ax: float, ay: float, bx: float, by: float, x: float,
                   y: float) -> tuple[float, float]:
    """The vector to the point (x, y) from its nearest point on the closed segment ab."""
    ex, ey, wx, wy = bx - ax, by - ay, x - ax, y - ay
    l2 = ex * ex + ey * ey
    t = 0.0 if l2 == 0.0 else min(1.0, max(0.0, (ex * wx + ey * wy) / l2))
    return wx - t * ex, wy - t * ey


def segment_distance(ax: float, ay: float, bx: float, by: float, x: float, y: float) -> float:
    """Euclidean distance from the point (x, y) to the closed segment ab."""
    px, py = segment_offset(ax, ay, bx, by, x, y)
    return math.hypot(px, py)


def nearer(best: float, px: float, py: float) -> float:
    """``min(best, math.hypot(px, py))``, the same float, without the hypot when
    ``max(|px|, |py|)``, which it never falls below, is not below ``best`` (a
    NaN compares as the builtins do: it never replaces ``best``)."""
    if max(abs(px), abs(py)) < best:
        d = math.hypot(px, py)
        if d < best:
            return d
    return best


def polygon_distance(xs: list[float], ys: list[float], x: float, y: float) -> float:
    """Distance from the point to the closed CCW polygon of points (xs, ys) (0
    inside or on it)."""
    if not edge_separates(xs, ys, [x], [y]):
        return 0.0
    best = math.inf
    ax, ay = xs[-1], ys[-1]
    for bx, by in zip(xs, ys):  # min() over the edges' distances, the hypot only where it may win
        px, py = segment_offset(ax, ay, bx, by, x, y)
        best = nearer(best, px, py)
        ax, ay = bx, by
    return best


def segment_meets_rect(x0: float, y0: float, x1: float, y1: float, box: BBox,
                       rect: BBox, xs: list[float], ys: list[float]) -> bool:
    """SAT: bounding boxes (the rect's axes), then the segment's line against the
    corners (xs, ys)."""
    return boxes_overlap(box, rect) and not strictly_one_side(x0, y0, x1, y1, xs, ys)


def segment_meets_disc(x0: float, y0: float, x1: float, y1: float, box: BBox,
                       disc_box: BBox, cx: float, cy: float, r: float) -> bool:
    """The centre is within ``r`` of the closed segment (tangent counts)."""
    return boxes_overlap(box, disc_box) and near_segment(x0, y0, x1, y1, cx, cy, r * r)


def segment_meets_polygon(x0: float, y0: float, x1: float, y1: float, box: BBox,
                          poly_box: BBox, xs: list[float], ys: list[float]) -> bool:
    """SAT with the edge lines of the polygon (xs, ys) and the segment's own line."""
    if not boxes_overlap(box, poly_box):
        return False
    if edge_separates(xs, ys, [x0, x1], [y0, y1]):
        return False
    return not strictly_one_side(x0, y0, x1, y1, xs, ys)


def segment_disc_gap(x0: float, y0: float, x1: float, y1: float,
                     cx: float, cy: float, r: float) -> float:
    """Distance from a closed segment to a closed disc it does not touch."""
    return segment_distance(x0, y0, x1, y1, cx, cy) - r


def segment_rect_gap(x0: float, y0: float, x1: float, y1: float, rect: BBox,
                     xs: list[float], ys: list[float]) -> float:
    """Distance from a closed segment to a closed rect (corners xs, ys) it does not touch."""
    rx0, ry0, rx1, ry1 = rect
    best = math.hypot(max(max(rx0 - x0, 0.0), x0 - rx1), max(max(ry0 - y0, 0.0), y0 - ry1))
    best = nearer(best, max(max(rx0 - x1, 0.0), x1 - rx1), max(max(ry0 - y1, 0.0), y1 - ry1))
    return corner_gap(x0, y0, x1, y1, xs, ys, best)


def segment_polygon_gap(x0: float, y0: float, x1: float, y1: float,
                        xs: list[float], ys: list[float]) -> float:
    """Distance from a closed segment to a closed CCW polygon (xs, ys) it does not touch."""
    best = min(polygon_distance(xs, ys, x0, y0), polygon_distance(xs, ys, x1, y1))
    return corner_gap(x0, y0, x1, y1, xs, ys, best)


def corner_gap(x0: float, y0: float, x1: float, y1: float, xs: list[float],
               ys: list[float], best: float) -> float:
    """``best`` or a corner's (xs, ys) distance to the segment, whichever is less
    (two disjoint convex sets are nearest at a vertex of one of them)."""
    for vx, vy in zip(xs, ys):
        px, py = segment_offset(x0, y0, x1, y1, vx, vy)
        best = nearer(best, px, py)
    return best


class Obstacles:
    """A world's box and obstacles, bound once on plain floats (for segment,
    point and body queries)."""

    def __init__(self, box: Optional[BBox], kinds: list[int], boxes: list[BBox],
                 xs: list[list[float]], ys: list[list[float]],
                 discs: list[tuple[float, float, float]]):
        self.has_box = box is not None
        self.box: BBox = box if box is not None else (-math.inf, -math.inf, math.inf, math.inf)
        self.kinds = kinds
        """Per obstacle: RECT, DISC or POLYGON."""
        self.boxes = boxes
        """Per obstacle: its bounding box."""
        self.xs = xs
        self.ys = ys
        """Per obstacle: the x and the y coordinates of a rect's corners or a
        polygon's points (CCW); empty for a disc."""
        self.discs = discs
        """Per obstacle: a disc's (cx, cy, r); zeros for the others."""


class SegmentTests:
    """Segment queries against a world's :class:`Obstacles` (its fields read
    straight off, for native access in the loops)."""

    def __init__(self, world: Obstacles):
        self.has_box, self.box = world.has_box, world.box
        self.kinds, self.boxes = world.kinds, world.boxes
        self.xs, self.ys, self.discs = world.xs, world.ys, world.discs

    def free(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """The closed segment is in the closed box and touches no closed obstacle (a
        NaN end is never free)."""
        # not min()/max(): they drop a NaN, these keep one in the box (so xmin <= xmax fails)
        xmin, xmax = (x0, x1) if x0 <= x1 else (x1, x0)
        ymin, ymax = (y0, y1) if y0 <= y1 else (y1, y0)
        if not (xmin <= xmax and ymin <= ymax):
            return False
        box = self.box
        if self.has_box and not (box[0] <= xmin and xmax <= box[2]
                                 and box[1] <= ymin and ymax <= box[3]):
            return False
        extent: BBox = (xmin, ymin, xmax, ymax)
        for i in range(len(self.kinds)):
            ox0, oy0, ox1, oy1 = self.boxes[i]
            if not (ox0 <= xmax and xmin <= ox1 and oy0 <= ymax and ymin <= oy1):
                continue
            if self._meets(i, x0, y0, x1, y1, extent):
                return False
        return True

    def _meets(self, i: int, x0: float, y0: float, x1: float, y1: float, extent: BBox) -> bool:
        kind = self.kinds[i]
        if kind == RECT:
            return segment_meets_rect(x0, y0, x1, y1, extent, self.boxes[i], self.xs[i], self.ys[i])
        if kind == DISC:
            cx, cy, r = self.discs[i]
            return segment_meets_disc(x0, y0, x1, y1, extent, self.boxes[i], cx, cy, r)
        return segment_meets_polygon(x0, y0, x1, y1, extent, self.boxes[i],
                                     self.xs[i], self.ys[i])

    def gap(self, x0: float, y0: float, x1: float, y1: float, enough: float) -> float:
        """The distance from a free closed segment to the box's sides and the
        obstacles, or a value of at least ``enough``."""
        lx, hx = (x0, x1) if x0 <= x1 else (x1, x0)
        ly, hy = (y0, y1) if y0 <= y1 else (y1, y0)
        box = self.box
        best = min(min(min(min(lx - box[0], box[2] - hx), ly - box[1]), box[3] - hy), enough)
        for i in range(len(self.kinds)):
            ox0, oy0, ox1, oy1 = self.boxes[i]
            # How far the obstacle's box lies beyond the segment's on some side, the
            # largest of four as max() takes it: no nearer than that (else skipped).
            far = ox0 - hx
            if lx - ox1 > far:
                far = lx - ox1
            if oy0 - hy > far:
                far = oy0 - hy
            if ly - oy1 > far:
                far = ly - oy1
            if far < best:
                best = min(best, self._gap_to(i, x0, y0, x1, y1))
        return best

    def _gap_to(self, i: int, x0: float, y0: float, x1: float, y1: float) -> float:
        kind = self.kinds[i]
        if kind == DISC:
            cx, cy, r = self.discs[i]
            return segment_disc_gap(x0, y0, x1, y1, cx, cy, r)
        if kind == RECT:
            return segment_rect_gap(x0, y0, x1, y1, self.boxes[i], self.xs[i], self.ys[i])
        return segment_polygon_gap(x0, y0, x1, y1, self.xs[i], self.ys[i])
