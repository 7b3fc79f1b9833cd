"""The kit every shape builder is made from: the ``Builder`` type and the decorator that
registers one, the secondary colours, and the solid primitives.

Each solid returns one coloured mesh (per-face colours, linear RGB in [0, 1]); a builder
concatenates them with ``combine``. Parts a builder repeats along a length number at
most ``MAX_REPEATS`` (``repeats``), so a mesh's detail never grows with its size.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import trimesh

from scenewright.core.limits import MAX_REPEATS

Builder = Callable[[tuple[float, float, float], tuple[float, float, float]], trimesh.Trimesh]


def register_in(builders: dict[str, Builder]) -> Callable[[str], Callable[[Builder], Builder]]:
    """A decorator ``@builder("name")`` that files a builder in ``builders`` under ``name``."""

    def builder(name: str) -> Callable[[Builder], Builder]:
        def register(function: Builder) -> Builder:
            builders[name] = function
            return function

        return register

    return builder


# ---------------------------------------------------------------------------------
# Secondary colours (linear RGB). The catalog colour stays the main one.

WOOD = (0.52, 0.35, 0.2)
DARK_WOOD = (0.3, 0.2, 0.12)
IRON = (0.22, 0.22, 0.25)
ROOF = (0.55, 0.22, 0.15)
STRAW = (0.8, 0.68, 0.38)
SOIL = (0.38, 0.27, 0.17)
LEAVES = (0.22, 0.48, 0.2)
BARK = (0.36, 0.25, 0.15)
GLASS = (0.35, 0.5, 0.65)
GLOW = (1.0, 0.55, 0.15)
LIGHT = (1.0, 0.9, 0.55)
LINEN = (0.92, 0.9, 0.84)
COAL = (0.08, 0.08, 0.09)
SCREEN = (0.1, 0.14, 0.2)
PAGES = (0.93, 0.9, 0.8)
BLOSSOM = (0.9, 0.3, 0.45)
CHROME = (0.78, 0.79, 0.82)
WORKTOP = (0.28, 0.28, 0.3)
WATER = (0.55, 0.75, 0.88)
SHOWER_GLASS = (0.78, 0.9, 0.94)


def repeats(length: float, spacing: float, least: int = 1) -> int:
    """How many parts ``spacing`` apart fit along ``length``: at least ``least``, at most
    ``MAX_REPEATS``, so a mesh's triangle count is bounded whatever its size."""
    return min(max(least, int(length / spacing)), MAX_REPEATS)


def shade(colour, factor: float) -> tuple[float, float, float]:
    """``colour`` made darker (factor < 1) or lighter (factor > 1), clipped to [0, 1]."""
    return tuple(float(c) for c in np.clip(np.asarray(colour, dtype=float) * factor, 0.0, 1.0))


# ---------------------------------------------------------------------------------
# Solids. Each returns one coloured mesh; builders concatenate them with ``combine``.


def coloured(mesh: trimesh.Trimesh, colour) -> trimesh.Trimesh:
    """Give every face of ``mesh`` one RGB colour in [0, 1]."""
    rgba = np.append(np.clip(np.asarray(colour, dtype=float), 0, 1), 1.0)
    mesh.visual.face_colors = np.tile((rgba * 255).round().astype(np.uint8), (len(mesh.faces), 1))
    return mesh


def block(extents, centre, colour) -> trimesh.Trimesh:
    """An axis-aligned box with the given extents (x, y, z) and centre, in one colour."""
    mesh = trimesh.creation.box(extents=extents)
    mesh.apply_translation(centre)
    return coloured(mesh, colour)


