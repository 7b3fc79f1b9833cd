"""A request -> a rule set: the room, one catalog entry per kind of thing asked for, and
one production that makes exactly the things asked for with their relations.

The rule set is ordinary rules text (``rules_text``), so it loads through the same
checks as any rule set, and a user can keep it (``compose --rules-out``) and edit it.
Each thing is one statement (``bed as e1 AgainstWall wall #1``); a relation to a thing
made later is a statement of its own after them (``e1 FacingTowards e4``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from scenewright.describer.colours import COLOUR_TERMS
from scenewright.describer.rooms import DOOR_NEAR_CORNER
from scenewright.generator.catalog import CatalogEntry, Style

from .outdoor import Ground, made_first, scene_name, settle
from .outdoor import extent as ground_extent
from .request import Issue, Place, Request, Statement

#: The production every composed rule set starts from.
START = "Compose"
#: Openings (metres): a door's width; a window's width, sill and height.
DOOR_WIDTH = 0.9
WINDOW = (1.4, 0.9, 1.3)
#: The walls' height (the rules language's default), and how far from its wall's first
#: corner a door is put when the text names "the corner by the door" (its opening then
#: ends within the describer's reach of that corner).
WALL_HEIGHT = 2.6
DOOR_BY_CORNER = 1.3
#: Each wall's first corner (walls run clockwise seen from above, north up).
FIRST_CORNER = {
    "north": ("north", "west"),
    "east": ("east", "north"),
    "south": ("south", "east"),
    "west": ("west", "south"),
}
#: A room with no size of its own is this many times the floor its things cover (plus
#: a margin for walking), and no smaller than MIN_SIDE on a side.
FLOOR_PER_FOOTPRINT = 3.2
FLOOR_MARGIN = 6.0
MIN_SIDE = 2.6
_SIDES = ("north", "east", "south", "west")


def _hex(rgb: tuple[float, float, float]) -> str:
    return "#" + "".join(f"{max(0, min(255, round(c * 255))):02x}" for c in rgb)


def _number(x: float) -> str:
    return f"{x:.3f}".rstrip("0").rstrip(".")


def _quote(text: str) -> str:
    return '"' + text.replace('"', "'") + '"'


def _looks(
    noun: str | None, plural: str | None, size, shape: str | None, mesh: str | None, colour
) -> str:
    parts = []
    if noun is not None:
        parts.append(f"noun {_quote(noun)}")
    if plural is not None:
        parts.append(f"plural {_quote(plural)}")
    if size is not None:
        parts.append("size " + " x ".join(_number(v) for v in size))
    if mesh is not None:
        parts.append(f"mesh {_quote(mesh)}")
    elif shape is not None:
        parts.append(f"shape {shape}")
    if colour is not None:
        parts.append(f"colour {_hex(colour)}")
    return " ".join(parts)


def entry_text(name: str, entry: CatalogEntry, style: str | None, colour: str | None) -> str:
    """One catalog entry: the catalog's, keeping only the style asked for (all of them
    when none was), its colour replaced by a colour word's when one was asked for."""
    if entry.kind == "group":
        plural = f" plural {_quote(entry.plural)}" if entry.plural else ""
        return f"group {name} {{ noun {_quote(entry.noun)}{plural} }}"
    rgb = COLOUR_TERMS[colour] if colour else None
    head = _looks(
        entry.noun, entry.plural, entry.size, entry.shape, entry.mesh, rgb or entry.colour
    )
    fields = [head]
    fields += [f"clearance {side} {_number(depth)}" for side, depth in entry.clearance]
    if tuple(entry.access) != ("any",):
        fields.append("access " + (" ".join(entry.access) or "none"))
    styles: list[Style] = [s for s in entry.styles if style is None or s.name == style]
    for s in styles:
        weight = _number(s.weight) if style is None else "1"
        looks = _looks(s.noun, s.plural, s.size, s.shape, s.mesh, None if rgb else s.colour)
        fields.append(f"style {s.name} {weight} {{ {looks} }}")
    return f"object {name} {{\n    " + "\n    ".join(fields) + "\n}"


