"""The records of an induction: what ``induce`` found in the examples and
``rules_text`` writes as a rule set. ``Induction`` holds the catalog (``TypeEntry``, its
styles ``StyleStats``), the groups (``Group``, their tree of ``Member``s, each with its
pose ``Cluster``s and written ``Placement``s), the loose types (``Loose``) and how often
each type stood against a wall (``WallShare``); ``Induction.to_dict()`` is the report
``scenewright learn`` writes beside the rules.
"""

from __future__ import annotations

import statistics
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field

from scenewright.core.room import Room
from scenewright.generator.layout.relation_terms import WALL_TOLERANCE

from .pose_labels import (
    CATEGORIES,
    HAND_GAP,
)
from .relation_results import RelationsResult
from .rule_names import colour_text

#: A wall label is written for a type when it holds for at least this share of its objects:
#: more than half, since a label written is drawn independently of where the rest stands
#: (a sofa against a wall in 61 % of living rooms, always put there, left no room for the
#: TV stand that stood within 2 m in front of it when it was not).
WALL_SHARE = 0.75
#: A member's placement gets the wall label held by more than this share of its own
#: objects (``Placement.wall``): within one way of standing by the parent, the majority
#: is the nearest the examples' share that a label written or not can come.
PLACEMENT_WALL_SHARE = 0.5
#: A type's wall label drawn with its share (``WallShare.drawn``: a type related to no
#: other, a group's anchor) is the first held for at least this share of its objects,
#: else AgainstWall where any stood at a wall (a corner is against a wall too).
WALL_DRAW_SHARE = 0.25
#: The most ``wall_gap`` written (metres): a wall label holds within WALL_TOLERANCE of
#: the gap, and an object is measured at a wall within HAND_GAP of it, so an object
#: kept further out would, laid out a little further still, no longer read as at the wall.
MOST_WALL_GAP = HAND_GAP - WALL_TOLERANCE


# -- the catalog ----------------------------------------------------------------------


@dataclass(frozen=True)
class StyleStats:
    """One style of a type: how many objects had it, and its looks where they differ
    from the type's (None where they do not)."""

    name: str
    source: str | None  # the style as the examples name it (None: no style given)
    count: int
    size: tuple[float, float, float] | None = None
    noun: str | None = None
    shape: str | None = None
    colour: tuple[float, ...] | None = None


@dataclass(frozen=True)
class TypeEntry:
    """One type of the induced catalog (``induce``'s module docstring, step 1)."""

    name: str
    sources: tuple[str, ...]
    objects: int
    scenes: int
    size: tuple[float, float, float]
    noun: str
    plural: str | None
    shape: str | None
    colour: tuple[float, ...]
    styles: tuple[StyleStats, ...]
    borrowed: str | None = None

    def to_dict(self) -> dict:
        return {
            "type": self.name,
            "seen_as": list(self.sources),
            "objects": self.objects,
            "scenes": self.scenes,
            "size": [round(v, 4) for v in self.size],
            "noun": self.noun,
            "plural": self.plural,
            "shape": self.shape,
            "colour": colour_text(self.colour),
            "looks_from": self.borrowed or "examples",
            "styles": [
                {
                    "style": s.name,
                    "seen_as": s.source,
                    "objects": s.count,
                    "weight": s.count,
                    **({"size": [round(v, 4) for v in s.size]} if s.size else {}),
                }
                for s in self.styles
            ],
        }


# -- placements -----------------------------------------------------------------------


@dataclass(frozen=True)
class Cluster:
    """One cluster of relative poses: its size, its centre pose (x, z, turn in
    degrees), whether it rests on the parent, and the labels that hold there (empty
    when no label of the vocabulary does)."""

    size: int
    centre: tuple[float, float, float]
    resting: bool
    labels: tuple[str, ...]

    def to_dict(self) -> dict:
        return {
            "size": self.size,
            "centre": [round(v, 3) for v in self.centre],
            "rests_on_parent": self.resting,
            "labels": list(self.labels),
        }


