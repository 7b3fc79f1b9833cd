"""Procedural low-poly mesh builders, one per ``shape`` name a catalog entry may use.

A builder takes the catalog size (w, h, d) and colour and returns a ``trimesh.Trimesh``
in the object's local frame: base centre at the origin, +Y up, front towards +Z (the
convention of ``scenewright.core.frames``). The shape names, and what each one's front
is, are the registry ``scenewright.core.shapes.SHAPES``, which the static checks read
too; importing this module fails unless its builders and that registry name exactly
the same shapes. ``scenewright.render.meshes`` then fits the result exactly to
the size, so a builder only has to get proportions right; each one builds at the real
size so the fit barely scales. Colours go on as per-face colours so one object can have
several: the catalog colour is the main one (a house's walls), the builder picks the
others (its roof, door and windows) from the palette of ``mesh_parts``. A builder's
detail never grows with the size: parts it repeats along a length (a field's crop rows)
number at most ``MAX_REPEATS`` (``repeats``), so a 1 km field costs what a 30 m one does.

The builders live by where they appear (``builders_furniture``, ``builders_village``,
``builders_home``, ``builders_kitchen_bath``, ``builders_gym``, ``builders_keep``), built from the colours
and solids of ``mesh_parts``; this module gathers them into ``BUILDERS``. Every builder
stays well under 500 triangles.
"""

from __future__ import annotations

from collections.abc import Mapping

from scenewright.core.shapes import SHAPES, Shape

from .builders_furniture import FURNITURE, desk
from .builders_gym import GYM
from .builders_home import HOME
from .builders_keep import KEEP
from .builders_kitchen_bath import KITCHEN_BATH
from .builders_village import VILLAGE
from .mesh_parts import Builder

#: Every builder by shape name. A new one registers with its family module's ``@builder``.
BUILDERS: dict[str, Builder] = {
    **FURNITURE,
    **VILLAGE,
    **HOME,
    **KITCHEN_BATH,
    **GYM,
    **KEEP,
    # A teacher's desk is a writing desk; its own name lets a classroom say which desk it is.
    "teacher_desk": desk,
}


# ---------------------------------------------------------------------------------
# The builders and the shape registry name the same shapes, or this module fails to import.


class ShapeRegistryMismatch(RuntimeError):
    """``BUILDERS`` and ``scenewright.core.shapes.SHAPES`` name different shapes."""


def check_registry(builders: Mapping[str, Builder], shapes: Mapping[str, Shape]) -> None:
    """Raise ``ShapeRegistryMismatch`` unless ``builders`` and ``shapes`` have the same names."""
    unregistered = sorted(set(builders) - set(shapes))
    unbuilt = sorted(set(shapes) - set(builders))
    problems = []
    if unregistered:
        problems.append(
            f"builders with no entry in scenewright.core.shapes.SHAPES: {', '.join(unregistered)}"
        )
    if unbuilt:
        problems.append(
            f"shapes in scenewright.core.shapes.SHAPES with no builder: {', '.join(unbuilt)}"
        )
    if problems:
        raise ShapeRegistryMismatch("; ".join(problems))


check_registry(BUILDERS, SHAPES)
