"""Lots: what stands beside a road placed along it the way towns are built.

In a large outdoor scene (one the group decomposition lays out, ``decompose``), the
roads are laid first and spread out (``initial_roads``); then every top-level item that
must stand next to a road (a home, a market, a park, a street lamp) gets a *lot*: a
stretch of one side of its road as wide as the item, found by a one-dimensional packing
along the road's polyline (``plan_lots``). Each item knows its width along the road and
its depth from the road from its own arrangement (a group's frame, laid out first: the
house with its garden behind and beside it), turned so that the member the road
relation is about (the house) is nearest the road and faces it. Items take their road's
sides in creation order, each on the side with the most room left; a lot is refused
where the item would touch another road, a lot already given, a junction or the
scene's edge, and the packing then tries a metre further on. The MCMC then refines
the whole layout from there.

``some road`` draws each item's road at random, so one road may be asked for more
frontage than it has while others have room. An item whose road relations were all
drawn that way (``Problem.free_paths``) and that found no lot on its road then takes
one on another road of the same type, after every item has been given its own road's
lots: the road with the most side left first, in creation order, so the same scene
always gets the same roads. Its relations are then pointed at that road
(``Problem.retarget``), and the layout's verdict (scene.json's relations) names it. A
scene where every item found a lot on its own road is laid out exactly as before.

When items do not fit, those left over are placed the ordinary way, and if the layout
ends up not ``ok`` its report says how many metres of frontage were missing
(``shortage``), road by road, or over all the roads of the type for items drawn by
``some road``: "14 houses, 2 street lamps need 150 m of road frontage beside road_7;
its sides give 56 m (3 found no room)", "40 houses need 341 m of road frontage beside
road_1, road_2 and road_3; their sides give 171 m (27 found no room)".

Items that relations tie together but that the rule set did not put in a group (a house
and its garden written as loose objects) are put in a group of their own for the
layout (``wrap_clusters``), so that they get a frame and a lot like a written group.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import networkx as nx

from scenewright.core.geometry import (
    Rect,
    corners,
    polyline_rect_penetration,
    rect_overlap,
    rect_penetration,
)
from scenewright.core.scene_graph import SceneGraph

from .energy import Energy
from .families import LAYOUT_FAMILIES
from .motion import wrap

#: Loose objects tied by relations are grouped for the layout up to this many objects;
#: a bigger cluster (a whole scene tied to one landmark) is left as it was.
MAX_CLUSTER = 24
#: The group type given to such a cluster (never a node a user wrote: the id has a colon).
CLUSTER_TYPE = "cluster"
#: Metres between an item's footprint and the edge of its road.
ROAD_GAP = 0.3
#: Metres kept free between neighbouring lots, and around them when testing overlaps.
LOT_SPACING = 0.6
#: How far (metres) the packing moves on along a side when a lot is refused there.
LOT_STEP = 1.0
#: A member the road relation is about may stand this far (metres) behind the near edge
#: of its item's footprint and still be next to the road.
ANCHOR_SLACK = 1.2
#: Cell (metres) of the grid the given lots are kept in for the overlap tests.
GRID_CELL = 10.0


@dataclass
class LotItem:
    """One top-level item that stands beside a road."""

    unit: tuple[str, int]
    boxes: list[int]  # every box that moves with it
    anchor: int  # the box that faces the road (the related member, or a group's first)
    anchor_bound: bool  # whether the road relation is the anchor's own (not the group's)
    path: int
    name: str  # the type the report counts it by
    # Poses of ``boxes`` in the road's frame (x along the road, z away from it, the
    # item's near edge on z = 0, its left end on x = 0), and its width along the road.
    local: dict[int, tuple[float, float, float]] = field(default_factory=dict)
    width: float = 0.0
    # Its relation terms to ``path``, and the roads it may take instead when all of them
    # were drawn by ``some TYPE`` (``Problem.free_paths``; else empty).
    terms: list[int] = field(default_factory=list)
    roads: tuple[int, ...] = ()


@dataclass
class LotPlan:
    """Where the lots went: poses per placed item, and the items left over."""

    poses: dict[tuple[str, int], dict[int, tuple[float, float, float]]]
    left: list[LotItem]
    items: list[LotItem]
    sides: list[float]  # per road, metres of road side it gives (both sides)
    moved: list[LotItem] = field(default_factory=list)  # items given another road (``path``)


def wrap_clusters(graph: SceneGraph) -> SceneGraph:
    """``graph`` with every cluster of loose objects tied by relations (two to
    ``MAX_CLUSTER`` objects outside any group, joined by relations among themselves) put
    in a group of its own; ``graph`` itself when there is none. Node order, ids and
    edges are kept, so the layout's boxes and relations are the same."""
    whole = graph.graph
    loose = [
        node_id
        for node_id, data in whole.nodes(data=True)
        if data["kind"] == "object" and data["parent"] is None
    ]
    is_loose = set(loose)
    parent = {node_id: node_id for node_id in loose}

    def find(node_id: str) -> str:
        while parent[node_id] != node_id:
            parent[node_id] = parent[parent[node_id]]
            node_id = parent[node_id]
        return node_id

    for source, target in whole.edges():
        if source in is_loose and target in is_loose and find(source) != find(target):
            parent[find(source)] = find(target)
    members: dict[str, list[str]] = {}
    for node_id in loose:
        members.setdefault(find(node_id), []).append(node_id)
    clusters = [m for m in members.values() if 2 <= len(m) <= MAX_CLUSTER]
    if not clusters:
        return graph
    cluster_of = {node_id: k for k, m in enumerate(clusters) for node_id in m}
    ordered = sorted(whole.nodes(data=True), key=lambda item: item[1]["order"])
    wrapped = nx.MultiDiGraph()
    opened: set[int] = set()
    for node_id, data in ordered:
        k = cluster_of.get(node_id)
        if k is not None and k not in opened:
            opened.add(k)
            group_id = f"{node_id}:{CLUSTER_TYPE}"
            wrapped.add_node(
                group_id,
                **{
                    **data,
                    "id": group_id,
                    "type": CLUSTER_TYPE,
                    "kind": "group",
                    "noun": CLUSTER_TYPE,
                    "plural": None,
                    "size": (0.0, 0.0, 0.0),
                    "shape": None,
                    "mesh": None,
                    "style": None,
                    "order": wrapped.number_of_nodes(),
                },
            )
        new = dict(data, order=wrapped.number_of_nodes())
        if k is not None:
            new["parent"] = f"{clusters[k][0]}:{CLUSTER_TYPE}"
        wrapped.add_node(node_id, **new)
    for source, target, data in whole.edges(data=True):
        wrapped.add_edge(source, target, **data)
    return SceneGraph(params=graph.params, graph=wrapped, derivation=graph.derivation)


