"""Content selection, document structure and aggregation: what the text says, in what order.

The plan follows the derivation. The first section is the scene: an inventory of the
top-level entities ("The scene consists of three roads meeting at an intersection, ...")
then what stands on what and how they relate. Each group follows in depth-first
derivation order with the same shape: its inventory, the members that stand on other
members ("A big pot of stew is in the middle of this table."), then statements.

In a room, the scene's inventory is followed by the room sentence: its shape when it is
L-shaped and its doors and windows, wall by wall ("The room has a door in the south
wall and two windows in the north wall."). Walls, doors, windows and corners are never
in an inventory; relations to them are told like any other, naming the part of the
room their words say (``World.target_of``: "The wardrobe stands against the north
wall.").

Only relations the layout reports as satisfied are selected; ``Implicit*`` never;
``PathConnectedTo`` only as a road network in an inventory. A relation is told in the
first section where both its ends have been introduced (a room's parts are known from
the start). Statements are aggregated: the sources sharing a relation to one target
become one subject ("The mill and the street lamp are next to the first road."), and
the clauses of one subject one sentence.

The plan is plain data over entity ids; referring expressions and words come later.
"""

from __future__ import annotations

from dataclasses import dataclass

from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.scene import Fact, Scene

from .lexicon import is_described, is_symmetric, place_phrases, relation_wordings
from .summary import (
    Composition,
    Pattern,
    Quantified,
    compositions,
    hidden_owners,
    patterns,
    quantified,
    summarised_groups,
)
from .world import Entity, World

#: The most clauses one statement joins ("The chair is in front of the desk and faces it.").
MAX_CLAUSES = 2

#: The most phrases one subject joins; more are told in a second sentence with "also".
#: Long lists are hard to read (and beyond what link-grammar parses).
MAX_CONJUNCTS = 4


@dataclass(frozen=True)
class Clause:
    """A relation from the sentence's subjects to each of ``targets``."""

    label: str
    chosen: str | None
    targets: tuple[str, ...]


@dataclass(frozen=True)
class Network:
    """Paths starting at one junction: "three roads meeting at an intersection"."""

    junction: str
    paths: tuple[str, ...]


#: One item of an inventory: entities of one noun counted together, or a road network.
Item = tuple[str, ...] | Network


@dataclass(frozen=True)
class Inventory:
    """What a group (or the scene, owner ``None``) consists of.

    ``link``, when set, relates the first item to the second, which is then a single
    entity: "consists of a sign to the right of a table". It is only used with exactly
    two items, where the list cannot be misread.
    """

    owner: str | None
    items: tuple[Item, ...]
    link: Clause | None = None


@dataclass(frozen=True)
class RoomOutline:
    """The room sentence: "The L-shaped room has a door in the south wall and two windows
    in the north wall."

    ``shape``: "L-shaped" or None; ``openings``: (kind, wall id, opening ids) for each
    wall with doors or windows of a kind.
    """

    shape: str | None
    openings: tuple[tuple[str, str, tuple[str, ...]], ...]


@dataclass(frozen=True)
class Introduction:
    """New entities that stand on (or are part of) one already introduced: "Two books are on top of this table."."""

    subjects: tuple[tuple[str, ...], ...]  # entities grouped by noun
    clause: Clause


@dataclass(frozen=True)
class Statement:
    """Known entities and one or more relations they share.

    A clause's label gives its words; relations of other labels with the same words
    ("to the left of" is ``NextToLeft`` or ``NextToChooseSide`` "left") are told in the
    same clause, so ``facts`` lists what each subject's own relation is.
    ``also``: the statement continues the one before it with more subjects ("The mill
    and the well are also next to the road."); the two are never separated.
    """

    subjects: tuple[str, ...]
    clauses: tuple[Clause, ...]
    facts: tuple[Fact, ...]
    also: bool = False


Message = Inventory | RoomOutline | Introduction | Statement | Composition | Pattern | Quantified


@dataclass(frozen=True)
class Section:
    """The scene's or one group's part of the text."""

    owner: str | None
    messages: tuple[Message, ...]


