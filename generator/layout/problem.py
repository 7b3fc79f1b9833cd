"""A scene graph compiled into the flat, indexed form the energy and sampler work on.

Objects and junctions become numbered boxes (junctions are flat boxes paths start
from); groups become the tuple of boxes they contain; paths become numbered polylines;
every relation edge becomes a ``RelationTerm`` whose endpoints say what geometry they
stand for. Per box and per path the terms that touch it are listed up front, so a move
re-evaluates only those.

Line of sight (a room with ``line_of_sight``): "in front of" / "behind" (next-to labels
whose directions are on B's own front or back) and FacingTowards / FacingAwayFrom
between two objects do not hold through a tall object standing between them. Each such
term lists, in ``sight``, the ground boxes at least ``SIGHT_HEIGHT`` tall that could
stand in the way (all but A, B and what they rest on or carry), and those boxes list
the term in ``terms_of_box``, so moving a tall box re-evaluates the relations it may
block.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS, RelationLabel
from scenewright.core.room import ROOM_KINDS, ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph

from .families import LAYOUT_FAMILIES
from .families.entry import room_is_fixed
from .terms import Endpoint, RelationTerm

if TYPE_CHECKING:  # made after the problem, from it and a mask or a context
    from .learned_term import CompiledLearned
    from .mask_term import CompiledMask

#: Line of sight: a ground box at least this tall (metres) blocks the view between two
#: objects (a seated person's eye height: a desk or a sofa does not, a wardrobe does).
SIGHT_HEIGHT = 1.2


def needs_sight(spec: RelationLabel) -> bool:
    """Whether a label needs a clear view from A to B (its family says: a next-to label
    whose directions are all on B's own front or back, "in front of" or "behind", or
    facing towards or away from B)."""
    family = LAYOUT_FAMILIES.get(spec.family)
    return family is not None and family.needs_sight(spec)


#: Boxes on the ground at most this tall (metres; rugs, mats) are floor coverings, a
#: layer of their own: furniture stands on them (they collide only with each other),
#: and they block no corridor, door swing, clearance zone or window.
FLAT_HEIGHT = 0.05


@dataclass
class Problem:
    """Static data of one layout problem (nothing here changes while sampling)."""

    ids: list[str]  # box ids: objects and junctions, creation order
    is_junction: list[bool]
    half_width: list[float]
    half_depth: list[float]
    height: list[float]
    size: list[float]  # footprint diagonal, the normaliser of penetration depths
    support: list[int]  # the box each box rests on, -1 for the ground
    dependents: list[list[int]]  # boxes resting directly on each box
    group_ids: list[str]
    group_members: list[tuple[int, ...]]  # boxes inside each group (nested ones too)
    path_ids: list[str]
    path_width: list[float]
    path_max_length: list[float]
    path_segments: list[int]
    path_start: list[int]  # junction box a path starts at, -1 if free
    relations: list[RelationTerm]
    #: Every edge of the graph in order, as (source, target, label, index of its term in
    #: ``relations``, or None for a structural edge such as PathConnectedTo).
    edges: list[tuple[str, str, str, int | None]]
    extent: tuple[float, float]
    #: The walls, doors and windows (None outdoors), and the room's layout policies.
    room: Room | None
    square: bool
    line_of_sight: bool
    clearance: list[tuple[tuple[str, float], ...]]  # per box: free floor to keep, by side
    access: list[tuple[str, ...]]  # per box: the sides a person uses it from
    terms_of_box: list[list[int]] = field(default_factory=list)
    #: Per box, whether it is a floor covering (``FLAT_HEIGHT``): the layer under furniture.
    covering: list[bool] = field(default_factory=list)
    terms_of_path: list[list[int]] = field(default_factory=list)
    paths_of_junction: dict[int, list[int]] = field(default_factory=dict)
    top_groups: list[int] = field(default_factory=list)  # groups not inside another group
    free_boxes: list[int] = field(default_factory=list)  # ground boxes in no group, no junctions
    units: list[tuple[str, int]] = field(
        default_factory=list
    )  # ("group", g) / ("object", box): top groups and free boxes, creation order
    outgoing: dict[tuple[str, int], list[RelationTerm]] = field(
        default_factory=dict
    )  # by (kind, index) of A
    incoming: dict[tuple[str, int], list[RelationTerm]] = field(
        default_factory=dict
    )  # by (kind, index) of B
    #: Per relation term to a path whose target ``some TYPE`` drew (``SceneGraph``: the
    #: edge's ``some``), every path of that type, in path order: the lots may give the
    #: relation another of them (``lots.plan_lots``, ``retarget``).
    free_paths: dict[int, tuple[int, ...]] = field(default_factory=dict)
    #: Per path, the path it branches from (``road PathConnectedTo other_road``: it
    #: starts at a point along that one, a T junction), -1 if none; per path, its
    #: branches; and the paths in an order where each comes after the one it branches
    #: from (the order they are laid in).
    path_parent: list[int] = field(default_factory=list)
    branches_of: dict[int, list[int]] = field(default_factory=dict)
    path_order: list[int] = field(default_factory=list)
    #: Per box: a junction that starts a grid (``network grid``); per path: whether it
    #: belongs to a grid (it starts at a grid's junction, or branches from a grid's
    #: road). A grid's roads are laid straight and square, and stay where they are laid.
    grid: list[bool] = field(default_factory=list)
    #: Per box: how far a wall label keeps its back off the wall (catalog ``wall_gap``;
    #: 0: flush).
    wall_gap: list[float] = field(default_factory=list)
    path_grid: list[bool] = field(default_factory=list)
    #: The layout mask the energy's ``mask`` part reads (``mask_term.CompiledMask``);
    #: None (no such part) unless ``layout_scene`` or ``measure_layout`` is given one.
    mask: CompiledMask | None = None
    #: The learned pairs the energy's ``learned`` part reads (``learned_term.CompiledLearned``);
    #: None (no such part) unless ``layout_scene`` is given a context.
    learned: CompiledLearned | None = None

    @property
    def walls(self) -> bool:
        """Whether the scene is a room bounded by walls."""
        return self.room is not None

    def indoors(self) -> Room:
        """The room, where only a room has what is asked for (walls, openings)."""
        assert self.room is not None, "a room's part asked for outdoors"
        return self.room

    @property
    def n_boxes(self) -> int:
        return len(self.ids)

    @property
    def n_paths(self) -> int:
        return len(self.path_ids)

    def beneath(self, box: int) -> list[int]:
        """The boxes under ``box``: its support, that one's support, ... down to the ground."""
        found = []
        below = self.support[box]
        while below >= 0:
            found.append(below)
            below = self.support[below]
        return found

    def with_own_relations(self) -> Problem:
        """A copy whose relations (and the lists that index them) ``retarget`` may change
        without changing this problem's: one chain's choice of roads is its own."""
        return replace(
            self,
            relations=list(self.relations),
            edges=list(self.edges),
            terms_of_path=[list(terms) for terms in self.terms_of_path],
            outgoing={key: list(terms) for key, terms in self.outgoing.items()},
            incoming={key: list(terms) for key, terms in self.incoming.items()},
        )

    def retarget(self, term_index: int, path: int) -> None:
        """Point relation ``term_index`` (B a path, one of ``free_paths[term_index]``) at
        ``path`` instead; its edge then names that path (the layout's verdict and
        scene.json say which road was used). Only before the relation's boxes are placed:
        the energy's caches of it are empty then."""
        old = self.relations[term_index]
        assert old.b.kind == "path" and path in self.free_paths.get(term_index, ())
        if old.b.index == path:
            return
        new = replace(old, target=self.path_ids[path], b=Endpoint("path", path, ()))
        self.relations[term_index] = new
        position = next(k for k, edge in enumerate(self.edges) if edge[3] == term_index)
        source, _, label, _ = self.edges[position]
        self.edges[position] = (source, new.target, label, term_index)
        self.terms_of_path[old.b.index].remove(term_index)
        self.terms_of_path[path] = sorted(self.terms_of_path[path] + [term_index])
        mine = self.outgoing[(old.a.kind, old.a.index)]
        mine[mine.index(old)] = new
        for end in (old.b.index, path):  # in term order, as compiled
            self.incoming[("path", end)] = [
                self.relations[t]
                for t in self.terms_of_path[end]
                if self.relations[t].b == Endpoint("path", end, ())
            ]

    def carried(self, box: int) -> list[int]:
        """The box and everything resting on it, transitively (they move together)."""
        found = [box]
        for item in found:
            found.extend(self.dependents[item])
        return found