def frontage_items(
    energy: Energy, frames: Mapping[int, Mapping[int, tuple[float, float, float]]]
) -> list[LotItem]:
    """The top-level items that must stand next to a road, in creation order: a group
    laid out in its own frame, or a lone object with nothing on it, with a placing
    NextTo* to a path (the group's own, or one of its members')."""
    problem = energy.problem
    items = []
    for kind, index in problem.units:
        if kind == "group":
            if index not in frames:
                continue
            boxes = list(problem.group_members[index])
            sources = [("group", index)] + [("object", b) for b in boxes]
        else:
            if problem.is_junction[index] or len(problem.carried(index)) > 1:
                continue
            boxes = [index]
            sources = [("object", index)]
        road = None
        for source in sources:
            for term in problem.outgoing.get(source, []):
                if term.b.kind == "path" and LAYOUT_FAMILIES[term.spec.family].pulls_roads:
                    road = (source, term.b.index)
                    break
            if road:
                break
        if road is None:
            continue
        (source_kind, source_index), path = road
        bound = source_kind == "object"
        anchor = source_index if bound else problem.group_members[index][0]
        name = _type_of(problem.ids[anchor]) if bound or kind == "object" else None
        if name is None:
            name = _type_of(problem.group_ids[index])
        item = LotItem((kind, index), boxes, anchor, bound, path, name)
        ends = set(sources)
        item.terms = [
            t
            for t in problem.terms_of_path[path]
            if (problem.relations[t].a.kind, problem.relations[t].a.index) in ends
            and problem.relations[t].b.kind == "path"
        ]
        if all(t in problem.free_paths for t in item.terms):
            item.roads = problem.free_paths[item.terms[0]]
        _shape(energy, item, frames.get(index) if kind == "group" else None)
        items.append(item)
    return items


def _type_of(node_id: str) -> str:
    """A node's type from its id (``house_12`` -> ``house``)."""
    head, _, tail = node_id.rpartition("_")
    return head if head and tail.isdigit() else node_id