@dataclass(frozen=True)
class Placement:
    """One way a child stands by its parent: the labels written and how many objects
    (the clusters' members) stood that way; ``wall``: the wall label held by more than
    ``PLACEMENT_WALL_SHARE`` of those objects (a lamp flush with the wall beside the
    armchair, and none for the lamps standing out in the room), else ``AgainstWall``
    where it held for any of them, else None; ``wall_share``: the share of them it
    held for (0 with no label), which ``rules_text`` writes as a draw between the label
    and kept off the walls where it is under 1 (a lamp at the wall in 7 of 9 corners,
    the others a few centimetres further out)."""

    labels: tuple[str, ...]
    weight: int
    wall: str | None = None
    wall_share: float = 1.0


@dataclass(frozen=True)
class SideTest:
    """Two members below one parent (``sides_together``) tested for placements chosen
    together: over the ``parents`` objects of that parent type holding one of each,
    placed, whether the placement of one tells the other's (the test's ``statistic``
    and ``p_value``). Each member is named by its type and what places it."""

    first: tuple[str, str]  # (type, placed by)
    second: tuple[str, str]
    parents: int
    statistic: float
    p_value: float
    coupled: bool

    def to_dict(self) -> dict:
        return {
            "types": [self.first[0], self.second[0]],
            "placed_by": [self.first[1], self.second[1]],
            "parent_objects": self.parents,
            "statistic": round(self.statistic, 4),
            "p_value": round(self.p_value, 4),
            "together": self.coupled,
        }


@dataclass
class Joint:
    """Members below one parent type (``root``) whose placements are drawn together:
    ``members`` (in the order of the tree) and ``ways``, each a placement index per
    member (into its ``placements``) with its weight, the ``root`` objects that stood
    that way (``sides_together``: those missing a member shared among the ways they
    fit), most first; ``tops``: the root's own members that are members of the joint
    or stand above one (a filing cabinet whose waste bin is); ``parents``: the root
    objects counted, ``complete`` of them holding one of each, placed, and ``missing``
    of them missing some member (shared among the ways they fit; the rest hold a member
    in no placement); ``p_value``: the largest p of the coupled pairs that join it."""

    root: str
    members: tuple[Member, ...]
    tops: tuple[Member, ...]
    ways: tuple[tuple[tuple[int, ...], float], ...]
    parents: int
    complete: int
    missing: int
    p_value: float

    @property
    def types(self) -> tuple[str, ...]:
        return tuple(member.type for member in self.members)

    def to_dict(self) -> dict:
        return {
            "types": list(self.types),
            "placed_by": [member.parent for member in self.members],
            "parent_objects": self.parents,
            "holding_each": self.complete,
            "missing_some": self.missing,
            "p_value": round(self.p_value, 4),
            "ways": [
                {
                    "placements": [
                        list(member.placements[k].labels)
                        for member, k in zip(self.members, way, strict=True)
                    ],
                    "parent_objects": round(count, 3),
                }
                for way, count in self.ways
            ],
        }


def sides_report(tests: list[SideTest], joints: list[Joint]) -> dict:
    """The report of the side tests below one parent and of the joints placed there."""
    return {
        "tests": [test.to_dict() for test in tests],
        "together": [joint.to_dict() for joint in joints],
    }


# -- the model of the induced rules --------------------------------------------------------


@dataclass
class Member:
    """A child type placed relative to its parent type in a group (a tree edge)."""

    type: str
    parent: str
    instances: int
    per_parent: Counter
    placements: list[Placement]
    clusters: list[Cluster]
    outliers: int
    wall: str | None
    children: list[Member] = field(default_factory=list)
    #: It rests on its parent (only the objects resting on one are its members).
    carried: bool = False
    #: The side tests of the members below it and the joints placed by it.
    side_tests: list[SideTest] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    #: (scene index, parent object id) -> the placement index of its one object of this
    #: type there (-1: in no placement), and that object's (scene index, id); parent
    #: objects with several are left out.
    chosen: dict[tuple[int, str], int] = field(default_factory=dict, repr=False, compare=False)
    objects: dict[tuple[int, str], tuple[int, str]] = field(
        default_factory=dict, repr=False, compare=False
    )

    @property
    def single(self) -> bool:
        """Exactly one object by every parent object."""
        return set(self.per_parent) == {1}

    @property
    def parents(self) -> int:
        return sum(self.per_parent.values())

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "parent": self.parent,
            "objects": self.instances,
            "parent_objects": self.parents,
            "children_per_parent": {str(k): v for k, v in sorted(self.per_parent.items())},
            "placements": [
                {
                    "labels": list(p.labels),
                    "objects": p.weight,
                    "wall": p.wall,
                    **({"wall_share": round(p.wall_share, 3)} if p.wall else {}),
                }
                for p in self.placements
            ],
            "clusters": [c.to_dict() for c in self.clusters],
            "outliers": self.outliers,
            "wall": self.wall,
            "rests_on_parent": self.carried,
            "children": [child.to_dict() for child in self.children],
            "children_sides": sides_report(self.side_tests, self.joints),
        }


