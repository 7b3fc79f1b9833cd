"""Lark's parse tree of a rules file -> the dataclasses of ``rules_ast``.

``ToAst`` is a lark ``Transformer`` that builds, bottom-up, one ``rules_ast`` value per
grammar rule, each with the place it was written, for the static checks to point at.
"""

from __future__ import annotations

from dataclasses import dataclass

from lark import Token, Transformer, v_args

from scenewright.core.limits import MAX_NODES

from . import rules_ast as ast
from .catalog import SourceLocation

#: Catalog fields and scene settings: the grammar's rules of these names each become an
#: ``ast.Setting`` (the ``start`` setting's rule is ``start_symbol``).
ENTRY_FIELDS = (
    "noun",
    "plural",
    "size",
    "shape",
    "mesh",
    "colour",
    "width",
    "max_length",
    "segments",
    "clearance",
    "access",
    "wall_gap",
    "network",
)
SCENE_SETTINGS = (
    "extent",
    "ground",
    "walls",
    "room",
    "square",
    "line_of_sight",
    "start",
    "max_depth",
    "max_nodes",
    "templates",
)


@dataclass(frozen=True)
class _Located:
    """A value and where it was written (a statement's probability or ``as`` name),
    passed up to ``statement``, which keeps the two in separate fields."""

    value: object
    location: SourceLocation


@dataclass(frozen=True)
class _Block:
    statements: tuple[ast.Statement, ...]
    location: SourceLocation


