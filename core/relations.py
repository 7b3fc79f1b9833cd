"""The relation registry: one record per edge label, and the one relation type.

Every edge of a scene graph carries one label of this registry. A label's record says
everything the stages need to know about it, so no stage routes on label spellings:

- ``family``: which geometry it asks for (``next_to``, ``support``, ``facing``,
  ``wall``, ``clearance``, ``alignment``, ``structural``). The layout implements one energy term, measurement (satisfied or
  not, and the complaint when not) and data-driven proposer per family, and refuses at
  import a family it does not implement; a label's parameters below steer them.
- next-to parameters: ``directions`` (name -> unit vector (x, z)) in ``frame``
  ``"world"`` (compass words) or ``"target"`` (B's own sides). No direction: plain
  next to. Several: the layout chooses whichever fits and records it as ``chosen``.
- support parameters: ``placement`` (``anywhere``, ``middle``, ``edge``,
  ``front_edge``); support labels rest A on B (A's height follows B's top).
- facing parameters: ``facing`` (``towards``, ``away``, ``same``, ``orthogonal``,
  ``opposite``).
- wall parameters: ``wall`` (``against``: A's back to a wall; ``corner``: against a
  wall with one side against the next; ``under_window`` / ``beside_window``: against a
  window's wall, under it or next to it). B is a wall or a window, or the room (the
  layout then chooses the wall or window that fits and records it as ``chosen``).
  ``reach``: the largest gap (metres) between A and B at which the label holds; None
  for the layout's general next-to distance (2 m, the paper's). ``seat``: A is a seat
  used at B's side (a chair at a desk): it also faces B, square to that side.
  ``direction_wordings``: the words of each direction a label that chooses may take
  (default ``DIRECTION_WORDINGS``; the close ``Beside`` says "just to the left of", its
  own words, so a reader can tell it from the 2 m ``NextToChooseSide``).
- ``clearance``: A's footprint kept off a wall (B a wall, or the room: every wall);
  no parameters. With the wall labels, the labels whose B is the room or a part of it
  (``by_room``).
- ``alignment``: A parallel to B with one face flush (no parameters).
- ``phrase``: how the layout report names it ("north of"); ``wordings``: the verb
  phrases the describer may use (canonical first); ``place``: the wording says where A
  is, so the describer may invert it ("On top of it is a pot."); ``symmetric``: A-B is
  B-A, stated once.
- ``implicitable``: the label has an ``Implicit`` form, which constrains the layout
  but is never described. ``registry[name]`` looks up either form.

Labels are the vocabulary of Table 1 of the paper. ``register`` adds one (a later
capability's label, or a test's) and checks it is complete; looking up a label that is
not registered raises ``UnknownLabel`` at once, never falls through to some default.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field, replace

#: The families a label may belong to. The layout implements each one.
FAMILIES = ("next_to", "support", "facing", "wall", "clearance", "alignment", "structural")

IMPLICIT_PREFIX = "Implicit"

#: How a wall label places A: its back against a wall, in a corner, under or beside a window.
WALL_PLACEMENTS = ("against", "corner", "under_window", "beside_window")

#: World directions (x, z): north is -Z, east +X.
COMPASS: dict[str, tuple[float, float]] = {
    "north": (0.0, -1.0),
    "east": (1.0, 0.0),
    "south": (0.0, 1.0),
    "west": (-1.0, 0.0),
}

#: An object's own sides in its local frame (x, z): left is local +X, front local +Z.
SIDES: dict[str, tuple[float, float]] = {
    "left": (1.0, 0.0),
    "right": (-1.0, 0.0),
    "front": (0.0, 1.0),
    "behind": (0.0, -1.0),
}

#: How the describer words each direction a next-to label can name ("is north of").
DIRECTION_WORDINGS: dict[str, tuple[str, ...]] = {
    **{d: (f"is {d} of", f"is on the {d} side of") for d in COMPASS},
    "left": ("is to the left of",),
    "right": ("is to the right of",),
    "front": ("is in front of",),
    "behind": ("is behind",),
}

#: How the describer words the sides of a close label (``Beside*``, within
#: ``BESIDE_REACH``): "just to the left of" says both the side and that A is close, and
#: no other label shares these words, so composing reads them back as that label.
CLOSE_DIRECTION_WORDINGS: dict[str, tuple[str, ...]] = {
    "left": ("is just to the left of", "is immediately to the left of"),
    "right": ("is just to the right of", "is immediately to the right of"),
}

#: How the layout report names each direction ("north of").
DIRECTION_PHRASES: dict[str, str] = {
    **{d: f"{d} of" for d in COMPASS},
    "left": "to the left of",
    "right": "to the right of",
    "front": "in front of",
    "behind": "behind",
}


class UnknownLabel(KeyError):
    """A relation label that is not in the registry."""

    def __str__(self) -> str:
        return f"unknown relation label {self.args[0]!r}"


@dataclass(frozen=True)
class RelationLabel:
    """Everything about one relation label (see the module docstring)."""

    name: str
    family: str
    phrase: str
    wordings: tuple[str, ...] = ()
    directions: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    frame: str | None = None  # "world" or "target" for next_to labels with directions
    placement: str | None = None  # support labels
    facing: str | None = None  # facing labels
    wall: str | None = None  # wall labels: against, corner, under_window, beside_window
    reach: float | None = None  # next_to labels: the gap they hold within (None: the layout's)
    seat: bool = False  # next_to labels: A is a seat at B's side, facing it squarely
    # next_to labels that choose: the words for each direction (None: DIRECTION_WORDINGS)
    direction_wordings: Mapping[str, tuple[str, ...]] | None = None
    place: bool = False
    symmetric: bool = False
    part_of: bool = False  # a support label worded as belonging ("is part of")
    implicitable: bool = True
    implicit: bool = False  # this record is the Implicit form of ``base``
    base: str = ""  # the label without its Implicit prefix (set by the registry)

    @property
    def support(self) -> bool:
        """A rests on B: its height follows B's top, and it moves with B."""
        return self.family == "support"

    @property
    def by_room(self) -> bool:
        """B is the room or one of its walls or windows (``some wall`` names the room:
        the layout chooses the wall)."""
        return self.family in ("wall", "clearance")

    @property
    def described(self) -> bool:
        """Whether the text may state it when it holds."""
        return not self.implicit and self.family != "structural"

    @property
    def chooses(self) -> bool:
        """The layout chooses one of several directions and records it as ``chosen``."""
        return len(self.directions) > 1

    @property
    def names_target_side(self) -> bool:
        """A direction on B's own sides: turning B can satisfy it."""
        return self.frame == "target" and bool(self.directions)

    def direction_vectors(self, c: float = 1.0, s: float = 0.0) -> dict[str, tuple[float, float]]:
        """The wanted directions from B to A as world unit vectors (x, z); ``c``, ``s``
        are B's yaw's cosine and sine (used for directions on B's own sides)."""
        if self.frame != "target":
            return dict(self.directions)
        # B's local (lx, lz) in the world: lx * left + lz * forward, left (c, -s), forward (s, c)
        return {
            name: (lx * c + lz * s, -lx * s + lz * c) for name, (lx, lz) in self.directions.items()
        }

    def wordings_for(self, chosen: str | None = None) -> tuple[str, ...]:
        """The verb phrases that state this label (canonical first); a label that chooses
        its direction is worded by the direction chosen (in ``direction_wordings``), or
        as plain "next to", which every next-to label implies."""
        if self.chooses and not self.seat:
            return self.side_wordings.get(chosen or "", _NEXT_TO_WORDINGS)
        return self.wordings

    @property
    def side_wordings(self) -> Mapping[str, tuple[str, ...]]:
        """The words for each direction this label may choose."""
        return DIRECTION_WORDINGS if self.direction_wordings is None else self.direction_wordings


