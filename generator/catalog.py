"""The object catalog: what each type in a rules file is (kind, noun, size, look).

A ``Catalog`` is plain data built by the rules loader (``rules``) from a file's
``object``, ``group``, ``path`` and ``junction`` entries. Grammar expansion copies the
resolved fields of an entry (after choosing a style) onto every node it creates, so
the later stages read nodes, never the catalog.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, replace

#: The kinds of catalog entry. ``object``: has a collision box and a mesh; ``group``:
#: abstract, its extent is the union of its members; ``path``: a polyline with a width;
#: ``junction``: where paths start (an intersection).
KINDS = ("object", "group", "path", "junction")
#: The kinds of road network a junction may start (``network``): ``organic`` (roads at
#: evenly spread headings, bending gently; the default) or ``grid`` (straight roads at
#: right angles, branches square to their roads).
NETWORKS = ("organic", "grid")

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class SourceLocation:
    """Where something was written: file, 1-based line and column."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


@dataclass(frozen=True)
class Style:
    """One style variant of a catalog entry (an Or-node): overrides and a weight."""

    name: str
    weight: float = 1.0
    noun: str | None = None
    plural: str | None = None
    size: Vec3 | None = None
    shape: str | None = None
    mesh: str | None = None
    colour: Vec3 | None = None


#: The look fields a style may override, in declaration order (not its name or weight).
STYLE_FIELDS: tuple[str, ...] = tuple(
    f.name for f in fields(Style) if f.name not in ("name", "weight")
)


@dataclass(frozen=True)
class CatalogEntry:
    """A type a rules file may instantiate.

    ``size`` is (width along local x, height along y, depth along local z) in metres.
    ``shape`` names a procedural mesh builder (``scenewright.render.builders``);
    ``mesh`` is instead a user mesh file (absolute path) fitted to ``size``.
    ``colour`` is sRGB in [0, 1] (the hex value over 255, as written). Paths use
    ``width`` and ``max_length`` (the paper's l_A) and ``segments`` (how many straight
    pieces the polyline has); junctions ``network`` (one of ``NETWORKS``).
    """

    name: str
    kind: str
    noun: str
    plural: str | None = None
    size: Vec3 = (1.0, 1.0, 1.0)
    shape: str | None = None
    mesh: str | None = None
    colour: Vec3 = (0.6, 0.6, 0.6)
    styles: tuple[Style, ...] = ()
    width: float = 3.0
    max_length: float = 30.0
    segments: int = 3
    #: Free floor kept beside it, by side, and the sides it is used from (``SceneNode``).
    clearance: tuple[tuple[str, float], ...] = ()
    access: tuple[str, ...] = ("any",)
    #: How far its back stands off a wall a wall label puts it against (metres; None: flush).
    wall_gap: float | None = None
    network: str = "organic"
    location: SourceLocation | None = None

    def with_style(self, style: Style | None) -> CatalogEntry:
        """The entry as it looks in ``style`` (its overrides applied)."""
        if style is None:
            return self
        overrides = {
            name: getattr(style, name) for name in STYLE_FIELDS if getattr(style, name) is not None
        }
        if "noun" in overrides and "plural" not in overrides:
            overrides["plural"] = None  # a new noun must not keep the old irregular plural
        return replace(self, **overrides)


@dataclass
class Catalog:
    """All catalog entries of a rules file (and its includes), by type name."""

    entries: dict[str, CatalogEntry] = field(default_factory=dict)

    def __contains__(self, name: str) -> bool:
        return name in self.entries

    def __getitem__(self, name: str) -> CatalogEntry:
        return self.entries[name]

    def __iter__(self):
        return iter(self.entries.values())

    def __len__(self) -> int:
        return len(self.entries)

    def add(self, entry: CatalogEntry) -> None:
        self.entries[entry.name] = entry