def slab(low, high, colour) -> trimesh.Trimesh:
    """An axis-aligned box between the corners ``low`` and ``high`` (x, y, z)."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    return block(high - low, (low + high) / 2.0, colour)


def cylinder(radius: float, bottom, top, colour, sections: int = 10) -> trimesh.Trimesh:
    """A cylinder from point ``bottom`` to point ``top`` (any direction)."""
    mesh = trimesh.creation.cylinder(radius=radius, segment=[bottom, top], sections=sections)
    return coloured(mesh, colour)


def frustum(
    bottom_radius: float,
    top_radius: float,
    y0: float,
    y1: float,
    colour,
    sections: int = 10,
    centre=(0.0, 0.0),
) -> trimesh.Trimesh:
    """An upright truncated cone from height ``y0`` to ``y1`` around (x, z) ``centre``."""
    x, z = centre
    mesh = trimesh.creation.cylinder(
        radius=bottom_radius, segment=[(x, y0, z), (x, y1, z)], sections=sections
    )
    vertices = mesh.vertices.copy()
    top = np.isclose(vertices[:, 1], y1)
    vertices[top, 0] = x + (vertices[top, 0] - x) * (top_radius / bottom_radius)
    vertices[top, 2] = z + (vertices[top, 2] - z) * (top_radius / bottom_radius)
    mesh.vertices = vertices
    return coloured(mesh, colour)


def cone(radius: float, base, apex, colour, sections: int = 10) -> trimesh.Trimesh:
    """A cone with its base disc centred on ``base`` and its tip at ``apex``."""
    base, apex = np.asarray(base, dtype=float), np.asarray(apex, dtype=float)
    axis = apex - base
    # trimesh builds cones along +Z from the origin: turn that axis onto ours, then move.
    transform = trimesh.geometry.align_vectors([0.0, 0.0, 1.0], axis / np.linalg.norm(axis))
    transform[:3, 3] = base
    mesh = trimesh.creation.cone(
        radius=radius, height=float(np.linalg.norm(axis)), sections=sections, transform=transform
    )
    return coloured(mesh, colour)


def ball(radius, centre, colour, subdivisions: int = 1) -> trimesh.Trimesh:
    """A sphere, or an ellipsoid when ``radius`` is (rx, ry, rz)."""
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=1.0)
    mesh.apply_scale(np.broadcast_to(np.asarray(radius, dtype=float), (3,)))
    mesh.apply_translation(centre)
    return coloured(mesh, colour)


def gable_roof(width: float, depth: float, eave_y: float, rise: float, colour) -> trimesh.Trimesh:
    """A triangular prism roof: ridge along x at ``eave_y + rise``, slopes to front and back."""
    half_w, half_d = width / 2.0, depth / 2.0
    vertices = np.array(
        [
            [-half_w, eave_y, -half_d],
            [-half_w, eave_y, half_d],
            [-half_w, eave_y + rise, 0.0],
            [half_w, eave_y, -half_d],
            [half_w, eave_y, half_d],
            [half_w, eave_y + rise, 0.0],
        ]
    )
    faces = np.array(
        [[0, 1, 2], [3, 5, 4], [1, 4, 5], [1, 5, 2], [0, 2, 5], [0, 5, 3], [0, 3, 4], [0, 4, 1]]
    )
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    mesh.fix_normals()
    return coloured(mesh, colour)


def legs(
    width: float, depth: float, height: float, thickness: float, colour
) -> list[trimesh.Trimesh]:
    """Four square legs standing at the corners of a ``width`` x ``depth`` footprint."""
    x = width / 2.0 - thickness / 2.0
    z = depth / 2.0 - thickness / 2.0
    return [
        block((thickness, height, thickness), (sx * x, height / 2.0, sz * z), colour)
        for sx in (-1, 1)
        for sz in (-1, 1)
    ]


def combine(*parts) -> trimesh.Trimesh:
    """One mesh of all ``parts`` (meshes or lists of meshes), face colours kept."""
    flat: list[trimesh.Trimesh] = []
    for part in parts:
        flat.extend(part if isinstance(part, (list, tuple)) else [part])
    return trimesh.util.concatenate(flat)


# ---------------------------------------------------------------------------------
# Round parts: a washer, and any round part made oval.


def ring(inner: float, outer: float, start, end, colour, sections: int = 12) -> trimesh.Trimesh:
    """A flat ring (a washer) from point ``start`` to point ``end`` along its axis."""
    mesh = trimesh.creation.annulus(
        r_min=inner, r_max=outer, segment=[start, end], sections=sections
    )
    return coloured(mesh, colour)


def oval(mesh: trimesh.Trimesh, ratio: float, centre_z: float = 0.0) -> trimesh.Trimesh:
    """``mesh`` (built round the Y axis) stretched along Z by ``ratio`` and moved to ``centre_z``:
    a round part made oval, as a toilet bowl or a basin is."""
    mesh.apply_scale((1.0, 1.0, ratio))
    mesh.apply_translation((0.0, 0.0, centre_z))
    return mesh
