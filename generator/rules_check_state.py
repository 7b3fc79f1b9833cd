"""What the static checks of a rule set share while they run.

``CheckState`` holds the diagnostics found so far and what the checks learn of the rule
set on the way (its types, its productions, the types some statement creates, the
scene's room and node limit), and reports errors and warnings. Each kind of check
(``rules_check_catalog``, ``rules_check_scene``, ``rules_check_productions``,
``rules_check_grammar``) extends it; ``rules_check`` runs them in order.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from scenewright.core.limits import forbidden_character
from scenewright.core.room import Room

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_check_values import DEFAULT_MAX_NODES
from .rules_errors import WARNING, Diagnostic, SourceTexts
from .rules_scope import ReadScope


@dataclass
class CheckState:
    """The diagnostics of a rule set found so far, and what the checks know of it."""

    sources: SourceTexts
    paths: dict[str, Path]
    scope: ReadScope  # where the rule set may read files: meshes and templates must lie in it
    diagnostics: list[Diagnostic] = field(default_factory=list)
    kinds: dict[str, str] = field(default_factory=dict)  # type name -> kind
    productions: dict[str, ast.Production] = field(default_factory=dict)  # the first of each name
    created_types: set[str] = field(default_factory=set)  # types some statement creates
    #: Type -> the statements that create it and whether each may make none (``0.6? T``,
    #: ``0..2 T``): a ``some T`` where every one may is a warning (``check_type_reference``).
    makers: dict[str, list[tuple[bool, SourceLocation]]] = field(default_factory=dict)
    max_nodes: int = DEFAULT_MAX_NODES  # the scene's, once its block is checked
    room: Room | None = None  # the scene's room, once its block is checked
    has_room: bool = False  # the scene declares a room (even one with errors)

    def error(self, location: SourceLocation, message: str) -> None:
        self.diagnostics.append(self.sources.diagnostic(location, message))

    def warning(self, location: SourceLocation, message: str) -> None:
        self.diagnostics.append(self.sources.diagnostic(location, message, WARNING))

    def check_text(self, name: str, value: str, at: SourceLocation) -> bool:
        """Error (and True) when a string holds a control or bidirectional-control
        character, which would garble or reorder the lines it is printed on."""
        bad = forbidden_character(value)
        if bad is not None:
            self.error(
                at,
                f"'{name}' contains the character {bad}; text may not hold control or "
                "bidirectional-control characters",
            )
        return bad is not None

    def folder_of(self, setting: ast.Setting) -> Path:
        """The folder of the file a setting is written in: its paths are relative to it."""
        return self.paths[setting.location.file].parent
