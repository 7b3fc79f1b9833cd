"""The summary level: repeated things told by counts that hold, not one by one.

A scene with many things of one kind (a town of thirty-eight homes) gets a full text of
thousands of words, most of them the same paragraph again. The summary style keeps the
full text's shape (``plan``) but tells every *cohort* of at least ``SUMMARY_COHORT``
things (same noun, same parent) in aggregate:

- a cohort of groups is not given a paragraph per group. Its parent's paragraph says
  what the groups hold (``Composition``: "All four market stands have a table and a
  sign.", "One of the thirty-eight homes has an oak tree.", counted exactly: "a bush"
  is exactly one bush) and how their members stand to each other (``Pattern``: "In
  most of the thirty-eight homes, the flowerpot is in front of the house.");
- relations from a cohort's members to several different things of one noun are one
  statement (``Quantified``: "All thirty-eight homes are next to a road.").

Every such sentence carries a ``Claim``: which cohort it counts over, what must hold of
a member, and the quantifier, computed from the scene: "all" (every member), "most"
(more than half), "some" (at least two), "one of" (exactly one, for what the groups
hold). A relation claim counts the members with a satisfied relation of those words,
so it is a lower bound of what the geometry shows; its quantifiers are all lower
bounds too ("some" is never "only some"). ``tests/test_describer_e2e.py`` counts every
claim again from the scene, measuring the relations with the layout's own code.
"""

from __future__ import annotations

from dataclasses import dataclass

from scenewright.core.relations import RELATIONS, Relation

from .lexicon import relation_wordings
from .world import Entity, World

#: Cohorts of at least this many things are told in aggregate.
SUMMARY_COHORT = 4
#: At most this many sentences say what the groups of one cohort hold, and at most
#: ``MAX_PATTERNS`` how their members stand: the most common first.
MAX_COMPOSITIONS = 6
MAX_PATTERNS = 4

Fact = tuple[str, str, str]


@dataclass(frozen=True)
class Claim:
    """A count over ``members`` (a cohort's ids) that a sentence states with ``quantifier``.

    ``kind``: "has" (each counted group has exactly ``items``: (noun, how many) of its
    direct members), "is" (each counted member has a relation with ``words`` (``label``,
    ``chosen``) to an entity of ``target_noun``) or "in" (in each counted group, a member
    of ``subject_noun`` has such a relation to a member of ``target_noun``).
    ``holders``: the members it holds for, as the describer counted them.
    """

    kind: str
    quantifier: str
    members: tuple[str, ...]
    holders: tuple[str, ...]
    items: tuple[tuple[str, int], ...] = ()
    label: str = ""
    chosen: str | None = None
    subject_noun: str = ""
    target_noun: str = ""


@dataclass(frozen=True)
class Composition:
    """ "All four market stands have a table and a sign."."""

    claim: Claim


@dataclass(frozen=True)
class Pattern:
    """ "In most of the thirty-eight homes, the flowerpot is in front of the house."

    ``subject_definite`` / ``target_definite``: every counted group has exactly one
    member of that noun ("the house"), else "a bush"."""

    claim: Claim
    facts: tuple[Fact, ...]
    subject_definite: bool
    target_definite: bool
    targets: tuple[str, ...]  # the members of ``target_noun`` the counted relations reach


@dataclass(frozen=True)
class Quantified:
    """ "Most of the twelve street lamps are next to a road."."""

    claim: Claim
    facts: tuple[Fact, ...]
    targets: tuple[str, ...]


SummaryMessage = Composition | Pattern | Quantified


def quantifier(count: int, total: int, *, exact: bool) -> str | None:
    """ "all", "most", "some" or (``exact`` counts only) "one": the word for ``count`` of ``total``."""
    if count == total:
        return "all"
    if 2 * count > total:
        return "most"
    if count >= 2:
        return "some"
    return "one" if exact and count == 1 else None


def summarised_groups(world: World) -> list[tuple[str, ...]]:
    """The cohorts of groups told in aggregate (not inside another such group), in derivation order."""
    found: list[tuple[str, ...]] = []
    hidden: set[str] = set()
    for cohort in world.cohorts.values():
        first = world[cohort[0]]
        if (
            first.kind != "group"
            or len(cohort) < SUMMARY_COHORT
            or _has_ancestor_in(first, hidden, world)
        ):
            continue
        found.append(cohort)
        hidden.update(cohort)
    return found


def _has_ancestor_in(entity: Entity, ids: set[str], world: World) -> bool:
    parent = entity.parent
    while parent is not None:
        if parent in ids:
            return True
        parent = world[parent].parent
    return False