def _shape(energy: Energy, item: LotItem, frame: Mapping | None) -> None:
    """The item's poses in the road's frame: the anchor facing the road (-z), else the
    quarter turn that brings the anchor nearest the road; its width along the road."""
    problem = energy.problem
    poses = dict(frame) if frame is not None else {item.anchor: (0.0, 0.0, 0.0)}
    ground = [b for b in item.boxes if problem.support[b] < 0]
    best = None
    for quarter in range(4):
        turn = wrap(math.pi - poses[item.anchor][2] + quarter * math.pi / 2.0)
        c, s = math.cos(turn), math.sin(turn)
        turned = {
            b: (x * c + z * s, -x * s + z * c, wrap(yaw + turn)) for b, (x, z, yaw) in poses.items()
        }
        rects = {b: _rect(problem, b, turned[b]) for b in ground}
        xs = [p[0] for b in ground for p in corners(rects[b])]
        zs = [p[1] for b in ground for p in corners(rects[b])]
        near = min(zs)
        anchor_near = min(p[1] for p in corners(rects[item.anchor]))
        behind = anchor_near - near
        width = max(xs) - min(xs)
        fits = not item.anchor_bound or behind <= ANCHOR_SLACK
        rank = (not fits, quarter != 0, width)
        if best is None or rank < best[0]:
            best = (rank, turned, min(xs), near, width)
    assert best is not None
    _, turned, left, near, width = best
    item.local = {b: (x - left, z - near, yaw) for b, (x, z, yaw) in turned.items()}
    item.width = width


def _rect(problem, box: int, pose: tuple[float, float, float]) -> Rect:
    x, z, yaw = pose
    return Rect(
        x, z, problem.half_width[box], problem.half_depth[box], math.cos(yaw), math.sin(yaw)
    )


class _Road:
    """A road's polyline by arc length."""

    def __init__(self, points: list) -> None:
        self.points = [(float(p[0]), float(p[1])) for p in points]
        self.starts = [0.0]
        for (ax, az), (bx, bz) in zip(self.points, self.points[1:], strict=False):
            self.starts.append(self.starts[-1] + math.hypot(bx - ax, bz - az))
        self.length = self.starts[-1]

    def at(self, s: float) -> tuple[float, float, float, float]:
        """The point at arc length ``s`` and the unit tangent there."""
        k = 0
        while k + 2 < len(self.starts) and self.starts[k + 1] < s:
            k += 1
        (ax, az), (bx, bz) = self.points[k], self.points[k + 1]
        length = (self.starts[k + 1] - self.starts[k]) or 1.0
        t = (s - self.starts[k]) / length
        return ax + t * (bx - ax), az + t * (bz - az), (bx - ax) / length, (bz - az) / length


class _Taken:
    """Footprints given so far (grown by half the lot spacing), in a grid of cells."""

    def __init__(self) -> None:
        self.cells: dict[tuple[int, int], list[Rect]] = {}

    def _keys(self, rect: Rect):
        points = corners(rect)
        x0, x1 = min(p[0] for p in points), max(p[0] for p in points)
        z0, z1 = min(p[1] for p in points), max(p[1] for p in points)
        for i in range(math.floor(x0 / GRID_CELL), math.floor(x1 / GRID_CELL) + 1):
            for j in range(math.floor(z0 / GRID_CELL), math.floor(z1 / GRID_CELL) + 1):
                yield i, j

    def add(self, rect: Rect) -> None:
        for key in self._keys(rect):
            self.cells.setdefault(key, []).append(rect)

    def hits(self, rect: Rect) -> bool:
        for key in self._keys(rect):
            for other in self.cells.get(key, ()):
                if rect_overlap(rect, other) > 0.0:
                    return True
        return False


def _grown(rect: Rect, margin: float) -> Rect:
    return Rect(rect.cx, rect.cz, rect.hw + margin, rect.hd + margin, rect.c, rect.s)


