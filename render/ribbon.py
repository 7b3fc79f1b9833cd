"""A path's ribbon as one layer of triangles that never overlap, for exported files.

The preview's ribbon (``meshes.path_mesh``) is a quad per segment plus a disc at each
joint: simple and gap-free, but the quads and discs cover the joints two or three
times over. The renderer draws it in one flat colour without lighting differences, so
that is invisible there; a path tracer (Blender's Cycles) shades coplanar overlapping
triangles as black patches. Here each joint is closed exactly instead: on the inside of
the turn both segments' edges end at the point where they cross (a mitre), and on the
outside a fan of triangles round the joint fills the wedge between them, so the outline
is the preview's (a round join outside, the ribbon's edge inside) and every point of the
ribbon is covered once.
"""

from __future__ import annotations

import math

import numpy as np
import trimesh

from scenewright.core.scene import ScenePath

from .meshes import PATH_LIFT, coloured

#: Largest angle (radians) one triangle of a round join spans, as the preview's
#: 16-sided joint discs.
ARC_STEP = 2 * math.pi / 16


def ribbon_mesh(path: ScenePath, lift: float = 0.0) -> trimesh.Trimesh:
    """The path's ribbon ``PATH_LIFT + lift`` above the ground, facing up, in its colour:
    no two triangles overlap. A path that starts at no junction gets a round cap at its
    start, as the preview draws a disc there. Empty when all its points coincide."""
    points = _distinct(np.asarray(path.points, dtype=float).reshape(-1, 2))
    half = path.width / 2.0
    if len(points) < 2:
        return trimesh.Trimesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=int), process=False)
    direction = np.diff(points, axis=0)
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    normal = np.column_stack([-direction[:, 1], direction[:, 0]])
    triangles: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    # Each segment's quad runs from the edge where it leaves its start joint to the edge
    # where it enters its end joint: (left, right) points of each.
    leave = [(points[0] + half * normal[0], points[0] - half * normal[0])]
    enter = []
    for j in range(1, len(points) - 1):
        into, out_of, centre = j - 1, j, points[j]
        inner = 1.0 if float(normal[into] @ direction[out_of]) > 0 else -1.0
        bisector = normal[into] + normal[out_of]
        if np.linalg.norm(bisector) < 1e-9:  # a U-turn: no mitre exists; cap it round
            mitre = centre
        else:
            bisector /= np.linalg.norm(bisector)
            mitre = centre + inner * half * bisector / float(bisector @ normal[into])
        outer_in = centre - inner * half * normal[into]
        outer_out = centre - inner * half * normal[out_of]
        arc = _arc(centre, outer_in, outer_out, half)
        triangles += [(mitre, a, b) for a, b in zip(arc[:-1], arc[1:], strict=False)]
        if inner > 0:  # turning left: the mitre is on the left
            enter.append((mitre, outer_in))
            leave.append((mitre, outer_out))
        else:
            enter.append((outer_in, mitre))
            leave.append((outer_out, mitre))
    enter.append((points[-1] + half * normal[-1], points[-1] - half * normal[-1]))
    for (l0, r0), (l1, r1) in zip(leave, enter, strict=False):
        triangles += [(l0, r0, r1), (l0, r1, l1)]
    if path.start is None:  # the half disc behind the start
        start, back = points[0], -direction[0]
        left, right = start + half * normal[0], start - half * normal[0]
        arc = _arc(start, left, right, half, through=start + half * back)
        triangles += [(start, a, b) for a, b in zip(arc[:-1], arc[1:], strict=False)]
    flat = np.array([corner for triangle in triangles for corner in triangle]).reshape(-1, 3, 2)
    flat = _facing_up(_without_slivers(flat))
    vertices = np.column_stack(
        [flat[..., 0].ravel(), np.full(flat.shape[0] * 3, PATH_LIFT + lift), flat[..., 1].ravel()]
    )
    faces = np.arange(len(vertices)).reshape(-1, 3)
    normals = np.tile([0.0, 1.0, 0.0], (len(faces), 1))
    return coloured(
        trimesh.Trimesh(vertices, faces, face_normals=normals, process=False), path.colour
    )


def _distinct(points: np.ndarray) -> np.ndarray:
    """``points`` without those that repeat the one before."""
    if len(points) < 2:
        return points
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    return np.vstack([points[:1], points[1:][step >= 1e-9]])


def _arc(centre, start, end, radius: float, through=None) -> list[np.ndarray]:
    """Points on the circle round ``centre`` from ``start`` to ``end`` the short way (or
    the way that passes ``through``), at most ``ARC_STEP`` apart in angle."""
    a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
    a1 = math.atan2(end[1] - centre[1], end[0] - centre[0])
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi  # short way, in (-pi, pi]
    if through is not None:
        mid = math.atan2(through[1] - centre[1], through[0] - centre[0])
        if (mid - a0) % (2 * math.pi) > (a1 - a0) % (2 * math.pi):
            sweep = (a1 - a0) % (2 * math.pi) - 2 * math.pi  # clockwise
        else:
            sweep = (a1 - a0) % (2 * math.pi)
    steps = max(1, math.ceil(abs(sweep) / ARC_STEP - 1e-9))
    angles = a0 + sweep * np.arange(steps + 1) / steps
    arc = [centre + radius * np.array([math.cos(a), math.sin(a)]) for a in angles[1:-1]]
    return [np.asarray(start, dtype=float), *arc, np.asarray(end, dtype=float)]


def _without_slivers(triangles: np.ndarray) -> np.ndarray:
    """Triangles (n, 3, 2) without those of no area (a straight joint's empty wedge),
    which would have no normal."""
    return triangles[np.abs(_signed_area(triangles)) > 1e-12]


def _facing_up(triangles: np.ndarray) -> np.ndarray:
    """Triangles (n, 3, 2) in (x, z) wound so their normal is +Y (clockwise in x, z)."""
    flip = _signed_area(triangles) > 0
    turned = triangles.copy()
    turned[flip] = triangles[flip][:, ::-1]
    return turned


def _signed_area(triangles: np.ndarray) -> np.ndarray:
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    return 0.5 * (
        (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    )