def room_size(request: Request, entries: Mapping[str, CatalogEntry]) -> tuple[float, float]:
    """The room's sides (W along x, D along z): as written, or the room word's default
    times its size word, made larger where the things asked for need the floor."""
    if request.size is not None:
        return request.size
    from .vocabulary import ROOMS

    base = next((size for name, size in ROOMS.values() if name == request.room), (0.0, 0.0))
    footprint = 0.0
    for e in request.entities:
        if e.group:
            continue  # its members count
        w, _, d = entries[e.type].size
        style = next((s for s in entries[e.type].styles if s.name == e.style), None)
        if style is not None and style.size is not None:
            w, _, d = style.size
        if not any(s.source == e.id and s.label.startswith("OnTopOf") for s in request.statements):
            footprint += w * d
    side = math.sqrt(footprint * FLOOR_PER_FOOTPRINT + FLOOR_MARGIN)
    f = request.size_factor
    width = max(base[0] * f, side * 1.08, MIN_SIDE)
    depth = max(base[1] * f, side * 0.93, MIN_SIDE)
    # A thing beside a window needs the window's wall longer than the two side by side.
    beside, count = _beside_window(request, entries)
    if beside:  # one on each side of it, where there are two
        width = max(width, WINDOW[0] + min(count, 2) * (beside + 0.3) + 0.3)
    # A corner named on the door's wall ("a plant in the south-east corner", the door in
    # the south wall) stays a corner of its own, not "the corner by the door": the wall
    # leaves more than the describer's reach between the door and each of its ends.
    corners = [s.target.corner for s in request.statements if isinstance(s.target, Place)]
    need = DOOR_WIDTH + 2 * (DOOR_NEAR_CORNER + 0.3)
    for wall in request.doors:
        if any(corner is not None and wall in corner for corner in corners):
            if wall in ("north", "south"):
                width = max(width, need)
            else:
                depth = max(depth, need)
    return round(width, 1), round(depth, 1)


def _size(entries: Mapping[str, CatalogEntry], e) -> tuple[float, float, float]:
    """A thing's size in its style."""
    style = next((s for s in entries[e.type].styles if s.name == e.style), None)
    return style.size if style is not None and style.size is not None else entries[e.type].size


def _openings(
    request: Request, size: tuple[float, float], entries: Mapping[str, CatalogEntry]
) -> list[str]:
    """The door and window lines: on the walls the text named, else a door on the wall
    with the fewest things against it and, where a window is named, a window on the
    north wall; several on one wall are spread evenly along it."""
    against = {side: 0 for side in _SIDES}
    for s in request.statements:
        if isinstance(s.target, Place) and s.target.number is not None:
            against[_SIDES[s.target.number - 1]] += 1
    doors = [d or "" for d in request.doors] or [""]
    windows = list(request.windows)
    wants_window = any(
        isinstance(s.target, Place) and s.target.kind == "window" for s in request.statements
    )
    if wants_window and not windows:
        windows = [""]
    free = min(("south", "west", "east", "north"), key=lambda side: (against[side], 0))
    doors = [d or free for d in doors]
    request.door_walls = doors
    windows = [w or ("north" if free != "north" else "east") for w in windows]
    by_door = any(isinstance(s.target, Place) and s.target.by_door for s in request.statements)
    under = max(
        (
            _size(entries, e)[1]
            for e in request.entities
            for s in request.statements
            if s.source == e.id and s.label == "UnderWindow"
        ),
        default=0.0,
    )
    beside, count = _beside_window(request, entries)
    named = {
        frozenset(s.target.corner)
        for s in request.statements
        if isinstance(s.target, Place) and s.target.corner is not None
    }
    by_wall: dict[str, list[str]] = {side: [] for side in _SIDES}
    for side in doors:
        by_wall[side].append("door")
    for side in windows:
        by_wall[side].append("window")
    lines = []
    for side in _SIDES:
        kinds = by_wall[side]
        length = size[0] if side in ("north", "south") else size[1]
        # Things asked to stand against a wall with openings take its middle: the
        # openings then keep to its west or north half.
        ends = [
            frozenset(FIRST_CORNER[w]) in named
            for w in (side, _SIDES[(_SIDES.index(side) + 1) % 4])
        ]
        share = 0.5 if against[side] and not all(ends) else 1.0
        if len(kinds) > 1 and length * share / (len(kinds) + 1) < WINDOW[0] + 0.2:  # too close
            share = 1.0
        for k, kind in enumerate(kinds):
            offset = _number(max(0.9, length * share * (k + 1) / (len(kinds) + 1)))
            if share < 1.0 and len(kinds) == 1:  # alone on a wall wanted by others: aside
                offset = _number(WINDOW[0] / 2 + 0.35)
            if ends[0] and share < 1.0:
                # a corner named for something else is at this end: use the other end
                offset = _number(length - float(offset))
            if kind == "door" and k == 0 and side == doors[0] and by_door:
                offset = _number(DOOR_BY_CORNER)
            if kind == "door":
                lines.append(f"door {side} {offset} {_number(DOOR_WIDTH)}")
            else:
                w, sill, h = WINDOW
                # A thing asked to stand under a window must fit under its sill.
                sill = max(sill, under + 0.05)
                h = min(h, WALL_HEIGHT - 0.1 - sill)
                if (
                    beside
                    and count == 1
                    and len(kinds) == 1
                    and max(float(offset), length - float(offset)) - w / 2 < beside + 0.15
                ):
                    # a thing asked to stand beside it needs the wall on one side: the
                    # window goes towards the other end
                    offset = _number(max(w / 2 + 0.1, length - w / 2 - beside - 0.25))
                lines.append(f"window {side} {offset} {_number(w)} {_number(sill)} {_number(h)}")
    return lines


