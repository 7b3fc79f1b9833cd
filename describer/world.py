"""What the describer can talk about: every entity of a scene with its noun and place in
the derivation, and the parts of its room.

An entity is an object, group, junction or path. Entities that share a noun and a
parent form a *cohort* ("the three market stands" of the scene, "the two signs" of one
stand): ordinals and counts are taken within a cohort, in derivation order.

A room's walls, doors, windows and corners are not entities: they are never counted,
never introduced as objects are, and always named by what sets them apart in the room
("the north wall", "the corner by the door"; see ``rooms``). They can be what a
relation's words name: ``target_of`` gives, for each relation, the entity or room part
its object phrase names.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from scenewright.core.relations import Relation
from scenewright.core.scene import Scene

from scenewright.core.errors import InputError

from .english import plural_of
from .grounding import holds_marks
from .rooms import RoomView


@dataclass(frozen=True)
class Entity:
    """One thing in the scene as the text sees it."""

    id: str
    kind: str  # object, group, junction or path
    noun: str
    plural: str
    parent: str | None
    order: int


@dataclass(frozen=True)
class World:
    """The scene's entities in derivation order, with cohort lookups."""

    entities: dict[str, Entity]
    cohorts: dict[tuple[str, str | None], tuple[str, ...]]
    by_noun: dict[str, tuple[str, ...]]
    children: dict[str | None, tuple[str, ...]]
    #: The scene's room as the text names it; None outdoors.
    room: RoomView | None = None
    #: ``_shown_by``'s answers so far (a cache, not part of the world's value).
    _shown: dict[str, tuple[str, ...]] = field(default_factory=dict, compare=False, repr=False)

    def __getitem__(self, entity_id: str) -> Entity:
        return self.entities[entity_id]

    def __contains__(self, entity_id: str) -> bool:
        return entity_id in self.entities

    def target_of(self, relation: Relation) -> str | None:
        """What the relation's object phrase names: its target entity, or the part of
        the room its words name (``RoomView.place``); None when the text cannot name it."""
        if relation.target in self.entities:
            return relation.target
        return self.room.place(relation) if self.room is not None else None

    def place_kind(self, target_id: str) -> str | None:
        """"wall", "door", "window" or "corner" for a part of the room; None for an entity."""
        if target_id in self.entities or self.room is None:
            return None
        return self.room.kind(target_id)

    def cohort(self, entity_id: str) -> tuple[str, ...]:
        """The entities with the same noun and parent as this one (itself included)."""
        entity = self.entities[entity_id]
        return self.cohorts[(entity.noun, entity.parent)]

    def namesakes(self, entity_id: str) -> tuple[str, ...]:
        """Every entity in the scene with this one's noun (itself included)."""
        return self.by_noun[self.entities[entity_id].noun]

    def members(self, owner: str | None) -> list[Entity]:
        """The direct members of a group, or the top-level entities for ``None``."""
        return [self.entities[i] for i in self.children.get(owner, ())]

    def grounded_ids(self, named: tuple[str, ...]) -> tuple[str, ...]:
        """What a phrase naming ``named`` shows in a picture: each entity itself, and for
        a group its objects, paths and junctions, at any depth (no duplicates, in the order
        named, members in derivation order). A door or window (not an entity) is itself."""
        found: dict[str, None] = {}
        for entity_id in named:
            found.update(dict.fromkeys(self._shown_by(entity_id)))
        return tuple(found)

    def _shown_by(self, entity_id: str) -> tuple[str, ...]:
        """``grounded_ids`` of one entity, kept: every mention of a group (and of each
        group around it, in nested phrases) asks again, and deep nesting made that
        quadratic."""
        shown = self._shown.get(entity_id)
        if shown is None:
            if entity_id in self.entities and self.entities[entity_id].kind == "group":
                found: dict[str, None] = {}
                for member in self.children.get(entity_id, ()):
                    found.update(dict.fromkeys(self._shown_by(member)))
                shown = tuple(found)
            else:
                shown = (entity_id,)
            self._shown[entity_id] = shown
        return shown

    def owners(self) -> list[str | None]:
        """The scene (``None``) and then every entity with members, depth-first in derivation order."""
        found: list[str | None] = [None]

        def visit(owner: str | None) -> None:
            for member in self.members(owner):
                if self.members(member.id):
                    found.append(member.id)
                    visit(member.id)

        visit(None)
        return found


def world_of(scene: Scene) -> World:
    """The describable entities of a scene, in derivation order."""
    raw = [(o.order, 0, i, o) for i, o in enumerate(scene.objects)]
    raw += [(p.order, 1, i, p) for i, p in enumerate(scene.paths)]
    raw.sort(key=lambda item: item[:3])
    object_ids = {o.id for o in scene.objects}
    entities: dict[str, Entity] = {}
    for _, is_path, _, thing in raw:
        if holds_marks(thing.noun) or holds_marks(thing.plural or ""):
            raise InputError(f"{thing.id}: its noun holds a private-use character (U+E000, U+E001 or "
                             "U+F0000..U+FFFFD) the describer marks phrases with")
        entities[thing.id] = Entity(
            id=thing.id,
            kind="path" if is_path else thing.kind,
            noun=thing.noun,
            plural=plural_of(thing.noun, thing.plural),
            # A parent the scene does not hold cannot be named: treat the entity as top-level.
            parent=thing.parent if thing.parent in object_ids else None,
            order=thing.order,
        )
    cohorts: dict[tuple[str, str | None], tuple[str, ...]] = {}
    by_noun: dict[str, tuple[str, ...]] = {}
    children: dict[str | None, tuple[str, ...]] = {}
    for entity in entities.values():
        key = (entity.noun, entity.parent)
        cohorts[key] = cohorts.get(key, ()) + (entity.id,)
        by_noun[entity.noun] = by_noun.get(entity.noun, ()) + (entity.id,)
        children[entity.parent] = children.get(entity.parent, ()) + (entity.id,)
    room = RoomView(scene.room, scene.objects) if scene.room is not None else None
    return World(entities, cohorts, by_noun, children, room)
