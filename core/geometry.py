"""Planar geometry every stage shares: angles, segments, polygons, rotated rectangles, polylines.

Everything is in the ground plane (x, z). An angle is wrapped to the direction it
points, atan2's principal value (``wrap_angle``); a caller that needs a half-open range
folds the end it excludes itself, from that value.

A footprint ``Rect`` is (cx, cz, hw, hd, c, s): its centre, half width along the
object's local +X (its left), half depth along local +Z (its forward), and the cosine
and sine of its yaw. Yaw turns forward (+Z) towards +X, so the local axes in world
coordinates are left u = (c, -s) and forward v = (s, c) (the convention of
``scenewright.core.frames``, whose vectorised forms the tests compare with these).

The functions are scalar pure Python: the sampler evaluates a handful of small shapes
per step, where this beats numpy by an order of magnitude. All are exact for convex
shapes: the overlap of two rectangles uses the separating axis theorem (SAT), and the
distance between disjoint convex shapes is attained between a vertex of one and the
other shape, which is what the corner-to-box distances compute.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from scenewright.core.frames import corners_of


def wrap_angle(angle: float) -> float:
    """``angle`` turned by whole turns into [-pi, pi]: atan2's principal value of the
    direction it points. Both ends occur (-pi where the sine rounds to a negative
    value too small to move atan2 off -pi, as at -pi itself)."""
    return math.atan2(math.sin(angle), math.cos(angle))


def wrap_angles(angles: np.ndarray) -> np.ndarray:
    """``wrap_angle`` of every element, as the argument of the unit complex number at
    each angle."""
    return np.angle(np.exp(1j * angles))


def point_segment_distance(
    px: float, pz: float, ax: float, az: float, bx: float, bz: float
) -> float:
    """Distance from point p to segment a-b (to a itself when a and b coincide)."""
    ex, ez = bx - ax, bz - az
    length2 = ex * ex + ez * ez
    t = 0.0 if length2 == 0.0 else max(0.0, min(1.0, ((px - ax) * ex + (pz - az) * ez) / length2))
    return math.hypot(px - ax - t * ex, pz - az - t * ez)


def left_normal(ax: float, az: float, bx: float, bz: float) -> tuple[float, float] | None:
    """The unit normal on the left of the way from a to b (its direction turned a
    quarter counter-clockwise in (x, z)), without negative zeros; None when a and b
    coincide."""
    length = math.hypot(bx - ax, bz - az)
    if length == 0.0:
        return None
    return -((bz - az) / length) + 0.0, (bx - ax) / length + 0.0


class Rect(NamedTuple):
    """A rotated rectangle: centre, half extents along local x / z, cos and sin of yaw."""

    cx: float
    cz: float
    hw: float
    hd: float
    c: float
    s: float


def make_rect(cx: float, cz: float, width: float, depth: float, yaw: float) -> Rect:
    """The footprint of a box of ``width`` x ``depth`` at (cx, cz) turned by ``yaw``."""
    return Rect(cx, cz, width / 2.0, depth / 2.0, math.cos(yaw), math.sin(yaw))


#: ``rect_distance`` takes two rectangles as square to each other when the sine (or
#: cosine) of the angle between them is below this: quarter turns leave it at ~1e-16.
SQUARE_EPSILON = 1e-9

#: ``polyline_rect_penetration`` skips a segment on a lower bound of its gap only when
#: the bound clears the buffer by this share of the coordinates' magnitude: the exact
#: test's rounding is ~1e-15 of it, so a skipped segment would have given 0 there too.
BOUND_MARGIN = 1e-9


def corners(rect: Rect) -> list[tuple[float, float]]:
    """The four (x, z) corners, counter-clockwise in local coordinates."""
    return corners_of(*rect)


def to_local(rect: Rect, px: float, pz: float) -> tuple[float, float]:
    """A world point in the rectangle's frame: (along its left, along its forward)."""
    dx, dz = px - rect.cx, pz - rect.cz
    return dx * rect.c - dz * rect.s, dx * rect.s + dz * rect.c


def point_rect_distance(px: float, pz: float, rect: Rect) -> float:
    """Distance from a point to the (filled) rectangle; 0 inside."""
    lx, lz = to_local(rect, px, pz)
    ex = abs(lx) - rect.hw
    ez = abs(lz) - rect.hd
    if ex <= 0.0 and ez <= 0.0:
        return 0.0
    return math.hypot(max(ex, 0.0), max(ez, 0.0))