def _beside_window(request: Request, entries: Mapping[str, CatalogEntry]) -> tuple[float, int]:
    """The widest thing asked to stand beside a window (0: none), and how many are."""
    widths = [
        max(_size(entries, e)[0], _size(entries, e)[2])
        for e in request.entities
        for s in request.statements
        if s.source == e.id and s.label == "BesideWindow"
    ]
    return max(widths, default=0.0), len(widths)


def _target(target: str | Place, windows: int) -> str:
    if not isinstance(target, Place):
        return target
    if target.by_door or target.corner is not None:  # held in its corner (corner_starts)
        return "some wall"
    if target.kind == "window":
        return (
            f"window #{target.number}"
            if target.number and target.number <= windows
            else "some window"
        )
    if target.number is not None:
        return f"wall #{target.number}"
    return "some wall"


def _implicit(request: Request, entries: Mapping[str, CatalogEntry]) -> list[Statement]:
    """Constraints the text implies but does not state, never described: things on each
    side of one against a wall stand against that wall too, and a tall thing used from
    its front that nothing else places (a wardrobe) stands against some wall."""
    walls = {
        s.source: s.target
        for s in request.statements
        if s.label in ("AgainstWall", "InCorner", "UnderWindow") and isinstance(s.target, Place)
    }
    placed = {s.source for s in request.statements if not s.label.startswith("Implicit")}
    out = []
    for s in request.statements:
        if s.label == "ImplicitAlignedWith" and isinstance(s.target, str) and s.target in walls:
            place = walls[s.target]
            if place.kind == "window":
                place = Place("wall")
            out.append(
                Statement(
                    s.source, "ImplicitAgainstWall", Place("wall", place.number), s.start, s.end
                )
            )
    for e in request.entities:
        entry = entries[e.type]
        if e.id not in placed and tuple(entry.access) == ("front",) and entry.size[1] >= 0.8:
            out.append(Statement(e.id, "ImplicitAgainstWall", Place("wall"), e.start, e.end))
    return out