def facts_of(message: Message) -> list[Fact]:
    """Every (subject id, label, object id) the message states (in plan order: a variant may word them in another)."""
    if isinstance(message, Inventory):
        facts = [
            (path, "PathConnectedTo", item.junction)
            for item in message.items
            if isinstance(item, Network)
            for path in item.paths
        ]
        if message.link is not None:
            first = message.items[0]
            assert not isinstance(first, Network)  # a link follows counted entities
            facts += _clause_facts(first, message.link)
        return facts
    if isinstance(message, Introduction):
        subjects = tuple(s for unit in message.subjects for s in unit)
        return _clause_facts(subjects, message.clause)
    if isinstance(message, (RoomOutline, Composition)):
        return []  # the room's own parts, what groups hold: no relation
    return list(message.facts)


def introduced_by(message: Message) -> list[str]:
    """The entities a message introduces (first mentions), in order."""
    if isinstance(message, Inventory):
        found: list[str] = []
        for item in message.items:
            found += [item.junction, *item.paths] if isinstance(item, Network) else list(item)
        return found
    if isinstance(message, Introduction):
        return [s for unit in message.subjects for s in unit]
    return []


def plan_document(
    scene: Scene, world: World, first: dict[str, int] | None = None, *, summary: bool = False
) -> list[Section]:
    """The sections of the full description, in reading order: a group's paragraph
    before its siblings' when ``first`` puts it first (``World.owners``).

    ``summary``: the summary level (``summary``): big cohorts of groups get no paragraphs
    of their own but counts in their parent's, and a big cohort's relations to several
    things of one noun are told as one count.
    """
    networks = _network_links(scene, world)
    owners = world.owners(first)
    section_of_owner = {owner: index for index, owner in enumerate(owners)}
    pools: list[list[Relation]] = [[] for _ in owners]
    stated = stated_relations(scene, world)
    for relation in stated:
        # A room's parts are known from the start: only an entity end waits for its section.
        ends = [end for end in (relation.source, relation.target) if end in world]
        pools[max(section_of_owner[world[end].parent] for end in ends)].append(relation)
    if not summary:
        return [
            _section(owner, world.members(owner), pool, networks, world)
            for owner, pool in zip(owners, pools, strict=True)
        ]
    cohorts = summarised_groups(world)
    hidden = hidden_owners(world, cohorts)
    sections = []
    for owner, pool in zip(owners, pools, strict=True):
        if owner in hidden:
            continue  # told by the counts in its parent's paragraph, with what it holds
        counts, rest = quantified(pool, world)
        section = _section(owner, world.members(owner), rest, networks, world)
        extra: list[Message] = list(counts)
        for cohort in cohorts:
            if world[cohort[0]].parent == owner:
                extra += compositions(cohort, world)
                extra += patterns(cohort, stated, world)
        sections.append(Section(owner, section.messages + tuple(extra)))
    return sections


def stated_relations(scene: Scene, world: World) -> list[Relation]:
    """The relations the text may state: satisfied, describable, each said once."""
    selected: list[Relation] = []
    seen: set[tuple[str, str, str]] = set()
    for relation in scene.relations:
        if not relation.satisfied or not is_described(relation.label):
            continue
        if relation.source not in world or world.target_of(relation) is None:
            continue
        key = (relation.source, relation.label, relation.target)
        mirrored = (relation.target, relation.label, relation.source)
        if key in seen or (is_symmetric(relation.label) and mirrored in seen):
            continue
        seen.add(key)
        selected.append(relation)
    return selected


def _network_links(scene: Scene, world: World) -> dict[str, str]:
    """Path id -> the junction it starts at (in the same scope), for the network phrase.

    A path's ``start`` is structural (the layout attaches the path's end to the
    junction), so it always holds; a satisfied ``PathConnectedTo`` relation counts too.
    """
    starts = [(path.id, path.start) for path in scene.paths if path.start is not None]
    starts += [
        (r.source, r.target)
        for r in scene.relations
        if r.label in RELATIONS and RELATIONS[r.label].family == "structural" and r.satisfied
    ]
    links: dict[str, str] = {}
    for path, junction in starts:
        if path in links or path not in world or junction not in world:
            continue
        if (
            world[path].kind == "path"
            and world[junction].kind == "junction"
            and world[path].parent == world[junction].parent
        ):
            links[path] = junction
    return links