@dataclass
class Group:
    """A connected component of related types: a production named ``rule``."""

    rule: str
    anchor: str
    per_scene: Counter
    wall: str | None
    members: list[Member]
    types: list[str]
    unwritten: list[tuple[str, str]]
    #: The side tests of the members below the anchor and the joints placed by it.
    side_tests: list[SideTest] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {
            "rule": self.rule,
            "anchor": self.anchor,
            "types": self.types,
            "anchors_per_scene": {str(k): v for k, v in sorted(self.per_scene.items())},
            "wall": self.wall,
            "members": [member.to_dict() for member in self.members],
            "members_sides": sides_report(self.side_tests, self.joints),
            "related_but_placed_through_the_tree": [list(pair) for pair in self.unwritten],
        }


@dataclass
class Loose:
    """A type made at the top level, counted per scene: related to no other type, a
    child seen in scenes without its parent type (``without``), or objects of a type
    that usually rests on others resting on none of them (``unsupported``)."""

    type: str
    per_scene: Counter
    wall: str | None
    without: str | None = None
    #: ``without`` names what it usually rests on (it was seen resting on none of them).
    unsupported: bool = False
    #: For a child seen without its parent: the group member it is elsewhere, whose own
    #: members it brings (``rules_text``).
    member: Member | None = field(default=None, repr=False, compare=False)
    #: The share of its objects ``wall`` held for: a type related to no other is put at
    #: the wall by a draw of it where it is under 1 (``WallShare.drawn``, ``rules_text``).
    wall_share: float = 1.0

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "per_scene": {str(k): v for k, v in sorted(self.per_scene.items())},
            "wall": self.wall,
            **({"wall_share": round(self.wall_share, 3)} if self.wall else {}),
            "seen_without": None if self.unsupported else self.without,
            "seen_resting_on_none_of": self.without.split(" or ") if self.unsupported else None,
        }


@dataclass
class WallShare:
    """How many standing objects of a type were measured against walls, per label how
    many it held for, and the gaps their placers left to the wall where one held
    (``pose_labels.hand_gap``)."""

    objects: int = 0
    held: Counter = field(default_factory=Counter)
    gaps: list[float] = field(default_factory=list)

    def drawn(self) -> tuple[str, float] | None:
        """The wall label a type standing by no parent (related to no other, a group's
        anchor) is given, with the share of its objects it held for, written as a draw
        of that share where under 1: ``label()`` where it is written, else the first held
        for at least ``WALL_DRAW_SHARE``, else AgainstWall where it held for any (a coat
        stand in the corner in 7 of 12 halls is put there in about 7 of 12 scenes, not in
        every one, nor left to stand where the layout puts it); None if none held."""
        if not self.objects:
            return None
        firm = self.label()
        for label in (firm,) if firm else CATEGORIES["wall"]:
            share = self.held[label] / self.objects
            if firm or share >= WALL_DRAW_SHARE:
                return label, share
        if self.held["AgainstWall"]:
            return "AgainstWall", self.held["AgainstWall"] / self.objects
        return None

    def kept_off(self) -> bool:
        """Whether none of the type's standing objects stood at a wall (it had some)."""
        return self.objects > 0 and not any(self.held[label] for label in CATEGORIES["wall"])

    def gap(self) -> float | None:
        """The gap the type keeps to a wall it stands against: the median of ``gaps``
        to the centimetre (robust to the odd one pushed flush or set further out), at
        most ``MOST_WALL_GAP``; None when it rounds to nothing (flush) or none held."""
        median = self.median_gap()
        if median is None:
            return None
        kept = round(min(median, MOST_WALL_GAP), 2)
        return kept if kept > 0.0 else None

    def median_gap(self) -> float | None:
        """The median of ``gaps`` (None: none)."""
        return statistics.median(self.gaps) if self.gaps else None

    def label(self) -> str | None:
        for label in CATEGORIES["wall"]:
            if self.objects and self.held[label] >= WALL_SHARE * self.objects:
                return label
        return None


