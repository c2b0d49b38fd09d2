"""Exact closed-set geometry on plain floats (SPEC 5.1, 5.2).

Every shape is a CLOSED set, and every test asks "do the two closed sets share
a point?": a shared edge, a shared vertex or a tangent disc is an intersection.

Ties: no tolerance is used anywhere in the tests. Each decision is one float
comparison (an orientation ``cross``, an interval gap, ``d**2`` against
``r**2``) and an exact 0 counts as touching, hence as an intersection; the
comparisons are ``<=`` for "touching or overlapping" and ``<`` / ``>`` for
"strictly apart". So whenever a touching configuration is exactly
representable in floats (edges on the same coordinate, 3-4-5 distances, ...)
the answer is "intersects"; a gap of one ulp is a gap. Rounding in the
inputs (a rotated vertex, ``r1 + r2``) is not corrected: the computed values
are what is compared.

Conventions: polygons are stored counter-clockwise. For an edge ``a -> b``
with ``e = b - a`` and a point ``q``, ``cross = ex*(qy-ay) - ey*(qx-ax)`` is
> 0 strictly inside the edge's line, 0 on it, < 0 strictly outside it.
A separating axis is an edge line (or a segment's line) with the other shape
STRICTLY on its outer side; axis-aligned axes are the closed bounding boxes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterable, Sequence, Union

from planning_core.worlds.body_tests import SNAP, disc_distance, placed_coordinates, rect_distance
from planning_core.worlds.body_tests import poly_disc as _poly_disc
from planning_core.worlds.segment_tests import (boxes_overlap, polygon_distance, segment_disc_gap,
                                                segment_meets_disc, segment_meets_polygon,
                                                segment_meets_rect, segment_polygon_gap,
                                                segment_rect_gap)
from planning_core.worlds.segment_tests import edge_separates as _edge_separates
from planning_core.worlds.segment_tests import segment_distance as _segment_distance
from planning_core.worlds.segment_tests import strictly_one_side as _strictly_one_side

Point = tuple[float, float]
BBox = tuple[float, float, float, float]  # xmin, ymin, xmax, ymax (closed)

# Validation only: consecutive edges with |cross| <= this * |e1| * |e2| are collinear.
COLLINEAR_RTOL = 1e-12


def _require_finite(what: str, values: Iterable[float]) -> None:
    for v in values:
        if not math.isfinite(v):
            raise ValueError(f"{what}: coordinates must be finite, got {v!r}")


@dataclass(frozen=True)
class Rect:
    """The closed axis-aligned box ``[x0, x1] x [y0, y1]``; needs x0 < x1, y0 < y1."""

    x0: float
    y0: float
    x1: float
    y1: float
    bbox: BBox = field(init=False, repr=False, compare=False)
    corners: tuple[Point, ...] = field(init=False, repr=False, compare=False)
    xs: list[float] = field(init=False, repr=False, compare=False)
    ys: list[float] = field(init=False, repr=False, compare=False)
    """The corners' x and y coordinates (as the primitives take them; not to be changed)."""

    def __post_init__(self) -> None:
        x0, y0, x1, y1 = (float(v) for v in (self.x0, self.y0, self.x1, self.y1))
        _require_finite("rect", (x0, y0, x1, y1))
        if not (x0 < x1 and y0 < y1):
            raise ValueError(f"rect: needs x0 < x1 and y0 < y1 (min corner, max corner), "
                             f"got {x0!r} {y0!r} {x1!r} {y1!r}")
        for name, v in (("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1)):
            object.__setattr__(self, name, v)
        object.__setattr__(self, "bbox", (x0, y0, x1, y1))
        object.__setattr__(self, "corners", ((x0, y0), (x1, y0), (x1, y1), (x0, y1)))
        object.__setattr__(self, "xs", [x0, x1, x1, x0])
        object.__setattr__(self, "ys", [y0, y0, y1, y1])

    @property
    def polygon(self) -> ConvexPolygon:
        """The same closed set as a counter-clockwise :class:`ConvexPolygon`."""
        return ConvexPolygon._trusted(self.corners, self.bbox)


@dataclass(frozen=True)
class Disc:
    """The closed disc of centre ``(cx, cy)`` and radius ``r > 0``."""

    cx: float
    cy: float
    r: float
    bbox: BBox = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        cx, cy, r = float(self.cx), float(self.cy), float(self.r)
        _require_finite("circle", (cx, cy, r))
        if not r > 0.0:
            raise ValueError(f"circle: radius must be > 0, got {r!r}")
        object.__setattr__(self, "cx", cx)
        object.__setattr__(self, "cy", cy)
        object.__setattr__(self, "r", r)
        object.__setattr__(self, "bbox", (cx - r, cy - r, cx + r, cy + r))


@dataclass(frozen=True)
class Segment:
    """The closed segment from ``(x0, y0)`` to ``(x1, y1)`` (a point when they coincide)."""

    x0: float
    y0: float
    x1: float
    y1: float
    bbox: BBox = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        x0, y0, x1, y1 = (float(v) for v in (self.x0, self.y0, self.x1, self.y1))
        _require_finite("segment", (x0, y0, x1, y1))
        for name, v in (("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1)):
            object.__setattr__(self, name, v)
        object.__setattr__(self, "bbox", (min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)))

    @classmethod
    def _trusted(cls, x0: float, y0: float, x1: float, y1: float) -> Segment:
        """No validation or conversion (the hot path of arm links)."""
        # not min()/max(): they drop a NaN, these keep one in the box (so xmin <= xmax fails)
        xmin, xmax = (x0, x1) if x0 <= x1 else (x1, x0)
        ymin, ymax = (y0, y1) if y0 <= y1 else (y1, y0)
        seg = object.__new__(cls)
        seg.__dict__.update(x0=x0, y0=y0, x1=x1, y1=y1, bbox=(xmin, ymin, xmax, ymax))
        return seg


@dataclass(frozen=True)
class ConvexPolygon:
    """A closed convex polygon, validated and stored counter-clockwise.

    ``points``: at least 3 ``(x, y)`` vertices, either winding. Rejected with
    ValueError: fewer than 3 vertices, non-finite coordinates, a repeated vertex
    or three consecutive collinear vertices (relative tolerance
    ``COLLINEAR_RTOL``), a reflex vertex, a self-intersecting boundary.
    """

    points: tuple[Point, ...]
    bbox: BBox = field(init=False, repr=False, compare=False)
    xs: list[float] = field(init=False, repr=False, compare=False)
    ys: list[float] = field(init=False, repr=False, compare=False)
    """The points' x and y coordinates (as the primitives take them; not to be changed)."""

    def __post_init__(self) -> None:
        pts = _validated_ccw(self.points)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "bbox", _bbox_of(pts))
        object.__setattr__(self, "xs", [p[0] for p in pts])
        object.__setattr__(self, "ys", [p[1] for p in pts])

    @classmethod
    def _trusted(cls, points: tuple[Point, ...], bbox: BBox) -> ConvexPolygon:
        """No validation: ``points`` are known convex and counter-clockwise."""
        poly = object.__new__(cls)
        poly.__dict__.update(points=points, bbox=bbox,  # frozen: bypass __setattr__
                             xs=[p[0] for p in points], ys=[p[1] for p in points])
        return poly


Shape = Union[Rect, Disc, ConvexPolygon, Segment]


def _bbox_of(pts: Sequence[Point]) -> BBox:
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    return (min(xs), min(ys), max(xs), max(ys))


def _validated_ccw(points: Iterable) -> tuple[Point, ...]:
    """The vertices as float pairs, counter-clockwise; ValueError when not a convex polygon."""
    try:
        pts = tuple((float(x), float(y)) for x, y in points)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"polygon: vertices must be (x, y) pairs of numbers ({exc})") from None
    if len(pts) < 3:
        raise ValueError(f"polygon: needs at least 3 vertices, got {len(pts)}")
    _require_finite("polygon", (c for p in pts for c in p))
    sign, turning, n = 0, 0.0, len(pts)
    for i in range(n):
        (ax, ay), (bx, by), (cx, cy) = pts[i - 1], pts[i], pts[(i + 1) % n]
        e1x, e1y, e2x, e2y = bx - ax, by - ay, cx - bx, cy - by
        cross = e1x * e2y - e1y * e2x
        if abs(cross) <= COLLINEAR_RTOL * math.hypot(e1x, e1y) * math.hypot(e2x, e2y):
            raise ValueError(f"polygon: degenerate at vertex {i + 1} {pts[i]}: repeated, "
                             f"or collinear with its neighbours")
        turn = 1 if cross > 0 else -1
        if sign and turn != sign:
            raise ValueError(f"polygon: not convex (reflex turn at vertex {i + 1} {pts[i]})")
        sign = turn
        turning += math.atan2(cross, e1x * e2x + e1y * e2y)
    if abs(turning) > 3 * math.pi:  # a convex boundary turns exactly once (2 pi)
        raise ValueError("polygon: not convex (its boundary crosses itself)")
    return pts if sign > 0 else pts[::-1]


def body_polygon(kind: str, dims: Sequence[float]) -> ConvexPolygon:
    """A body footprint in its own frame (SPEC 5.1 ``body KIND ...``).

    ``square SIDE`` and ``rect LENGTH WIDTH`` are centred on the origin, the
    length along the body's x axis; ``polygon X1 Y1 X2 Y2 ...`` is taken as given.
    """
    dims = tuple(float(d) for d in dims)
    if kind in ("square", "rect"):
        wanted = 1 if kind == "square" else 2
        if len(dims) != wanted:
            names = "SIDE" if kind == "square" else "LENGTH WIDTH"
            raise ValueError(f"body {kind}: takes {names}, got {len(dims)} numbers")
        length, width = (dims[0], dims[0]) if kind == "square" else dims
        _require_finite(f"body {kind}", dims)
        if not (length > 0.0 and width > 0.0):
            raise ValueError(f"body {kind}: sizes must be > 0, got {dims}")
        hx, hy = length / 2.0, width / 2.0
        corners = ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))
        return ConvexPolygon._trusted(corners, (-hx, -hy, hx, hy))
    if kind == "polygon":
        if len(dims) % 2 or len(dims) < 6:
            raise ValueError(f"body polygon: needs X Y pairs for at least 3 vertices, "
                             f"got {len(dims)} numbers")
        return ConvexPolygon(tuple(zip(dims[0::2], dims[1::2])))
    raise ValueError(f"body: unknown kind {kind!r} (square | rect | polygon)")