def _section(
    owner: str | None,
    members: list[Entity],
    pool: list[Relation],
    networks: dict[str, str],
    world: World,
) -> Section:
    remaining = list(pool)
    placements = _placements(members, remaining)
    for relation in placements.values():
        remaining.remove(relation)
    ground = [m for m in members if m.id not in placements]
    items = _inventory_items(ground, networks)
    link = None
    if len(items) == 2:
        items, link = _link(items, remaining)
    messages: list[Message] = []
    if items or owner is None:  # an empty scene still says so
        messages.append(Inventory(owner, items, link))
    if owner is None and world.room is not None:
        outline = RoomOutline(world.room.shape, tuple(world.room.opening_groups()))
        if outline.shape or outline.openings:
            messages.append(outline)
    messages += _introductions(placements, world)
    messages += aggregate(remaining, world)
    return Section(owner, tuple(messages))


def _placements(members: list[Entity], pool: list[Relation]) -> dict[str, Relation]:
    """Members that stand on a sibling, with the support relation that introduces them.

    Only chains that end on a member standing on the ground count (a cycle of support
    relations cannot hold, but a wrong input must not loop).
    """
    ids = {m.id for m in members}
    support: dict[str, Relation] = {}
    for relation in pool:
        if relation.source in ids and relation.target in ids and RELATIONS[relation.label].support:
            support.setdefault(relation.source, relation)
    grounded: dict[str, Relation] = {}
    changed = True
    while changed:
        changed = False
        for source, relation in support.items():
            if source not in grounded and (
                relation.target not in support or relation.target in grounded
            ):
                grounded[source] = relation
                changed = True
    return {m.id: grounded[m.id] for m in members if m.id in grounded}


def _inventory_items(ground: list[Entity], networks: dict[str, str]) -> tuple[Item, ...]:
    """Ground members as list items: networks at their junction, others counted by noun."""
    ids = {m.id for m in ground}
    paths_at: dict[str, list[str]] = {}
    for member in ground:
        junction = networks.get(member.id)
        if junction in ids:
            paths_at.setdefault(junction, []).append(member.id)
    items: list[Item] = []
    by_noun: dict[str, int] = {}
    for member in ground:
        if member.id in paths_at:
            items.append(Network(member.id, tuple(paths_at[member.id])))
        elif networks.get(member.id) in paths_at:
            continue  # told with its junction
        elif member.noun in by_noun:
            counted = items[by_noun[member.noun]]
            assert not isinstance(counted, Network)  # by_noun indexes counted entities only
            items[by_noun[member.noun]] = counted + (member.id,)
        else:
            by_noun[member.noun] = len(items)
            items.append((member.id,))
    return tuple(items)


def _link(items: tuple[Item, ...], pool: list[Relation]) -> tuple[tuple[Item, ...], Clause | None]:
    """Relate one of two inventory items to the other when all its entities share a place relation to it.

    Returns the items (subject item first) and the clause; the relations it folds in are
    taken out of ``pool`` so no statement repeats them.
    """
    for subjects, target in (items, items[::-1]):
        if isinstance(subjects, Network) or isinstance(target, Network) or len(target) != 1:
            continue
        for relation in pool:
            if relation.source != subjects[0] or relation.target != target[0]:
                continue
            if not place_phrases(relation.label, relation.chosen):
                continue  # only a place phrase can follow a noun: "a sign to the right of a table"
            shared = [_find(pool, s, relation.label, relation.chosen, target[0]) for s in subjects]
            found_all = [found for found in shared if found is not None]
            if len(found_all) == len(shared):
                for found in found_all:
                    pool.remove(found)
                return (subjects, target), Clause(relation.label, relation.chosen, target)
    return items, None


def _find(
    pool: list[Relation], source: str, label: str, chosen: str | None, target: str
) -> Relation | None:
    for relation in pool:
        if (relation.source, relation.label, relation.chosen, relation.target) == (
            source,
            label,
            chosen,
            target,
        ):
            return relation
    return None


def _introductions(placements: dict[str, Relation], world: World) -> list[Introduction]:
    """Introduce stacked members level by level, those sharing a relation to one target together."""
    introductions: list[Introduction] = []
    told: set[str] = set()
    pending = dict(placements)
    while pending:
        ready = {s: r for s, r in pending.items() if r.target not in pending}
        grouped: dict[tuple[str, str | None, str], list[str]] = {}
        for source, relation in ready.items():
            grouped.setdefault((relation.label, relation.chosen, relation.target), []).append(
                source
            )
        for (label, chosen, target), sources in grouped.items():
            introductions.append(
                Introduction(_by_noun(sources, world), Clause(label, chosen, (target,)))
            )
        told.update(ready)
        pending = {s: r for s, r in pending.items() if s not in told}
    return introductions


