"""Complete a room end to end: a request (an empty room and a few categories) -> a
furnished, laid-out scene (``scenewright complete``).

The steps, each in its module:

1. ``request.parse_request``: the room, its doors and windows and the requested
   categories -> a ``Request`` holding a ``core.room.Room``.
2. ``contents.choose_contents``: the room's type(s) and per type its categories
   (Equation 2, Algorithm 1), and the layout mask (Equation 4); a rectangular room of
   several types is split by virtual walls (``regions``), and the layout keeps each
   type's pieces in its region (``region_boxes``).
3. ``furnishing.build_graph``: a ``SceneGraph`` of the indoor catalog's entries with
   the relations a room's rules would state.
4. ``starting_poses.starting_poses``: where the layout starts, the large pieces placed
   on the layout mask along the walls.
5. ``complete`` (here): the MCMC layout (``generator.layout.layout_scene``) from those
   poses, whose energy holds the walls, clearances, door swings and reachability, and the
   layout mask as a preference for the large pieces (``masked``; the energy's ``mask``
   part, ``generator.layout.mask_term``); the scene with its ``completion`` record
   (``completion_record``). While the layout is not ok, the room gives up one added
   piece (``fewer_pieces``: of the added categories its problems name, the one most
   weakly tied to the request) and is laid out again, at most ``FIT_ATTEMPTS`` times:
   Algorithm 1 weighs floor area, not whether the pieces fit round the door and each
   other, so a small room can be chosen more than it holds. A try after a failed one
   first starts one short chain where the failed layout left the remaining pieces
   (``WARM_PARAMS``) and lays the room out afresh only when that is not ok
   (``FIT_PARAMS``).

A furnished scene can be completed too (``request.existing_request``, ``pin_existing``:
its objects stay where they stand). ``explanation`` reads the record back for people.

The mask guides the start and, through its energy part, the chains: a large piece
costs more the less of the mask lies under it. It is a preference: the layout's
verdict does not read it, so it may cost a relation nothing and the chains still move
pieces off the mask where the relations ask for it. Everything is deterministic for
the seed: the selection and the starting poses draw nothing, the layout draws from the
seed's layout streams.
"""

from __future__ import annotations

import re
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from scenewright.completion.plan_model import PlanModel
from scenewright.core.poses import Pose
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph
from scenewright.generator.layout.params import LayoutParams

from .contents import Contents, choose_contents
from .furnishing import build_graph, relation_weights
from .request import Request
from .stances import stands_by_room
from .starting_poses import FLAT, starting_poses

if TYPE_CHECKING:
    from scenewright.generator.layout.mask_term import FloorMask

#: Layouts tried with one added piece fewer each (``fewer_pieces``) while the layout is
#: not ok: a room the selection filled past what can be laid out gives up its weakest pieces.
FIT_ATTEMPTS = 4
#: Why a category the selection chose is not in the room: the layout failed with it.
#: The layout's parameters for each try: two chains (one restart), as most rooms are ok
#: on their first chain and one that fails twice is better off with a piece fewer. The
#: restart gives up after 800 steps without progress (design notes, docs/notes/design.md,
#: "Room completion").
FIT_PARAMS = LayoutParams(restarts=1, restart_patience=800)
#: A try after a failed one first runs one chain from the failed layout's poses (the
#: pieces still in the room where they stood; a warm start), which gives up after
#: ``patience`` steps without progress: the piece given up mostly was what kept the rest
#: from fitting, so the chain is often ok at once (design notes, "Room completion").
#: Only when it is not does the try lay the room out afresh with ``FIT_PARAMS``.
WARM_PARAMS = LayoutParams(restarts=0, patience=200)
ROOM_FULL = "no room for it with the rest: the layout failed with it"


def masked(model: PlanModel, graph: SceneGraph) -> list[str]:
    """The ids of ``graph``'s large furniture, which the layout mask is for in the
    layout's energy: pieces of a category the plans show standing against a wall or
    free in the middle (``stances.stands_by_room``) that stand so here, with a relation
    to the room's walls or with no relation at all (an armchair beside the coffee table
    follows the table). Their accessories (night tables, chairs, lamps) follow them by
    the poses learned from the plans, as the paper places accessories after their large
    furniture."""
    own: dict[str, set[str]] = {}
    for relation in graph.edges():
        own.setdefault(relation.source, set()).add(relation.target)
    return [
        node.id
        for node in graph.nodes("object")
        if stands_by_room(model, node.type) and ROOM_NODE in own.get(node.id, {ROOM_NODE})
    ]


