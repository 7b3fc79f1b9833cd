"""One scene from a house and its furnished rooms, and the rooms back out of it.

A house scene is a ``Scene`` with ``house`` set and no ``room``: its objects are every
room's objects moved into the house's frame, each id prefixed with its room's
(``bedroom_2/bed_1``), and its relations every room's relations with their ends named
the same way (a wall of a room is ``bedroom_2/wall_3``, "whichever wall fits" is
``bedroom_2/room``). ``room_scene`` gives a room back as the room scene it was laid out
as (its own frame, its own ids), which is what the describer, the checks and the
layout read: a house is checked and described room by room.
"""

from __future__ import annotations

from dataclasses import asdict, replace

from scenewright.core.house import ID_SEPARATOR, House, HouseRoom, in_room, room_of
from scenewright.core.relations import Relation
from scenewright.core.scene import LayoutStats, Scene, SceneObject

#: The floor of every room of a house.
HOUSE_GROUND = "floor"


def house_scene(house: House, rooms: list[Scene], *, rules: str, seed: int, name: str) -> Scene:
    """The house scene of ``house`` furnished with ``rooms`` (one scene per house room, in order)."""
    objects: list[SceneObject] = []
    relations: list[Relation] = []
    furnished = []
    order = 0
    for house_room, scene in zip(house.rooms, rooms, strict=False):
        ox, oz = house_room.offset
        for obj in scene.objects:
            x, y, z = obj.position
            objects.append(
                replace(
                    obj,
                    id=in_room(house_room.id, obj.id),
                    parent=in_room(house_room.id, obj.parent) if obj.parent else None,
                    position=[x + ox, y, z + oz],
                    order=order + obj.order,
                )
            )
        order += max((o.order for o in scene.objects), default=0) + 1
        for relation in scene.relations:
            relations.append(
                replace(
                    relation,
                    source=in_room(house_room.id, relation.source),
                    target=in_room(house_room.id, relation.target),
                )
            )
        furnished.append(
            replace(
                house_room,
                seed=scene.seed,
                # wall-clock seconds stay out: scene.json is the same from run to run
                layout={k: v for k, v in asdict(scene.layout).items() if k != "seconds"},
                derivation=tuple(scene.derivation),
            )
        )
    stats = LayoutStats(
        energy=sum(s.layout.energy for s in rooms),
        parts=_summed_parts(rooms),
        steps=sum(s.layout.steps for s in rooms),
        acceptance=(sum(s.layout.acceptance for s in rooms) / len(rooms)) if rooms else 0.0,
        seconds=sum(s.layout.seconds for s in rooms),
        ok=all(s.layout.ok for s in rooms),
        problems=[
            f"{house_room.id}: {problem}"
            for house_room, s in zip(house.rooms, rooms, strict=False)
            for problem in s.layout.problems
        ],
    )
    width, depth = house.extent
    return Scene(
        rules=rules,
        seed=seed,
        extent=[width, depth],
        objects=objects,
        paths=[],
        relations=relations,
        layout=stats,
        room=None,
        house=replace(house, rooms=tuple(furnished)),
        ground=HOUSE_GROUND,
        name=name,
        version=rooms[0].version if rooms else "",
    )


def room_scene(scene: Scene, room_id: str) -> Scene:
    """Room ``room_id`` of a house scene as the room scene it was laid out as."""
    assert scene.house is not None
    house_room: HouseRoom = scene.house.room(room_id)
    ox, oz = house_room.offset
    prefix = room_id + ID_SEPARATOR
    objects = [
        replace(
            obj,
            id=obj.id[len(prefix) :],
            parent=obj.parent[len(prefix) :] if obj.parent else None,
            position=[obj.position[0] - ox, obj.position[1], obj.position[2] - oz],
        )
        for obj in scene.objects
        if room_of(obj.id) == room_id
    ]
    relations = [
        replace(r, source=r.source[len(prefix) :], target=r.target[len(prefix) :])
        for r in scene.relations
        if room_of(r.source) == room_id
    ]
    layout = house_room.layout
    return Scene(
        rules=house_room.rules,
        seed=house_room.seed,
        extent=list(house_room.room.extent),
        objects=objects,
        paths=[],
        relations=relations,
        layout=LayoutStats(**layout) if layout else LayoutStats(),
        room=house_room.room,
        ground=HOUSE_GROUND,
        name=house_room.type,
        derivation=list(house_room.derivation),
        version=scene.version,
    )


def _summed_parts(rooms: list[Scene]) -> dict[str, float]:
    parts: dict[str, float] = {}
    for scene in rooms:
        for key, value in scene.layout.parts.items():
            parts[key] = parts.get(key, 0.0) + value
    return parts
