"""The Augmented Graph: the examples' structure graphs merged through their matchings.

Each node is a set of matched objects (members: example and object id), each edge the
union of the relation sets its members' edges have. Built as the paper does: the
layout subgraphs are matched pairwise, the pair with the most kept pairs is merged
first, then again and again the example with the most kept pairs against the graph
merged so far. Against a merged graph, a node's object similarity is the largest of
its members', and an edge's similarity the largest of its member edges' (the paper's
max rule). Matched objects join their node; unmatched ones become nodes of their own
(node augmentation); edges and relation sets follow from the members (edge and
attribution augmentation). Supported objects are added last, each a node of its own
resting on its supporter's node. Every input object belongs to exactly one node.

Deterministic: ties go to the earlier example, and node ids (``n1``, ``n2``, ...) follow
the order nodes are made.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from scenewright.examples import Example

from .matching import (
    CONFIDENCE,
    LAMBDA,
    EdgeTable,
    Problem,
    box_similarity,
    edge_similarity,
    match_graphs,
    place_similarity,
    solve,
    withdraw,
)
from .structure import RELATION_CODES, StructureGraph, structure_graph

Member = tuple[int, str]  # (example index, object id)


@dataclass
class AGNode:
    """A node: its members, and for a supported node the node it rests on."""

    id: str
    members: list[Member]
    supporter: str | None = None

    @property
    def supported(self) -> bool:
        return self.supporter is not None


@dataclass
class AugmentedGraph:
    """Nodes, the node of every input object, and the edges (node pair -> relations and
    the member pairs that have them)."""

    examples: list[Example]
    graphs: list[StructureGraph]
    nodes: list[AGNode] = field(default_factory=list)
    node_of: dict[Member, str] = field(default_factory=dict)
    edges: dict[tuple[str, str], set[str]] = field(default_factory=dict)
    sources: dict[tuple[str, str], list[tuple[int, str, str]]] = field(default_factory=dict)

    def node(self, node_id: str) -> AGNode:
        return self.nodes[int(node_id[1:]) - 1]

    def add_node(self, members: list[Member], supporter: str | None = None) -> AGNode:
        node = AGNode(f"n{len(self.nodes) + 1}", list(members), supporter)
        self.nodes.append(node)
        for member in members:
            self.node_of[member] = node.id
        return node

    def layout_nodes(self) -> list[AGNode]:
        return [n for n in self.nodes if not n.supported]

    def neighbours(self, node_id: str) -> list[str]:
        return sorted({b for (a, b) in self.edges if a == node_id}, key=lambda n: int(n[1:]))

    def index(self, member: Member) -> int:
        return self.graphs[member[0]].index(member[1])

    def derive_edges(self) -> None:
        """Edges and relation sets from the members' structure-graph edges (both directions)."""
        self.edges.clear()
        self.sources.clear()
        for e, graph in enumerate(self.graphs):
            for (i, j), edge in sorted(graph.edges.items()):
                if not edge.relations:
                    continue
                key = (self.node_of[(e, graph.ids[i])], self.node_of[(e, graph.ids[j])])
                if key[0] == key[1]:
                    continue
                self.edges.setdefault(key, set()).update(edge.relations)
                self.sources.setdefault(key, []).append((e, graph.ids[i], graph.ids[j]))

    def to_dict(self) -> dict:
        """Plain data: examples, nodes with members, edges (each node pair once) with relations."""

        def member(m: Member) -> dict:
            graph = self.graphs[m[0]]
            k = graph.index(m[1])
            return {
                "example": self.examples[m[0]].name,
                "object": m[1],
                "type": graph.types[k],
                "style": graph.styles[k],
                "size": [round(float(v), 4) for v in graph.sizes[k]],
            }

        return {
            "examples": [
                {"name": e.name, "path": e.path, "format": e.format} for e in self.examples
            ],
            "nodes": [
                {"id": n.id, "supported_by": n.supporter, "members": [member(m) for m in n.members]}
                for n in self.nodes
            ],
            "edges": [
                {
                    "a": a,
                    "b": b,
                    "relations": _ordered(
                        self.edges[(a, b)] | _mirrored(self.edges.get((b, a), set()))
                    ),
                    "pairs": [[self.examples[e].name, x, y] for e, x, y in self.sources[(a, b)]],
                }
                for (a, b) in sorted(self.edges, key=lambda k: (int(k[0][1:]), int(k[1][1:])))
                if int(a[1:]) < int(b[1:])
            ],
        }

    def to_dot(self) -> str:
        """Graphviz text: layout nodes as boxes, supported ones as ellipses, edges labelled with relation codes."""
        lines = ["digraph augmented {", "  node [fontname=Helvetica, fontsize=10];"]
        for node in self.nodes:
            names = sorted({self.graphs[e].types[self.graphs[e].index(o)] for e, o in node.members})
            label = f"{node.id}\\n{', '.join(names)}\\n{len(node.members)} member{'s' * (len(node.members) != 1)}"
            shape = "ellipse" if node.supported else "box"
            lines.append(f'  {node.id} [shape={shape}, label="{label}"];')
        for item in self.to_dict()["edges"]:
            lines.append(
                f'  {item["a"]} -> {item["b"]} [dir=none, label="{"".join(item["relations"])}"];'
            )
        lines.append("}")
        return "\n".join(lines) + "\n"