def region_boxes(
    types: dict[str, str], relations, owners: dict[str, int], count: int, large: set[str]
) -> list[list[str]]:
    """Per region (``count`` of them) the ids of the floor pieces that belong there,
    from the pieces' categories (``types``: id -> category), the ``relations`` (source,
    target, label) between them and the region of each category (``owners``). A large
    piece (of a category in ``large``: those ``masked`` picks) belongs to its category's region; any
    other follows the piece its first relation to another piece names, up to a large one
    (a night table stays by its bed, a chair at its table, wherever their categories'
    types would put them); one with no such relation goes by its own category. Pieces that stand on others (a support
    relation) belong nowhere: they go with their support."""
    from scenewright.core.relations import RELATIONS

    anchor: dict[str, str] = {}
    carried = {source for source, _, label in relations if RELATIONS[label].support}
    for source, target, _ in relations:
        if (
            source in types
            and target in types
            and source not in anchor
            and types[source] not in large
        ):
            anchor[source] = target
    out: list[list[str]] = [[] for _ in range(count)]
    for box in types:
        if box in carried:
            continue
        root, seen = box, {box}
        while types[root] not in large and root in anchor and anchor[root] not in seen:
            root = anchor[root]
            seen.add(root)
        out[owners[types[root]]].append(box)
    return out


def _graph_and_start(model: PlanModel, contents: Contents, room: Room, catalog):
    """The scene graph of ``contents``, the categories left out with why, and the
    starting poses; a rug the starting poses find no free floor for is left out."""
    from scenewright.core.relations import RELATIONS

    graph, dropped, placements = build_graph(model, contents, room, catalog)
    start = starting_poses(graph, room, contents.mask, placements)
    carried = {r.source for r in graph.edges() if RELATIONS[r.label].support}
    unplaced = sorted(
        {
            n.type
            for n in graph.nodes("object")
            if n.size[1] <= FLAT and n.id not in carried and n.id not in start
        }
    )
    if unplaced:
        before = graph
        graph, dropped, placements = build_graph(model, contents, room, catalog, leave_out=unplaced)
        kept = {n.id for n in graph.nodes("object")}
        gone = {n.id for n in before.nodes("object")} - kept
        # A piece with no starting pose took no place another's start depends on: when
        # the rest of the graph is the same, the rest's starts are too.
        if [
            r for r in before.edges() if r.source not in gone and r.target not in gone
        ] == graph.edges():
            start = {box: pose for box, pose in start.items() if box in kept}
        else:
            start = starting_poses(graph, room, contents.mask, placements)
    return graph, dropped, start


def fewer_pieces(
    model: PlanModel, contents: Contents, request: Request, graph: SceneGraph, problems
) -> Contents | None:
    """``contents`` with one added piece fewer after a layout with ``problems`` (its
    report's lines): of the added categories whose pieces the problems name (all added
    ones when they name none), the one most weakly tied to the requested categories
    (summed relation weight ``W``; then the larger footprint, then the name) loses one
    piece, or the whole category at its last. None when nothing was added. Requested
    categories keep their counts: the request is what the room must hold."""
    added = [name for name in contents.counts if name not in request.requested]
    if not added:
        return None
    types = {node.id: node.type for node in graph.nodes("object")}
    named = {
        types[word]
        for line in problems
        for word in re.findall(r"[A-Za-z0-9_]+", line)
        if word in types
    }
    candidates = [name for name in added if name in named] or added
    weights = relation_weights(model, contents.types)
    sizes = {node.type: node.size[0] * node.size[2] for node in graph.nodes("object")}

    def tie(name: str) -> float:
        return sum(
            weights.get((min(name, r), max(name, r)), 0.0) for r in request.requested if r != name
        )

    weakest = min(candidates, key=lambda name: (tie(name), -sizes.get(name, 0.0), name))
    counts = dict(contents.counts)
    counts[weakest] -= 1
    if not counts[weakest]:
        del counts[weakest]
        # What was added to stand at the piece just left out goes with it when nothing
        # it stood at in the plans is left (a desk's chair; what stood on it
        # ``build_graph`` puts elsewhere or leaves out by itself).
        for name in added:
            entry = model.accessories.get(name)
            if entry is None or entry.on or name not in counts:
                continue
            anchors = {anchor.anchor for anchor in entry.anchors}
            if weakest in anchors and not any(counts.get(a) for a in anchors):
                del counts[name]
    return replace(contents, counts=counts)


