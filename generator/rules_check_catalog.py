"""Static checks of a rule set's catalog: its entries, their fields and styles.

Each field's value is checked against its kind of entry and its bounds: sizes, path
widths and segments, colours, nouns of at most ``MAX_NOUN_CHARS``, clearances and
access sides and wall gaps of objects, a junction's kind of road network, mesh files that must load and lie in the rule set's
``ReadScope``, and shape names the renderer must know (a warning).
"""

from __future__ import annotations

from scenewright.core.errors import MeshFileError
from scenewright.core.limits import MAX_SIZE, MAX_WEIGHT, MIN_LENGTH
from scenewright.core.shapes import MESH_SUFFIXES, SHAPES, load_mesh_file

from . import rules_ast as ast
from .catalog import NETWORKS, STYLE_FIELDS
from .rules_check_state import CheckState
from .rules_check_values import (
    UPPER_LIMITS,
    is_whole,
    number_text,
    too_large,
    too_small,
    with_article,
)
from .rules_errors import did_you_mean

#: The sides a clearance or access may name, and the words access also takes.
SIDE_WORDS = ("front", "back", "left", "right")
ACCESS_WORDS = ("any", "none", *SIDE_WORDS)
#: The most free floor a clearance may keep beside an object (metres).
MAX_CLEARANCE = 10.0
#: The farthest off a wall its wall label may keep an object (metres): further out it is
#: no longer against the wall.
MAX_WALL_GAP = 0.5
#: Fields that shape a path's polyline, so only ``path`` entries take them.
PATH_FIELDS = ("width", "max_length", "segments")
#: The longest noun or plural, in characters: a noun phrase is a few words, and the
#: describer's English (inflection) takes time that grows fast with its length.
MAX_NOUN_CHARS = 200


