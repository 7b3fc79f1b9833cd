"""The plan model: what a set of plans teaches about each room type (paper Sections 4.2, 5.1).

``build_model(plans)`` returns a ``plan_model.PlanModel`` (written as the JSON object
of ``MODEL_FORMAT``), the same for the same plans whatever their order on disk:

- ``categories``: per category its functional purpose (``activity``), the mean short
  and long side of its footprint ``f_obj`` and its mean floor area ``theta_c`` (0 for
  things that stand on others or lie flat: they take no floor);
- ``activity``: the pairs with A(o_i, o_j) = 1 and why (``activity.activity_prior``);
- per type: the number of plans, the mean room area ``theta_s``; per category
  ``P(o | s)`` (the mean of ``exist(o, r)`` over the type's plans) and ``max_count``
  ``N(o, s)`` (the most instances in one plan); per pair the co-occurrence
  ``P(o_i, o_j | s)`` (Equation 1) and the edge weight ``W_s = P(o_i, o_j | s) *
  A(o_i, o_j)``; the layout-mask clusters;
- per plan: its type, room area, category counts, canonical frame, room feature
  ``f_r`` and 10 x 10 layout mask, and its cluster;
- ``accessories``: what stands on or at what, and where (``accessories.learn_accessories``);
- ``stances``: per category how its pieces stand in the room: in a corner, against a
  wall, free, under a window, in a row with, before, close before, facing or beside
  what (``stances.learn_stances``, ``neighbours``).

``exist(o, r)`` is 1 when plan ``r`` has a piece of category ``o``. Otherwise it comes
from the plan's free areas: the paper writes it as ``||f_obj^o - f_obj^area||^2``, a
squared distance, which grows as the sizes differ and so cannot be the existence
probability it is used as; here it is ``exp(-||f_obj^o - f_obj^area||^2 / FIT_SCALE^2)``
for a category the area suits (``suits``, or when it names none any category of the
type, which keeps a refrigerator out of a study, as the paper filters irrational
ones by hand) and whose footprint fits the area, 0 otherwise.

Masks are clustered per type with scikit-learn's ``MeanShift`` (flat kernel, every
mask a seed, so the result does not depend on a random state), its bandwidth from
``estimate_bandwidth`` over all the type's masks at ``BANDWIDTH_QUANTILE``; clusters
are numbered by size, largest first, ties by their first plan id, and each stores the
mean mask of its members.
"""

from __future__ import annotations

import functools
import json
import math
from collections import Counter

import numpy as np

from scenewright.completion import shipped_plans_dir
from scenewright.completion.accessories import learn_accessories
from scenewright.completion.activity import activity_prior, purpose
from scenewright.completion.features import MASK_SIZE, canonical_frame, occupancy_mask, room_feature
from scenewright.completion.floor_plan import load_plans, rounded
from scenewright.completion.plan_checks import FLAT_HEIGHT, is_flat
from scenewright.completion.plan_model import MODEL_FORMAT, MODEL_VERSION, PlanModel
from scenewright.completion.stances import learn_stances
from scenewright.core.errors import InputError
from scenewright.generator import indoor_catalog

#: Metres of size difference at which a free area's fit for a category falls to 1/e.
FIT_SCALE = 0.5
#: The share of nearest neighbours scikit-learn's bandwidth estimate looks at (its default).
BANDWIDTH_QUANTILE = 0.3
#: Decimals kept in the model's numbers (the file is the same bytes on every machine).
DECIMALS = 6


def floor_pieces(plan, catalog=None) -> list:
    """The pieces of ``plan`` that cover floor: not standing on another, not flat."""
    catalog = catalog or indoor_catalog()
    return [piece for piece in plan.furniture if piece.on is None and not is_flat(piece, catalog)]