def place(polygon: ConvexPolygon, x: float, y: float, theta: float) -> ConvexPolygon:
    """``polygon`` rotated by ``theta`` about the origin, then translated by ``(x, y)``.

    A cosine or sine below ``SNAP`` in magnitude is taken as 0 (the other one is
    then exactly +-1 already), so quarter turns such as ``math.pi / 2`` (whose
    float cosine is 6e-17) rotate exactly: a 2 x 1 rect at ``pi/2`` spans
    exactly ``x in [-0.5, 0.5]``. This moves no vertex by more than
    ``SNAP`` times its distance from the origin.
    """
    xs, ys = placed_coordinates(polygon.xs, polygon.ys, x, y, theta)
    return ConvexPolygon._trusted(tuple(zip(xs, ys)), (min(xs), min(ys), max(xs), max(ys)))


# --- Primitive predicates -----------------------------------------------------------


def _box_within(inner: BBox, outer: BBox) -> bool:
    return (outer[0] <= inner[0] and inner[2] <= outer[2]
            and outer[1] <= inner[1] and inner[3] <= outer[3])


# --- Pairwise tests (both shapes closed; touching is an intersection) ---------------


def polygons_intersect(a: ConvexPolygon, b: ConvexPolygon) -> bool:
    """Separating axis theorem over both polygons' edge normals."""
    if not boxes_overlap(a.bbox, b.bbox):
        return False
    return not (_edge_separates(a.xs, a.ys, b.xs, b.ys) or _edge_separates(b.xs, b.ys, a.xs, a.ys))