class CatalogChecks(CheckState):
    """The checks of catalog entries and their styles."""

    def check_entry(self, entry: ast.EntryDecl) -> None:
        fields = self.check_fields(entry.fields, entry.kind, style=False)
        if "noun" not in fields:
            self.error(
                entry.name_location, f"catalog entry '{entry.name}' has no noun (add: noun \"...\")"
            )
        seen: dict[str, ast.StyleDecl] = {}
        for style in entry.styles:
            if style.name in seen:
                self.error(style.location, f"duplicate style '{style.name}' of '{entry.name}'")
            seen[style.name] = style
            if style.weight is not None:
                assert style.weight_location is not None  # the parser sets both
                if style.weight <= 0:
                    self.error(
                        style.weight_location,
                        f"style weight must be positive, not {number_text(style.weight)}",
                    )
                elif style.weight > MAX_WEIGHT:
                    self.error(
                        style.weight_location,
                        too_large("a style weight", style.weight, MAX_WEIGHT, ""),
                    )
            self.check_fields(style.fields, entry.kind, style=True)

    def check_fields(
        self, fields: tuple[ast.Setting, ...], kind: str, style: bool
    ) -> dict[str, ast.Setting]:
        seen: dict[str, ast.Setting] = {}
        sides: set[str] = set()
        for setting in fields:
            name, value, at = setting.name, setting.value, setting.value_location
            if name == "clearance":  # one line per side
                self.check_clearance(setting, kind, sides)
                continue
            if name in seen:
                self.error(setting.location, f"duplicate field '{name}'")
                continue
            seen[name] = setting
            if name == "access":
                self.check_access(setting, kind)
                continue
            if name == "network":
                self.check_network(setting, kind)
                continue
            if name == "wall_gap":
                self.check_wall_gap(setting, kind)
                continue
            if isinstance(value, str) and self.check_text(name, value, at):
                continue
            if style and name not in STYLE_FIELDS:
                self.error(
                    setting.location,
                    f"a style cannot set '{name}' (only {', '.join(STYLE_FIELDS)})",
                )
            elif name in PATH_FIELDS and kind != "path":
                self.error(
                    setting.location,
                    f"'{name}' applies to paths only, not to {with_article(kind)}",
                )
            if name == "size" and any(v <= 0 for v in setting.numbers()):
                self.error(at, "sizes must be positive")
            elif name == "size" and min(setting.numbers()) < MIN_LENGTH:
                self.error(at, too_small("each side of a size", min(setting.numbers())))
            elif name == "size" and max(setting.numbers()) > MAX_SIZE:
                self.error(
                    at, too_large("each side of a size", max(setting.numbers()), MAX_SIZE, " m")
                )
            elif name in ("width", "max_length") and setting.number() <= 0:
                self.error(at, f"'{name}' must be positive, not {number_text(setting.number())}")
            elif name in ("width", "max_length") and setting.number() < MIN_LENGTH:
                self.error(at, too_small(f"'{name}'", setting.number()))
            elif name == "segments" and (setting.number() < 1 or not is_whole(setting.number())):
                self.error(
                    at,
                    "'segments' must be a whole number of at least 1, "
                    f"not {number_text(setting.number())}",
                )
            elif name in UPPER_LIMITS and setting.number() > UPPER_LIMITS[name]:
                self.error(
                    at,
                    too_large(
                        f"'{name}'",
                        setting.number(),
                        UPPER_LIMITS[name],
                        "" if name == "segments" else " m",
                    ),
                )
            elif name == "colour" and not _is_hex_colour(setting.text()):
                self.error(at, f"colour '{value}' is not of the form #rrggbb")
            elif name == "mesh":
                self.check_mesh(setting.text(), setting)
            elif name == "shape":
                self.check_shape(setting.text(), setting)
            elif name in ("noun", "plural") and not setting.text().strip():
                self.error(at, f"'{name}' must not be empty")
            elif name in ("noun", "plural") and len(setting.text()) > MAX_NOUN_CHARS:
                self.error(
                    at,
                    f"'{name}' is {len(setting.text())} characters long; "
                    f"it may have at most {MAX_NOUN_CHARS}",
                )
        return seen

    def check_clearance(self, setting: ast.Setting, kind: str, sides: set[str]) -> None:
        side, metres = setting.word_and_number()
        if kind != "object":
            self.error(
                setting.location,
                f"'clearance' applies to objects only, not to {with_article(kind)}",
            )
        elif side not in SIDE_WORDS:
            self.error(
                setting.value_location,
                f"clearance side '{side}' is not one of {', '.join(SIDE_WORDS)}"
                + did_you_mean(side, SIDE_WORDS),
            )
        elif side in sides:
            self.error(setting.location, f"a second clearance {side}")
        elif not 0 < metres <= MAX_CLEARANCE:
            self.error(
                setting.location,
                f"a clearance must be more than 0 and at most {MAX_CLEARANCE:g} m, "
                f"not {number_text(metres)}",
            )
        sides.add(side)

    def check_access(self, setting: ast.Setting, kind: str) -> None:
        words = setting.words()
        if kind != "object":
            self.error(
                setting.location, f"'access' applies to objects only, not to {with_article(kind)}"
            )
            return
        for word in words:
            if word not in ACCESS_WORDS:
                self.error(
                    setting.value_location,
                    f"access '{word}' is not one of {', '.join(ACCESS_WORDS)}"
                    + did_you_mean(word, ACCESS_WORDS),
                )
                return
        if len(words) > 1 and ({"any", "none"} & set(words)):
            self.error(setting.value_location, "'access any' and 'access none' stand alone")
        elif len(set(words)) < len(words):
            self.error(setting.value_location, "a side is named twice")

    def check_wall_gap(self, setting: ast.Setting, kind: str) -> None:
        """``wall_gap M``: an object's, 0 to ``MAX_WALL_GAP`` metres."""
        if kind != "object":
            self.error(
                setting.location,
                f"'wall_gap' applies to objects only, not to {with_article(kind)}",
            )
        elif not 0 <= setting.number() <= MAX_WALL_GAP:
            self.error(
                setting.value_location,
                f"a wall gap must be at least 0 and at most {MAX_WALL_GAP:g} m, "
                f"not {number_text(setting.number())}",
            )

    def check_network(self, setting: ast.Setting, kind: str) -> None:
        """``network grid`` or ``network organic``, on a junction only."""
        if kind != "junction":
            self.error(
                setting.location,
                f"'network' applies to junctions only, not to {with_article(kind)}",
            )
        elif setting.text() not in NETWORKS:
            self.error(
                setting.value_location,
                f"network '{setting.text()}' is not one of {', '.join(NETWORKS)}"
                + did_you_mean(setting.text(), NETWORKS),
            )

    def check_mesh(self, file: str, setting: ast.Setting) -> None:
        folder = self.folder_of(setting)
        if not file.lower().endswith(MESH_SUFFIXES):
            suffixes = ", ".join(MESH_SUFFIXES[:-1]) + " or " + MESH_SUFFIXES[-1]
            self.error(setting.value_location, f"mesh '{file}' is not a {suffixes} file")
        elif (outside := self.scope.outside(folder / file)) is not None:
            self.error(setting.value_location, f"mesh file '{file}' {outside}")
        elif not (folder / file).exists():
            self.error(
                setting.value_location,
                f"mesh file '{file}' not found (looked in {folder.resolve()})",
            )
        else:
            try:
                load_mesh_file(folder / file)
            except MeshFileError as problem:
                self.error(setting.value_location, f"mesh file '{file}' {problem.reason}")

    def check_shape(self, shape: str, setting: ast.Setting) -> None:
        """A shape the renderer has no builder for is drawn as a plain box: warn."""
        if shape not in SHAPES:
            self.warning(
                setting.value_location,
                f"unknown shape '{shape}', drawn as a plain box"
                + (did_you_mean(shape, SHAPES) or "; 'scenewright list --shapes' lists the shapes"),
            )


def _is_hex_colour(text: str) -> bool:
    digits = text[1:]
    return len(digits) == 6 and all(c in "0123456789abcdefABCDEF" for c in digits)
