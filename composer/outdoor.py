"""Composing outdoors: a village, town or city of roads and the junctions they meet at,
on open ground.

A text is outdoors when it names an outdoor scene ("a village"), a road, lane, street
or junction, or when the rule set given as its catalog has no room. Its nouns then come
from the outdoor catalog (``outdoor_catalog``: the types of the shipped village, town
and city rule sets) and the given rule set's own, not the indoor catalog. The rule set
it writes is the indoor one's (``composer.plan``) with open ground for a room: an
``extent`` as large as what it holds needs (or the catalog rule set's, when larger),
its junctions and paths made first (each path after the junction or path it starts
at, as ``PathConnectedTo`` needs), and its groups kept together.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

from scenewright.generator.catalog import CatalogEntry

from .request import Entity, Issue, Request, Statement, tokenize
from .vocabulary import OUTDOOR_SCENES, ROOMS
from .vocabulary import SYNONYMS as INDOOR_SYNONYMS

#: The shipped rule sets whose types make the outdoor catalog, the first's entry kept
#: where two declare a type (the village's oak tree, not the town's).
OUTDOOR_RULE_SETS = ("village", "town", "city")

#: Everyday words for the outdoor catalog's nouns (word -> catalog noun), as
#: ``vocabulary.SYNONYMS`` is for the indoor one's.
SYNONYMS: dict[str, str] = {
    "crossroads": "intersection",
    "crossroad": "intersection",
    "junction": "intersection",
    "crossing": "intersection",
    "street": "road",
    "dirt road": "road",
    "path": "lane",
    "track": "lane",
    "alley": "lane",
    "footpath": "lane",
    "lamp": "street lamp",
    "lamp post": "street lamp",
    "lamppost": "street lamp",
    "streetlight": "street lamp",
    "street light": "street lamp",
    "lantern": "street lamp",
    "market stall": "market stand",
    "stall": "market stand",
    "stand": "market stand",
    "smithy": "blacksmith",
    "blacksmith's": "blacksmith",
    "forge": "blacksmith forge",
    "windmill": "windmill building",
    "watermill": "mill",
    "farm": "farmstead",
    "farmhouse": "cottage",
    "cabin": "cottage",
    "hut": "shed",
    "barn": "shed",
    "grove": "group of trees",
    "copse": "group of trees",
    "clump of trees": "group of trees",
    "cluster of trees": "group of trees",
    "stand of trees": "group of trees",
    "tree": "oak tree",
    "oak": "oak tree",
    "pine": "pine tree",
    "fir": "pine tree",
    "fir tree": "pine tree",
    "shrub": "bush",
    "wagon": "empty wagon",
    "cart": "empty wagon",
    "grain cart": "wagon of grain",
    "flower pot": "flowerpot",
    "planter": "flowerpot",
    "watchtower": "tower",
    "wheat field": "field",
    "cornfield": "field",
    "sheaf": "wheat sheaf",
    "washing line": "clothes line",
    "clothesline": "clothes line",
    "vegetable garden": "vegetable patch",
    "plaza": "square",
    "town square": "square",
    "market square": "market",
    "bench": "chair",
}

#: What a group named without its members holds ("a group of trees"): its noun's
#: meaning, the least the shipped rule sets make of it. Types the catalog lacks are
#: left out; a group type not here is made empty.
MEMBERS: dict[str, tuple[str, ...]] = {
    "group_of_trees": ("pine_tree", "pine_tree", "bush"),
    "market_stand": ("table", "sign"),
    "blacksmith": ("forge", "brazier", "anvil"),
    "farmstead": ("house", "field", "shed"),
    "mill": ("windmill", "pallet_of_grain_sheaves", "sack_of_flour"),
    "home": ("house", "bush"),
    "park": ("oak_tree", "pine_tree", "bush"),
    "market": ("well", "wagon_of_crates", "crate"),
    "shop": ("shop_house", "sign"),
}

#: The ground's side: at least this (metres), at least the longest path twice over
#: plus ``JUNCTION_MARGIN`` (roads leave a junction in the middle both ways), and this
#: many times the ground what stands on it covers.
MIN_EXTENT = 30.0
JUNCTION_MARGIN = 8.0
GROUND_PER_FOOTPRINT = 10.0
#: The scene's name when the text names none (a "scene" of roads).
DEFAULT_SCENE = "village"


@dataclass(frozen=True)
class Ground:
    """An outdoor scene's settings from the rule set given as the catalog (its scene's
    name and extent), or none."""

    name: str | None = None
    extent: tuple[float, float] | None = None


def _noun_key(entry: CatalogEntry) -> str:
    return entry.noun.lower()


@functools.cache
def outdoor_catalog() -> Mapping[str, CatalogEntry]:
    """The outdoor catalog: every type of ``OUTDOOR_RULE_SETS``, the first rule set's
    entry where several declare a type, and one type per noun (an object before a group:
    the city's "shop" is its shop building; the village's intersection before the
    city's crossroads, which is also "an intersection")."""
    from scenewright.generator import load_rules

    out: dict[str, CatalogEntry] = {}
    nouns: set[str] = set()
    for name in OUTDOOR_RULE_SETS:
        entries = load_rules(name).catalog.entries
        for type_, entry in sorted(entries.items(), key=lambda kv: kv[1].kind == "group"):
            if type_ in out or _noun_key(entry) in nouns:
                continue
            out[type_] = entry
            nouns.add(_noun_key(entry))
    return out


@functools.cache
def _outdoor_words() -> frozenset[str]:
    """Phrases that make a text outdoors: scene words, and the nouns and plurals of the
    outdoor catalog's paths and junctions and their synonyms (not "square", which a
    room's table may be)."""
    from .vocabulary import _entry_nouns

    words = set(OUTDOOR_SCENES)
    for entry in outdoor_catalog().values():
        if entry.kind in ("path", "junction"):
            words.update(_entry_nouns(entry))
    ways = {e.noun.lower() for e in outdoor_catalog().values() if e.kind in ("path", "junction")}
    for word, noun in SYNONYMS.items():
        if noun in ways:
            words.update((word, word + "s"))
    words.discard("square")
    words.discard("squares")
    return frozenset(words)


@functools.cache
def _nouns_only_in() -> tuple[frozenset[str], frozenset[str]]:
    """The nouns (and their everyday words) only the outdoor catalog knows, and those
    only the indoor one knows."""
    from scenewright.generator.rules import indoor_catalog

    from .vocabulary import vocabulary

    outdoor = set(vocabulary(outdoor_catalog(), synonyms=synonyms()).nouns)
    indoor = set(vocabulary(indoor_catalog()).nouns)
    return frozenset(outdoor - indoor), frozenset(indoor - outdoor)


def is_outdoor_text(text: str) -> bool:
    """Whether a text asks for an outdoor scene (see the module docstring): it names an
    outdoor scene, a road or a junction; or, naming no room, more things only the
    outdoor catalog has ("a market stand with a table and two barrels") than things
    only the indoor one has."""
    words = [t.low for t in tokenize(text)]
    phrases = [" ".join(words[i : i + n]) for i in range(len(words)) for n in (1, 2, 3, 4)]
    if any(p in _outdoor_words() for p in phrases):
        return True
    if any(p in ROOMS and p != "scene" for p in phrases):
        return False
    outdoor, indoor = _nouns_only_in()
    return sum(p in outdoor for p in phrases) > sum(p in indoor for p in phrases)


def synonyms() -> dict[str, str]:
    """The everyday words understood outdoors: the outdoor ones, then the indoor ones."""
    return {**SYNONYMS, **{w: n for w, n in INDOOR_SYNONYMS.items() if w not in SYNONYMS}}


def catalog_for(text: str, own=None) -> tuple[dict[str, CatalogEntry], set[str], Ground | None]:
    """The catalog a text is composed with: (entries, the types that name a noun several
    share, the ground when it is outdoors, else None). ``own``: the rule set (``Rules``)
    given as the catalog, or None. Indoors that is the shipped indoor catalog and the
    rule set's own; outdoors the outdoor catalog and the rule set's own."""
    from scenewright.generator.rules import created_types, indoor_catalog

    outdoor_own = own is not None and own.params.room is None
    if outdoor_own or is_outdoor_text(text):
        entries = dict(outdoor_catalog())
        prefer: set[str] = set()
        ground = Ground()
        if own is not None:
            entries.update(own.catalog.entries)
            prefer = created_types(own)
            if outdoor_own:
                ground = Ground(own.params.name, tuple(own.params.extent))
        return entries, prefer, ground
    entries = dict(indoor_catalog())
    prefer = set()
    if own is not None:
        entries.update(own.catalog.entries)
        prefer = created_types(own)
    return entries, prefer, None


# -- the request, outdoors ---------------------------------------------------------


def settle(request: Request, entries: Mapping[str, CatalogEntry]) -> None:
    """Outdoors, after reading: a thing first named in a group's paragraph and related
    only to that group's members is one of them ("Three flowerpots are on top of this
    table." after "the first market stand consists of ..."); a group named without its
    members gets the things its noun means (``MEMBERS``); and members nothing relates to
    the rest of their group stand next to its first member (implicitly: it is a group),
    so that the group stays together. First, what is said of roads is made what a road
    can be (``fit_to_ways``)."""
    fit_to_ways(request, entries)
    adopt_members(request)
    for group in [e for e in request.entities if e.group and e.parent is None]:
        members = [e for e in request.entities if e.parent == group.id]
        if not members:
            for type_ in MEMBERS.get(group.type, ()):
                if type_ in entries:
                    members.append(_add(request, type_, group))
        _keep_together(request, group, members)


def fit_to_ways(request: Request, entries: Mapping[str, CatalogEntry]) -> None:
    """Relations with a path or junction made ones the layout can hold: a thing is next
    to a road, to its left, in front of it or facing it; whatever else a phrase says of
    it ("on the road", "on each side of the road", "close beside the junction") is next
    to it, and lined up with it, which a road cannot be, is left out. A road said to be
    next to (or left of ...) a thing puts the thing next to the road ("a well between
    the road and the tower"); anything else said of a road, and a road next to a road,
    is reported and left out (roads meet at junctions or branch off each other)."""

    def way(end: object) -> bool:
        return isinstance(end, str) and entries[by_id[end].type].kind in ("path", "junction")

    by_id = {e.id: e for e in request.entities}
    kept: list[Statement] = []
    for s in request.statements:
        if s.label == "PathConnectedTo" or not (way(s.source) or way(s.target)):
            kept.append(s)
        elif s.label.startswith("Implicit"):
            continue
        elif not way(s.source):
            near = s.label.startswith(("NextTo", "Facing"))
            kept.append(s if near else replace(s, label="NextTo"))
        elif s.label.startswith(("NextTo", "Beside")) and not way(s.target):
            assert isinstance(s.target, str)
            kept.append(replace(s, source=s.target, label="NextTo", target=s.source))
        else:
            request.issues.append(
                Issue(s.start, s.end, "", "a road or junction is only next to things")
            )
    request.statements = kept


def adopt_members(request: Request) -> None:
    """See ``settle``: each top-level thing named in a group's paragraph whose stated
    relations all go to or come from that group's members becomes one."""
    by_id = {e.id: e for e in request.entities}
    for e in request.entities:
        if e.parent is not None or e.group or e.paragraph is None:
            continue
        others = [
            other
            for s in request.statements
            for other in (s.source, s.target)
            if e.id in (s.source, s.target) and isinstance(other, str) and other != e.id
        ]
        if others and all(by_id[o].parent == e.paragraph for o in others):
            e.parent = e.paragraph


def _add(request: Request, type_: str, group: Entity) -> Entity:
    entity = Entity(
        f"e{len(request.entities) + 1}", type_, None, None, group.start, group.end, group.id
    )
    request.entities.append(entity)
    return entity


def _keep_together(request: Request, group: Entity, members: list[Entity]) -> None:
    ids = {m.id for m in members}
    linked = {
        end
        for s in request.statements
        if s.source in ids and s.target in ids
        for end in (s.source, s.target)
    }
    for m in members[1:]:
        if m.id not in linked:
            request.statements.append(
                Statement(m.id, "ImplicitNextTo", members[0].id, group.start, group.end)
            )


def made_first(top: list[Entity], request: Request, entries: Mapping[str, CatalogEntry]):
    """The top level's things in the order the production makes them: the junctions,
    then each path after what it starts at, then the rest as named."""

    def kind(e: Entity) -> str:
        return entries[e.type].kind

    starts = {
        s.source: s.target
        for s in request.statements
        if s.label == "PathConnectedTo" and isinstance(s.target, str)
    }
    junctions = [e for e in top if kind(e) == "junction"]
    paths = [e for e in top if kind(e) == "path"]
    done = {e.id for e in junctions}
    ordered = list(junctions)
    while paths:
        ready = [p for p in paths if starts.get(p.id) in done or p.id not in starts]
        ready = ready or paths[:1]  # paths starting on each other in a circle: as named
        for p in ready:
            ordered.append(p)
            done.add(p.id)
        paths = [p for p in paths if p.id not in done]
    return ordered + [e for e in top if kind(e) not in ("junction", "path")]


def extent(
    request: Request, entries: Mapping[str, CatalogEntry], ground: Ground
) -> tuple[float, float]:
    """The ground's sides: see ``MIN_EXTENT``; the catalog rule set's extent when larger;
    a size word before the scene's ("a small village") scales what the things need."""
    footprint = 0.0
    longest = 0.0
    on_top = {s.source for s in request.statements if s.label.startswith("OnTopOf")}
    for e in request.entities:
        entry = entries[e.type]
        if entry.kind == "path":
            longest = max(longest, entry.max_length)
            continue
        if e.group or e.id in on_top:
            continue
        style = next((s for s in entry.styles if s.name == e.style), None)
        w, _, d = style.size if style is not None and style.size is not None else entry.size
        footprint += w * d
    side = max(math.sqrt(footprint * GROUND_PER_FOOTPRINT), MIN_EXTENT) * request.size_factor
    side = max(side, 2 * longest + JUNCTION_MARGIN)
    side = 5.0 * math.ceil(side / 5.0)
    if ground.extent is not None:
        return max(side, ground.extent[0]), max(side, ground.extent[1])
    return side, side


def scene_name(request: Request, ground: Ground) -> str:
    """The scene's name: the text's outdoor scene word's, else the catalog rule set's,
    else ``DEFAULT_SCENE``."""
    named = {name for name, _ in OUTDOOR_SCENES.values()}
    if request.room in named:
        return request.room
    return ground.name or DEFAULT_SCENE
