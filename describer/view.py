"""Captions of one rendered picture: only what the picture shows, only what holds in it.

``describe_view(scene, picture, frame=..., variant=k)`` captions the scene as one
picture of it (a ``render.visibility.PictureView``) shows it. It describes the *view
scene*: the scene cut down to

- the objects, junctions and paths the picture shows well enough to name
  (``PictureView.seen``: visible fraction and box size over the thresholds), and the
  groups with at least one of those among their members (a group is grounded to its
  seen members only, and counted by them: "two market stands" when the third is hidden);
- the relations between those that hold in the picture too: not when a third solid
  thing stands between the two in the picture (``PictureView.between``; "the chair is
  in front of the desk" with a board between them in the picture is not said), and to
  a room's parts only when the picture shows the part (a wall the view cuts away, a
  door or window under the thresholds, a corner with neither wall drawn: not said).

With ``frame="camera"`` the words for sides are the picture's: a next-to relation that
names a direction ("north of", "to the left of B" as B's own left) is told by where the
picture shows A from B (``PictureView.picture_side``): "to the left of the tent in the
picture", "in front of the well in the picture" (nearer the camera); when the picture
does not settle it, or an end is a path (a road has no one centre to be left of), it
is told as plain "next to", which every next-to relation implies. Such a relation's
fact is then ``NextToChooseSide`` (the side: the picture's) or ``NextTo``.

A large scene (``LARGE_SCENE`` objects or more: a town) is captioned by concrete
things: each group the picture shows is named by the one of its objects the picture
shows that most of the group's relations lead to, the biggest on a tie ("three houses
and a cottage", not "four homes"; "two tents", not "two camp pitches"), and the
caption's second sentence only relates things it named.

Ordinals and counts are those of the view scene, ordinals in the order the caption
names things. The layout-true full description is ``describe``'s, unchanged.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.scene import Scene

from .description import Description, describe_frame
from .realise import PICTURE_SIDE_LABEL
from .world import World, world_of

if TYPE_CHECKING:
    from scenewright.render.visibility import PictureView

#: The frames side words may be told in: the scene's (compass, and B's own sides) or the picture's.
FRAMES = ("scene", "camera")
#: A scene of at least this many objects (groups not counted) is captioned by concrete
#: things: each group a picture shows by the thing of it, among those it shows, that the
#: group is arranged around.
LARGE_SCENE = 100


def describe_view(
    scene: Scene,
    picture: PictureView,
    *,
    frame: str = "scene",
    variant: int = 0,
    templates: str | Path | None = None,
) -> Description:
    """The short caption (``style="short"``) of ``scene`` as ``picture`` shows it."""
    if frame not in FRAMES:
        raise InputError(f"unknown caption frame {frame!r}; expected one of: {', '.join(FRAMES)}")
    view = view_scene(scene, picture, frame=frame)
    unseen = not (view.objects or view.paths) and bool(scene.objects or scene.paths)
    large = sum(o.kind == "object" for o in scene.objects) >= LARGE_SCENE
    return describe_frame(
        view,
        style="short",
        variant=variant,
        templates=templates,
        picture=True,
        picture_sides=frame == "camera",
        unseen=unseen,
        concrete=large,
    )


def grounding_records(description: Description, picture: PictureView) -> list[dict]:
    """The description's mentions as a dataset row's ``grounding`` lists them:
    ``{"span": [start, end], "ids": [...], "boxes": [[x0, y0, x1, y1] or None, ...],
    "segments": [label or None, ...]}``, ``boxes`` the picture's pixel boxes of ``ids`` in
    the same order (None for one the picture does not show at all: only the layout-true
    text names such) and ``segments`` their labels in the segmentation image (None for
    one the picture does not draw). Mentions that ground to nothing (a group without
    members) are left out."""
    return [
        {
            "span": [m.start, m.end],
            "ids": list(m.ids),
            "boxes": [picture.box(i) for i in m.ids],
            "segments": [picture.segment(i) for i in m.ids],
        }
        for m in description.mentions
        if m.ids
    ]


def view_scene(scene: Scene, picture: PictureView, *, frame: str = "scene") -> Scene:
    """``scene`` cut down to what ``picture`` shows and the relations that hold in it
    (see the module docstring); in the camera frame, side relations reworded by the picture."""
    world = world_of(scene)
    seen = {
        entity_id
        for entity_id, entity in world.entities.items()
        if entity.kind != "group" and picture.seen(entity_id)
    }
    kept = seen | {
        entity_id
        for entity_id, entity in world.entities.items()
        if entity.kind == "group" and seen.intersection(world.grounded_ids((entity_id,)))
    }
    resting = _resting_on(scene)
    relations = []
    for relation in scene.relations:
        if relation.source not in kept or not relation.satisfied:
            continue
        if relation.target in world:
            if relation.target not in kept or _something_between(
                relation, world, seen, resting, picture
            ):
                continue
            if frame == "camera" and _names_a_side(relation.label):
                relation = _in_picture_words(relation, world, picture)
        elif not _part_in_picture(relation, world, picture):
            continue
        relations.append(relation)
    return replace(
        scene,
        objects=[o for o in scene.objects if o.id in kept],
        paths=[p for p in scene.paths if p.id in kept],
        relations=relations,
    )


def _resting_on(scene: Scene) -> dict[str, set[str]]:
    """For each entity, everything that rests on it, directly or through others (a pot on
    a table on a cart): what stands in front of it in a picture is part of it there."""
    supports: dict[str, set[str]] = {}
    for relation in scene.relations:
        if relation.satisfied and relation.label in RELATIONS and RELATIONS[relation.label].support:
            supports.setdefault(relation.target, set()).add(relation.source)
    closed: dict[str, set[str]] = {}
    for base in supports:
        found, todo = set(), [base]
        while todo:
            for above in supports.get(todo.pop(), ()):
                if above not in found:
                    found.add(above)
                    todo.append(above)
        closed[base] = found
    return closed


def _something_between(
    relation: Relation,
    world: World,
    seen: set[str],
    resting: dict[str, set[str]],
    picture: PictureView,
) -> bool:
    """Whether a third solid thing stands between the relation's ends in the picture."""
    ends = []
    for end in (relation.source, relation.target):
        ends.append([i for i in world.grounded_ids((end,)) if i in seen])
    ignore = set()
    for end_ids in ends:
        for entity_id in end_ids:
            ignore |= resting.get(entity_id, set())
    return picture.between(ends[0], ends[1], ignore=tuple(sorted(ignore)))


def _names_a_side(label: str) -> bool:
    """Next-to labels whose words name a direction (compass or the target's own sides)."""
    spec = RELATIONS[label]
    return spec.family == "next_to" and (bool(spec.directions) or spec.chooses)


def _in_picture_words(relation: Relation, world: World, picture: PictureView) -> Relation:
    """The relation as the picture's side of A from B says it, or as plain "next to"."""
    paths = any(world[end].kind == "path" for end in (relation.source, relation.target))
    side = None if paths else picture.picture_side(relation.source, relation.target)
    if side is None:
        return replace(relation, label="NextTo", chosen=None)
    return replace(relation, label=PICTURE_SIDE_LABEL, chosen=side)


def _part_in_picture(relation: Relation, world: World, picture: PictureView) -> bool:
    """Whether the picture shows the part of the room the relation's words name: a door
    or window seen, a wall drawn, a corner with a wall drawn."""
    place = world.target_of(relation)
    if place is None or world.room is None:
        return False
    kind = world.room.kind(place)
    if kind in ("door", "window"):
        return picture.seen(place)
    if kind == "corner":
        corner = world.room.corners[place]
        return corner.before in picture.walls or corner.after in picture.walls
    return place in picture.walls
