"""A rules file and, depth-first, the files it includes, read and parsed.

``parse_tree`` parses a file and the files it includes (paths relative to the
including file; each file once; a cycle is reported at the ``include`` that closes
it). A rule set reads only inside its ``ReadScope`` (its own folder, unless the user
allows more) and only regular files of at most ``MAX_RULES_BYTES``, so a pipe, a device
or a huge file cannot stall or exhaust it.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from scenewright.core.files import UnusableFile, read_regular_file

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_errors import Diagnostic, SourceTexts, is_rules_file_name
from .rules_parser import parse_text
from .rules_scope import ReadScope

#: The most a rules file may hold (4 MiB): far more than any rule set needs, little
#: enough that reading and parsing it stays quick.
MAX_RULES_BYTES = 4 * 1024 * 1024


@dataclass
class ParsedTree:
    """A rules file and everything it includes, parsed (or the diagnostics why not).

    ``files`` is in depth-first include order, each included file before the file
    that includes it; ``paths`` maps each file's display name to its real path;
    ``scope`` is where the rule set may read files.
    """

    scope: ReadScope
    files: list[ast.RulesFile] = field(default_factory=list)
    paths: dict[str, Path] = field(default_factory=dict)
    sources: SourceTexts = field(default_factory=SourceTexts)
    diagnostics: list[Diagnostic] = field(default_factory=list)


def parse_tree(
    path: Path, display: str, allow: Iterable[str | os.PathLike[str]] = ()
) -> ParsedTree:
    """Parse ``path`` (shown as ``display`` in diagnostics) and the files it includes,
    which must lie in its folder or in ``allow`` (``ReadScope``)."""
    tree = ParsedTree(ReadScope.of(path, allow))
    _parse_into(tree, Path(path), display, include_stack=[], include_location=None)
    return tree


def _parse_into(
    tree: ParsedTree,
    path: Path,
    display: str,
    include_stack: list[tuple[Path, str]],
    include_location: SourceLocation | None,
) -> None:
    real = path.resolve()
    for index, (seen, _) in enumerate(include_stack):
        if seen == real:
            assert include_location is not None  # only an included file closes a cycle
            chain = " -> ".join([name for _, name in include_stack[index:]] + [display])
            tree.diagnostics.append(
                tree.sources.diagnostic(include_location, f"include cycle: {chain}")
            )
            return
    if any(known.resolve() == real for known in tree.paths.values()):
        return  # already included along another route: its declarations are in once
    text = _read_rules_file(tree, path, display, include_location)
    if text is None:
        return
    tree.paths[display] = path
    # Quoted only when named *.rules both as written and where its links lead.
    parsed = parse_text(text, display, tree.sources, quoted=is_rules_file_name(real.name))
    if isinstance(parsed, Diagnostic):
        tree.diagnostics.append(parsed)
        return
    stack = include_stack + [(real, display)]
    for include in parsed.includes:
        child = path.parent / include.path
        outside = tree.scope.outside(child)
        if outside is not None:
            message = f"included file '{include.path}' {outside}"
            tree.diagnostics.append(tree.sources.diagnostic(include.location, message))
            continue
        child_display = os.path.normpath(os.path.join(os.path.dirname(display), include.path))
        _parse_into(tree, child, child_display, stack, include.location)
    tree.files.append(parsed)


def _read_rules_file(
    tree: ParsedTree, path: Path, display: str, include_location: SourceLocation | None
) -> str | None:
    """The text of a rules file: a regular file of at most ``MAX_RULES_BYTES`` of UTF-8;
    or None, with a diagnostic saying why not (at the ``include``, for an included file)."""
    try:
        text = read_regular_file(path, MAX_RULES_BYTES, "a rules file").decode("utf-8")
    except UnicodeDecodeError:
        reason = "not UTF-8 text"
    except UnusableFile as problem:
        reason = f"it {problem}"
    except OSError as error:
        reason = error.strerror or str(error)
    else:
        # Lines are counted at "\n" only, as the parser counts them (no newline translation).
        return text
    if include_location is None:  # the file asked for: the error is at its start
        tree.diagnostics.append(
            Diagnostic(SourceLocation(display, 1, 1), f"cannot read '{display}': {reason}")
        )
    else:
        tree.diagnostics.append(
            tree.sources.diagnostic(
                include_location, f"cannot read included file '{display}': {reason}"
            )
        )
    return None