def rect_overlap(a: Rect, b: Rect) -> float:
    """SAT overlap of two rectangles: the minimum separating translation when positive.

    Negative (or zero) when a separating axis exists; its magnitude is then a lower bound
    of the gap. The four candidate axes are both rectangles' local axes.
    """
    acx, acz, ahw, ahd, ac, as_ = a  # unpacked once: field reads by name cost a call each
    bcx, bcz, bhw, bhd, bc, bs = b
    dx, dz = bcx - acx, bcz - acz
    k1 = abs(ac * bc + as_ * bs)  # |cos(yaw_b - yaw_a)|
    k2 = abs(ac * bs - as_ * bc)  # |sin(yaw_b - yaw_a)|
    best = ahw + bhw * k1 + bhd * k2 - abs(dx * ac - dz * as_)
    overlap = ahd + bhw * k2 + bhd * k1 - abs(dx * as_ + dz * ac)
    if overlap < best:
        best = overlap
    overlap = bhw + ahw * k1 + ahd * k2 - abs(dx * bc - dz * bs)
    if overlap < best:
        best = overlap
    overlap = bhd + ahw * k2 + ahd * k1 - abs(dx * bs + dz * bc)
    if overlap < best:
        best = overlap
    return best


def rect_penetration(a: Rect, b: Rect) -> float:
    """Minimum translation that separates two rectangles (0 when they do not overlap)."""
    overlap = rect_overlap(a, b)
    return overlap if overlap > 0.0 else 0.0


def rect_distance(a: Rect, b: Rect) -> float:
    """Minimum distance between two filled rectangles (0 when they touch or overlap).

    Rectangles square to each other (parallel or at right angles, as furniture in a room
    mostly is) are separated along a's axes: the distance is the hypotenuse of the two
    gaps between their extents, without visiting corners.
    """
    acx, acz, ahw, ahd, ac, as_ = a  # unpacked once, as in ``rect_overlap``
    bcx, bcz, bhw, bhd, bc, bs = b
    k2 = ac * bs - as_ * bc  # sin(yaw_b - yaw_a)
    k1 = ac * bc + as_ * bs  # cos(yaw_b - yaw_a)
    if -SQUARE_EPSILON < k2 < SQUARE_EPSILON or -SQUARE_EPSILON < k1 < SQUARE_EPSILON:
        bw, bd = (bhw, bhd) if -SQUARE_EPSILON < k2 < SQUARE_EPSILON else (bhd, bhw)
        dx, dz = bcx - acx, bcz - acz
        gx = abs(dx * ac - dz * as_) - ahw - bw
        gz = abs(dx * as_ + dz * ac) - ahd - bd
        if gx <= 0.0 and gz <= 0.0:
            return 0.0
        return math.hypot(gx if gx > 0.0 else 0.0, gz if gz > 0.0 else 0.0)
    if rect_overlap(a, b) >= 0.0:
        return 0.0
    return _corners_to(b, a, _corners_to(a, b, math.inf))


def _corners_to(a: Rect, b: Rect, best: float) -> float:
    """The least of ``best`` and ``point_rect_distance`` from each corner of ``a`` to ``b``,
    kept corner by corner as ``min(best, ...)`` keeps it (``rect_distance``'s corners,
    written out: it runs for every NextTo* between boxes not square to each other)."""
    cx, cz, hw, hd, c, s = a
    ux, uz, vx, vz = c * hw, -s * hw, s * hd, c * hd  # as ``corners_of``
    bx, bz, bw, bd, bc, bs = b
    hypot = math.hypot
    for px, pz in (
        (cx - ux - vx, cz - uz - vz),
        (cx + ux - vx, cz + uz - vz),
        (cx + ux + vx, cz + uz + vz),
        (cx - ux + vx, cz - uz + vz),
    ):
        dx, dz = px - bx, pz - bz  # as ``point_rect_distance``
        ex = abs(dx * bc - dz * bs) - bw
        ez = abs(dx * bs + dz * bc) - bd
        distance = (
            0.0
            if ex <= 0.0 and ez <= 0.0
            else hypot(ex if ex > 0.0 else 0.0, ez if ez > 0.0 else 0.0)
        )
        if distance < best:
            best = distance
    return best