@dataclass(frozen=True)
class Relation:
    """One relation ``source`` -label-> ``target``, with the layout's verdict once measured.

    A scene graph's edges have no verdict yet (``value`` and ``satisfied`` None). After
    layout ``value`` is the log factor (<= 0; 0 when it holds perfectly), ``satisfied``
    applies the documented threshold, and ``chosen`` is the direction a label that
    chooses its direction resolved to ("north", "left", ...). scene.json lists exactly
    these records, ``PathConnectedTo`` included.
    """

    source: str
    target: str
    label: str
    value: float | None = None
    satisfied: bool | None = None
    chosen: str | None = None


class Registry:
    """The labels by name, with their Implicit forms."""

    def __init__(self, labels: tuple[RelationLabel, ...] = ()) -> None:
        self._labels: dict[str, RelationLabel] = {}
        for label in labels:
            self.register(label)

    def register(self, label: RelationLabel) -> None:
        """Add a label (and its Implicit form); refuses an incomplete or duplicate one."""
        _check_complete(label)
        forms = [replace(label, base=label.name)]
        if label.implicitable:
            forms.append(
                replace(label, name=IMPLICIT_PREFIX + label.name, implicit=True, base=label.name)
            )
        for form in forms:
            if form.name in self._labels:
                raise ValueError(f"relation label {form.name!r} is registered twice")
        for form in forms:
            self._labels[form.name] = form

    def unregister(self, name: str) -> None:
        """Remove a label and its Implicit form."""
        self._labels.pop(name, None)
        self._labels.pop(IMPLICIT_PREFIX + name, None)

    @contextmanager
    def extended(self, *labels: RelationLabel) -> Iterator[Registry]:
        """The registry with ``labels`` added for the ``with`` block only."""
        for label in labels:
            self.register(label)
        try:
            yield self
        finally:
            for label in labels:
                self.unregister(label.name)

    def __getitem__(self, name: str) -> RelationLabel:
        try:
            return self._labels[name]
        except KeyError:
            raise UnknownLabel(name) from None

    def __contains__(self, name: object) -> bool:
        return name in self._labels

    def __iter__(self) -> Iterator[RelationLabel]:
        return iter(self._labels.values())

    def names(self) -> frozenset[str]:
        """Every label a rules file may use."""
        return frozenset(self._labels)