def rules_text(
    request: Request, entries: Mapping[str, CatalogEntry], ground: Ground | None = None
) -> str:
    """The rule set of a request (see the module docstring); ``ground``: outdoors, open
    ground for a room (``composer.outdoor``)."""
    keys: dict[tuple[str, str | None, str | None], str] = {}
    by_type: dict[str, int] = {}
    for e in request.entities:
        key = (e.type, e.style, e.colour)
        if key not in keys:
            by_type[e.type] = by_type.get(e.type, 0) + 1
            keys[key] = e.type if by_type[e.type] == 1 else f"{e.type}_{by_type[e.type]}"
    out = ["# Composed from English; edit it as any rule set (docs/rules-language.md).", ""]
    if ground is not None:
        return _outdoor_text(request, entries, ground, keys, out)
    size = room_size(request, entries)
    request.planned_size = size
    openings = _openings(request, size, entries)
    windows = sum(1 for line in openings if line.startswith("window"))
    out.append(f"scene {request.room} {{")
    out.append(f"    room {_number(size[0])} x {_number(size[1])} {{")
    out += [f"        {line}" for line in openings]
    out.append("    }")
    out.append("    ground floor")
    out.append(f"    start {START}")
    out.append("    max_depth 4")
    out.append(f"    max_nodes {max(len(request.entities), 1) + 4}")
    out.append("}")
    out.append("")
    for (type_, style, colour), name in keys.items():
        out.append(entry_text(name, entries[type_], style, colour))
    out.append("")
    statements = [f"{START} -> {{"]
    statements += _production_body(
        request, keys, request.statements + _implicit(request, entries), windows
    )
    statements.append("}")
    if len(statements) == 2:  # nothing asked for: an empty room
        statements = [f"{START} -> {{ }}"]
    out += statements
    return "\n".join(out) + "\n"


def _outdoor_text(
    request: Request,
    entries: Mapping[str, CatalogEntry],
    ground: Ground,
    keys: dict[tuple[str, str | None, str | None], str],
    out: list[str],
) -> str:
    """``rules_text`` outdoors: open ground, the ways' entries, no walls."""
    settle(request, entries)
    out += _ground_lines(request, entries, ground, len(request.entities) + 4)
    out.append("")
    for e in request.entities:  # the members ``settle`` added
        key = (e.type, e.style, e.colour)
        if key not in keys:
            same = sum(1 for k in keys if k[0] == e.type)
            keys[key] = e.type if not same else f"{e.type}_{same + 1}"
    for (type_, style, colour), name in keys.items():
        entry = entries[type_]
        if entry.kind in ("path", "junction"):
            out.append(_way_entry_text(name, entry))
        else:
            out.append(entry_text(name, entry, style, colour))
    out.append("")
    body = _production_body(request, keys, request.statements, 0, entries)
    out += [f"{START} -> {{", *body, "}"] if body else [f"{START} -> {{ }}"]
    return "\n".join(out) + "\n"


def _ground_lines(
    request: Request, entries: Mapping[str, CatalogEntry], ground: Ground, nodes: int
) -> list[str]:
    """The scene block of an outdoor rule set."""
    w, d = ground_extent(request, entries, ground)
    request.planned_size = (w, d)
    return [
        f"scene {scene_name(request, ground)} {{",
        f"    extent {_number(w)} x {_number(d)}",
        "    ground grass",
        f"    start {START}",
        "    max_depth 4",
        f"    max_nodes {nodes}",
        "}",
    ]


def _way_entry_text(name: str, entry: CatalogEntry) -> str:
    """A path's or junction's catalog entry, as the catalog has it."""
    parts = [f"noun {_quote(entry.noun)}"]
    if entry.plural:
        parts.append(f"plural {_quote(entry.plural)}")
    if entry.kind == "path":
        parts.append(
            f"width {_number(entry.width)} max_length {_number(entry.max_length)} "
            f"segments {entry.segments}"
        )
    else:
        parts.append("size " + " x ".join(_number(v) for v in entry.size))
        if entry.network != "organic":
            parts.append(f"network {entry.network}")
    parts.append(f"colour {_hex(entry.colour)}")
    return f"{entry.kind} {name} {{ {' '.join(parts)} }}"