def polygon_rect_intersect(p: ConvexPolygon, rect: Rect) -> bool:
    """SAT: the rect's axes are the bounding-box test, then the polygon's edges."""
    return boxes_overlap(p.bbox, rect.bbox) and not _edge_separates(p.xs, p.ys, rect.xs, rect.ys)


def polygon_disc_intersect(p: ConvexPolygon, d: Disc) -> bool:
    """Centre inside the polygon, or the polygon's closest point within ``r`` (tangent counts)."""
    return boxes_overlap(p.bbox, d.bbox) and _poly_disc(p.xs, p.ys, d.cx, d.cy, d.r)


def segment_polygon_intersect(s: Segment, p: ConvexPolygon) -> bool:
    """SAT with the polygon's edge lines and the segment's own line."""
    return segment_meets_polygon(s.x0, s.y0, s.x1, s.y1, s.bbox, p.bbox, p.xs, p.ys)


def segment_rect_intersect(s: Segment, rect: Rect) -> bool:
    """SAT: bounding boxes (the rect's axes), then the segment's line against the corners."""
    return segment_meets_rect(s.x0, s.y0, s.x1, s.y1, s.bbox, rect.bbox, rect.xs, rect.ys)


def segment_disc_intersect(s: Segment, d: Disc) -> bool:
    """The centre is within ``r`` of the closed segment (tangent counts)."""
    return segment_meets_disc(s.x0, s.y0, s.x1, s.y1, s.bbox, d.bbox, d.cx, d.cy, d.r)


def segments_intersect(s: Segment, t: Segment) -> bool:
    """Closed segments share a point (orientation tests; collinear ones by their boxes)."""
    if not boxes_overlap(s.bbox, t.bbox):
        return False
    if _strictly_one_side(s.x0, s.y0, s.x1, s.y1, [t.x0, t.x1], [t.y0, t.y1]):
        return False
    # not strictly apart on either line, boxes overlap: they meet (collinear case included)
    return not _strictly_one_side(t.x0, t.y0, t.x1, t.y1, [s.x0, s.x1], [s.y0, s.y1])