def completion_record(
    contents: Contents, dropped, model: PlanModel, masked=(), given_up=None, by_region=()
) -> dict:
    """What scene.json's ``completion`` holds: the types, per type the categories
    Algorithm 1 chose (requested or added, with their count, P(category | type) and the
    summed relation weight to the requested ones), its cost and reference plans, and the
    layout mask's reference plans with their weights and the pieces ``masked`` in the
    layout's energy; ``given_up``: category -> pieces of it the room gave up to be laid
    out (``fewer_pieces``; a category given up whole is also in ``left_out``). A room
    split by virtual walls also has ``regions`` (per region its type, rectangle, whether
    its door is virtual, its layout mask and the pieces that belong there, ``by_region``)
    and ``virtual_walls``; its ``mask`` is the first region's."""
    types: dict[str, dict[str, Any]] = {}
    for room_type, exploration in contents.explorations.items():
        entry = model.types[room_type]
        weights = {tuple(pair.pair): pair.weight for pair in entry.pairs}
        requested = [n for n, owner in contents.owners.items() if owner == room_type]
        types[room_type] = {
            "categories": [
                {
                    "category": name,
                    "count": count,
                    "requested": name in requested,
                    "p": entry.probability(name),
                    "weight_to_requested": sum(
                        weights.get((min(name, r), max(name, r)), 0.0)
                        for r in requested
                        if r != name
                    ),
                }
                for name, count in exploration.counts.items()
            ],
            "cost": exploration.cost,
            "references": list(exploration.references),
        }
    record: dict[str, Any] = {
        "types": list(contents.types),
        "owners": dict(sorted(contents.owners.items())),
        "selection": types,
        "counts": {name: n for name, n in contents.counts.items() if name not in dropped},
        "left_out": dict(sorted(dropped.items())),
        "given_up": dict(sorted((given_up or {}).items())),
    }
    if not contents.regions:
        record["mask"] = _mask_record(contents.types[0], contents.room_mask(), masked)
        return record
    from scenewright.completion.regions import virtual_walls

    regions = []
    for k, (region, layout) in enumerate(
        zip(contents.regions, contents.region_masks().masks, strict=False)
    ):
        pieces = list(by_region[k]) if by_region else []
        described: dict[str, Any] = {
            **region.to_dict(),
            **_mask_record(region.room_type, layout, [b for b in pieces if b in masked]),
        }
        described["pieces"] = pieces
        described["categories"] = sorted(
            name
            for name, k_ in contents.region_masks().owners.items()
            if k_ == k and name not in dropped
        )
        regions.append(described)
    record["mask"] = {
        key: regions[0][key] for key in ("type", "frame", "references", "cells", "boxes", "bounds")
    }
    record["regions"] = regions
    record["virtual_walls"] = [[list(a), list(b)] for a, b in virtual_walls(contents.regions)]
    return record


def _mask_record(room_type: str, layout, boxes) -> dict:
    return {
        "type": room_type,
        "frame": layout.frame.to_dict(),
        "references": dict(sorted(layout.weights.items())),
        "cells": np.round(layout.mask, 6).tolist(),
        "boxes": list(boxes),
    }