def build_model(plans) -> PlanModel:
    """The plan model of ``plans`` (``plan.Plan``; at least one)."""
    plans = sorted(plans, key=lambda plan: plan.id)
    if not plans:
        raise InputError("a plan model needs at least one plan")
    catalog = indoor_catalog()
    categories = _category_table(plans, catalog)
    types = sorted({plan.type for plan in plans})
    prior = activity_prior(plans)
    model_types, model_plans = {}, []
    for room_type in types:
        members = [plan for plan in plans if plan.type == room_type]
        mean_area = float(np.mean([plan.room.area for plan in members]))
        known = sorted(
            {piece.category for plan in members for piece in plan.furniture}
            | {name for plan in members for area in plan.free_areas for name in area.suits}
        )
        exists = [_existence(plan, known, categories) for plan in members]
        entries = []
        for plan, exist in zip(members, exists, strict=False):
            floor = floor_pieces(plan, catalog)
            frame = canonical_frame(plan.room, floor)
            entries.append(
                {
                    "id": plan.id,
                    "type": room_type,
                    "area": plan.room.area,
                    "counts": dict(
                        sorted(Counter(piece.category for piece in plan.furniture).items())
                    ),
                    "exist": {name: value for name, value in sorted(exist.items()) if value > 0.0},
                    "frame": frame.to_dict(),
                    "feature": room_feature(
                        plan.room, sum(p.area for p in floor), mean_area
                    ).tolist(),
                    "mask": occupancy_mask(plan.room, floor, frame).tolist(),
                }
            )
        clusters = _clusters(entries)
        model_types[room_type] = {
            "plans": len(members),
            "mean_area": mean_area,
            "categories": {
                name: {
                    "p": float(np.mean([exist.get(name, 0.0) for exist in exists])),
                    "max_count": max(
                        plan_counts.get(name, 0) for plan_counts in (e["counts"] for e in entries)
                    ),
                }
                for name in known
            },
            "pairs": _pairs(known, exists, prior),
            "clusters": clusters,
        }
        model_plans += entries
    accessories = learn_accessories(plans, catalog)
    model = {
        "format": MODEL_FORMAT,
        "version": MODEL_VERSION,
        "categories": categories,
        "activity": [{"pair": list(pair), "why": why} for pair, why in prior.items()],
        "types": model_types,
        "plans": model_plans,
        "accessories": accessories,
        "stances": learn_stances(plans, catalog, set(accessories)),
    }
    return PlanModel.from_dict(rounded(model, DECIMALS))


@functools.cache
def shipped_model() -> PlanModel:
    """The model of the shipped plan set, built once a process: the completions that
    bring no plans of their own share it (nothing changes a model once built) instead
    of building it again, a third of a second each."""
    return build_model(load_plans(shipped_plans_dir()))


def model_json(model: PlanModel) -> str:
    """The model's file text: sorted keys, each number list of a mask row on one line."""
    return json.dumps(model.to_dict(), indent=1, sort_keys=True) + "\n"


def relation_graph(model: PlanModel, room_type: str) -> dict:
    """A type's object relation graph: the edges with ``W_s > 0`` and the categories
    they join (isolated ones removed, as in the paper)."""
    if room_type not in model.types:
        raise InputError(
            f"the plans have no type {room_type!r} (they have {', '.join(sorted(model.types))})"
        )
    entry = model.types[room_type]
    edges = [pair.to_dict() for pair in entry.pairs if pair.weight > 0.0]
    names = sorted({name for edge in edges for name in edge["pair"]})
    nodes = [
        {
            "category": name,
            "p": entry.categories[name].p,
            "purpose": model.categories[name].purpose,
        }
        for name in names
    ]
    return {"type": room_type, "nodes": nodes, "edges": edges}


def graph_dot(graph: dict) -> str:
    """Graphviz text of a ``relation_graph``: node labels carry P(o | s), edges W_s
    (drawn thicker as they weigh more)."""
    lines = [f"graph {json.dumps(graph['type'])} {{", "  node [shape=box];"]
    for node in graph["nodes"]:
        label = f"{node['category']}\\nP={node['p']:.2f}"
        lines.append(f'  {json.dumps(node["category"])} [label="{label}"];')
    for edge in graph["edges"]:
        first, second = edge["pair"]
        width = 0.5 + 4.0 * edge["weight"]
        lines.append(
            f"  {json.dumps(first)} -- {json.dumps(second)} "
            f'[label="{edge["weight"]:.2f}", penwidth={width:.2f}];'
        )
    lines.append("}")
    return "\n".join(lines) + "\n"


def read_model(path: str) -> PlanModel:
    """A model file written by ``scenewright plans build``; ``InputError`` if it is not one."""
    from scenewright.core.files import UnusableFile, load_json, read_regular_file

    try:
        data = load_json(read_regular_file(path, 64 * 1024 * 1024, "a plan model").decode("utf-8"))
    except UnusableFile as problem:
        raise InputError(f"{path}: cannot read: it {problem}") from None
    except OSError as error:
        raise InputError(f"{path}: cannot read: {error.strerror or error}") from None
    except (UnicodeDecodeError, ValueError) as error:
        raise InputError(f"{path}: not a JSON plan model: {error}") from None
    if not isinstance(data, dict) or data.get("format") != MODEL_FORMAT:
        raise InputError(f"{path}: not a plan model ('format' is not {MODEL_FORMAT!r})")
    if data.get("version") != MODEL_VERSION:
        raise InputError(
            f"{path}: plan model version {data.get('version')!r}; this scenewright reads {MODEL_VERSION}"
        )
    for key, kind in (
        ("categories", dict),
        ("activity", list),
        ("types", dict),
        ("plans", list),
        ("accessories", dict),
        ("stances", dict),
    ):
        if not isinstance(data.get(key), kind):
            raise InputError(
                f"{path}: $.{key}: missing or not a JSON {'object' if kind is dict else 'array'}"
            )
    for name, entry in data["types"].items():
        if not isinstance(entry, dict) or not all(
            isinstance(entry.get(k), list) for k in ("pairs", "clusters")
        ):
            raise InputError(f"{path}: $.types.{name}: not a type entry of a plan model")
    try:
        return PlanModel.from_dict(data)
    except (KeyError, TypeError, AttributeError) as error:
        raise InputError(f"{path}: not a plan model of version {MODEL_VERSION}: {error}") from None