def compile_problem(graph: SceneGraph) -> Problem:
    """Index a scene graph's nodes and relations; refuse relations that cannot be laid out."""
    ids: list[str] = []
    is_junction: list[bool] = []
    half_width: list[float] = []
    half_depth: list[float] = []
    height: list[float] = []
    size: list[float] = []
    clearance: list[tuple[tuple[str, float], ...]] = []
    access: list[tuple[str, ...]] = []
    grid: list[bool] = []
    wall_gap: list[float] = []
    path_ids: list[str] = []
    path_width: list[float] = []
    path_max_length: list[float] = []
    path_segments: list[int] = []
    path_types: list[str] = []
    group_ids: list[str] = []
    box_index: dict[str, int] = {}
    path_index: dict[str, int] = {}
    group_index: dict[str, int] = {}
    parent_of: dict[str, str | None] = {}
    for node in graph.nodes():
        parent_of[node.id] = node.parent
        if node.kind in ("object", "junction"):
            box_index[node.id] = len(ids)
            ids.append(node.id)
            is_junction.append(node.kind == "junction")
            width, tall, depth = (max(float(v), 1e-3) for v in node.size)
            half_width.append(width / 2.0)
            half_depth.append(depth / 2.0)
            height.append(tall)
            size.append(math.hypot(width, depth))
            clearance.append(node.clearance)
            access.append(node.access)
            grid.append(node.network == "grid")
            wall_gap.append(float(node.wall_gap or 0.0))
        elif node.kind == "path":
            path_index[node.id] = len(path_ids)
            path_ids.append(node.id)
            path_width.append(float(node.width or 3.0))
            path_max_length.append(float(node.max_length or 30.0))
            path_segments.append(max(int(node.segments or 1), 1))
            path_types.append(node.type)
        elif node.kind in ROOM_KINDS:
            continue  # fixed: the room's parts are endpoints, not boxes
        else:
            group_index[node.id] = len(group_ids)
            group_ids.append(node.id)

    group_members: list[list[int]] = [[] for _ in group_ids]
    for node_id, box in box_index.items():
        ancestor = parent_of[node_id]
        while ancestor is not None:
            if ancestor in group_index:
                group_members[group_index[ancestor]].append(box)
            ancestor = parent_of.get(ancestor)

    room = graph.params.room
    room_parts = {}
    if room is not None:
        room_parts[ROOM_NODE] = Endpoint("room", 0, ())
        room_parts.update({wall.id: Endpoint("wall", k, ()) for k, wall in enumerate(room.walls)})
        room_parts.update({o.id: Endpoint("opening", k, ()) for k, o in enumerate(room.openings)})

    def endpoint(node_id: str) -> Endpoint:
        if node_id in room_parts:
            return room_parts[node_id]
        if node_id in box_index:
            return Endpoint("object", box_index[node_id], (box_index[node_id],))
        if node_id in path_index:
            return Endpoint("path", path_index[node_id], ())
        group = group_index[node_id]
        return Endpoint("group", group, tuple(group_members[group]))

    support = [-1] * len(ids)
    path_start = [-1] * len(path_ids)
    path_parent = [-1] * len(path_ids)
    relations: list[RelationTerm] = []
    edges: list[tuple[str, str, str, int | None]] = []
    free_paths: dict[int, tuple[int, ...]] = {}
    drawn = (data.get("some", False) for _, _, data in graph.graph.edges(data=True))
    for edge, some in zip(graph.edges(), drawn, strict=True):
        spec = RELATIONS[edge.label]
        if spec.family == "structural":
            path, start = _path_connection(edge, path_index, box_index)
            if start[0] == "path" or path_parent[path] >= 0:
                _refuse_second_start(edge, path, path_start, path_parent, path_ids, ids)
            if start[0] == "path":
                path_parent[path] = start[1]
            else:
                path_start[path] = start[1]
            edges.append((edge.source, edge.target, edge.label, None))
            continue
        a, b = endpoint(edge.source), endpoint(edge.target)
        _refuse_room_misuse(edge, spec, a, b, room)
        if spec.support:
            if a.kind != "object" or b.kind != "object":
                raise InputError(
                    f"{edge.source} {edge.label} {edge.target}: only objects can rest on objects"
                )
            if support[a.index] == -1:
                support[a.index] = b.index
        if some and b.kind == "path":
            free_paths[len(relations)] = tuple(
                p for p, kind in enumerate(path_types) if kind == path_types[b.index]
            )
        edges.append((edge.source, edge.target, edge.label, len(relations)))
        relations.append(RelationTerm(edge.source, edge.target, edge.label, spec, a, b))

    dependents: list[list[int]] = [[] for _ in ids]
    for box, below in enumerate(support):
        if below >= 0:
            dependents[below].append(box)
    _refuse_support_cycles(support, ids)
    if room is not None and graph.params.line_of_sight:
        relations = _with_sight(relations, support, dependents, is_junction, height)

    problem = Problem(
        ids=ids,
        is_junction=is_junction,
        half_width=half_width,
        half_depth=half_depth,
        height=height,
        size=size,
        support=support,
        dependents=dependents,
        group_ids=group_ids,
        group_members=[tuple(m) for m in group_members],
        path_ids=path_ids,
        path_width=path_width,
        path_max_length=path_max_length,
        path_segments=path_segments,
        path_start=path_start,
        relations=relations,
        edges=edges,
        extent=(float(graph.params.extent[0]), float(graph.params.extent[1])),
        room=room,
        square=graph.params.square,
        line_of_sight=graph.params.line_of_sight,
        clearance=clearance,
        access=access,
        free_paths=free_paths,
        grid=grid,
        wall_gap=wall_gap,
        path_parent=path_parent,
        path_order=_branch_order(path_parent, path_ids),
    )
    for path in problem.path_order:  # a branch belongs to its road's network
        parent = path_parent[path]
        if parent >= 0:
            problem.branches_of.setdefault(parent, []).append(path)
    problem.path_grid = [False] * len(path_ids)
    for path in problem.path_order:
        junction, parent = path_start[path], path_parent[path]
        problem.path_grid[path] = (junction >= 0 and grid[junction]) or (
            parent >= 0 and problem.path_grid[parent]
        )
    problem.terms_of_box = [[] for _ in ids]
    problem.terms_of_path = [[] for _ in path_ids]
    problem.covering = [
        support[b] == -1 and not is_junction[b] and height[b] <= FLAT_HEIGHT
        for b in range(len(ids))
    ]
    for term_index, term in enumerate(relations):
        for end in (term.a, term.b):
            for box in end.members:
                if term_index not in problem.terms_of_box[box]:
                    problem.terms_of_box[box].append(term_index)
            if end.kind == "path" and term_index not in problem.terms_of_path[end.index]:
                problem.terms_of_path[end.index].append(term_index)
        for box in term.sight:  # a tall box moving may block or clear the view
            if term_index not in problem.terms_of_box[box]:
                problem.terms_of_box[box].append(term_index)
    for term in relations:
        problem.outgoing.setdefault((term.a.kind, term.a.index), []).append(term)
        problem.incoming.setdefault((term.b.kind, term.b.index), []).append(term)
    for path, junction in enumerate(path_start):
        if junction >= 0:
            problem.paths_of_junction.setdefault(junction, []).append(path)
    problem.top_groups = [g for g, gid in enumerate(group_ids) if parent_of[gid] not in group_index]
    problem.free_boxes = [
        box
        for box, box_id in enumerate(ids)
        if parent_of[box_id] is None and support[box] == -1 and not is_junction[box]
    ]
    for node in graph.nodes():
        if node.id in group_index and group_index[node.id] in problem.top_groups:
            problem.units.append(("group", group_index[node.id]))
        elif node.id in box_index and box_index[node.id] in problem.free_boxes:
            problem.units.append(("object", box_index[node.id]))
    return problem