def complete(
    request: Request,
    seed: int,
    *,
    plans=None,
    model: PlanModel | None = None,
    catalog=None,
    mask_term: bool = True,
    split: bool = True,
    keep=None,
):
    """The completed room as a ``Scene`` (laid out, not yet described): ``plans`` is a
    plan set folder (default: the shipped one), or give a built ``model``. A layout that
    could not satisfy everything comes back with ``scene.layout.ok`` false.
    ``mask_term=False`` leaves the mask out of the layout's energy (it then only
    chooses the starting poses), for comparison; ``split=False`` keeps a room of
    several types whole, with the first type's mask (no virtual walls), likewise.
    ``keep``: a furnished room (a ``Scene``) being completed (``existing_request``):
    what it holds is pinned where it stands (``pin_existing``) and the room is not split
    (its pieces stand where they stand, whatever part a split would give them)."""
    import time

    from scenewright.completion.floor_plan import load_plans
    from scenewright.completion.layout_mask import floor_mask, region_floor_masks
    from scenewright.completion.model_builder import build_model, shipped_model
    from scenewright.core.scene import assemble_scene
    from scenewright.core.seeds import check_seed
    from scenewright.core.timing import timed
    from scenewright.generator import indoor_catalog
    from scenewright.generator.layout import layout_scene

    seed = check_seed(seed)
    timings: dict[str, float] = {}
    with timed(timings, "complete"):
        model = model or (build_model(load_plans(plans)) if plans else shipped_model())
        catalog = catalog or indoor_catalog()
        contents = choose_contents(model, request, split=split and keep is None)
    chosen = dict(contents.counts)
    failed = None  # the last failed try's poses (box id -> Pose), where the next try starts first
    for attempt in range(1 + FIT_ATTEMPTS):
        with timed(timings, "complete"):
            graph, dropped, start = _graph_and_start(model, contents, request.room, catalog)
        large = masked(model, graph)
        masked_ids = large if mask_term else []
        mask: FloorMask | list[FloorMask] | None
        if contents.regions:
            by_region = region_boxes(
                {n.id: n.type for n in graph.nodes("object")},
                [(r.source, r.target, r.label) for r in graph.edges()],
                contents.region_masks().owners,
                len(contents.regions),
                {graph.node(box).type for box in large},
            )
            mask = (
                region_floor_masks(contents.region_masks(), by_region, set(masked_ids))
                if mask_term
                else None
            )
        else:
            by_region = []
            mask = (
                floor_mask(contents.room_mask(), request.room, masked_ids) if masked_ids else None
            )
        pinned = None
        if keep is not None:
            graph, pinned = pin_existing(graph, keep)
            start = {}  # the new pieces go where the layout's own placement finds room among the kept
        with timed(timings, "layout", time.perf_counter):
            layout = None
            if failed is not None:
                boxes = {n.id for n in graph.nodes("object")} - set(pinned or {})
                warm = {box: pose for box, pose in failed.items() if box in boxes}
                layout = layout_scene(
                    graph, seed, start=warm, mask=mask, params=WARM_PARAMS, pinned=pinned
                )
            if layout is None or not layout.ok:
                layout = layout_scene(
                    graph, seed, start=start, mask=mask, params=FIT_PARAMS, pinned=pinned
                )
        if layout.ok or attempt == FIT_ATTEMPTS:
            break
        failed = layout.poses
        smaller = fewer_pieces(model, contents, request, graph, layout.problems)
        if smaller is None:
            break
        contents = smaller
    given_up = {
        name: n - contents.counts.get(name, 0)
        for name, n in chosen.items()
        if contents.counts.get(name, 0) < n
    }
    for name in given_up:
        if name not in contents.counts:
            dropped.setdefault(name, ROOM_FULL)
    assert layout is not None  # the loop lays out at least once
    scene = assemble_scene(graph, layout, rules=contents.types[0], seed=seed)
    scene.completion = completion_record(contents, dropped, model, masked_ids, given_up, by_region)
    scene.timings.update(timings)
    return scene


def pin_existing(graph: SceneGraph, scene) -> tuple[SceneGraph, dict[str, Pose]]:
    """``graph`` with a node for each object of the furnished ``scene`` pinned at its
    pose (a type's nodes in id order for its objects in id order), and between things
    that no longer move (two of those objects, or one and the room) the scene's own
    relations instead of those ``build_graph`` would state: the room had them, or not,
    before it was completed; what is new is placed by its relations to them."""
    from scenewright.core.relations import RELATIONS

    nodes: dict[str, list[str]] = {}
    for node in sorted(graph.nodes("object"), key=lambda n: _id_order(n.id)):
        nodes.setdefault(node.type, []).append(node.id)
    pinned: dict[str, Pose] = {}
    node_of: dict[str, str] = {}
    for obj in sorted(scene.placed_objects(), key=lambda o: _id_order(o.id)):
        node_of[obj.id] = nodes[obj.type].pop(0)
        x, y, z = (float(v) for v in obj.position)
        pinned[node_of[obj.id]] = Pose(x, y, z, float(obj.yaw))
    fixed = set(pinned) | {
        n.id for n in graph.nodes() if n.kind in ("room", "wall", "door", "window")
    }
    kept = replace(graph, graph=graph.graph.copy())
    kept.graph.remove_edges_from(
        [
            (a, b, k)
            for a, b, k, label in kept.graph.edges(keys=True, data="label")
            # a kept piece stays where it stands: not on a support that is new (a lamp the
            # room had on the floor is not lifted onto a nightstand the completion adds)
            if a in fixed and (b in fixed or (a in pinned and _rests_on(label, RELATIONS)))
        ]
    )
    # The scene's own relations among what it holds: a chair's "in front of the desk"
    # also lets it stand in the desk's clearance; what rests on what keeps it on top.
    for relation in scene.relations:
        source, target = node_of.get(relation.source), node_of.get(relation.target, relation.target)
        if source is not None and target in fixed and relation.label in RELATIONS:
            kept.add_relation(source, target, relation.label)
    return kept, pinned


def _rests_on(label: str, relations) -> bool:
    """Whether a relation label rests its source on its target (OnTopOf and the like)."""
    return label in relations and relations[label].support


def _id_order(object_id: str) -> tuple[str, int]:
    """``bed_10`` after ``bed_2``."""
    stem, _, number = object_id.rpartition("_")
    return (stem, int(number)) if number.isdigit() else (object_id, 0)
