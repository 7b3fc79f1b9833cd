"""Roads that branch from other roads (``lane PathConnectedTo road``: a T junction).

A branch starts at a point along its road (its *parent*) instead of at a junction. Its
first control point stays on the parent: when a move changes the parent's points, the
branch's start goes to the same place on the changed polyline (the same segment, the
same share of it; ``attach``), so every proposal that moves a road carries its branches
along. The branch then leaves its road at an angle (``branch_angle``), which the path
shape energy and the report hold to at least ``gamma``, as for the roads at a junction.

Where branches start (``stations``): evenly along the parent, away from its ends; the
branches of a grid's road in pairs, one to each side at the same point (a crossroads),
each square to the road; an organic road's one after another, alternating sides.
"""

from __future__ import annotations

import math

from scenewright.core.geometry import nearest_on_polyline


def attach(problem, state, paths: dict) -> dict:
    """``paths`` (proposed points per path) with the branches of every path in it (and
    theirs) moved along: each branch not itself in ``paths`` keeps its points but its
    first, which goes to the same segment and share of it on its road's new points."""
    branches_of = problem.branches_of
    if not any(path in branches_of for path in paths):
        return paths
    out = dict(paths)
    todo = [path for path in paths if path in branches_of]
    while todo:
        parent = todo.pop(0)
        old, new = state.points[parent], out[parent]
        for branch in branches_of[parent]:
            if branch in paths:  # given by the proposal itself
                continue
            points = [list(p) for p in out.get(branch, state.points[branch])]
            points[0] = moved_point(old, new, state.points[branch][0])
            out[branch] = points
            if branch in branches_of:
                todo.append(branch)
    return out


def moved_point(old: list, new: list, point) -> list[float]:
    """Where ``point`` (on or near polyline ``old``) lies on ``new``: the same segment,
    the same share along it."""
    _, nx, nz, k = nearest_on_polyline(old, point[0], point[1])
    (ax, az), (bx, bz) = old[k], old[k + 1]
    length2 = (bx - ax) ** 2 + (bz - az) ** 2
    t = 0.0 if length2 <= 0.0 else ((nx - ax) * (bx - ax) + (nz - az) * (bz - az)) / length2
    (cx, cz), (dx, dz) = new[k], new[k + 1]
    return [cx + t * (dx - cx), cz + t * (dz - cz)]


def branch_angle(parent: list, points: list) -> float:
    """The angle (radians, 0 to pi/2) between a branch's first segment and its road
    where it starts: pi/2 when it leaves square to the road."""
    if len(points) < 2:
        return 0.0
    _, _, _, k = nearest_on_polyline(parent, points[0][0], points[0][1])
    (ax, az), (bx, bz) = parent[k], parent[k + 1]
    ux, uz = bx - ax, bz - az
    vx, vz = points[1][0] - points[0][0], points[1][1] - points[0][1]
    norms = math.hypot(ux, uz) * math.hypot(vx, vz)
    if norms <= 0.0:
        return 0.0
    cosine = abs(ux * vx + uz * vz) / norms
    return math.acos(min(1.0, cosine))


def stations(length: float, count: int, grid: bool) -> list[tuple[float, int]]:
    """(arc length, side) where each of ``count`` branches of a road ``length`` long
    starts: side +1 to the road's left, -1 to its right. A grid's in pairs at the same
    point (a crossroads), an organic road's one at a time, alternating sides."""
    if grid:
        points = (count + 1) // 2
        return [
            (length * (k // 2 + 1) / (points + 1), 1 if k % 2 == 0 else -1) for k in range(count)
        ]
    return [(length * (k + 1) / (count + 1), 1 if k % 2 == 0 else -1) for k in range(count)]


def along(points: list, s: float) -> tuple[float, float, float]:
    """The point at arc length ``s`` along a polyline (clamped to its ends) and its
    heading there (radians)."""
    walked, last = 0.0, len(points) - 2
    for k in range(last + 1):
        (ax, az), (bx, bz) = points[k], points[k + 1]
        segment = math.hypot(bx - ax, bz - az)
        if walked + segment >= s or k == last:
            t = 0.0 if segment <= 0.0 else min(max((s - walked) / segment, 0.0), 1.0)
            return ax + t * (bx - ax), az + t * (bz - az), math.atan2(bz - az, bx - ax)
        walked += segment
    raise ValueError("a polyline needs two points")
