"""The in-memory form of an example (``Example``: a core ``Scene`` and where it came
from), its error, and ``example_scene``, which turns the objects a file lists into that
Scene: each object's looks (``default_looks``: the shipped indoor catalog's noun, shape
and colour for a type it has, else a noun from the type, the procedural shape of the
same name if there is one, and a colour of its own per type), and an ``OnTopOf``
relation for every support (given by the file or measured, ``stacking``)."""

from __future__ import annotations

import hashlib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from scenewright.core import VERSION
from scenewright.core.errors import InputError
from scenewright.core.geometry import wrap_angle
from scenewright.core.limits import (
    MAX_COORDINATE,
    MAX_EXTENT,
    MAX_NODES,
    MAX_SIZE,
    MIN_LENGTH,
    forbidden_character,
)
from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.room import Room
from scenewright.core.scene import LayoutStats, Scene, SceneObject
from scenewright.core.shapes import SHAPES

from .stacking import infer_supports

#: The support label an importer records (rests anywhere on the supporter's top).
SUPPORT_LABEL = "OnTopOf"


class ExampleError(InputError):
    """A file that cannot be read as an example; the message is one line that starts
    with the file and says where in it the problem is."""

    def __init__(self, path: str, where: str, message: str):
        super().__init__(f"{path}: {where}: {message}" if where else f"{path}: {message}")
        self.path, self.where, self.reason = str(path), where, message


@dataclass
class Example:
    """One example scene: ``scene`` (objects of kind ``object`` carry the layout),
    ``name`` (how reports call it; unique within one ``load_examples``), the file and
    the format it was read from."""

    name: str
    path: str
    format: str
    scene: Scene

    def objects(self) -> list[SceneObject]:
        """The placed objects (kind ``object``), in file order."""
        return self.scene.placed_objects()

    def supports(self) -> dict[str, str]:
        """Object id -> the id of the object it rests on (support-family relations)."""
        return scene_supports(self.scene)


def scene_supports(scene: Scene) -> dict[str, str]:
    """Object id -> the id of the object it rests on, from the scene's support-family
    relations between placed objects."""
    placed = {o.id for o in scene.placed_objects()}
    return {
        r.source: r.target
        for r in scene.relations
        if r.label in RELATIONS
        and RELATIONS[r.label].support
        and r.source in placed
        and r.target in placed
    }


@dataclass(frozen=True)
class ObjectRecord:
    """One object as a file states it: pose in the scene frame, yaw in radians."""

    id: str
    type: str
    size: tuple[float, float, float]
    position: tuple[float, float, float]
    yaw: float
    style: str | None = None


def type_colour(type_name: str) -> list[float]:
    """A stable, mid-bright colour for a type name (so previews tell types apart)."""
    digest = hashlib.sha256(type_name.encode("utf-8")).digest()
    return [round(0.3 + 0.5 * digest[k] / 255.0, 3) for k in range(3)]


@dataclass(frozen=True)
class Looks:
    """How an example's object is named and drawn: ``noun`` and ``plural`` (None: the
    regular one), ``shape`` (a procedural shape, None: a box) and ``colour`` (sRGB)."""

    noun: str
    plural: str | None
    shape: str | None
    colour: list[float]


def default_looks(type_name: str, style: str | None = None) -> Looks:
    """The looks of an example's object of ``type_name`` (and ``style``), which a file
    does not give: those of the shipped indoor catalog's entry of that name, where it
    has one (with its style of that name, where it has one: a white wardrobe), so a
    user's ``plant`` is a potted plant and a ``tv_stand`` a "TV stand"; else the type
    with underscores as spaces, the procedural shape of the same name if there is one,
    and ``type_colour``."""
    from scenewright.generator import indoor_catalog

    entry = indoor_catalog().get(type_name)
    if entry is None or entry.kind != "object":
        return Looks(
            type_name.replace("_", " "),
            None,
            type_name if type_name in SHAPES else None,
            type_colour(type_name),
        )
    look = next((s for s in entry.styles if s.name == style), None) if style else None
    noun = look.noun if look and look.noun else entry.noun
    plural = look.plural if look and look.plural else (entry.plural if noun == entry.noun else None)
    shape = look.shape if look and look.shape else entry.shape
    colour = look.colour if look and look.colour else entry.colour
    return Looks(
        noun,
        plural,
        shape,
        [float(v) for v in colour] if colour is not None else type_colour(type_name),
    )


