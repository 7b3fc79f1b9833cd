"""The object frame convention, written once: yaw, local <-> world, footprints.

World: metres, +Y up, north is -Z, east is +X. An object's forward is its local +Z, its
left its local +X. Yaw (radians about +Y) turns forward towards +X: at yaw 0 an object
faces south (+Z), at yaw pi/2 east (+X). In the ground plane (x, z) the local axes are

    left    u = ( cos yaw, -sin yaw)
    forward v = ( sin yaw,  cos yaw)

so a local point (lx, lz) lies at centre + lx u + lz v in the world. Every stage reads
the convention from here; each function has a scalar form (plain floats, for the
sampler's inner loop, where it beats numpy by an order of magnitude) and, where whole
scenes are processed at once, a vectorised numpy form. The tests check the two agree.
"""

from __future__ import annotations

import math

import numpy as np

# ---------------------------------------------------------------------------------
# Scalar forms.


def forward(yaw: float) -> tuple[float, float]:
    """The (x, z) unit vector an object at ``yaw`` faces (its local +Z)."""
    return math.sin(yaw), math.cos(yaw)


def left(yaw: float) -> tuple[float, float]:
    """The (x, z) unit vector of an object's own left (its local +X)."""
    return math.cos(yaw), -math.sin(yaw)


def yaw_of(dx: float, dz: float) -> float:
    """The yaw that makes an object face along (dx, dz)."""
    return math.atan2(dx, dz)


def to_world(cx: float, cz: float, yaw: float, lx: float, lz: float) -> tuple[float, float]:
    """A point given in the frame of an object at (cx, cz, yaw), in world (x, z)."""
    c, s = math.cos(yaw), math.sin(yaw)
    return cx + lx * c + lz * s, cz - lx * s + lz * c


def to_local(cx: float, cz: float, yaw: float, px: float, pz: float) -> tuple[float, float]:
    """A world point (px, pz) in the frame of an object at (cx, cz, yaw): (along its left, along its forward)."""
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dz = px - cx, pz - cz
    return dx * c - dz * s, dx * s + dz * c


def footprint_corners(
    cx: float, cz: float, yaw: float, width: float, depth: float
) -> list[tuple[float, float]]:
    """The four (x, z) corners of a ``width`` x ``depth`` footprint, counter-clockwise in
    local coordinates: back-right, back-left, front-left, front-right."""
    return corners_of(cx, cz, width / 2.0, depth / 2.0, math.cos(yaw), math.sin(yaw))


def corners_of(
    cx: float, cz: float, hw: float, hd: float, c: float, s: float
) -> list[tuple[float, float]]:
    """``footprint_corners`` from half extents and the yaw's cosine and sine (the form
    the layout keeps for every box, so its inner loop never recomputes them)."""
    ux, uz, vx, vz = c * hw, -s * hw, s * hd, c * hd
    return [
        (cx - ux - vx, cz - uz - vz),
        (cx + ux - vx, cz + uz - vz),
        (cx + ux + vx, cz + uz + vz),
        (cx - ux + vx, cz - uz + vz),
    ]


def footprint_reach(yaw: float, width: float, depth: float) -> tuple[float, float]:
    """Half extents along world x and z of a turned ``width`` x ``depth`` footprint
    (the half size of its axis-aligned bounding box)."""
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    return (width * c + depth * s) / 2.0, (width * s + depth * c) / 2.0


def transform_matrix(x: float, y: float, z: float, yaw: float) -> np.ndarray:
    """The 4x4 local-to-world matrix of an object whose base centre is (x, y, z): a
    rotation by ``yaw`` about +Y, then the translation."""
    c, s = math.cos(yaw), math.sin(yaw)
    matrix = np.eye(4)
    matrix[:3, :3] = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    matrix[:3, 3] = (x, y, z)
    return matrix


# ---------------------------------------------------------------------------------
# Vectorised forms: arrays of n objects.


def forward_many(yaw: np.ndarray) -> np.ndarray:
    """(n, 2) forward vectors of ``yaw`` (n,)."""
    yaw = np.asarray(yaw, dtype=float)
    return np.stack([np.sin(yaw), np.cos(yaw)], axis=-1)


def to_world_many(centres: np.ndarray, yaw: np.ndarray, local: np.ndarray) -> np.ndarray:
    """World (x, z) of local points: ``centres`` (n, 2), ``yaw`` (n,), ``local`` (n, k, 2)
    -> (n, k, 2)."""
    yaw = np.asarray(yaw, dtype=float)
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    local = np.asarray(local, dtype=float)
    lx, lz = local[..., 0], local[..., 1]
    centres = np.asarray(centres, dtype=float)
    return np.stack(
        [centres[:, None, 0] + lx * c + lz * s, centres[:, None, 1] - lx * s + lz * c], axis=-1
    )


def to_local_many(centres: np.ndarray, yaw: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Points (n, k, 2) in world (x, z) into the frames of n objects -> (n, k, 2)."""
    yaw = np.asarray(yaw, dtype=float)
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    delta = np.asarray(points, dtype=float) - np.asarray(centres, dtype=float)[:, None, :]
    dx, dz = delta[..., 0], delta[..., 1]
    return np.stack([dx * c - dz * s, dx * s + dz * c], axis=-1)


#: The corners of a unit footprint in local coordinates, in ``footprint_corners`` order.
_UNIT_CORNERS = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])


def footprint_corners_many(centres: np.ndarray, yaw: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """Corners of n footprints: ``centres`` (n, 2), ``yaw`` (n,), ``sizes`` (n, 2) as
    (width, depth) -> (n, 4, 2), in ``footprint_corners`` order."""
    local = _UNIT_CORNERS[None, :, :] * np.asarray(sizes, dtype=float)[:, None, :]
    return to_world_many(centres, yaw, local)


def footprint_reach_many(yaw: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """(n, 2) half extents along world x and z of n turned footprints (``sizes`` (n, 2))."""
    yaw = np.asarray(yaw, dtype=float)
    c, s = np.abs(np.cos(yaw)), np.abs(np.sin(yaw))
    sizes = np.asarray(sizes, dtype=float)
    w, d = sizes[:, 0], sizes[:, 1]
    return np.stack([(w * c + d * s) / 2.0, (w * s + d * c) / 2.0], axis=-1)
