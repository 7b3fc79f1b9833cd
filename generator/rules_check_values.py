"""The numbers the static checks hold a rule set to, and how their messages say values.

The scene's defaults for ``max_depth`` and ``max_nodes``, the upper limit of each
numeric field and setting (``scenewright.core.limits``, listed for users in
docs/limits.md), and the wording the checks share: a number as a rules file writes
it, a value below or above its bound, a kind with its article.
"""

from __future__ import annotations

from scenewright.core.limits import (
    MAX_DEPTH,
    MAX_NODES,
    MAX_PATH_LENGTH,
    MAX_SEGMENTS,
    MAX_SIZE,
    MIN_LENGTH,
)

#: A scene's ``max_depth`` and ``max_nodes`` where its block sets none.
DEFAULT_MAX_DEPTH = 32
DEFAULT_MAX_NODES = 2000

#: The largest value of each numeric field and scene setting (``core.limits``).
UPPER_LIMITS = {
    "width": MAX_SIZE,
    "max_length": MAX_PATH_LENGTH,
    "segments": MAX_SEGMENTS,
    "max_depth": MAX_DEPTH,
    "max_nodes": MAX_NODES,
}
#: Where every limit is listed.
LIMITS_DOC = "docs/limits.md"


def is_whole(value: float) -> bool:
    """Whether ``value`` is a whole number (a count, a node limit)."""
    return float(value).is_integer()


def number_text(value: float) -> str:
    """A number as a rules file writes it: ``3``, not ``3.0``."""
    return str(int(value)) if is_whole(value) else str(value)


def too_small(what: str, value: float) -> str:
    """The message for a length below ``MIN_LENGTH``."""
    return f"{what} must be at least {MIN_LENGTH:g} m, not {value:g} (the limits: {LIMITS_DOC})"


def too_large(what: str, value: float, limit: float, unit: str) -> str:
    """The message for a value above its ``limit`` (in ``unit``, written after it)."""
    shown = number_text(value) if value < 1e15 else f"{value:g}"
    return f"{what} may be at most {limit:g}{unit}, not {shown} (the limits: {LIMITS_DOC})"


def with_article(kind: str) -> str:
    """A kind with its indefinite article: "an object", "a path"."""
    return ("an " if kind[0] in "aeiou" else "a ") + kind