def nearest_on_segment(
    px: float, pz: float, ax: float, az: float, bx: float, bz: float
) -> tuple[float, float, float]:
    """(distance, x, z) of the point of segment a-b nearest to p."""
    ex, ez = bx - ax, bz - az
    length2 = ex * ex + ez * ez
    t = 0.0 if length2 <= 0.0 else max(0.0, min(1.0, ((px - ax) * ex + (pz - az) * ez) / length2))
    nx, nz = ax + t * ex, az + t * ez
    return math.hypot(px - nx, pz - nz), nx, nz


def nearest_on_polyline(points: list, px: float, pz: float) -> tuple[float, float, float, int]:
    """(distance, x, z, segment index) of the polyline point nearest to p."""
    best = (math.inf, points[0][0], points[0][1], 0)
    for index in range(len(points) - 1):
        (ax, az), (bx, bz) = points[index], points[index + 1]
        distance, nx, nz = nearest_on_segment(px, pz, ax, az, bx, bz)
        if distance < best[0]:
            best = (distance, nx, nz, index)
    return best


def _local_overlap(ax: float, az: float, bx: float, bz: float, hw: float, hd: float) -> float:
    """SAT overlap of segment a-b and the box [-hw, hw] x [-hd, hd] (both in the box's frame).

    Positive: they intersect, and it is the shortest slide that separates them.
    """
    # On the box's axes: how far the segment's interval must slide to clear the box's.
    low, high = (ax, bx) if ax < bx else (bx, ax)
    best = min(high + hw, hw - low)
    low, high = (az, bz) if az < bz else (bz, az)
    overlap = min(high + hd, hd - low)
    if overlap < best:
        best = overlap
    ex, ez = bx - ax, bz - az
    length = math.hypot(ex, ez)
    if length > 0.0:
        nx, nz = -ez / length, ex / length  # the segment's normal
        overlap = hw * abs(nx) + hd * abs(nz) - abs(ax * nx + az * nz)
        if overlap < best:
            best = overlap
    return best


def _local_distance(ax: float, az: float, bx: float, bz: float, hw: float, hd: float) -> float:
    """Distance between segment a-b and the box [-hw, hw] x [-hd, hd] when they do not meet."""
    best = min(
        math.hypot(max(abs(ax) - hw, 0.0), max(abs(az) - hd, 0.0)),
        math.hypot(max(abs(bx) - hw, 0.0), max(abs(bz) - hd, 0.0)),
    )
    ex, ez = bx - ax, bz - az
    length2 = ex * ex + ez * ez
    hypot = math.hypot
    for px, pz in ((hw, hd), (-hw, hd), (hw, -hd), (-hw, -hd)):
        if length2 <= 0.0:  # ``point_segment_distance``, written out: paths test boxes every step
            t = 0.0
        else:
            t = ((px - ax) * ex + (pz - az) * ez) / length2
            t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        distance = hypot(px - ax - t * ex, pz - az - t * ez)
        if distance < best:
            best = distance
    return best


def _segment_in(
    rect: Rect, ax: float, az: float, bx: float, bz: float
) -> tuple[float, float, float, float]:
    """Both ends of a segment in the rectangle's frame (``to_local`` of each, in one call)."""
    cx, cz, _, _, c, s = rect
    dx, dz, ex, ez = ax - cx, az - cz, bx - cx, bz - cz
    return dx * c - dz * s, dx * s + dz * c, ex * c - ez * s, ex * s + ez * c


def segment_rect_distance(ax: float, az: float, bx: float, bz: float, rect: Rect) -> float:
    """Minimum distance between a segment and a filled rectangle (0 when they meet)."""
    lax, laz, lbx, lbz = _segment_in(rect, ax, az, bx, bz)
    if _local_overlap(lax, laz, lbx, lbz, rect.hw, rect.hd) >= 0.0:
        return 0.0
    return _local_distance(lax, laz, lbx, lbz, rect.hw, rect.hd)


def capsule_rect_penetration(
    ax: float, az: float, bx: float, bz: float, radius: float, rect: Rect
) -> float:
    """How deep a rectangle reaches into a segment buffered by ``radius`` (0 if clear).

    Outside the segment it is ``radius`` minus the gap; once the rectangle crosses the
    centre line it grows by the rectangle's SAT overlap with the segment, so the value
    is continuous and keeps growing the deeper the rectangle sits.
    """
    lax, laz, lbx, lbz = _segment_in(rect, ax, az, bx, bz)
    overlap = _local_overlap(lax, laz, lbx, lbz, rect.hw, rect.hd)
    if overlap >= 0.0:
        return radius + overlap
    gap = _local_distance(lax, laz, lbx, lbz, rect.hw, rect.hd)
    return radius - gap if gap < radius else 0.0