def _production_body(
    request: Request,
    keys: Mapping[tuple[str, str | None, str | None], str],
    statements: list[Statement],
    windows: int,
    entries: Mapping[str, CatalogEntry] | None = None,
) -> list[str]:
    """The start production's lines: the things at the top level first, then each group
    with its members in its block (their things first, then the groups among them, each
    with its own block), each thing with its relations to what is made before it, the
    rest after the things of their block. A group's block sees the things of the blocks
    around it made before it, not another group's members: a relation between members
    of two groups cannot be written, and is left out. ``request.made`` gets the order
    the production makes the things in."""
    top = [e for e in request.entities if e.parent is None and not e.group]
    if entries is not None:  # outdoors: the junctions and paths first
        top = made_first(top, request, entries)
    groups = [e for e in request.entities if e.parent is None and e.group]
    members: dict[str, list] = {e.id: [] for e in request.entities if e.group}
    for e in request.entities:
        if e.parent is not None:
            members[e.parent].append(e)
    for ids in members.values():
        ids.sort(key=lambda e: e.group)  # a block's things before its groups

    def made(e) -> list[str]:
        return [e.id] + [eid for m in members.get(e.id, []) for eid in made(m)]

    order = [e.id for e in top] + [eid for g in groups for eid in made(g)]
    request.made = order
    rank = {eid: k for k, eid in enumerate(order)}
    parent = {e.id: e.parent for e in request.entities}

    def around(block: str | None) -> list[str | None]:
        """The block and the blocks around it, innermost first."""
        out: list[str | None] = [block]
        while out[-1] is not None:
            out.append(parent[out[-1]])
        return out

    def block_of(s: Statement) -> str | None | bool:
        """The block a statement is written in (a group's id, None for the top level),
        or False when no block sees both its things."""
        a = parent[s.source]
        b = parent[s.target] if isinstance(s.target, str) else a
        if a == b:
            return a
        if a in around(b):
            inner, outer = b, s.source
        elif b in around(a):
            inner, outer = a, s.target
        else:
            return False  # members of two groups
        return inner if rank[outer] < rank[inner] else False

    inline: dict[str, list[str]] = {}
    later: dict[str | None, list[str]] = {}
    for st in statements:
        block = block_of(st)
        if block is False:
            if not st.label.startswith("Implicit"):
                request.issues.append(
                    Issue(
                        st.start,
                        st.end,
                        "",
                        "a relation between things of two groups is not composed",
                    )
                )
            continue
        target = _target(st.target, windows)
        before = isinstance(st.target, Place) or rank[st.target] < rank[st.source]
        if before and parent[st.source] == block:
            inline.setdefault(st.source, []).extend([st.label, target])
        else:
            later.setdefault(block, []).append(f"{st.source} {st.label} {target}")

    def line(e, indent: str) -> str:
        return indent + " ".join(
            [keys[(e.type, e.style, e.colour)], "as", e.id, *inline.get(e.id, [])]
        )

    def block(g, indent: str) -> list[str]:
        out = [line(g, indent) + " {"]
        for m in members[g.id]:
            out += block(m, indent + "    ") if m.group else [line(m, indent + "    ")]
        out += [indent + "    " + text for text in later.get(g.id, [])]
        return out + [indent + "}"]

    lines = [line(e, "    ") for e in top]
    for g in groups:
        lines += block(g, "    ")
    lines += ["    " + text for text in later.get(None, [])]
    return lines


#: The yaw that turns a thing's back to each wall (its front, local +Z, into the room).
_BACK_TO = {"north": 0.0, "east": -math.pi / 2, "south": math.pi, "west": math.pi / 2}


def corner_starts(
    request: Request, entries: Mapping[str, CatalogEntry], size: tuple[float, float]
) -> dict[str, list[tuple[float, float, float]]]:
    """Where a thing asked for in a named corner may stand (x, z, yaw): in that corner,
    back to one of its two walls (the first-named wall's first). Its relation is
    ``InCorner`` to whichever wall the layout takes, which either corner of any wall
    satisfies; the layout is held to these poses in turn so that the named corner is
    the one it keeps (``compose.lay_out``)."""
    out = {}
    for s in request.statements:
        if not isinstance(s.target, Place) or (s.target.corner is None and not s.target.by_door):
            continue
        e = next(e for e in request.entities if e.id == s.source)
        first, second = s.target.corner or FIRST_CORNER[request.door_walls[0]]
        sign = {"north": -1.0, "south": 1.0, "west": -1.0, "east": 1.0}
        poses = []
        for back in (first, second):
            w, _, d = _size(entries, e)
            if back in ("east", "west"):
                w, d = d, w
            other = second if back == first else first
            x_side = back if back in ("east", "west") else other
            z_side = back if back in ("north", "south") else other
            x = sign[x_side] * (size[0] / 2 - w / 2 - 0.01)
            z = sign[z_side] * (size[1] / 2 - d / 2 - 0.01)
            poses.append((x, z, _BACK_TO[back]))
        out[e.id] = poses
    return out