def _mirrored(relations: set[str]) -> set[str]:
    swap = {"S": "s", "s": "S"}
    return {swap.get(r, r) for r in relations}


def _ordered(relations: set[str]) -> list[str]:
    return sorted(relations, key=lambda code: (RELATION_CODES.index(code.upper()), code.islower()))


def augment(
    examples: list[Example], *, threshold: float = CONFIDENCE, lam: float = LAMBDA
) -> AugmentedGraph:
    """The Augmented Graph of ``examples`` (see the module docstring)."""
    graphs = [structure_graph(e.scene) for e in examples]
    ag = AugmentedGraph(examples, graphs)
    first = _first_pair(graphs, threshold, lam)
    for member in graphs[first].layout_nodes():
        ag.add_node([(first, graphs[first].ids[member])])
    left = [k for k in range(len(graphs)) if k != first]
    while left:
        matchings = {k: _match_to_ag(ag, k, threshold, lam) for k in left}
        chosen = max(left, key=lambda k: (len(matchings[k]), -k))
        graph = graphs[chosen]
        for i in graph.layout_nodes():
            object_id = graph.ids[i]
            if object_id in matchings[chosen]:
                node = ag.node(matchings[chosen][object_id])
                node.members.append((chosen, object_id))
                ag.node_of[(chosen, object_id)] = node.id
            else:
                ag.add_node([(chosen, object_id)])
        left.remove(chosen)
    _add_supported(ag)
    ag.derive_edges()
    return ag


def _first_pair(graphs: list[StructureGraph], threshold: float, lam: float) -> int:
    """The example to start from: one of the pair with the most kept matches (the earlier on a tie)."""
    best, best_count = 0, -1
    for a in range(len(graphs)):
        for b in range(a + 1, len(graphs)):
            count = len(match_graphs(graphs[a], graphs[b], threshold=threshold, lam=lam).pairs)
            if count > best_count:
                best, best_count = a, count
    return best


def _add_supported(ag: AugmentedGraph) -> None:
    """Each supported object a node of its own, resting on its supporter's node (supporters first)."""
    pending = [
        (e, g.ids[i]) for e, g in enumerate(ag.graphs) for i in range(len(g)) if i in g.supporter
    ]
    while pending:
        for member in list(pending):
            graph = ag.graphs[member[0]]
            below = (member[0], graph.ids[graph.supporter[graph.index(member[1])]])
            if below in ag.node_of:
                ag.add_node([member], supporter=ag.node_of[below])
                pending.remove(member)


def _match_to_ag(ag: AugmentedGraph, k: int, threshold: float, lam: float) -> dict[str, str]:
    """Object id of example k -> the AG node it is matched to (kept pairs only)."""
    graph = ag.graphs[k]
    nodes = ag.layout_nodes()
    nodes_b = graph.layout_nodes()
    if not nodes or not nodes_b:
        return {}
    position = {node.id: p for p, node in enumerate(nodes)}
    unary = np.zeros((len(nodes), len(nodes_b)))
    place = np.zeros((len(nodes), len(nodes_b)))
    for p, node in enumerate(nodes):
        sizes = np.array([ag.graphs[e].sizes[ag.index((e, o))] for e, o in node.members])
        unary[p] = box_similarity(sizes, graph.sizes[nodes_b]).max(axis=0)
        places = np.array([ag.graphs[e].places[ag.index((e, o))] for e, o in node.members])
        place[p] = place_similarity(places, graph.places[nodes_b]).max(axis=0)
    table_b = EdgeTable.of(graph, nodes_b)
    rows = []
    for e, member_graph in enumerate(ag.graphs):
        members = [i for i in member_graph.layout_nodes() if (e, member_graph.ids[i]) in ag.node_of]
        if not members:
            continue
        table = EdgeTable.of(member_graph, members)
        to_ag = np.array([position[ag.node_of[(e, member_graph.ids[i])]] for i in members])
        rows.append((table, to_ag))
    first, pairwise = _max_table(rows, table_b)
    problem = Problem(unary, first, table_b, pairwise, lam, place)
    assignment = solve(problem)
    _, kept = withdraw(problem, assignment, threshold)
    return {graph.ids[nodes_b[assignment[p]]]: nodes[p].id for p in range(len(nodes)) if kept[p]}


def _max_table(
    rows: list[tuple[EdgeTable, np.ndarray]], second: EdgeTable
) -> tuple[EdgeTable, np.ndarray]:
    """The AG's edge table (one row per node pair, relations united) and each row's
    similarity to ``second``'s edges: the largest of its member edges'."""
    keys: dict[tuple[int, int], int] = {}
    merged: list[list] = []
    similarity_rows: list[np.ndarray] = []
    for table, to_ag in rows:
        similarities = edge_similarity(table, second)
        for r in range(len(table)):
            key = (int(to_ag[table.source[r]]), int(to_ag[table.target[r]]))
            if key[0] == key[1]:
                continue
            if key not in keys:
                keys[key] = len(merged)
                merged.append([*key, *table.row(r)[2:]])
                similarity_rows.append(similarities[r].copy())
            else:
                at = keys[key]
                merged[at][2:6] = np.maximum(merged[at][2:6], table.grades[r]).tolist()
                similarity_rows[at] = np.maximum(similarity_rows[at], similarities[r])
    table = EdgeTable.from_rows(merged)
    pairwise = np.array(similarity_rows).reshape(len(merged), len(second))
    return table, pairwise