def polyline_rect_penetration(points: list, radius: float, rect: Rect) -> float:
    """Deepest penetration of a rectangle into a buffered polyline (its worst segment).

    Segments whose bounding box, grown by ``radius``, misses the rectangle's bounding
    box cannot touch it and are skipped before the exact test; so are those whose
    distance to the rectangle's centre, less its circumradius (a lower bound of their
    gap), exceeds ``radius`` by more than ``BOUND_MARGIN`` of the coordinates' scale.
    Past that margin, rounding cannot make the exact test give anything but 0 (it
    errs by a few units in the last place of that scale): the same result.
    """
    best = 0.0
    cx, cz, hw, hd, c, s = rect
    reach_x = hw * abs(c) + hd * abs(s) + radius
    reach_z = hw * abs(s) + hd * abs(c) + radius
    x0, x1, z0, z1 = cx - reach_x, cx + reach_x, cz - reach_z, cz + reach_z
    clear = radius + math.hypot(hw, hd)  # a centre farther than this (and the margin) is clear
    scale = abs(cx) + abs(cz) + clear
    for index in range(len(points) - 1):
        (ax, az), (bx, bz) = points[index], points[index + 1]
        if (
            (ax < x0 and bx < x0)
            or (ax > x1 and bx > x1)
            or (az < z0 and bz < z0)
            or (az > z1 and bz > z1)
        ):
            continue
        ex, ez = (
            bx - ax,
            bz - az,
        )  # the centre's nearest point on the segment (``nearest_on_segment``)
        length2 = ex * ex + ez * ez
        t = ((cx - ax) * ex + (cz - az) * ez) / length2 if length2 > 0.0 else 0.0
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        if math.hypot(cx - ax - t * ex, cz - az - t * ez) > clear + BOUND_MARGIN * (
            scale + abs(ax) + abs(az) + abs(bx) + abs(bz)
        ):
            continue
        depth = capsule_rect_penetration(ax, az, bx, bz, radius, rect)
        if depth > best:
            best = depth
    return best


def polyline_rects_distance(points: Sequence[Sequence[float]], rects: list[Rect]) -> float:
    """Minimum distance between a polyline's centre line and the nearest of some filled rectangles.

    A rectangle's centre distance to a segment minus its circumradius bounds their exact
    distance from below, so (rectangle, segment) pairs are tested exactly nearest bound
    first, and only while a bound could still beat the best so far.
    """
    segments = []
    for i in range(len(points) - 1):
        (ax, az), (bx, bz) = points[i], points[i + 1]
        ex, ez = bx - ax, bz - az
        segments.append((ax, az, ex, ez, ex * ex + ez * ez))
    # Bound of pair (rectangle k, segment i) at position k * segments + i, so that the
    # order of (bound, position) is that of (bound, k, i); the least, first in that order.
    bounds: list[float] = []
    first, least = -1, math.inf
    hypot = math.hypot
    for px, pz, hw, hd, _, _ in rects:
        radius = hypot(hw, hd)
        for ax, az, ex, ez, length2 in segments:  # ``nearest_on_segment``'s distance, inlined
            if length2 > 0.0:
                t = ((px - ax) * ex + (pz - az) * ez) / length2
                if (
                    t < 0.0
                ):  # as max(0, min(1, t)); a t of -0.0 kept as it is moves the point no less
                    t = 0.0
                elif t > 1.0:
                    t = 1.0
            else:
                t = 0.0
            bound = hypot(px - (ax + t * ex), pz - (az + t * ez)) - radius
            if bound < least:
                first, least = len(bounds), bound
            bounds.append(bound)
    if first < 0:
        return math.inf
    # The pair of least bound first; then, nearest bound first, those whose bound could
    # beat the best so far (only fewer as it falls): the pairs and order a sort of all
    # of them would visit, without sorting all.
    count = len(segments)
    k, i = divmod(first, count)
    best = min(math.inf, _segment_rect_distance_at(points, i, rects[k]))
    for bound, position in sorted(
        [
            (bound, position)
            for position, bound in enumerate(bounds)
            if bound < best and position != first
        ]
    ):
        if bound >= best:
            break
        k, i = divmod(position, count)
        best = min(best, _segment_rect_distance_at(points, i, rects[k]))
    return best