@dataclass
class Induction:
    """Everything ``learn`` induced from the examples (``induce``'s module docstring)."""

    name: str
    examples: list[str]
    seed: int
    relations: RelationsResult
    resting: set[tuple[str, str]]
    resting_counts: dict[tuple[str, str], tuple[int, int]]
    routes: dict[tuple[str, str], tuple[str, str] | None]
    catalog: dict[str, TypeEntry]
    groups: list[Group]
    loose: list[Loose]
    walls: dict[str, WallShare]
    room: Room | None
    room_source: str | None
    extent: tuple[float, float]
    ground: str
    scenes: int

    def members(self) -> Iterator[Member]:
        """Every member of every group, each before its children."""

        def walk(member: Member) -> Iterator[Member]:
            yield member
            for child in member.children:
                yield from walk(child)

        for group in self.groups:
            for member in group.members:
                yield from walk(member)

    def walled_types(self) -> set[str]:
        """The types the rules put against a wall somewhere (a group's anchor, a loose
        type, a member or one of its placements): those whose ``wall_gap`` is written."""
        found = {g.anchor for g in self.groups if g.wall}
        found |= {item.type for item in self.loose if item.wall}
        found |= {m.type for m in self.members() if m.wall or any(p.wall for p in m.placements)}
        return found

    def written_pairs(self) -> dict[tuple[str, str], Member]:
        """(a, b) in name order -> the member that writes the relation of that pair."""
        return {tuple(sorted((m.parent, m.type))): m for m in self.members()}

    def pairs_report(self) -> list[dict]:
        written = self.written_pairs()
        rows = []
        for pair in self.relations.pairs:
            key = (pair.a, pair.b)
            member = written.get(key)
            supported = [
                (u, v) for u, v in ((pair.a, pair.b), (pair.b, pair.a)) if (u, v) in self.resting
            ]
            row = {
                **pair.to_dict(),
                "support": [
                    {
                        "upper": u,
                        "lower": v,
                        "scenes": self.resting_counts[(u, v)][0],
                        "scenes_holding_both": self.resting_counts[(u, v)][1],
                    }
                    for u, v in supported
                ],
                "written": member is not None,
            }
            if member is not None:
                row["parent"], row["child"] = member.parent, member.type
                row["labels"] = [
                    {"labels": list(p.labels), "objects": p.weight} for p in member.placements
                ]
                row["clusters"] = [c.to_dict() for c in member.clusters]
                row["outliers"] = member.outliers
            elif pair.a == pair.b and pair.related:
                row["why_not_written"] = "two objects of one type: not written as a relation"
            elif pair.related and self.routes.get(key) is None:
                row["why_not_written"] = "both rest on one thing, which places them"
            elif pair.related and self.routes[key] != key:
                first, second = self.routes[key]
                row["why_not_written"] = (
                    f"written between {first} and {second}: what rests on a thing is placed by it"
                )
            elif pair.related:
                row["why_not_written"] = "its types are placed through other members of their group"
            rows.append(row)
        return rows

    def to_dict(self) -> dict:
        return {
            "rules": self.name,
            "examples": self.examples,
            "seed": self.seed,
            "relations": {
                key: value for key, value in self.relations.to_dict().items() if key != "pairs"
            },
            "pairs": self.pairs_report(),
            "catalog": [entry.to_dict() for entry in self.catalog.values()],
            "groups": [group.to_dict() for group in self.groups],
            "loose": [item.to_dict() for item in self.loose],
            "walls": {
                name: {
                    "objects": share.objects,
                    **{label: share.held[label] for label in CATEGORIES["wall"]},
                    "written": share.label(),
                    "gap": share.gap(),
                }
                for name, share in sorted(self.walls.items())
            },
            "room": self.room.to_dict() if self.room else None,
            "room_from": self.room_source,
            "extent": [round(v, 3) for v in self.extent],
        }