def plan_lots(energy: Energy, items: list[LotItem]) -> LotPlan:
    """Lots for ``items`` along their roads (module docstring), at the roads as laid now."""
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    roads = [_Road(state.points[p]) for p in range(problem.n_paths)]
    reach = [
        (
            min(x for x, _ in road.points) - problem.path_width[p],
            max(x for x, _ in road.points) + problem.path_width[p],
            min(z for _, z in road.points) - problem.path_width[p],
            max(z for _, z in road.points) + problem.path_width[p],
        )
        for p, road in enumerate(roads)
    ]
    taken = _Taken()
    for box in range(problem.n_boxes):
        if problem.is_junction[box] and energy.active[box]:
            taken.add(_grown(state.rects[box], LOT_SPACING))
    # Each side of each road: where its next lot may start.
    cursor = {(p, side): 0.0 for p in range(problem.n_paths) for side in (1, -1)}
    poses: dict[tuple[str, int], dict[int, tuple[float, float, float]]] = {}
    left: list[LotItem] = []

    def clear(rects: list[Rect]) -> bool:
        for rect in rects:
            for x, z in corners(rect):
                if abs(x) > half_x - 0.05 or abs(z) > half_z - 0.05:
                    return False
            if taken.hits(_grown(rect, LOT_SPACING / 2.0)):
                return False
            points = corners(rect)
            x0, x1 = min(p[0] for p in points), max(p[0] for p in points)
            z0, z1 = min(p[1] for p in points), max(p[1] for p in points)
            for p, road in enumerate(roads):
                rx0, rx1, rz0, rz1 = reach[p]
                if x1 < rx0 or x0 > rx1 or z1 < rz0 or z0 > rz1:
                    continue
                radius = problem.path_width[p] / 2.0 + ROAD_GAP / 2.0
                if polyline_rect_penetration(road.points, radius, rect) > 0.0:
                    return False
        return True

    def place(
        item: LotItem, side: int, s: float, path: int
    ) -> dict[int, tuple[float, float, float]]:
        """The item's poses on a lot from arc length ``s`` on ``side`` of ``path``."""
        px, pz, tx, tz = roads[path].at(s + item.width / 2.0)
        if side < 0:  # the item's frame runs the other way along the road
            tx, tz = -tx, -tz
        # The turn that takes the frame's x axis along the road (and z away from it).
        turn = math.atan2(-tz, tx)
        c, s_ = math.cos(turn), math.sin(turn)
        offset = problem.path_width[path] / 2.0 + ROAD_GAP
        placed = {}
        for box, (lx, lz, yaw) in item.local.items():
            u, v = lx - item.width / 2.0, lz + offset
            placed[box] = (px + u * c + v * s_, pz - u * s_ + v * c, wrap(yaw + turn))
        return placed

    def give(item: LotItem, path: int) -> bool:
        """The next free lot along ``path`` for ``item``, on the side with the most room
        left first; whether one was found."""
        sides = sorted((1, -1), key=lambda side: (cursor[(path, side)], -side))
        for side in sides:
            s = cursor[(path, side)]
            while s + item.width <= roads[path].length:
                placed = place(item, side, s, path)
                rects = [_rect(problem, b, placed[b]) for b in item.boxes if problem.support[b] < 0]
                if clear(rects):
                    for rect in rects:
                        taken.add(rect)
                    poses[item.unit] = placed
                    cursor[(path, side)] = s + item.width + LOT_SPACING
                    return True
                s += LOT_STEP
        return False

    for item in items:
        if not give(item, item.path):
            left.append(item)
    # Items whose roads ``some road`` drew, left without a lot on theirs: each on the
    # other road of its type with the most side left, the next if none is found there.
    moved = []
    for item in list(left):
        others = [p for p in item.roads if p != item.path]
        others.sort(
            key=lambda p: (-sum(roads[p].length - cursor[(p, side)] for side in (1, -1)), p)
        )
        for path in others:
            if give(item, path):
                item.path = path
                left.remove(item)
                moved.append(item)
                break
    return LotPlan(poses, left, items, [2.0 * road.length for road in roads], moved)


def shortage(
    plan: LotPlan, nouns: Mapping[str, tuple[str, str]], path_ids: list[str]
) -> str | None:
    """The report's line when some items got no lot: for each road with items left
    over, how many metres of frontage its items need (by type, ``nouns``: type -> noun
    and plural) against what its two sides give; for items whose road ``some road``
    drew (which found no room on any road of the type), the same over all those roads.
    None when every item got one."""
    if not plan.left:
        return None
    short = sorted({item.roads or (item.path,) for item in plan.left})
    lines = []
    for roads in short:
        beside = [item for item in plan.items if item.path in roads]
        counts: dict[str, list[LotItem]] = {}
        for item in beside:
            counts.setdefault(item.name, []).append(item)
        need = sum(item.width + LOT_SPACING for item in beside)
        named = ", ".join(
            f"{len(items)} {nouns.get(name, (name, name))[len(items) > 1]}"
            for name, items in sorted(counts.items(), key=lambda kv: -len(kv[1]))
        )
        left = sum(1 for item in plan.left if (item.roads or (item.path,)) == roads)
        given = sum(plan.sides[path] for path in roads)
        where = (
            f"beside {path_ids[roads[0]]}; its sides give"
            if len(roads) == 1
            else f"beside {_listed([path_ids[path] for path in roads])}; their sides give"
        )
        lines.append(
            f"{named} need {need:.0f} m of road frontage {where} {given:.0f} m "
            f"({left} found no room)"
        )
    return "; ".join(lines)