def _segment_rect_distance_at(points: Sequence[Sequence[float]], i: int, rect: Rect) -> float:
    """``segment_rect_distance`` of segment i of a polyline (points i and i + 1)."""
    (ax, az), (bx, bz) = points[i], points[i + 1]
    return segment_rect_distance(ax, az, bx, bz, rect)


def _cross(ox: float, oz: float, ax: float, az: float, bx: float, bz: float) -> float:
    return (ax - ox) * (bz - oz) - (az - oz) * (bx - ox)


def segment_distance(p: tuple, q: tuple, r: tuple, t: tuple) -> float:
    """Minimum distance between segments p-q and r-t (0 when they cross)."""
    d1, d2 = _cross(*r, *t, *p), _cross(*r, *t, *q)
    d3, d4 = _cross(*p, *q, *r), _cross(*p, *q, *t)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)):
        return 0.0
    return min(
        nearest_on_segment(*p, *r, *t)[0],
        nearest_on_segment(*q, *r, *t)[0],
        nearest_on_segment(*r, *p, *q)[0],
        nearest_on_segment(*t, *p, *q)[0],
    )


def polyline_distance(first: list, second: list) -> float:
    """Minimum distance between two polylines' centre lines."""
    return min(
        segment_distance(
            tuple(first[i]), tuple(first[i + 1]), tuple(second[j]), tuple(second[j + 1])
        )
        for i in range(len(first) - 1)
        for j in range(len(second) - 1)
    )


def polyline_length(points: list) -> float:
    """Total length of a polyline."""
    return sum(
        math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:], strict=False)
    )


def polyline_turns(points: list) -> list[float]:
    """The turn angle (radians) at each inner control point of a polyline."""
    return [turn_angle(points[i - 1], points[i], points[i + 1]) for i in range(1, len(points) - 1)]


def turn_angle(a: tuple, b: tuple, c: tuple) -> float:
    """The turn at b between a-b and b-c in radians (0 when straight on)."""
    ux, uz = b[0] - a[0], b[1] - a[1]
    vx, vz = c[0] - b[0], c[1] - b[1]
    norms = math.hypot(ux, uz) * math.hypot(vx, vz)
    if norms <= 0.0:
        return 0.0
    return math.acos(max(-1.0, min(1.0, (ux * vx + uz * vz) / norms)))


# -- polygons and grids of points -------------------------------------------------------


def signed_area(points: Sequence[Sequence[float]]) -> float:
    """The shoelace area of a polygon's corners (x, z): positive counter-clockwise in (x, z)."""
    n = len(points)
    return 0.5 * sum(
        points[k][0] * points[(k + 1) % n][1] - points[(k + 1) % n][0] * points[k][1]
        for k in range(n)
    )


def points_in_polygon(
    corners: Sequence[Sequence[float]], gx: np.ndarray, gz: np.ndarray
) -> np.ndarray:
    """Even-odd test of every point (gx, gz) against the polygon ``corners``, at once."""
    inside = np.zeros(gx.shape, dtype=bool)
    n = len(corners)
    for k in range(n):
        (x0, z0), (x1, z1) = corners[k], corners[(k + 1) % n]
        if z0 == z1:
            continue
        crosses = (z0 > gz) != (z1 > gz)
        inside ^= crosses & (gx < x0 + (gz - z0) * (x1 - x0) / (z1 - z0))
    return inside


def points_segments_distance(gx: np.ndarray, gz: np.ndarray, segments) -> np.ndarray:
    """Distance from every point (gx, gz) to the nearest of some segments (inf if none)."""
    best = np.full(gx.shape, np.inf)
    for (ax, az), (bx, bz) in segments:
        ex, ez = bx - ax, bz - az
        length2 = ex * ex + ez * ez
        t = (
            np.zeros(gx.shape)
            if length2 == 0.0
            else np.clip(((gx - ax) * ex + (gz - az) * ez) / length2, 0.0, 1.0)
        )
        best = np.minimum(best, np.hypot(gx - ax - t * ex, gz - az - t * ez))
    return best
