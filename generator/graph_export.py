"""Scene graphs as Graphviz DOT text, for ``scenewright expand --format dot``.

Groups become clusters holding their members, so the nesting shows; each node is
labelled with its id, type and style, and its tooltip names the production that made
it; each edge carries its relation label (``Implicit*`` ones dashed).
"""

from __future__ import annotations

import json

from scenewright.core.relations import RELATIONS
from scenewright.core.scene_graph import SceneGraph, SceneNode

_INDENT = "  "


def _quote(text: str) -> str:
    # A JSON string is a valid DOT quoted string (same escapes for quotes, backslashes).
    return json.dumps(text)


def _node_line(node: SceneNode) -> str:
    label = f"{node.id}\\n{node.type}" + (f" ({node.style})" if node.style else "")
    shape = {"group": "folder", "path": "cds", "junction": "diamond"}.get(node.kind, "box")
    tooltip = f"rule: {node.rule}" if node.rule else "rule: -"
    return f'{_quote(node.id)} [label="{label}", shape={shape}, tooltip={_quote(tooltip)}];'


def graph_to_dot(graph: SceneGraph) -> str:
    """The graph as a DOT ``digraph``: nodes in creation order, groups as clusters."""
    lines = [f"digraph {_quote(graph.params.name)} {{", f"{_INDENT}node [fontname=Helvetica];"]
    members = graph.by_parent()

    def emit(parent: str | None, depth: int) -> None:
        for node in members.get(parent, []):
            indent = _INDENT * depth
            if node.kind == "group":
                lines.append(f"{indent}subgraph {_quote('cluster_' + node.id)} {{")
                lines.append(f"{indent}{_INDENT}label={_quote(node.id)};")
                lines.append(f"{indent}{_INDENT}{_node_line(node)}")
                emit(node.id, depth + 1)
                lines.append(f"{indent}}}")
            else:
                lines.append(f"{indent}{_node_line(node)}")

    emit(None, 1)
    for edge in graph.edges():
        style = ", style=dashed" if RELATIONS[edge.label].implicit else ""
        lines.append(
            f"{_INDENT}{_quote(edge.source)} -> {_quote(edge.target)} [label={_quote(edge.label)}{style}];"
        )
    lines.append("}")
    return "\n".join(lines) + "\n"