def _check_complete(label: RelationLabel) -> None:
    problems = []
    if label.family not in FAMILIES:
        problems.append(f"family {label.family!r} is not one of {', '.join(FAMILIES)}")
    if label.family == "next_to" and label.directions and label.frame not in ("world", "target"):
        problems.append("directions need a frame, 'world' or 'target'")
    if label.family == "support" and label.placement not in (
        "anywhere",
        "middle",
        "edge",
        "front_edge",
    ):
        problems.append(
            f"placement {label.placement!r} is not anywhere, middle, edge or front_edge"
        )
    if label.family == "facing" and label.facing not in (
        "towards",
        "away",
        "same",
        "orthogonal",
        "opposite",
    ):
        problems.append(
            f"facing {label.facing!r} is not towards, away, same, orthogonal or opposite"
        )
    if label.family == "wall" and label.wall not in WALL_PLACEMENTS:
        problems.append(f"wall placement {label.wall!r} is not one of {', '.join(WALL_PLACEMENTS)}")
    if label.family != "structural" and not label.chooses and not label.wordings:
        problems.append("it has no wording")
    if label.seat and not label.wordings:
        problems.append("a seat label is worded by its own wording, and it has none")
    if (label.reach is not None or label.seat) and label.family != "next_to":
        problems.append("reach and seat are next_to parameters")
    if label.seat and (label.frame != "target" or label.reach is None):
        problems.append("a seat label names sides of B and a reach")
    for name, (x, z) in label.directions.items():
        if abs(math.hypot(x, z) - 1.0) > 1e-9:
            problems.append(f"direction {name!r} is not a unit vector")
        if label.chooses and not label.seat and name not in label.side_wordings:
            problems.append(f"direction {name!r} has no wording")
    if problems:
        raise ValueError(f"relation label {label.name!r} is incomplete: " + "; ".join(problems))


_NEXT_TO_WORDINGS = ("is next to", "is beside")


def _next_to(
    name: str, phrase: str, wordings: tuple[str, ...], directions: tuple[str, ...] = (), **more
) -> RelationLabel:
    table = COMPASS if all(d in COMPASS for d in directions) else SIDES
    frame = None if not directions else ("world" if table is COMPASS else "target")
    return RelationLabel(
        name,
        "next_to",
        phrase,
        wordings,
        directions={d: table[d] for d in directions},
        frame=frame,
        place=True,
        **more,
    )


def _support(
    name: str, placement: str, phrase: str, wordings: tuple[str, ...], *, part_of: bool = False
) -> RelationLabel:
    return RelationLabel(
        name, "support", phrase, wordings, placement=placement, part_of=part_of, place=not part_of
    )


#: The gap (metres) within which a seat stands at the side it is used from: a chair's
#: front edge 5-35 cm from a desk's, as a person sitting at it pulls it up.
SEAT_REACH = 0.35

#: The gap (metres) within which paired furniture stands beside its partner: a
#: nightstand by the bed's head, a floor lamp by an armchair.
BESIDE_REACH = 0.15

#: How far (radians) a seat may turn off square to the side it is used from.
SEAT_SQUARE_TOLERANCE = math.radians(10.0)

#: Labels beyond Table 1 for furniture used together: a seat at its table's side,
#: paired furniture close beside its partner.
FURNITURE_LABELS: tuple[RelationLabel, ...] = (
    _next_to(
        "SeatedAt",
        "at",
        ("is pulled up to", "is drawn up to"),
        ("front",),
        reach=SEAT_REACH,
        seat=True,
    ),
    _next_to(
        "SeatedAtBack",
        "at the back of",
        ("is at the back of",),
        ("behind",),
        reach=SEAT_REACH,
        seat=True,
    ),
    _next_to(
        "SeatedAround",
        "at",
        ("is at",),
        tuple(SIDES),
        reach=SEAT_REACH,
        seat=True,
    ),
    _next_to(
        "Beside",
        "beside",
        (),
        ("left", "right"),
        reach=BESIDE_REACH,
        direction_wordings=CLOSE_DIRECTION_WORDINGS,
    ),
    _next_to(
        "BesideLeft",
        "to the left of",
        CLOSE_DIRECTION_WORDINGS["left"],
        ("left",),
        reach=BESIDE_REACH,
    ),
    _next_to(
        "BesideRight",
        "to the right of",
        CLOSE_DIRECTION_WORDINGS["right"],
        ("right",),
        reach=BESIDE_REACH,
    ),
)