class ToAst(Transformer):
    """Builds the dataclasses of ``rules_ast`` bottom-up from lark's parse tree."""

    def __init__(self, file: str):
        super().__init__()
        self.file = file

    def _at(self, item) -> SourceLocation:
        return SourceLocation(self.file, item.line, item.column)

    # settings of entries, styles and scenes

    def _setting(self, name: str, meta, values: list[Token]) -> ast.Setting:
        if not values:
            return ast.Setting(name, True, self._at(meta), self._at(meta))
        converted = [_value(token) for token in values]
        value = converted[0] if len(converted) == 1 else tuple(converted)
        return ast.Setting(name, value, self._at(meta), self._at(values[0]))

    def __default__(self, data, children, meta):
        # The grammar's rule `start` is a whole file, so the `start` setting's rule is
        # `start_symbol`; every other field and setting rule is named like its keyword.
        if data == "access":  # always a tuple of sides, however many
            setting = self._setting("access", meta, children)
            return (
                setting
                if isinstance(setting.value, tuple)
                else ast.Setting(
                    setting.name, (setting.value,), setting.location, setting.value_location
                )
            )
        if data in ENTRY_FIELDS or (data in SCENE_SETTINGS and data not in ("start", "room")):
            return self._setting(str(data), meta, children)
        if data == "start_symbol":
            return self._setting("start", meta, children)
        return super().__default__(data, children, meta)

    def kind(self, children):
        return children[0]

    # the room block

    @v_args(meta=True)
    def room(self, meta, children):
        shape, *rest = children
        body = rest[-1] if rest and isinstance(rest[-1], list) else []
        corners = [shape, *(item for item in rest if isinstance(item, tuple))]
        size = shape[1] if shape[0] == "size" else None
        height = next((item for item in body if isinstance(item, _Located)), None)
        room = ast.RoomDecl(
            size=size,
            corners=None if size else tuple(corner[1] for corner in corners),
            height=height.value if height else None,
            openings=tuple(item for item in body if isinstance(item, ast.OpeningDecl)),
            location=self._at(meta),
            height_location=height.location if height else None,
        )
        return ast.Setting("room", room, self._at(meta), self._at(meta))

    def room_size(self, children):
        return ("size", (float(children[0]), float(children[1])))

    def room_corner(self, children):
        return ("corner", (float(children[0]), float(children[1])))

    def room_body(self, children):
        return [child for child in children if child is not None]

    @v_args(meta=True)
    def wall_height(self, meta, children):
        return _Located(float(children[0]), self._at(children[0]))

    def wall_name(self, children):
        return children[0]

    @v_args(meta=True)
    def door(self, meta, children):
        return self._opening("door", meta, children)

    @v_args(meta=True)
    def window(self, meta, children):
        return self._opening("window", meta, children)

    def _opening(self, kind: str, meta, children) -> ast.OpeningDecl:
        wall, *numbers = children
        values = tuple(float(n) for n in numbers if n is not None)
        return ast.OpeningDecl(kind, str(wall), values, self._at(meta), self._at(wall))

    @v_args(meta=True)
    def style(self, meta, children):
        name, weight, *fields = children
        return ast.StyleDecl(
            str(name),
            float(weight) if weight is not None else None,
            tuple(fields),
            self._at(meta),
            self._at(weight) if weight is not None else None,
        )

    @v_args(meta=True)
    def entry(self, meta, children):
        kind, name, *rest = children
        fields = tuple(item for item in rest if isinstance(item, ast.Setting))
        styles = tuple(item for item in rest if isinstance(item, ast.StyleDecl))
        return ast.EntryDecl(str(kind), str(name), fields, styles, self._at(meta), self._at(name))

    @v_args(meta=True)
    def scene(self, meta, children):
        name, *settings = children
        return ast.SceneDecl(str(name), tuple(settings), self._at(meta))

    def include(self, children):
        return ast.IncludeDecl(children[0][1:-1], self._at(children[0]))

    # productions

    @v_args(meta=True)
    def name_ref(self, meta, children):
        return ast.Reference("name", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def some_ref(self, meta, children):
        return ast.Reference("some", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def each_ref(self, meta, children):
        return ast.Reference("each", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def nth_ref(self, meta, children):
        name, ordinal = children
        return ast.Reference("nth", str(name), self._at(meta), _ordinal(ordinal))

    def arguments(self, children):
        return tuple(child for child in children if child is not None)

    @v_args(meta=True)
    def call(self, meta, children):
        name, arguments = children
        return ast.Call(str(name), arguments or (), self._at(meta))

    def relation(self, children):
        label, target = children
        return ast.Relation(str(label), target, self._at(label))

    @v_args(meta=True)
    def count(self, meta, children):
        low, high, weights = children
        return ast.Count(
            float(low),
            float(high if high is not None else low),
            self._at(meta),
            weights.value if weights else None,
            weights.location if weights else None,
        )

    @v_args(meta=True)
    def count_weights(self, meta, children):
        return _Located(tuple(float(weight) for weight in children), self._at(meta))

    @v_args(meta=True)
    def probability(self, meta, children):
        return _Located(float(children[0]), self._at(meta))

    def binding(self, children):
        return _Located(str(children[0]), self._at(children[0]))

    @v_args(meta=True)
    def block(self, meta, children):
        return _Block(tuple(child for child in children if child is not None), self._at(meta))

    @v_args(meta=True)
    def statement(self, meta, children):
        count, probability, subject, binding, *relations, block = children
        return ast.Statement(
            subject=subject,
            location=self._at(meta),
            count=count,
            probability=probability.value if probability else None,
            probability_location=probability.location if probability else None,
            binding=binding.value if binding else None,
            binding_location=binding.location if binding else None,
            relations=tuple(relations),
            block=block.statements if block else None,
            block_location=block.location if block else None,
        )

    @v_args(meta=True)
    def alternative(self, meta, children):
        weight, block = children
        return ast.Alternative(
            float(weight) if weight is not None else None, block.statements, self._at(meta)
        )

    def params(self, children):
        return tuple(ast.Param(str(name), self._at(name)) for name in children if name is not None)

    @v_args(meta=True)
    def production(self, meta, children):
        name, params, *alternatives = children
        return ast.Production(str(name), params or (), tuple(alternatives), self._at(meta))

    def start(self, children):
        return ast.RulesFile(
            path=self.file,
            includes=tuple(c for c in children if isinstance(c, ast.IncludeDecl)),
            scenes=tuple(c for c in children if isinstance(c, ast.SceneDecl)),
            entries=tuple(c for c in children if isinstance(c, ast.EntryDecl)),
            productions=tuple(c for c in children if isinstance(c, ast.Production)),
        )


def _value(token: Token):
    if token.type == "NUMBER":
        return float(token)
    if token.type == "STRING":
        return str(token)[1:-1]
    return str(token)


def _ordinal(token: Token) -> int:
    """``#N`` as N. An N of more digits than any node count has (more than an int may
    be read from) stands as one past ``MAX_NODES``: the checks report it out of range."""
    digits = token[1:].lstrip("0") or "0"
    return int(digits) if len(digits) <= len(str(MAX_NODES)) else MAX_NODES + 1
