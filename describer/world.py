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

from scenewright.core.errors import InputError
from scenewright.core.relations import Relation
from scenewright.core.scene import Scene, SceneObject, ScenePath

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
    #: (noun, parent) -> the noun whose ordinals it shares: the most general noun among
    #: its siblings that it is a kind of ("white desk" -> "desk"), else its own.
    families: dict[tuple[str, str | None], str] = field(default_factory=dict)
    #: Nouns of groups nested in a group of the same noun (a row of desks made of rows
    #: of desks): their members are counted across the whole scene, never "at" their group.
    nested_nouns: frozenset[str] = frozenset()
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
        """ "wall", "door", "window" or "corner" for a part of the room; None for an entity."""
        if target_id in self.entities or self.room is None:
            return None
        return self.room.kind(target_id)

    def cohort(self, entity_id: str) -> tuple[str, ...]:
        """The entities with the same noun and parent as this one (itself included)."""
        entity = self.entities[entity_id]
        return self.cohorts[(entity.noun, entity.parent)]

    def family(self, entity_id: str) -> tuple[str, ...]:
        """The siblings whose nouns share this one's ordinals (itself included), in
        derivation order: its cohort and the cohorts of kinds of the same thing ("desk"
        and "white desk"), so "the second desk" never counts apart from "the first
        white desk". For a nested noun, every namesake in the scene."""
        entity = self.entities[entity_id]
        if entity.noun in self.nested_nouns:
            return self.namesakes(entity_id)
        family = self.families.get((entity.noun, entity.parent), entity.noun)
        return tuple(
            i
            for i in self.children.get(entity.parent, ())
            if self.families.get((self.entities[i].noun, entity.parent), self.entities[i].noun)
            == family
        )

    def family_noun(self, entity_id: str) -> str:
        """The noun that covers its whole family ("desk" for a "white desk" beside desks)."""
        entity = self.entities[entity_id]
        return self.families.get((entity.noun, entity.parent), entity.noun)

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

    def owners(self, first: dict[str, int] | None = None) -> list[str | None]:
        """The scene (``None``) and then every entity with members, depth-first in derivation
        order; within a family (``family``), members in ``first`` go first, in its order."""
        found: list[str | None] = [None]
        first = first or {}

        def visit(owner: str | None) -> None:
            members = self.members(owner)
            queues: dict[tuple[str, ...], list[Entity]] = {}
            for member in members:
                queues.setdefault(self.family(member.id), []).append(member)
            for queue in queues.values():
                queue.sort(key=lambda m: first.get(m.id, len(members)))
            for member in [queues[self.family(m.id)].pop(0) for m in members]:
                if self.members(member.id):
                    found.append(member.id)
                    visit(member.id)

        visit(None)
        return found


def world_of(scene: Scene) -> World:
    """The describable entities of a scene, in derivation order."""
    raw: list[tuple[int, int, int, SceneObject | ScenePath]]
    raw = [(o.order, 0, i, o) for i, o in enumerate(scene.objects)]
    raw += [(p.order, 1, i, p) for i, p in enumerate(scene.paths)]
    raw.sort(key=lambda item: item[:3])
    object_ids = {o.id for o in scene.objects}
    entities: dict[str, Entity] = {}
    for _, _, _, thing in raw:
        if holds_marks(thing.noun) or holds_marks(thing.plural or ""):
            raise InputError(
                f"{thing.id}: its noun holds a private-use character (U+E000, U+E001 or "
                "U+F0000..U+FFFFD) the describer marks phrases with"
            )
        entities[thing.id] = Entity(
            id=thing.id,
            kind=thing.kind if isinstance(thing, SceneObject) else "path",
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
    return World(
        entities, cohorts, by_noun, children, room, _families(cohorts), _nested_nouns(entities)
    )


def is_kind_of(noun: str, general: str) -> bool:
    """Whether a ``noun`` thing is also a ``general`` one to a person: ``general`` has no
    "of" phrase and ``noun``'s head (before any "of") ends with it ("office chair",
    "armchair" and "bucket of coal" are kinds of "chair", "chair" and "bucket")."""
    return noun != general and " of " not in general and noun.split(" of ")[0].endswith(general)


def _families(
    cohorts: dict[tuple[str, str | None], tuple[str, ...]],
) -> dict[tuple[str, str | None], str]:
    """Each cohort's family noun: the most general sibling noun it is a kind of, or its own."""
    nouns_of: dict[str | None, list[str]] = {}
    for noun, parent in cohorts:
        nouns_of.setdefault(parent, []).append(noun)
    families = {}
    for noun, parent in cohorts:
        general = [n for n in nouns_of[parent] if is_kind_of(noun, n)]
        families[(noun, parent)] = min(general, key=len) if general else noun
    return families


def _nested_nouns(entities: dict[str, Entity]) -> frozenset[str]:
    """Nouns of entities with an ancestor of the same noun."""
    nested = set()
    for entity in entities.values():
        parent = entity.parent
        while parent is not None:
            if entities[parent].noun == entity.noun:
                nested.add(entity.noun)
                break
            parent = entities[parent].parent
    return frozenset(nested)