#: The vocabulary of Table 1.
TABLE_1: tuple[RelationLabel, ...] = (
    _next_to("NextTo", "next to", _NEXT_TO_WORDINGS, symmetric=True),
    _next_to("NextToChooseDirection", "next to", (), tuple(COMPASS)),
    _next_to("NextToChooseSide", "beside", (), ("left", "right")),
    *(
        _next_to(f"NextTo{d.title()}", DIRECTION_PHRASES[d], DIRECTION_WORDINGS[d], (d,))
        for d in COMPASS
    ),
    *(
        _next_to(f"NextTo{d.title()}", DIRECTION_PHRASES[d], DIRECTION_WORDINGS[d], (d,))
        for d in SIDES
    ),
    _support("OnTopOf", "anywhere", "on top of", ("is on top of", "is on")),
    _support(
        "OnTopOfMiddle",
        "middle",
        "in the middle of",
        ("is in the middle of", "stands in the middle of"),
    ),
    _support(
        "OnTopOfEdge", "edge", "at the edge of", ("is on the edge of", "stands on the edge of")
    ),
    _support(
        "OnTopOfFrontEdge",
        "front_edge",
        "at the front edge of",
        ("is at the front edge of", "stands at the front edge of"),
    ),
    # IsPartOf* rests A on B like OnTopOf*, but A belongs to B (a sign on a stall).
    _support("IsPartOf", "anywhere", "part of", ("is part of", "forms part of"), part_of=True),
    _support(
        "IsPartOfMiddle",
        "middle",
        "attached to the middle of",
        ("is attached to the middle of",),
        part_of=True,
    ),
    _support(
        "IsPartOfEdge",
        "edge",
        "attached to the edge of",
        ("is attached to the edge of",),
        part_of=True,
    ),
    _support(
        "IsPartOfFrontEdge",
        "front_edge",
        "attached to the front edge of",
        ("is attached to the front edge of",),
        part_of=True,
    ),
    RelationLabel(
        "FacingTowards",
        "facing",
        "facing towards",
        ("faces", "is turned towards"),
        facing="towards",
    ),
    RelationLabel(
        "FacingAwayFrom",
        "facing",
        "facing away from",
        ("faces away from", "is turned away from"),
        facing="away",
    ),
    RelationLabel(
        "FacingSameDirection",
        "facing",
        "facing the same way as",
        ("faces the same way as", "faces the same direction as"),
        facing="same",
        symmetric=True,
    ),
    RelationLabel(
        "FacingOrthogonalDirection",
        "facing",
        "facing across",
        ("stands at a right angle to", "is at a right angle to"),
        facing="orthogonal",
        symmetric=True,
    ),
    RelationLabel(
        "FacingOpposite",
        "facing",
        "facing the opposite way to",
        ("faces the opposite way to", "faces the opposite direction to"),
        facing="opposite",
        symmetric=True,
    ),
    RelationLabel(
        "AlignedWith",
        "alignment",
        "lined up with",
        ("is lined up with", "is aligned with"),
        symmetric=True,
    ),
    # Rooms: B is a wall or a window, or the room itself (whichever wall or window fits).
    RelationLabel(
        "AgainstWall",
        "wall",
        "against",
        ("stands against", "is against"),
        wall="against",
        place=True,
    ),
    RelationLabel(
        "InCorner",
        "wall",
        "in a corner by",
        ("stands in a corner by", "is in a corner by"),
        wall="corner",
        place=True,
    ),
    RelationLabel(
        "UnderWindow",
        "wall",
        "under",
        ("is under", "stands under"),
        wall="under_window",
        place=True,
    ),
    RelationLabel(
        "BesideWindow",
        "wall",
        "beside",
        ("is beside", "stands beside"),
        wall="beside_window",
        place=True,
    ),
    # Kept off the walls: the complement of the wall labels, so that rules can say that a
    # thing stands out in the room (learned rules draw between the two, as the examples did).
    RelationLabel(
        "AwayFromWall",
        "clearance",
        "away from",
        ("stands away from", "is away from"),
    ),
    # Structural: a path starts at a junction (written either way round). No energy of
    # its own (the path's end is attached to the junction); the text tells it as the
    # road network rather than as a relation.
    RelationLabel("PathConnectedTo", "structural", "connected to", implicitable=False),
)

#: The registry every stage reads.
RELATIONS = Registry(TABLE_1 + FURNITURE_LABELS)