def _listed(names: list[str]) -> str:
    """``a, b and c``."""
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


#: ``settle``: pairs of ground boxes overlapping by more than this (metres) are pushed
#: apart, by as much plus ``SETTLE_MARGIN``, if the energy rises by at most
#: ``SETTLE_RISE``; at most ``SETTLE_PASSES`` sweeps (a box wedged between two that
#: was moved once is left, and the other of a later pair moved instead).
SETTLE_DEPTH = 0.005
SETTLE_MARGIN = 0.01
SETTLE_RISE = 0.5
SETTLE_PASSES = 5


def settle(energy: Energy) -> bool:
    """Push apart the boxes a finished layout leaves slightly overlapping.

    The verdict allows an overlap of 1 % of the two footprints' diagonals (8 cm for a
    house and its shed), which the annealing leaves where a relation pulls two boxes
    together. Each such pair found (through a grid of cells) is separated by moving the
    box with the smaller footprint, with what rests on it, straight away from the other
    by the overlap's depth; the move is kept when it costs the energy little (a few
    centimetres do not break a NextTo, nor turn a direction). Returns whether anything
    moved."""
    problem, state = energy.problem, energy.state
    ground = [
        b
        for b in range(problem.n_boxes)
        if problem.support[b] < 0 and not problem.is_junction[b] and energy.active[b]
    ]
    moved, shifted = False, set()
    for _ in range(SETTLE_PASSES):
        cells: dict[tuple[int, int], list[int]] = {}
        for box in ground:
            rect = state.rects[box]
            reach = math.hypot(rect.hw, rect.hd)
            for i in range(
                math.floor((rect.cx - reach) / GRID_CELL),
                math.floor((rect.cx + reach) / GRID_CELL) + 1,
            ):
                for j in range(
                    math.floor((rect.cz - reach) / GRID_CELL),
                    math.floor((rect.cz + reach) / GRID_CELL) + 1,
                ):
                    cells.setdefault((i, j), []).append(box)
        pairs = sorted(
            {
                (a, b)
                for members in cells.values()
                for k, a in enumerate(members)
                for b in members[k + 1 :]
                if rect_penetration(state.rects[a], state.rects[b]) > SETTLE_DEPTH
            }
        )
        if not pairs:
            break
        for a, b in pairs:
            depth = rect_penetration(state.rects[a], state.rects[b])
            if depth <= SETTLE_DEPTH:
                continue
            small, big = (a, b) if problem.size[a] <= problem.size[b] else (b, a)
            if small in shifted:  # wedged between two: move the other, not back again
                small, big = big, small
            for box, other in ((small, big), (big, small)):
                if _separate(energy, box, other, depth):
                    shifted.add(box)
                    moved = True
                    break
    return moved


def _separate(energy: Energy, box: int, other: int, depth: float) -> bool:
    """Move ``box`` (with what rests on it) out of ``other`` by ``depth`` and a margin:
    straight away from it, else along one of ``other``'s sides' normals, the one most
    in that direction first; the first move that leaves at most ``SETTLE_DEPTH`` of
    overlap and raises the energy by at most ``SETTLE_RISE`` is kept."""
    problem, state = energy.problem, energy.state
    if not _free(problem, box):
        return False
    dx, dz = state.x[box] - state.x[other], state.z[box] - state.z[other]
    length = math.hypot(dx, dz) or 1.0
    away = (dx / length, dz / length)
    rect = state.rects[other]
    axes = [(rect.c, -rect.s), (-rect.c, rect.s), (rect.s, rect.c), (-rect.s, -rect.c)]
    axes.sort(key=lambda axis: -(axis[0] * away[0] + axis[1] * away[1]))
    shift = depth + SETTLE_MARGIN
    for ux, uz in [away, *axes[:2]]:
        poses = {
            item: (state.x[item] + ux * shift, state.z[item] + uz * shift, state.yaw[item])
            for item in problem.carried(box)
        }
        delta = energy.propose(poses, {})
        if (
            delta <= SETTLE_RISE
            and rect_penetration(state.rects[box], state.rects[other]) <= SETTLE_DEPTH
        ):
            energy.accept()
            return True
        energy.reject()
    return False


def _free(problem, box: int) -> bool:
    """Whether ``settle`` may move a box: a ground object (junctions stay)."""
    return not problem.is_junction[box] and problem.support[box] < 0
