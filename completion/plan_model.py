"""The plan model as the completion reads it: ``PlanModel`` and its parts, one field per
statistic, and the JSON object of the model file they are written as and read from
(``to_dict``, ``from_dict``). ``model.build_model`` makes one from a set of plans; the
fields and what each statistic means are described there.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

MODEL_FORMAT = "scenewright-plan-model"
MODEL_VERSION = 4


@dataclass
class CategoryStats:
    """One category over all the plans: its functional purpose (``activity.purpose``),
    the mean short and long side of its footprint ``f_obj``, and its mean floor area
    ``theta_c`` (0 for things that stand on others or lie flat)."""

    purpose: str
    size: list[float]
    floor_area: float

    def to_dict(self) -> dict:
        return {"purpose": self.purpose, "size": self.size, "floor_area": self.floor_area}


@dataclass
class TypeCategory:
    """One category in one room type: ``P(o | s)`` and the most instances in one plan
    ``N(o, s)``."""

    p: float
    max_count: int

    def to_dict(self) -> dict:
        return {"p": self.p, "max_count": self.max_count}


@dataclass
class CategoryPair:
    """Two categories of one type that co-occur: ``P(o_i, o_j | s)`` (Equation 1), why
    the activity prior joins them (None: it does not) and the edge weight ``W_s``."""

    pair: list[str]
    cooccurrence: float
    activity: str | None
    weight: float

    def to_dict(self) -> dict:
        return {
            "pair": self.pair,
            "cooccurrence": self.cooccurrence,
            "activity": self.activity,
            "weight": self.weight,
        }


@dataclass
class MaskCluster:
    """One cluster of a type's layout masks: its plans' ids and their mean mask."""

    plans: list[str]
    mask: list[list[float]]

    def to_dict(self) -> dict:
        return {"plans": self.plans, "mask": self.mask}


@dataclass
class RoomTypeModel:
    """What the plans of one room type teach: how many there are, the mean room area
    ``theta_s``, per category its ``TypeCategory``, the co-occurring pairs and the
    layout-mask clusters."""

    plans: int
    mean_area: float
    categories: dict[str, TypeCategory]
    pairs: list[CategoryPair] = field(default_factory=list)
    clusters: list[MaskCluster] = field(default_factory=list)

    def probability(self, category: str) -> float:
        """``P(o | s)`` of ``category`` (0 for one no plan of the type has)."""
        stats = self.categories.get(category)
        return stats.p if stats is not None else 0.0

    def most(self, category: str) -> int:
        """``N(o, s)``: the most instances of ``category`` in one plan of the type."""
        stats = self.categories.get(category)
        return stats.max_count if stats is not None else 0

    def to_dict(self) -> dict:
        return {
            "plans": self.plans,
            "mean_area": self.mean_area,
            "categories": {name: entry.to_dict() for name, entry in self.categories.items()},
            "pairs": [pair.to_dict() for pair in self.pairs],
            "clusters": [cluster.to_dict() for cluster in self.clusters],
        }


@dataclass
class PlanEntry:
    """One plan as the model keeps it: its id, type, room area, category counts,
    ``exist(o, r)`` where above 0, canonical frame (``features.CanonicalFrame`` as a
    dict), room feature ``f_r``, layout mask and the number of its mask cluster."""

    id: str
    type: str
    area: float
    counts: dict[str, int]
    exist: dict[str, float]
    frame: dict[str, bool]
    feature: list[float]
    mask: list[list[float]]
    cluster: int = 0

    def to_dict(self) -> dict:
        return {
            "id": self.id,
            "type": self.type,
            "area": self.area,
            "counts": self.counts,
            "exist": self.exist,
            "frame": self.frame,
            "feature": self.feature,
            "mask": self.mask,
            "cluster": self.cluster,
        }


@dataclass
class ActivityPair:
    """Two categories with A(o_i, o_j) = 1 and why (``activity.activity_prior``)."""

    pair: list[str]
    why: str

    def to_dict(self) -> dict:
        return {"pair": self.pair, "why": self.why}


@dataclass
class AccessorySlot:
    """One side of an anchor an accessory stood at in the plans (``accessories``):
    ``side`` (``middle`` of its top, or its ``left``, ``right``, ``front``, ``behind``),
    the pieces seen there, the most at that side of one anchor in one plan, their mean
    centre ``offset`` (left, forward) in the anchor's frame (metres), their circular
    mean ``yaw`` relative to the anchor's (radians), the mean ``gap`` between the
    footprints (0 on top) and the share ``flush`` with the anchor (on top: at an edge
    of its top; beside: parallel with the backs in line)."""

    side: str
    pieces: int
    most: int
    offset: list[float]
    yaw: float
    gap: float
    flush: float


@dataclass
class AccessoryAnchor:
    """An anchor category an accessory stood on or at: the pieces seen, the most at one
    anchor in one plan, and the slots, most pieces first."""

    anchor: str
    pieces: int
    most: int
    slots: list[AccessorySlot]


@dataclass
class AccessoryCategory:
    """A category most of whose pieces stood on or at a larger piece: its pieces over
    all plans, the share with an anchor, whether it stands ``on`` its anchors (else
    beside them) and its anchor categories, most pieces first."""

    pieces: int
    anchored: float
    on: bool
    anchors: list[AccessoryAnchor]

    def to_dict(self) -> dict:
        return asdict(self)  # fields in order, nested slots and anchors as dicts

    @classmethod
    def from_dict(cls, data: dict) -> AccessoryCategory:
        return cls(
            pieces=data["pieces"],
            anchored=data["anchored"],
            on=data["on"],
            anchors=[
                AccessoryAnchor(
                    anchor=entry["anchor"],
                    pieces=entry["pieces"],
                    most=entry["most"],
                    slots=[AccessorySlot(**slot) for slot in entry["slots"]],
                )
                for entry in data["anchors"]
            ],
        )


@dataclass
class CategoryStance:
    """How one category stood on the floor over all the plans (``stances``): its
    pieces, whether most lay flat, the shares of its pieces in a corner, with their back
    against a wall, and free (exclusive), the share under a window (of the pieces whose
    plan has one), and per category the share in a row with one, before one, close
    before one, facing one and beside one (of the pieces whose plan has one), most
    first (``neighbours`` says what each means)."""

    pieces: int
    flat: bool
    corner: float
    wall: float
    free: float
    window: float
    row: dict[str, float]
    before: dict[str, float]
    close: dict[str, float]
    facing: dict[str, float]
    beside: dict[str, float]

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class PlanModel:
    """The plan model: the categories over all plans, the activity pairs, per room type
    its ``RoomTypeModel``, every plan's ``PlanEntry`` and what stands on or at what
    (``accessories``: per accessory category its ``AccessoryCategory``)."""

    categories: dict[str, CategoryStats]
    types: dict[str, RoomTypeModel]
    activity: list[ActivityPair] = field(default_factory=list)
    plans: list[PlanEntry] = field(default_factory=list)
    accessories: dict[str, AccessoryCategory] = field(default_factory=dict)
    stances: dict[str, CategoryStance] = field(default_factory=dict)

    def type_plans(self, room_type: str) -> list[PlanEntry]:
        """The plans of ``room_type``, in the model's order."""
        return [plan for plan in self.plans if plan.type == room_type]

    def to_dict(self) -> dict:
        """The model file's JSON object."""
        return {
            "format": MODEL_FORMAT,
            "version": MODEL_VERSION,
            "categories": {name: entry.to_dict() for name, entry in self.categories.items()},
            "activity": [pair.to_dict() for pair in self.activity],
            "types": {name: entry.to_dict() for name, entry in self.types.items()},
            "plans": [plan.to_dict() for plan in self.plans],
            "accessories": {name: entry.to_dict() for name, entry in self.accessories.items()},
            "stances": {name: entry.to_dict() for name, entry in self.stances.items()},
        }

    @classmethod
    def from_dict(cls, data: dict) -> PlanModel:
        """The model of a model file's JSON object (``format`` and ``version`` checked by
        the caller); ``KeyError`` or ``TypeError`` where a part is missing or malformed."""
        return cls(
            categories={name: CategoryStats(**entry) for name, entry in data["categories"].items()},
            types={
                name: RoomTypeModel(
                    plans=entry["plans"],
                    mean_area=entry["mean_area"],
                    categories={
                        category: TypeCategory(**stats)
                        for category, stats in entry["categories"].items()
                    },
                    pairs=[CategoryPair(**pair) for pair in entry["pairs"]],
                    clusters=[MaskCluster(**cluster) for cluster in entry["clusters"]],
                )
                for name, entry in data["types"].items()
            },
            activity=[ActivityPair(**pair) for pair in data["activity"]],
            plans=[PlanEntry(**plan) for plan in data["plans"]],
            accessories={
                name: AccessoryCategory.from_dict(entry)
                for name, entry in data["accessories"].items()
            },
            stances={name: CategoryStance(**entry) for name, entry in data["stances"].items()},
        )
