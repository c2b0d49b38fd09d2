"""The continuous world of SPEC 5.1: a closed box and closed obstacles.

A body (a placed :class:`ConvexPolygon`) or an arm link (a :class:`Segment`) is
free when it lies inside the closed world box (touching the border is fine,
crossing it is not) and shares no point with any closed obstacle (touching one
is a collision). Systems without a workspace (the pendulum) use ``box=None``:
then only the obstacles count, and there are usually none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence, Union

from planning_core.worlds.body_tests import BodyTest, clearance
from planning_core.worlds.link_tests import LinkTests
from planning_core.worlds.segment_tests import DISC, POLYGON, RECT, Obstacles, SegmentTests
from planning_core.worlds.shapes import (
    BBox,
    ConvexPolygon,
    Disc,
    Rect,
    Shape,
    inside_box,
    pair_test,
    place,
    point_in,
)

Obstacle = Union[Rect, Disc, ConvexPolygon]
OUTSIDE_BOX = -1
# A free disc (body_test) keeps this share of the world's scale clear of rounding.
CLEARANCE_MARGIN = 1e-9


@dataclass(frozen=True)
class ContinuousWorld:
    """The box (or None) and the obstacles, in the order the problem lists them."""

    box: Optional[Rect]
    obstacles: tuple[Obstacle, ...] = ()
    _bboxes: tuple[BBox, ...] = field(init=False, repr=False, compare=False)
    _tests: dict = field(init=False, repr=False, compare=False)
    _segments: SegmentTests = field(init=False, repr=False, compare=False)
    _bound: Obstacles = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.box is not None and not isinstance(self.box, Rect):
            raise TypeError(f"world box must be a Rect or None, got {type(self.box).__name__}")
        obstacles = tuple(self.obstacles)
        for i, obstacle in enumerate(obstacles):
            if not isinstance(obstacle, (Rect, Disc, ConvexPolygon)):
                raise TypeError(f"obstacle {i}: expected Rect, Disc or ConvexPolygon, "
                                f"got {type(obstacle).__name__}")
        object.__setattr__(self, "obstacles", obstacles)
        object.__setattr__(self, "_bboxes", tuple(o.bbox for o in obstacles))
        object.__setattr__(self, "_tests", {})
        segments, bound = _bind(self.box, obstacles)
        object.__setattr__(self, "_segments", segments)
        object.__setattr__(self, "_bound", bound)

    def __reduce__(self):
        # Pickled by its fields: the bound tests (compiled ones among them) are rebuilt.
        return (type(self), (self.box, self.obstacles))

    def _tests_for(self, kind: type) -> tuple[Callable[[Shape, Obstacle], bool], ...]:
        """Per obstacle, the exact test against a query of type ``kind`` (cached)."""
        tests = self._tests.get(kind)
        if tests is None:
            tests = tuple(pair_test(kind, type(o)) for o in self.obstacles)
            self._tests[kind] = tests
        return tests

    def first_obstacle(self, shape: Shape) -> Optional[int]:
        """``None`` when ``shape`` is free, ``-1`` when it is not inside the closed box,
        else the lowest index (in ``obstacles``) of an obstacle it touches or overlaps.

        A body placed at a NaN or infinite state, or a link with a NaN end, counts
        as outside (-1), with or without a box: its bounding box holds a NaN.
        """
        x0, y0, x1, y1 = shape.bbox
        if not (x0 <= x1 and y0 <= y1):
            return OUTSIDE_BOX
        box = self.box
        if box is not None and not (box.x0 <= x0 and x1 <= box.x1
                                    and box.y0 <= y0 and y1 <= box.y1):
            return OUTSIDE_BOX
        if not self.obstacles:
            return None
        tests = self._tests_for(type(shape))
        obstacles = self.obstacles
        for i, (ox0, oy0, ox1, oy1) in enumerate(self._bboxes):
            if ox0 <= x1 and x0 <= ox1 and oy0 <= y1 and y0 <= oy1 \
                    and tests[i](shape, obstacles[i]):
                return i
        return None

    def polygon_free(self, polygon: ConvexPolygon) -> bool:
        """Inside the closed box and disjoint from every closed obstacle."""
        return self.first_obstacle(polygon) is None

    def segment_free(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """The closed segment (an arm link) is in the box and touches no obstacle:
        ``first_obstacle(Segment(...)) is None``, by the same tests, without building
        the segment (:class:`SegmentTests`, compiled: the arm's hot path).

        A NaN end is never free."""
        return self._segments.free(x0, y0, x1, y1)

    def segment_clearance(self, x0: float, y0: float, x1: float, y1: float,
                          enough: float) -> float:
        """The distance from a free closed segment to the box's sides and the
        obstacles, or a value of at least ``enough``."""
        return self._segments.gap(x0, y0, x1, y1, enough)

    def point_free(self, x: float, y: float) -> bool:
        """The point is in the closed box and in no closed obstacle (NaN is never free)."""
        if not (x == x and y == y):
            return False
        box = self.box
        if box is not None and not (box.x0 <= x <= box.x1 and box.y0 <= y <= box.y1):
            return False
        for (ox0, oy0, ox1, oy1), obstacle in zip(self._bboxes, self.obstacles):
            if ox0 <= x <= ox1 and oy0 <= y <= oy1 and point_in(obstacle, x, y):
                return False
        return True

    def contains(self, shape: Shape) -> bool:
        """``shape`` is inside the closed box (always True without a box)."""
        return self.box is None or inside_box(shape, self.box)

    def clearance(self, x: float, y: float) -> float:
        """Distance from the point to the nearest obstacle or box side (0 when it is
        in an obstacle or outside the box)."""
        return clearance(self._bound, x, y)

    def scale(self) -> float:
        """The largest coordinate, in size, of the obstacles' and the box's bounding
        boxes, and at least 1: what a clearance margin far above rounding scales with."""
        values = [abs(v) for o in self.obstacles for v in o.bbox]
        values += [abs(v) for v in self.box.bbox] if self.box is not None else []
        return max(values + [1.0])

    def body_test(self, body: ConvexPolygon) -> Callable[[float, float, float], bool]:
        """``free(x, y, theta)``: the same answer as
        ``polygon_free(place(body, x, y, theta))``, the same float operations,
        without building the polygon object; the hot path of every family car
        (:class:`~planning_core.worlds.body_tests.BodyTest`, compiled).

        It also remembers a free disc: after a free pose it takes the clearance
        around (x, y) less the body's radius and a margin, and a later pose whose
        (x, y) lies in that disc is free whatever its angle (every vertex then
        keeps at least the margin, far above rounding, from every obstacle). The
        clearance grows at most as fast as (x, y) moves, so it is not recomputed
        while the last one plus the distance moved since leaves no room."""
        return self.body_tester(body).free

    def body_tester(self, body: ConvexPolygon) -> BodyTest:
        """The :class:`~planning_core.worlds.body_tests.BodyTest` behind
        :meth:`body_test` (the family's compiled slice loop calls its ``free``)."""
        radius = max(math.hypot(px, py) for px, py in body.points)
        margin = radius + CLEARANCE_MARGIN * max(self.scale(), radius)

        def meets(x: float, y: float, theta: float) -> bool:  # the reference
            return self.first_obstacle(place(body, x, y, theta)) is not None
        return BodyTest(self._bound, list(body.xs), list(body.ys), margin, meets)

    def link_tests(self, base_x: float, base_y: float, l1: float, l2: float,
                   lows: Sequence[float], highs: Sequence[float], margin: float) -> LinkTests:
        """A two-link arm's tests in this world (:class:`~planning_core.worlds.
        link_tests.LinkTests`, compiled: the arm's hot path): its links, bounds and
        reach margin bound to the world's segment tests."""
        return LinkTests(self._segments, base_x, base_y, l1, l2, lows, highs, margin)


def _bind(box: Optional[Rect],
          obstacles: tuple[Obstacle, ...]) -> tuple[SegmentTests, Obstacles]:
    """The world bound for segment queries and for point and body queries: per
    obstacle its kind, box and data."""
    kinds, boxes, xs, ys, discs = [], [], [], [], []
    for obstacle in obstacles:
        boxes.append(obstacle.bbox)
        if isinstance(obstacle, Disc):
            kinds.append(DISC)
            xs.append([])
            ys.append([])
            discs.append((obstacle.cx, obstacle.cy, obstacle.r))
            continue
        discs.append((0.0, 0.0, 0.0))
        kinds.append(RECT if isinstance(obstacle, Rect) else POLYGON)
        xs.append(list(obstacle.xs))  # a rect's corners, a polygon's points
        ys.append(list(obstacle.ys))
    bound = Obstacles(box.bbox if box is not None else None, kinds, boxes, xs, ys, discs)
    return SegmentTests(bound), bound
