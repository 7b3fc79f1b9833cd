"""Which members of a group take their places together: a lamp on the armchair's left
whenever the side table is on its right.

Each member of a group is placed relative to its parent by weighted alternatives, one
per placement (``induce.placements_of``), drawn for each member on its own. When the
examples chose two members' placements together (the lamp and the side table always
on opposite sides of the armchair), drawing them apart loses that: in a third to a
half of the scenes made, the two stood on one side. ``sides_together(group, seed)``
finds such members and gives the group (or the member below which they stand) a
``Joint`` for each set of them, which ``rules_text`` writes as one production of
weighted alternatives over the set: each alternative a way the examples placed them
all, weighted by how many parent objects stood so.

**Which members.** Below a parent type P (the anchor, or a member): P's members, and
the members of those of them of which every P object had exactly one (``Member.single``),
and so on down. So the waste bin placed by a filing cabinet, placed by the desk, is
tested against the cabinet's side of the desk and against the desk's other members.
Of those, a member with at least two placements with a label that says where it
stands (``NextTo...``, ``OnTopOf...``: a placement that only says which way a plant
faces has no side), and at most one object per parent object (a lamp by each armchair,
not books on a shelf). A parent object whose member stood in a placement with no side
is left out of the test (it tells nothing of the sides chosen); a joint holds that
placement as one of its ways. Each is read per P object (its
placement where it is, ``Member.chosen``, followed down through ``Member.objects``).

**The test.** For two such members, the P objects holding one of each, each in a
placement, give a contingency table (placement of the first x placement of the
second). Its statistic is the likelihood-ratio G = 2 sum O log(O N / (row x column)),
twice N times the mutual information of the two placements: 0 when the table is the
product of its margins. Under independence every relabelling of the second member's
placements among the P objects is as likely as the one seen, so the p-value is the
share of ``PERMUTATIONS`` random relabellings (each keeping both margins), with the one
seen, whose G is at least the seen one's. The two are *coupled* when p <= ``ALPHA``.
The permutations come from the pair's own stream (the ``relations`` stage, child keyed
by the names: ``relation_poses.pair_stream``), so a verdict depends on its table and
the seed alone. A pair is tested below the lowest parent both are read from.

This is Fisher's exact test done by sampling: nine armchairs with the lamp on the left
of six and the side table always on the other side give p = 1 / C(9, 3) = 1/84 = 0.012;
with three, the smallest p any table can reach is 1/3. Where no relabelling of the
pair's parent objects could reach ``ALPHA`` (the share of relabellings as extreme as the
most extreme one is above it: three examples, five split three to two, six split three
to three), the test cannot tell and the examples are all there is: a pair whose table
shows any association (G > 0) is coupled, so their ways are the examples' own.

**Joints.** Coupled pairs are joined into connected sets, each placed by the lowest
parent type all its members are read from. A set's ways are the combinations of
placements its parent objects showed, those holding one of each, placed; a set where
some member's placement occurs in none of them (seen only where another member was
missing) is left apart, since the joint could not make it. Each way is weighted by the
parent objects that stood so. A member there in no placement (a plant too far from
the cabinet for any label) is a way of its own, in which the rules draw its placement
on its own, as without the joint; a parent object missing some of the members counts
among the ways that agree with the rest of it, shared as those ways' own counts are,
so that each member's placements keep their shares: whether a member is there at all
(its count, ``0.8?``) stays its own draw.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence

import networkx as nx
import numpy as np

from .induction import Group, Joint, Member, SideTest
from .pose_labels import CATEGORIES
from .relation_poses import pair_stream

#: The level of the test: the share of independent pairs it couples by chance.
ALPHA = 0.05
#: Random relabellings of the test (p resolved to 1 / (PERMUTATIONS + 1)).
PERMUTATIONS = 1999
#: A member's placement by a parent object that holds none of it (-1: it is there, in
#: no placement).
ABSENT = -2


def g_statistic(first: np.ndarray, second: np.ndarray) -> float:
    """G = 2 sum O log(O N / (row x column)) of the table of the labels ``first`` and
    ``second`` (each (n,) small whole numbers)."""
    n = len(first)
    if n == 0:
        return 0.0
    rows, cols = int(first.max()) + 1, int(second.max()) + 1
    table = np.bincount(first * cols + second, minlength=rows * cols).reshape(rows, cols)
    return _g_of(table, n)


def _g_of(table: np.ndarray, n: int) -> float:
    expected = np.outer(table.sum(axis=1), table.sum(axis=0)) / n
    seen = table > 0
    return float(2.0 * np.sum(table[seen] * np.log(table[seen] / expected[seen])))


def association(
    first: np.ndarray, second: np.ndarray, rng: np.random.Generator
) -> tuple[float, float]:
    """(G, p) of the labels ``first`` and ``second`` (module docstring); p 1 when either
    takes one value only."""
    if len(first) < 2 or len(set(first.tolist())) < 2 or len(set(second.tolist())) < 2:
        return 0.0, 1.0
    seen = g_statistic(first, second)
    n = len(first)
    cols = int(second.max()) + 1
    size = (int(first.max()) + 1) * cols
    shuffled = np.argsort(rng.random((PERMUTATIONS, n)), axis=1)
    cells = first[None, :] * cols + second[shuffled]
    at_least = 0
    for row in cells:
        table = np.bincount(row, minlength=size).reshape(-1, cols)
        at_least += _g_of(table, n) >= seen - 1e-9
    return seen, (1 + at_least) / (PERMUTATIONS + 1)


#: Tables with at most this many relabellings are searched whole for the smallest
#: p-value they allow (more always allow one below ALPHA).
SEARCHED = 400


def _smallest_p(first: np.ndarray, second: np.ndarray) -> float:
    """The smallest p-value any relabelling of ``second`` against ``first`` can reach: the
    share of relabellings as extreme as the most extreme one (its mirror images count:
    three to three always opposite gives 2/20, not 1/20)."""
    counts = Counter(second.tolist())
    arrangements = math.factorial(len(second))
    for count in counts.values():
        arrangements //= math.factorial(count)
    if arrangements > SEARCHED:
        return 0.0
    statistics = [
        g_statistic(first, np.array(labels, dtype=int)) for labels in _relabellings(counts)
    ]
    top = max(statistics)
    return sum(g >= top - 1e-9 for g in statistics) / len(statistics)


def _relabellings(counts: Counter) -> list[tuple[int, ...]]:
    """Every distinct sequence of the labels with these counts."""
    if not +counts:
        return [()]
    out = []
    for label in sorted(counts):
        if counts[label]:
            rest = counts.copy()
            rest[label] -= 1
            out += [(label, *tail) for tail in _relabellings(rest)]
    return out


#: The labels that say where a thing stands by its parent (not only which way it faces).
PLACES = frozenset(CATEGORIES["near"] + CATEGORIES["support"])


def _sided(member: Member) -> set[int]:
    """The placements of ``member`` that say where it stands (``PLACES``)."""
    return {k for k, placement in enumerate(member.placements) if PLACES & set(placement.labels)}


def _eligible(member: Member) -> bool:
    """At least two placements saying where it stands, and at most one object by each
    parent object."""
    return len(_sided(member)) >= 2 and max(member.per_parent, default=0) <= 1


Path = tuple[Member, ...]


def _read_below(members: Sequence[Member], path: Path = ()) -> list[Path]:
    """The paths (from one of ``members`` down) to every member read per object of
    their parent type: the members, and below each member that is always one, its own."""
    found: list[Path] = []
    for member in members:
        here = (*path, member)
        found.append(here)
        if member.single:
            found += _read_below(member.children, here)
    return found


def _per_root(path: Path) -> dict[tuple[int, str], int]:
    """Root object (scene index, id) -> the placement of the last member of ``path``
    by it (-1: in no placement)."""
    *above, last = path
    found = {}
    for root, key in (path[0].objects if above else last.objects).items():
        for member in above[1:]:
            key = member.objects.get(key)  # type: ignore[assignment]
            if key is None:
                break
        else:
            index = last.chosen.get(key) if above else last.chosen.get(root)
            if index is not None:
                found[root] = index
    return found


def _tops(root_members: Sequence[Member], chosen: set[int]) -> tuple[Member, ...]:
    """The members of the root that are among ``chosen`` (``id``s) or stand above one."""

    def holds(member: Member) -> bool:
        return id(member) in chosen or any(holds(child) for child in member.children)

    return tuple(member for member in root_members if holds(member))


def sides_together(group: Group, seed: int) -> None:
    """Test, below the anchor of ``group`` and below each of its members, the
    placements of every two members read per parent object, and give each parent (the
    group, or the member) its tests and the joints of coupled members it places
    (module docstring)."""
    graph = nx.Graph()
    tested: set[tuple[int, int]] = set()
    parents: list[tuple[Group | Member, str, list[Member], list[Path]]] = []
    order: dict[int, int] = {}

    def visit(owner: Group | Member, root: str, members: list[Member]) -> None:
        for member in members:
            order.setdefault(id(member), len(order))
            visit(member, member.type, member.children)
        paths = [path for path in _read_below(members) if _eligible(path[-1])]
        owner.side_tests = []
        for i, first in enumerate(paths):
            for second in paths[i + 1 :]:
                key = (id(first[-1]), id(second[-1]))
                if key in tested:
                    continue
                tested.add(key)
                a_map, b_map = _per_root(first), _per_root(second)
                x, y = first[-1], second[-1]
                # Only where both stand in a placement that says where: a plant that stood
                # by no side of its waste bin tells nothing of the sides they chose.
                a_sided, b_sided = _sided(x), _sided(y)
                hosts = sorted(
                    h
                    for h in a_map.keys() & b_map.keys()
                    if a_map[h] in a_sided and b_map[h] in b_sided
                )
                rng = pair_stream(seed, "sides", root, x.parent, x.type, y.parent, y.type)
                # Too few parent objects for any table to reach ALPHA (three examples:
                # p >= 1/3): what the examples did together is all there is to go by,
                # so any association they show is kept rather than drawn apart.
                first_labels = np.array([a_map[h] for h in hosts], dtype=int)
                second_labels = np.array([b_map[h] for h in hosts], dtype=int)
                statistic, p_value = association(first_labels, second_labels, rng)
                coupled = p_value <= ALPHA or (
                    statistic > 1e-9 and _smallest_p(first_labels, second_labels) > ALPHA
                )
                owner.side_tests.append(
                    SideTest(
                        (x.type, x.parent),
                        (y.type, y.parent),
                        len(hosts),
                        statistic,
                        p_value,
                        coupled,
                    )
                )
                if coupled:
                    graph.add_edge(order[id(x)], order[id(y)], p_value=p_value)
        parents.append((owner, root, members, paths))

    order[id(group)] = -1
    visit(group, group.anchor, group.members)
    components = sorted(sorted(c) for c in nx.connected_components(graph))
    placed: set[int] = set()
    for owner, root, members, paths in parents:  # the lowest parents first
        by_number = {order[id(path[-1])]: path for path in paths}
        owner.joints = []
        for number_, component in enumerate(components):
            if number_ in placed or not set(component) <= set(by_number):
                continue
            placed.add(number_)
            chosen = [by_number[k] for k in component]
            maps = [_per_root(path) for path in chosen]
            hosts = sorted(set().union(*maps))
            # Per root object, each member's placement: -1 in none, -2 not there.
            seen = [tuple(m.get(h, ABSENT) for m in maps) for h in hosts]
            ways = Counter(way for way in seen if min(way) > ABSENT)
            if not all(
                {way[k] for way in ways} >= set(range(len(path[-1].placements)))
                for k, path in enumerate(chosen)
            ):
                continue
            weights = {way: float(count) for way, count in ways.items()}
            counted = sum(ways.values())
            for partial in seen:
                if min(partial) > ABSENT:
                    continue
                fits = [
                    w for w in ways if all(v == ABSENT or w[k] == v for k, v in enumerate(partial))
                ]
                if fits:  # shared among the ways it fits, as those ways' own counts are
                    total = sum(ways[w] for w in fits)
                    for w in fits:
                        weights[w] += ways[w] / total
                    counted += 1
            joint_members = tuple(path[-1] for path in chosen)
            owner.joints.append(
                Joint(
                    root,
                    joint_members,
                    _tops(members, {id(m) for m in joint_members}),
                    tuple(sorted(weights.items(), key=lambda item: (-item[1], item[0]))),
                    counted,
                    sum(count for way, count in ways.items() if min(way) >= 0),
                    counted - sum(ways.values()),
                    max(p for _, _, p in graph.subgraph(component).edges(data="p_value")),
                )
            )