def hidden_owners(world: World, cohorts: list[tuple[str, ...]]) -> set[str]:
    """Every group inside a summarised cohort (its groups too): none gets a paragraph."""
    inside = {i for cohort in cohorts for i in cohort}
    return {
        owner
        for owner in world.entities
        if owner in inside or _has_ancestor_in(world[owner], inside, world)
    }


def compositions(cohort: tuple[str, ...], world: World) -> list[Composition]:
    """What the cohort's groups hold, items with the same holders joined, the most held first."""
    counts: dict[str, dict[str, int]] = {}
    for group in cohort:
        for member in world.members(group):
            counts.setdefault(member.noun, {}).setdefault(group, 0)
            counts[member.noun][group] += 1
    held: dict[tuple[str, int], tuple[str, ...]] = {}
    for noun, by_group in counts.items():
        for number in sorted(set(by_group.values())):
            held[(noun, number)] = tuple(g for g in cohort if by_group.get(g) == number)
    by_holders: dict[tuple[str, ...], list[tuple[str, int]]] = {}
    for item, holders in held.items():
        by_holders.setdefault(holders, []).append(item)
    ranked = sorted(by_holders.items(), key=lambda entry: -len(entry[0]))
    messages = []
    for holders, items in ranked[:MAX_COMPOSITIONS]:
        word = quantifier(len(holders), len(cohort), exact=True)
        assert word is not None  # an exact count of one or more has its word
        messages.append(Composition(Claim("has", word, cohort, holders, tuple(items))))
    return messages


def patterns(cohort: tuple[str, ...], relations: list[Relation], world: World) -> list[Pattern]:
    """How members of the cohort's groups stand to each other, the most common first.

    ``relations``: the relations the text may state (``plan.stated_relations``).
    """
    in_cohort = set(cohort)
    found: dict[tuple[str, tuple[str, ...], str], list[Relation]] = {}
    for relation in relations:
        if relation.target not in world or relation.source not in world:
            continue
        source, target = world[relation.source], world[relation.target]
        if source.parent not in in_cohort or target.parent != source.parent:
            continue
        words = relation_wordings(relation.label, relation.chosen)
        found.setdefault((source.noun, words, target.noun), []).append(relation)
    messages = []
    for (subject_noun, _, target_noun), told in found.items():
        holders = tuple(g for g in cohort if any(world[r.source].parent == g for r in told))
        word = quantifier(len(holders), len(cohort), exact=False)
        if word is None:
            continue
        claim = Claim(
            "in",
            word,
            cohort,
            holders,
            label=told[0].label,
            chosen=told[0].chosen,
            subject_noun=subject_noun,
            target_noun=target_noun,
        )
        messages.append(
            Pattern(
                claim,
                tuple((r.source, r.label, r.target) for r in told),
                _one_each(holders, subject_noun, world),
                _one_each(holders, target_noun, world),
                tuple(dict.fromkeys(r.target for r in told)),
            )
        )
    messages.sort(key=lambda m: -len(m.claim.holders))
    return messages[:MAX_PATTERNS]


def _one_each(groups: tuple[str, ...], noun: str, world: World) -> bool:
    return all(sum(m.noun == noun for m in world.members(g)) == 1 for g in groups)


def quantified(relations: list[Relation], world: World) -> tuple[list[Quantified], list[Relation]]:
    """Relations from a big cohort's members to several things of one noun, as counts;
    and the relations left to tell one by one.

    Only relations to entities count (a room's parts keep their own names), and only
    when at least two members relate to at least two different things: "The four market
    stands are next to the well." is as short as any count.
    """
    found: dict[tuple[tuple[str, ...], tuple[str, ...], str], list[Relation]] = {}
    for relation in relations:
        if relation.target not in world or len(world.cohort(relation.source)) < SUMMARY_COHORT:
            continue
        if RELATIONS[relation.label].support:
            continue  # it introduces what stands on something ("Two books are on this table.")
        words = relation_wordings(relation.label, relation.chosen)
        key = (world.cohort(relation.source), words, world[relation.target].noun)
        found.setdefault(key, []).append(relation)
    messages: list[Quantified] = []
    told: set[int] = set()
    for (cohort, _, target_noun), group in found.items():
        holders = tuple(m for m in cohort if any(r.source == m for r in group))
        targets = tuple(dict.fromkeys(r.target for r in group))
        if len(holders) < 2 or len(targets) < 2:
            continue
        word = quantifier(len(holders), len(cohort), exact=False)
        assert word is not None  # two holders or more have their word
        claim = Claim(
            "is",
            word,
            cohort,
            holders,
            label=group[0].label,
            chosen=group[0].chosen,
            target_noun=target_noun,
        )
        messages.append(
            Quantified(claim, tuple((r.source, r.label, r.target) for r in group), targets)
        )
        told.update(id(r) for r in group)
    return messages, [r for r in relations if id(r) not in told]