def _with_sight(relations, support, dependents, is_junction, height) -> list[RelationTerm]:
    """The relations, each one that needs a clear view between two objects given the
    tall ground boxes that may block it (``RelationTerm.sight``)."""
    tall = [
        box
        for box in range(len(support))
        if support[box] == -1 and not is_junction[box] and height[box] >= SIGHT_HEIGHT
    ]
    if not tall:
        return relations

    def stack(box: int) -> set[int]:  # the box, what it rests on and what rests on it
        found, below = {box}, support[box]
        while below >= 0:
            found.add(below)
            below = support[below]
        todo = [box]
        while todo:
            for above in dependents[todo.pop()]:
                found.add(above)
                todo.append(above)
        return found

    out = []
    for term in relations:
        if term.a.kind == "object" and term.b.kind == "object" and needs_sight(term.spec):
            own = stack(term.a.index) | stack(term.b.index)
            blockers = tuple(box for box in tall if box not in own)
            if blockers:
                term = replace(term, sight=blockers)
        out.append(term)
    return out


def _refuse_room_misuse(
    edge, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """Each family checks its ends (wall labels stand an object against a room's wall or
    window; AlignedWith lines up two objects); and a room's parts are fixed, so they
    cannot be placed."""
    LAYOUT_FAMILIES[spec.family].check_ends(edge, spec, a, b, room)
    room_is_fixed(edge, spec, a, b, room)


def _path_connection(edge, path_index: dict, box_index: dict) -> tuple[int, tuple[str, int]]:
    """(path, where it starts) of a PathConnectedTo edge: ("junction", box) for a path
    and a junction written either way round, ("path", parent) for a path that branches
    from another (the source branches from the target)."""
    if edge.source in path_index and edge.target in path_index:
        return path_index[edge.source], ("path", path_index[edge.target])
    if edge.source in path_index and edge.target in box_index:
        return path_index[edge.source], ("junction", box_index[edge.target])
    if edge.target in path_index and edge.source in box_index:
        return path_index[edge.target], ("junction", box_index[edge.source])
    raise InputError(
        f"{edge.source} PathConnectedTo {edge.target}: needs a path and a junction, or two paths"
    )


def _refuse_second_start(edge, path, path_start, path_parent, path_ids, ids) -> None:
    """A branch starts on one road only, and not at a junction too."""
    if path_parent[path] >= 0:
        where = path_ids[path_parent[path]]
    elif path_start[path] >= 0:
        where = ids[path_start[path]]
    else:
        return
    raise InputError(
        f"{edge.source} PathConnectedTo {edge.target}: {path_ids[path]} already starts at "
        f"{where}; a path starts at one junction or branches from one path"
    )


def _branch_order(path_parent: list[int], path_ids: list[str]) -> list[int]:
    """The paths, each after the one it branches from (else in path order); a cycle of
    branches is refused."""
    order: list[int] = []
    placed = [False] * len(path_parent)
    for path in range(len(path_parent)):
        chain: list[int] = []
        seen: set[int] = set()
        while path >= 0 and not placed[path]:
            if path in seen:
                cycle = [*chain[chain.index(path) :], path]
                names = " -> ".join(path_ids[p] for p in cycle)
                raise InputError(f"paths branch from each other in a circle: {names}")
            seen.add(path)
            chain.append(path)
            path = path_parent[path]
        for link in reversed(chain):
            placed[link] = True
            order.append(link)
    return order


def _refuse_support_cycles(support: list[int], ids: list[str]) -> None:
    for start in range(len(support)):
        seen = {start}
        below = support[start]
        while below >= 0:
            if below in seen:
                raise InputError(
                    f"{ids[start]} rests on itself through a cycle of OnTopOf relations"
                )
            seen.add(below)
            below = support[below]
