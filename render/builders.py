"""Procedural low-poly mesh builders, one per ``shape`` name a catalog entry may use.

A builder takes the catalog size (w, h, d) and colour and returns a ``trimesh.Trimesh``
in the object's local frame: base centre at the origin, +Y up, front towards +Z
(DESIGN.md conventions). ``scenewright.render.meshes`` then fits the result exactly to
the size, so a builder only has to get proportions right. Colours go on as per-face
colours so one object can have several (a red roof on white walls).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import trimesh

Builder = Callable[[tuple[float, float, float], tuple[float, float, float]], trimesh.Trimesh]

#: Every builder by shape name. Register new ones with ``@builder("name")``.
BUILDERS: dict[str, Builder] = {}


def builder(name: str) -> Callable[[Builder], Builder]:
    def register(function: Builder) -> Builder:
        BUILDERS[name] = function
        return function

    return register


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


@builder("box")
def box(size, colour) -> trimesh.Trimesh:
    w, h, d = size
    return block((w, h, d), (0.0, h / 2.0, 0.0), colour)