def disc_rect_intersect(d: Disc, rect: Rect) -> bool:
    """The rect's closest point to the centre is within ``r`` (a touched corner counts)."""
    dx = d.cx - min(max(d.cx, rect.x0), rect.x1)
    dy = d.cy - min(max(d.cy, rect.y0), rect.y1)
    return dx * dx + dy * dy <= d.r * d.r


def discs_intersect(a: Disc, b: Disc) -> bool:
    """Centre distance <= r1 + r2."""
    dx, dy, rr = a.cx - b.cx, a.cy - b.cy, a.r + b.r
    return dx * dx + dy * dy <= rr * rr


def rects_intersect(a: Rect, b: Rect) -> bool:
    return boxes_overlap(a.bbox, b.bbox)


_PAIRS = {
    (ConvexPolygon, ConvexPolygon): polygons_intersect,
    (ConvexPolygon, Rect): polygon_rect_intersect,
    (ConvexPolygon, Disc): polygon_disc_intersect,
    (Segment, ConvexPolygon): segment_polygon_intersect,
    (Segment, Rect): segment_rect_intersect,
    (Segment, Disc): segment_disc_intersect,
    (Segment, Segment): segments_intersect,
    (Disc, Rect): disc_rect_intersect,
    (Disc, Disc): discs_intersect,
    (Rect, Rect): rects_intersect,
}


def pair_test(kind_a: type, kind_b: type):
    """The function ``f(a, b)`` testing shapes of these two types (argument order kept)."""
    fn = _PAIRS.get((kind_a, kind_b))
    if fn is not None:
        return fn
    swapped = _PAIRS.get((kind_b, kind_a))
    if swapped is None:
        raise TypeError(f"no intersection test for {kind_a.__name__} and {kind_b.__name__}")
    return lambda a, b: swapped(b, a)


def intersects(a: Shape, b: Shape) -> bool:
    """Closed ``a`` and ``b`` share a point; any pair of Rect, Disc, ConvexPolygon, Segment."""
    return pair_test(type(a), type(b))(a, b)


def inside_box(shape: Shape, box: Rect) -> bool:
    """``shape`` lies in the closed ``box`` (touching the border is inside).

    Compares bounding boxes, which for a polygon or segment are its extreme
    vertices: exactly "every vertex within the box"; a disc needs
    ``x0 <= cx - r`` and so on.
    """
    return _box_within(shape.bbox, box.bbox)


def point_in(shape: Shape, x: float, y: float) -> bool:
    """The point lies in the closed ``shape`` (on the boundary counts)."""
    if isinstance(shape, ConvexPolygon):
        return not _edge_separates(shape.xs, shape.ys, [x], [y])
    if isinstance(shape, Disc):
        dx, dy = x - shape.cx, y - shape.cy
        return dx * dx + dy * dy <= shape.r * shape.r
    if isinstance(shape, Rect):
        return shape.x0 <= x <= shape.x1 and shape.y0 <= y <= shape.y1
    return segments_intersect(shape, Segment(x, y, x, y))


def point_distance(shape: Shape, x: float, y: float) -> float:
    """Euclidean distance from the point to the closed ``shape`` (0 inside or on it).

    Rounded as floats are: callers that build a certainty on it keep a margin."""
    if isinstance(shape, Disc):
        return disc_distance(shape.cx, shape.cy, shape.r, x, y)
    if isinstance(shape, Rect):
        return rect_distance(shape.bbox, x, y)
    if isinstance(shape, Segment):
        return _segment_distance(shape.x0, shape.y0, shape.x1, shape.y1, x, y)
    return polygon_distance(shape.xs, shape.ys, x, y)


# --- Gaps (distances between disjoint shapes) ---------------------------------------


def segment_gap(shape: Union[Rect, Disc, ConvexPolygon],
                x0: float, y0: float, x1: float, y1: float) -> float:
    """Distance from the closed segment to the closed ``shape`` (a Disc, Rect or
    ConvexPolygon) that it does not touch. Rounded as floats are: keep a margin."""
    if isinstance(shape, Disc):
        return segment_disc_gap(x0, y0, x1, y1, shape.cx, shape.cy, shape.r)
    if isinstance(shape, Rect):
        return segment_rect_gap(x0, y0, x1, y1, shape.bbox, shape.xs, shape.ys)
    return segment_polygon_gap(x0, y0, x1, y1, shape.xs, shape.ys)