# -- the pieces ---------------------------------------------------------------------------


def _category_table(plans, catalog) -> dict:
    """Per category of the plans' furniture and free areas: purpose, mean (short, long)
    footprint sides and mean floor area; a category only a free area names (a piano no
    plan has) takes its catalog footprint."""
    drawn = {piece.category for plan in plans for piece in plan.furniture}
    suited = {name for plan in plans for area in plan.free_areas for name in area.suits}
    table = {}
    for name in sorted(drawn | suited):
        pieces = [piece for plan in plans for piece in plan.furniture if piece.category == name]
        if pieces:
            sides = np.array([sorted(piece.size) for piece in pieces]).mean(axis=0).tolist()
            floor = float(
                np.mean(
                    [0.0 if p.on is not None or is_flat(p, catalog) else p.area for p in pieces]
                )
            )
        else:
            width, height, depth = catalog[name].size
            sides = sorted((width, depth))
            floor = 0.0 if height <= FLAT_HEIGHT else width * depth
        table[name] = {"purpose": purpose(name), "size": sides, "floor_area": floor}
    return table


def _existence(plan, known: list[str], categories: dict) -> dict[str, float]:
    """exist(o, r) for each category ``known`` to the plan's type (module docstring)."""
    present = {piece.category for piece in plan.furniture}
    exist = {name: 1.0 for name in present}
    for area in plan.free_areas:
        short, long = sorted(area.size)
        for name in area.suits or known:
            if name in present:
                continue
            object_short, object_long = categories[name]["size"]
            if object_short > short or object_long > long:
                continue
            fit = math.exp(
                -((object_short - short) ** 2 + (object_long - long) ** 2) / FIT_SCALE**2
            )
            exist[name] = max(exist.get(name, 0.0), fit)
    return exist


def _pairs(known: list[str], exists: list[dict], prior: dict) -> list[dict]:
    """Every pair of ``known`` categories that co-occur: P(o_i, o_j | s) (Equation 1), A, W_s."""
    pairs = []
    for k, first in enumerate(known):
        for second in known[k + 1 :]:
            together = float(
                np.mean([exist.get(first, 0.0) * exist.get(second, 0.0) for exist in exists])
            )
            if together <= 0.0:
                continue
            why = prior.get((first, second))
            pairs.append(
                {
                    "pair": [first, second],
                    "cooccurrence": together,
                    "activity": why,
                    "weight": together if why else 0.0,
                }
            )
    return pairs


def _clusters(entries: list[dict]) -> list[dict]:
    """MeanShift clusters of the entries' masks (module docstring); sets each entry's ``cluster``."""
    from sklearn.cluster import MeanShift, estimate_bandwidth
    from threadpoolctl import threadpool_limits  # type: ignore[import-untyped]

    masks = np.array([np.ravel(entry["mask"]) for entry in entries])
    labels = np.zeros(len(entries), dtype=int)
    if len(entries) > 1:
        # One thread: a few dozen masks are quicker clustered than a thread pool is started.
        with threadpool_limits(limits=1):
            bandwidth = estimate_bandwidth(masks, quantile=BANDWIDTH_QUANTILE)
            if bandwidth > 0.0:
                labels = MeanShift(bandwidth=bandwidth).fit(masks).labels_
    groups: dict[int, list[int]] = {}
    for index, label in enumerate(labels):
        groups.setdefault(int(label), []).append(index)
    ordered = sorted(
        groups.values(), key=lambda members: (-len(members), entries[members[0]]["id"])
    )
    clusters = []
    for number, members in enumerate(ordered):
        for index in members:
            entries[index]["cluster"] = number
        clusters.append(
            {
                "plans": [entries[index]["id"] for index in members],
                "mask": masks[members].mean(axis=0).reshape(MASK_SIZE, MASK_SIZE).tolist(),
            }
        )
    return clusters
