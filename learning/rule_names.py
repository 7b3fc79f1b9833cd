"""Names as a learned rule set writes them: a type seen in the examples made a rules
identifier (``identifier``), a nonterminal (``camel``), a name made unique among those
taken (``unique_name``), and a colour as ``#rrggbb`` (``colour_text``).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

_NOT_NAME = re.compile(r"[^a-z0-9_]+")


def identifier(raw: str, taken: set[str], reserved: frozenset[str] = frozenset()) -> str:
    """``raw`` as a rules identifier (``[a-z_][a-z0-9_]*``) not in ``taken`` or
    ``reserved``; added to ``taken``."""
    base = _NOT_NAME.sub("_", raw.strip().lower()).strip("_") or "thing"
    if base[0].isdigit():
        base = "n_" + base
    name, k = base, 1
    while name in taken or name in reserved:
        k += 1
        name = f"{base}_{k}"
    taken.add(name)
    return name


def camel(name: str) -> str:
    """``writing_desk`` -> ``WritingDesk`` (a nonterminal)."""
    words = [w for w in name.split("_") if w]
    text = "".join(w[:1].upper() + w[1:] for w in words) or "Thing"
    return text if text[0].isalpha() else "N" + text


def unique_name(name: str, taken: set[str]) -> str:
    """``name``, else ``name2``, ``name3``...: the first not in ``taken``; added to ``taken``."""
    candidate, k = name, 1
    while candidate in taken:
        k += 1
        candidate = f"{name}{k}"
    taken.add(candidate)
    return candidate


def colour_text(colour: Sequence[float]) -> str:
    """``#rrggbb`` of a colour in [0, 1]."""
    return "#" + "".join(f"{min(255, max(0, round(float(v) * 255))):02x}" for v in colour)
