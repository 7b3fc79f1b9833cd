"""The bounds every stage respects, so no input can exhaust memory or time.

One number in a rules file or a scene.json (a size, an extent, a count) sizes the
work of every later stage: the layout's grid, the meshes, the camera. These bounds are
far above any real scene (a 1 km building, a 10 km map, ten thousand objects), and
everything within them is built in bounded memory and time. The rules checker and the
scene.json check refuse values beyond them with the limit named; the mesh builders
draw at most ``MAX_REPEATS`` repeated parts whatever the size. ``docs/limits.md``
lists them all.

Text that is printed or written (nouns, ids, paths) must not carry control characters
or bidirectional overrides, which would garble a terminal or make a line read
differently from what it holds: ``forbidden_character`` finds the first such one, and
``printable`` shows a line of a file with each one replaced by U+FFFD.
"""

from __future__ import annotations

import re
import unicodedata

#: The shortest side of an object or extent, the narrowest and the shortest path, in
#: metres: scene.json keeps lengths to the micrometre, so a shorter one would read as 0.
MIN_LENGTH = 0.001
#: The longest side of an object (and the widest path), in metres.
MAX_SIZE = 1_000.0
#: The longest side of a scene's extent, in metres.
MAX_EXTENT = 10_000.0
#: A path's longest allowed length (``max_length``), in metres: corner to corner of the
#: largest extent, with room to bend.
MAX_PATH_LENGTH = 20_000.0
#: The most straight pieces a path's polyline may have (``segments``).
MAX_SEGMENTS = 100
#: How far from the origin a scene.json coordinate may lie, in metres (ten extents).
MAX_COORDINATE = 100_000.0
#: The largest ``max_nodes`` a scene block may set: nodes of one scene (objects,
#: groups, junctions and paths), and so the largest count of a range.
MAX_NODES = 10_000
#: The largest ``max_depth`` a scene block may set: nested production calls.
MAX_DEPTH = 64
#: How deep statement blocks may nest inside one production (``g { h { ... } }``).
MAX_BLOCK_NESTING = 6
#: How deep groups may nest in a scene: what the deepest calls and blocks can make.
MAX_GROUP_DEPTH = MAX_DEPTH * MAX_BLOCK_NESTING
#: The largest weight of an alternative or a style (weights are relative).
MAX_WEIGHT = 1_000_000.0
#: The most parts a mesh builder repeats along a size (a field's crop rows).
MAX_REPEATS = 32
#: How deep a scene.json document may nest (scene.json itself nests 5 deep).
MAX_JSON_DEPTH = 64
#: The largest scene.json file read (a scene of ``MAX_NODES`` nodes takes about 10 MiB).
MAX_SCENE_JSON_BYTES = 64 * 1024 * 1024

#: Characters that change the direction of the text after them (Unicode Bidi_Control).
_BIDI_CONTROLS = frozenset(
    "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
)


# The forbidden characters as one character class: category Cc is U+0000-U+001F and
# U+007F-U+009F, Zl is U+2028 alone and Zp U+2029 alone (tests/test_limits.py checks
# the class against unicodedata over every code point). Searched by the regex engine,
# not character by character in Python: every rules file, template and scene.json
# string passes through here.
_CLASS = "\x7f-\x9f\u2028\u2029" + "".join(sorted(_BIDI_CONTROLS))
_FORBIDDEN = re.compile(f"[\x00-\x1f{_CLASS}]")
_FORBIDDEN_BUT_TAB = re.compile(f"[\x00-\x08\x0a-\x1f{_CLASS}]")


def forbidden_character(text: str) -> str | None:
    """The first control, line-separator or bidirectional-control character of ``text``
    as ``U+XXXX (name)``, or None when there is none."""
    found = _FORBIDDEN.search(text)
    if found is None:
        return None
    character = found.group()
    name = unicodedata.name(character, "control character")
    return f"U+{ord(character):04X} ({name.lower()})"


def printable(line: str) -> str:
    """``line`` with each forbidden character but the tab replaced by U+FFFD, one for
    one, so it prints as it reads and columns stay where they were."""
    return _FORBIDDEN_BUT_TAB.sub("\ufffd", line)