def _by_noun(ids: list[str], world: World) -> tuple[tuple[str, ...], ...]:
    groups: dict[str, tuple[str, ...]] = {}
    for entity_id in ids:
        noun = world[entity_id].noun
        groups[noun] = groups.get(noun, ()) + (entity_id,)
    return tuple(groups.values())


def aggregate(relations: list[Relation], world: World) -> list[Statement]:
    """Statements for relations: shared relations to one target joined, then shared subjects.

    "The mill and the street lamp are next to the first road."; "The chair is in front
    of the desk and faces it." Relations are joined by what they say, not by label, so
    one sentence never repeats another's predicate; and by what their object phrase
    names (``World.target_of``), so a wardrobe against the room's chosen north wall and
    one against that wall by name stand in one sentence. At most ``MAX_CLAUSES``
    clauses go in one sentence.
    """

    def named_target(relation: Relation) -> str:
        target = world.target_of(relation)
        assert target is not None  # the planner tells only relations whose object it can name
        return target

    by_target: dict[tuple[tuple[str, ...], str], list[Relation]] = {}
    for relation in relations:
        target = named_target(relation)
        words = relation_wordings(relation.label, relation.chosen, world.place_kind(target))
        by_target.setdefault((words, target), []).append(relation)
    shared_by: dict[tuple[str, ...], dict[tuple[str, ...], list[Relation]]] = {}
    for (words, _), found in by_target.items():
        subjects = tuple(
            sorted(dict.fromkeys(r.source for r in found), key=lambda s: world[s].order)
        )
        shared_by.setdefault(subjects, {}).setdefault(words, []).extend(found)
    statements: list[Statement] = []
    for subjects, by_words in shared_by.items():
        joined = list(by_words.values())
        for start in range(0, len(joined), MAX_CLAUSES):
            shared = joined[start : start + MAX_CLAUSES]
            clauses = tuple(
                Clause(
                    found[0].label,
                    found[0].chosen,
                    tuple(dict.fromkeys(named_target(r) for r in found)),
                )
                for found in shared
            )
            for index, piece in enumerate(_subject_pieces(subjects, world)):
                facts = _piece_facts(piece, clauses, shared, world)
                statements.append(Statement(piece, clauses, facts, also=index > 0))
    return statements


def _piece_facts(
    piece: tuple[str, ...], clauses: tuple[Clause, ...], shared: list[list[Relation]], world: World
) -> tuple[Fact, ...]:
    """The facts a statement about ``piece`` states: clause by clause, subject by subject,
    target by target. A fact keeps the relation's own target (``room`` for a wall the
    layout chose), whatever part of the room the words name."""
    facts: list[Fact] = []
    for clause, found in zip(clauses, shared, strict=True):
        told = [r for r in found if r.source in piece]
        told.sort(key=lambda r: (piece.index(r.source), clause.targets.index(world.target_of(r))))
        facts += [(r.source, r.label, r.target) for r in told]
    return tuple(facts)


def _subject_pieces(subjects: tuple[str, ...], world: World) -> list[tuple[str, ...]]:
    """Split a subject into pieces of at most ``MAX_CONJUNCTS`` phrases (one per cohort).

    Each piece names at most one part of a cohort: "two of the street lamps and two of
    the market stands" reads as if the counts went together.
    """
    chunks: dict[tuple[str, ...], tuple[str, ...]] = {}
    for subject in subjects:
        cohort = world.cohort(subject)
        chunks[cohort] = chunks.get(cohort, ()) + (subject,)
    pieces: list[list[tuple[str, ...]]] = [[]]
    for cohort, chunk in chunks.items():
        partial = 1 < len(chunk) < len(cohort)
        piece = pieces[-1]
        has_partial = any(1 < len(c) < len(world.cohort(c[0])) for c in piece)
        if len(piece) == MAX_CONJUNCTS or (partial and has_partial):
            pieces.append([])
        pieces[-1].append(chunk)
    return [tuple(s for chunk in piece for s in chunk) for piece in pieces]


def _clause_facts(subjects: tuple[str, ...], clause: Clause) -> list[Fact]:
    return [(s, clause.label, t) for s in subjects for t in clause.targets]
