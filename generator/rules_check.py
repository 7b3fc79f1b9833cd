"""Static checks of a parsed rule set: everything that can be wrong before expansion.

``check_tree`` looks at a file and its includes together and returns diagnostics in
file order: the catalog (fields, values, nouns of at most ``MAX_NOUN_CHARS``, styles,
mesh files that must load and lie in the rule set's ``ReadScope``, shape names the
renderer must know - a warning), the scene block (and its templates folder, in the
scope too), and the productions (labels, types, names in scope, calls and their
arguments, counts, probabilities and weights, blocks on groups only, PathConnectedTo
from a path to a junction), then the whole grammar: undefined nonterminals,
nonterminals that can never finish expanding (a fixpoint over the alternatives), and -
as warnings - nonterminals the start symbol never reaches and types no statement
creates.
Numbers must lie within the bounds of ``scenewright.core.limits`` and text may hold
no control or bidirectional-control characters.
A rule set with no error diagnostics is safe to turn into a catalog and to expand.

Each kind of check is a module of its own (``rules_check_catalog``,
``rules_check_scene``, ``rules_check_productions``, ``rules_check_grammar``), sharing
``rules_check_state``; this one runs them in order over the whole rule set.
"""

from __future__ import annotations

from . import rules_ast as ast
from .rules_check_catalog import CatalogChecks
from .rules_check_grammar import GrammarChecks
from .rules_check_productions import ProductionChecks
from .rules_check_scene import ROOM_TYPES, SceneChecks
from .rules_errors import Diagnostic
from .rules_includes import ParsedTree


def check_tree(tree: ParsedTree) -> list[Diagnostic]:
    """Every diagnostic about a parsed rule set (errors and warnings)."""
    checker = _Checker(tree.sources, tree.paths, tree.scope)
    checker.check(tree.files)
    file_order = {file.path: index for index, file in enumerate(tree.files)}
    return sorted(
        checker.diagnostics,
        key=lambda d: (file_order.get(d.location.file, -1), d.location.line, d.location.column),
    )


class _Checker(CatalogChecks, SceneChecks, ProductionChecks, GrammarChecks):
    """One pass over a parsed rule set, collecting its diagnostics."""

    def check(self, files: list[ast.RulesFile]) -> None:
        entries = [entry for file in files for entry in file.entries]
        first_entry: dict[str, ast.EntryDecl] = {}
        for entry in entries:
            if entry.name in first_entry:
                self.error(
                    entry.name_location,
                    f"duplicate catalog entry '{entry.name}' "
                    f"(first declared at {first_entry[entry.name].location})",
                )
                continue
            first_entry[entry.name] = entry
            self.kinds[entry.name] = entry.kind
        for entry in entries:
            self.check_entry(entry)

        start = self.check_scenes(files)
        if self.has_room:
            for name in ROOM_TYPES:
                if name in first_entry:
                    self.error(
                        first_entry[name].name_location,
                        f"'{name}' names the room's {name}s in a scene "
                        f"with a room; give this catalog entry another name",
                    )
        for file in files:
            for production in file.productions:
                if production.name in self.productions:
                    self.error(
                        production.location,
                        f"duplicate production for '{production.name}' "
                        f"(first at {self.productions[production.name].location})",
                    )
                else:
                    self.productions[production.name] = production
        for production in self.productions.values():
            self.note_makers(production)
        for production in self.productions.values():
            self.check_production(production)
        root = files[-1].path
        for entry in first_entry.values():
            # An included file may be a catalog several rule sets share: each makes only some of it.
            if entry.name not in self.created_types and entry.location.file == root:
                self.warning(
                    entry.name_location,
                    f"type '{entry.name}' is never created (no statement makes one)",
                )
        if start is not None:
            self.check_start(*start)
        self.check_termination()