def example_scene(
    records: Sequence[ObjectRecord],
    *,
    name: str,
    source: str,
    extent: tuple[float, float],
    room: Room | None,
    parents: Mapping[str, str] | None = None,
) -> Scene:
    """The Scene of the objects a file lists; ``parents`` (id -> id it stands on) as
    the file gave them, the other supports measured from the boxes. ``ExampleError`` for
    a name, id, type or style a scene.json may not carry (a control, line-separator or
    bidirectional-control character): every scene made from the example would carry it."""
    _check_text(source, "name", name)
    if len(records) > MAX_NODES:
        raise ExampleError(
            source, "", f"{len(records)} objects; an example may have at most {MAX_NODES}"
        )
    for k, r in enumerate(records):
        for field, value in (("id", r.id), ("type", r.type), ("style", r.style)):
            if value is not None:
                _check_text(source, f"object {k + 1} ({field})", value)
        _check_box(source, k, r)
    if not all(MIN_LENGTH <= side <= MAX_EXTENT for side in extent):
        raise ExampleError(
            source,
            "",
            f"its extent is {extent[0]:g} x {extent[1]:g} m; each side must lie between "
            f"{MIN_LENGTH:g} and {MAX_EXTENT:g} m (docs/limits.md)",
        )
    objects = [
        SceneObject(
            id=r.id,
            type=r.type,
            kind="object",
            noun=looks.noun,
            plural=looks.plural,
            parent=None,
            style=r.style,
            position=[float(v) for v in r.position],
            yaw=_wrapped(r.yaw),
            size=[float(v) for v in r.size],
            shape=looks.shape,
            colour=looks.colour,
            rule=None,
            order=k,
        )
        for k, r in enumerate(records)
        for looks in [default_looks(r.type, r.style)]
    ]
    supports = {**infer_supports(objects), **(parents or {})}
    relations = [
        Relation(o.id, supports[o.id], SUPPORT_LABEL, 0.0, True)
        for o in objects
        if o.id in supports
    ]
    return Scene(
        rules=source,
        seed=0,
        extent=[float(extent[0]), float(extent[1])],
        objects=objects,
        paths=[],
        relations=relations,
        layout=LayoutStats(),
        room=room,
        ground="floor" if room else "grass",
        name=name,
        version=VERSION,
    )


def _wrapped(yaw: float) -> float:
    """``yaw`` in (-pi, pi]."""
    wrapped = wrap_angle(yaw)
    return math.pi if wrapped == -math.pi else wrapped


def _check_box(source: str, index: int, record: ObjectRecord) -> None:
    """Refuse an object a scene.json could not hold: a side beyond ``MAX_SIZE``, a base
    centre beyond ``MAX_COORDINATE``, or a number that is not finite."""
    where = f"object {index + 1} ({record.id[:40]!r})"
    if not all(math.isfinite(v) and 0.0 < v <= MAX_SIZE for v in record.size):
        sides = " x ".join(f"{v:g}" for v in record.size)
        raise ExampleError(
            source, where, f"is {sides} m; each side may be at most {MAX_SIZE:g} m (docs/limits.md)"
        )
    if not all(math.isfinite(v) and abs(v) <= MAX_COORDINATE for v in record.position):
        raise ExampleError(
            source,
            where,
            f"stands further than {MAX_COORDINATE:g} m from the origin (docs/limits.md)",
        )
    if not math.isfinite(record.yaw):
        raise ExampleError(source, where, "has a turn that is not a finite number")


def _check_text(source: str, where: str, text: str) -> None:
    bad = forbidden_character(text)
    if bad is not None:
        raise ExampleError(
            source,
            where,
            f"holds the character {bad}, which a scene.json may not carry (no control, "
            "line-separator or bidirectional-control characters)",
        )
