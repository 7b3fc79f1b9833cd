"""Writes an ``Induction`` (``induce``) as a rules file a person can read and edit.

The file has the scene block (the room or extent, ``max_nodes`` the most objects the
rules can make), the catalog (one entry per type, a comment saying how many objects
and examples it rests on), the start production ``Scene`` (each group's production and
each loose type with its count per scene), each group's production (its anchor bound
as ``the_ANCHOR``, then a statement per member relative to it), and the productions of
members with several placements (``ChairAtDesk(the_desk) -> 14: {...} | 3: {...}``) or
with members of their own, and of members placed together (``sides_together``:
``FloorLampAndSideTableAtArmchair(the_armchair) -> 6: {...} | 3: {...}``, each
alternative a way the examples placed them all, with what stands by them). Every
number carries a comment saying what it was read from ("with 12 of 20 desks (1: 5,
2: 5, 3: 2)"). Numbers are written as the grammar
reads them: decimals without exponents, probabilities with two decimals and never 0.
"""

from __future__ import annotations

import math
import textwrap
from collections import Counter
from collections.abc import Sequence

from scenewright.core.room import Room
from scenewright.describer.english import plural_of, with_article

from .induction import Group, Induction, Joint, Member, Placement
from .rule_names import camel, colour_text, identifier, unique_name


def _holds(member: Member, chosen) -> bool:
    """Whether a member below ``member`` (at any depth) is in ``chosen`` (``id``s)."""
    return any(id(child) in chosen or _holds(child, chosen) for child in member.children)


#: Probabilities are written with two decimals, never as 0.
PROBABILITY_DECIMALS = 2


def number(value: float, decimals: int = 3) -> str:
    """A decimal the rules grammar reads (no exponent), trailing zeros dropped."""
    text = f"{value:.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def size_text(size: Sequence[float]) -> str:
    return " x ".join(number(max(v, 0.001)) for v in size)


def probability_text(share: float) -> str:
    return number(
        max(round(share, PROBABILITY_DECIMALS), 10.0**-PROBABILITY_DECIMALS), PROBABILITY_DECIMALS
    )


def drawn_share(share: float) -> bool:
    """Whether a wall label held for ``share`` of the objects is written as a draw: its
    share is under 1 as written."""
    return probability_text(share) != "1"


def _quoted(text: str) -> str:
    return '"' + text.replace('"', "'").replace("\n", " ")[:200] + '"'


# -- writing the rules ------------------------------------------------------------------


def count_parts(distribution: Counter, total: int) -> tuple[str, str, str]:
    """The ``[COUNT] [PROB?]`` words of a statement made ``distribution`` times (count ->
    how many of ``total`` parents or scenes had that many); how many had any ("12 of
    20"); and how many had how many ("1: 5, 2: 5, 3: 2"; empty when always the same)."""
    present = {k: v for k, v in distribution.items() if k > 0}
    seen = sum(present.values())
    if not present:
        return "", f"0 of {total}", ""
    words = []
    low, high = min(present), max(present)
    if low == high:
        if low > 1:
            words.append(str(low))
    else:
        words.append(
            f"{low}..{high} {{{' '.join(str(present.get(k, 0)) for k in range(low, high + 1))}}}"
        )
    if seen < total:
        words.append(probability_text(seen / total) + "?")
    detail = "" if low == high else ", ".join(f"{k}: {present[k]}" for k in sorted(present))
    return " ".join(words), f"{seen} of {total}", detail


def comment_lines(text: str, width: int = 100) -> list[str]:
    """``text`` as ``#`` comment lines of at most ``width`` characters."""
    return ["# " + line for line in textwrap.wrap(text, width - 2, break_on_hyphens=False)]


#: The label the objects of a drawn wall label's other share get, and a placement that
#: never stood at the wall beside a parent that does: kept off the walls, and not
#: described (the examples said nothing of it).
AWAY = "ImplicitAwayFromWall"


def rules_text(induction: Induction) -> str:
    """The rules file of ``induction``."""
    return RulesWriter(induction).text()


class RulesWriter:
    """Writes an ``Induction`` as a rules file a person can read and edit."""

    INDENT = "    "

    def __init__(self, induction: Induction):
        self.induction = induction
        self.productions: list[list[str]] = []
        self.rule_names: set[str] = {"Scene"} | {group.rule for group in induction.groups}
        self.depth = 1
        self.types = set(induction.catalog)
        #: Member productions written, by member: written once, called wherever needed;
        #: so are the productions of members placed together, by joint.
        self.written: dict[object, tuple[str, int]] = {}

    # -- names --

    def binding(self, type_name: str, taken: set[str]) -> str:
        base = f"the_{type_name}"
        name, k = base, 1
        while name in self.types or name in taken:
            k += 1
            name = f"{base}_{k}"
        taken.add(name)
        return name

    # -- parts --

    def header(self) -> list[str]:
        ind = self.induction
        shown = ", ".join(ind.examples[:3]) + (", ..." if len(ind.examples) > 3 else "")
        return [
            f"# {ind.name}.rules - induced by `scenewright learn` from {ind.scenes} example scenes ({shown}),",
            f"# seed {ind.seed}. Related type pairs: the {ind.relations.test} test (learning/relation_finding.py), and",
            "# what rests on what, measured from the boxes. Where each object stands by its parent:",
            "# density-peak clusters of its relative poses, labelled by the relations that hold at each",
            "# cluster's centre (the layout's own measures). 'k of n' says how many examples, or parent",
            "# objects, showed it. An ordinary rules file: edit it freely.",
            "",
        ]

    def scene_block(self, max_nodes: int) -> list[str]:
        ind = self.induction
        lines = [f"scene {identifier(ind.name, set())} {{"]
        if ind.room is not None:
            lines += self.room_lines(ind.room, ind.room_source)
        else:
            lines.append(
                f"{self.INDENT}extent {number(ind.extent[0], 2)} x {number(ind.extent[1], 2)}"
                f"    # the median extent of the {ind.scenes} examples"
            )
            lines.append(f"{self.INDENT}ground {identifier(ind.ground, set())}")
        lines += [
            f"{self.INDENT}start Scene",
            f"{self.INDENT}max_depth {self.depth + 2}",
            f"{self.INDENT}max_nodes {max(max_nodes, 1)}    # the most objects these rules can make",
            "}",
            "",
        ]
        return lines

    def room_lines(self, room: Room, source: str | None) -> list[str]:
        width, depth = room.extent
        hw, hd = width / 2.0, depth / 2.0
        rectangle = [(-hw, -hd), (hw, -hd), (hw, hd), (-hw, hd)]
        is_rectangle = len(room.corners) == 4 and all(
            math.isclose(x, rx, abs_tol=1e-6) and math.isclose(z, rz, abs_tol=1e-6)
            for (x, z), (rx, rz) in zip(room.corners, rectangle, strict=False)
        )
        shape = (
            f"{number(width)} x {number(depth)}"
            if is_rectangle
            else " ".join(f"({number(x)}, {number(z)})" for x, z in room.corners)
        )
        lines = [
            f"{self.INDENT}room {shape} {{    # the room of {source}, the example room nearest the median size"
        ]
        lines.append(f"{self.INDENT * 2}height {number(room.height)}")
        wall_number = {wall.id: k + 1 for k, wall in enumerate(room.walls)}
        for opening in room.openings:
            where = f"{wall_number[opening.wall]} {number(opening.offset)} {number(opening.width)}"
            if opening.kind == "door":
                lines.append(f"{self.INDENT * 2}door {where} {number(opening.height)}")
            else:
                lines.append(
                    f"{self.INDENT * 2}window {where} {number(opening.sill)} {number(opening.height)}"
                )
        lines.append(f"{self.INDENT}}}")
        return lines

    def catalog_lines(self) -> list[str]:
        ind = self.induction
        lines = [
            f"# -- catalog: the {len(ind.catalog)} types seen; sizes are medians (W x H x D, metres) "
            + "-" * 8,
            "",
        ]
        walled = ind.walled_types()
        for entry in ind.catalog.values():
            seen_as = (
                f" (seen as {', '.join(entry.sources)})"
                if list(entry.sources) != [entry.name]
                else ""
            )
            borrowed = (
                f"; noun, shape and colour from the shipped {entry.borrowed}"
                if entry.borrowed
                else ""
            )
            lines.append(
                f"# {entry.name}: {entry.objects} objects in {entry.scenes} of {ind.scenes} examples{seen_as}{borrowed}"
            )
            lines.append(f"object {entry.name} {{")
            lines.append(f"{self.INDENT}noun {_quoted(entry.noun)}")
            if entry.plural:
                lines.append(f"{self.INDENT}plural {_quoted(entry.plural)}")
            lines.append(f"{self.INDENT}size {size_text(entry.size)}")
            if entry.shape:
                lines.append(f"{self.INDENT}shape {entry.shape}")
            lines.append(f"{self.INDENT}colour {colour_text(entry.colour)}")
            share = ind.walls.get(entry.name)
            kept = share.gap() if share is not None and entry.name in walled else None
            if share is not None and kept is not None:
                median = share.median_gap() or 0.0
                capped = f", written {number(kept, 2)}" if round(median, 2) > kept else ""
                lines.append(
                    f"{self.INDENT}wall_gap {number(kept, 2)}    # off the wall: the median of "
                    f"{len(share.gaps)} at one, {median:.2f} m{capped}"
                )
            for style in entry.styles:
                fields = []
                if style.noun:
                    fields.append(f"noun {_quoted(style.noun)}")
                if style.size:
                    fields.append(f"size {size_text(style.size)}")
                if style.shape:
                    fields.append(f"shape {style.shape}")
                if style.colour:
                    fields.append(f"colour {colour_text(style.colour)}")
                body = "{ " + " ".join(fields) + " }" if fields else "{ }"
                seen = (
                    "no style given"
                    if style.source is None
                    else f"{style.source!r}"
                    if style.source != style.name
                    else ""
                )
                note = f"{style.count} of {entry.objects}" + (f", {seen}" if seen else "")
                lines.append(f"{self.INDENT}style {style.name} {style.count} {body}    # {note}")
            lines.append("}")
            lines.append("")
        return lines

    def relation_words(self, labels: Sequence[str], target: str) -> str:
        return " ".join(f"{label} {target}" for label in labels)

    @staticmethod
    def wall_words(wall: str | None) -> str:
        return f" {wall} some wall" if wall else ""

    def placed_wall(self, member: Member, index: int | None = None) -> str:
        """The wall words of ``member``'s object in its placement ``index`` (its only
        one when None): the label its objects there held (``Placement.wall``), so a lamp
        flush with the wall in most examples and out in the room in the rest is put at
        the wall only in its flush placement. A member with no placement takes its type's."""
        if not member.placements:
            return self.wall_words(member.wall)
        if self.wall_draw(member, index) is not None:
            return ""  # a draw of its own (``draw_line``)
        if self.kept_off(member, index):
            return f" {AWAY} some wall"
        return self.wall_words(self.placement(member, index).wall)

    @staticmethod
    def placement(member: Member, index: int | None) -> Placement:
        """``member``'s placement ``index``, its only one when None."""
        return member.placements[0 if index is None else index]

    def kept_off(self, member: Member, index: int | None = None) -> bool:
        """Whether ``member``'s placement ``index`` is kept off the walls outright: none
        of its objects stood at one, they stood on the floor, and their parent type stands
        at a wall, so that where they stand by it could come within a wall label's reach
        of the wall (a side table beside an armchair 4 cm off it)."""
        if member.carried or self.induction.room is None:
            return False
        parent = self.induction.walls.get(member.parent)
        return (
            self.placement(member, index).wall is None
            and parent is not None
            and parent.label() is not None
        )

    def wall_draw(self, member: Member, index: int | None = None) -> Placement | None:
        """``member``'s placement ``index`` (its only one when None) where its wall label
        held for some of its objects only (``Placement.wall_share`` under 1 as written):
        the label is then a draw of that share (``draw_line``), so a lamp at the wall in
        7 of 9 corners is put there in about 7 of 9 scenes; else None."""
        if not member.placements:
            return None
        placement = self.placement(member, index)
        return placement if placement.wall and drawn_share(placement.wall_share) else None

    def draw_line(
        self, type_name: str, placement: Placement, bound: str, noted: bool = True
    ) -> str:
        """The statement drawing ``placement``'s wall label for the object (of type
        ``type_name``) bound to ``bound``; ``noted``: with how many of its objects held it."""
        held = round(placement.wall_share * placement.weight)
        note = f"    # at the wall: {held} of {placement.weight}" if noted else ""
        assert placement.wall is not None  # only a placement with a wall label is drawn
        return self.wall_draw_words(type_name, placement.wall, placement.wall_share, bound) + note

    def wall_draw_words(self, type_name: str, wall: str, share: float, bound: str) -> str:
        """The call drawing, for the object (of type ``type_name``) bound to ``bound``,
        ``wall`` (a wall label) with ``share`` and kept off the walls otherwise: a
        production (written once per type, label and share) of those two weighted
        alternatives, the second ``AWAY``. A draw of the label alone would leave the rest
        where the layout puts them, some by a wall: a lamp beside an armchair at the
        wall, in 4 of 9 examples at the wall, was at it in two thirds of the scenes made."""
        key = ("wall draw", type_name, wall, probability_text(share))
        if key not in self.written:
            name = unique_name(f"{camel(type_name)}{wall}OrAway", self.rule_names)
            param = self.binding(type_name, set())
            noun = self.induction.catalog[type_name].noun
            at, away = probability_text(share), probability_text(1.0 - share)
            lines = comment_lines(
                f"{name}: {with_article(noun)} placed this way stood {wall} in {at} of the "
                "examples; kept off the walls otherwise"
            )
            lines.append(
                f"{name}({param}) -> {at}: {{ {param}{self.wall_words(wall)} }} "
                f"| {away}: {{ {param} {AWAY} some wall }}"
            )
            lines.append("")
            self.productions.append(lines)
            self.written[key] = (name, 0)
        return f"{self.written[key][0]}({bound})"

    def noun_plural(self, type_name: str) -> str:
        """The type's noun in the plural, for comments ("with 18 of 20 desks")."""
        entry = self.induction.catalog[type_name]
        return plural_of(entry.noun, entry.plural)

    def member_note(self, member: Member) -> str:
        """How many parent objects had ``member``'s objects ("with 7 of 9 side tables
        (1: 4, 2: 3)")."""
        _, seen, detail = count_parts(member.per_parent, member.parents)
        return f"with {seen} {self.noun_plural(member.parent)}" + (f" ({detail})" if detail else "")

    def statements(
        self,
        members: Sequence[Member],
        joints: Sequence[Joint],
        target: str,
        depth: int,
        fixed: dict[int, int] | None = None,
        taken: set[str] | None = None,
        noted: bool = True,
    ) -> tuple[list[str], int]:
        """The statements (indented) making ``members`` by one parent object bound to
        ``target``, those of a joint in one call where its first member stands; and the
        most objects they make. Inside an alternative of a joint: ``fixed``, the
        placement of each of its members (by ``id``), whose members (and the members
        above them) are written here with their placements; ``taken``, the names bound
        in the alternative; ``noted``: with comments."""
        fixed = fixed or {}
        taken = set() if taken is None else taken
        lines, most = [], 0
        first_of = {id(joint.tops[0]): joint for joint in joints}
        in_joint = {id(m) for joint in joints for m in joint.tops}
        for member in members:
            if id(member) in fixed or _holds(member, fixed):
                body, made = self.placed_lines(member, fixed, target, taken, depth, noted)
                lines += [self.INDENT + line for line in body]
            elif id(member) in first_of:
                statement, made = self.joint_statement(first_of[id(member)], target, depth)
                lines.append(self.INDENT + statement)
            elif id(member) in in_joint:
                continue  # made by its joint's call
            else:
                statement, made = self.member_statement(member, target, depth)
                lines.append(self.INDENT + (statement if noted else statement.split("    #")[0]))
            most += made
        return lines, most

    def joint_statement(self, joint: Joint, target: str, depth: int) -> tuple[str, int]:
        """The call of the production placing the members of ``joint`` together (written
        once), and the most objects it makes."""
        self.depth = max(self.depth, depth)
        if id(joint) not in self.written:
            self.written[id(joint)] = self.joint_production(joint, depth + 1)
        name, most = self.written[id(joint)]
        notes = "; ".join(
            f"{self.noun_plural(m.type)} {self.member_note(m)}" for m in joint.members
        )
        return f"{name}({target})    # {notes}; placed together", most

    def joint_production(self, joint: Joint, depth: int) -> tuple[str, int]:
        """Write the production of weighted alternatives placing the members of
        ``joint`` as the examples placed them together, with what stands by them;
        returns its name and the most objects one call makes."""
        self.depth = max(self.depth, depth + 1)
        root = joint.root
        param = self.binding(root, set())
        nouns = [self.induction.catalog[m.type].noun for m in joint.members]
        name = unique_name(
            "And".join(camel(m.type) for m in joint.members) + f"At{camel(root)}",
            self.rule_names,
        )
        listed = ", ".join(with_article(n) for n in nouns[:-1]) + f" and {with_article(nouns[-1])}"
        lines = comment_lines(
            f"{name}: where {listed} stand by {with_article(self.induction.catalog[root].noun)} "
            f"(each by what it is placed by), placed together as the examples placed them: "
            f"{joint.complete} {self.noun_plural(root)} with one of each, in {len(joint.ways)} "
            f"ways (where one stands tells where the other does: p {joint.p_value:.2g})"
            + (
                f"; {unplaced} more with one in no placement"
                if (unplaced := joint.parents - joint.complete - joint.missing)
                else ""
            )
            + (
                f"; {joint.missing} more missing some, counted in the ways they fit"
                if joint.missing
                else ""
            )
        )
        head = f"{name}({param}) -> "
        most = 0
        for k, (way, count) in enumerate(joint.ways):
            lead = head if k == 0 else self.INDENT + "| "
            weight = number(count, 2)
            own = [
                self.induction.catalog[m.type].noun
                for m, index in zip(joint.members, way, strict=True)
                if index < 0
            ]
            drawn = (
                f"; the {' and the '.join(own)} in no placement: drawn on its own" if own else ""
            )
            lines.append(f"{lead}{weight}: {{    # {weight} of {joint.parents}{drawn}")
            fixed = {id(m): index for m, index in zip(joint.members, way, strict=True)}
            body, made = self.statements(
                joint.tops, [], param, depth + 1, fixed, {param}, noted=k == 0
            )
            lines += [self.INDENT + line for line in body]
            lines.append(self.INDENT + "}")
            most = max(most, made)
        lines.append("")
        self.productions.append(lines)
        return name, most

    def placed_lines(
        self,
        member: Member,
        fixed: dict[int, int],
        param: str,
        taken: set[str],
        depth: int,
        noted: bool,
    ) -> tuple[list[str], int]:
        """The lines (not indented) making ``member``'s object (at most one) by the
        parent bound to ``param``, in its placement in ``fixed`` (else drawn as its own),
        with what stands by it, members of the joint among them in theirs; and the most
        objects they make. ``noted``: with the member's comment."""
        counts, _, _ = count_parts(member.per_parent, member.parents)
        prefix = (counts + " ") if counts else ""
        index = fixed.get(id(member))
        note = f"    # {self.member_note(member)}" if noted else ""
        wall = self.placed_wall(member, index if index is not None and index >= 0 else None)
        if index == -1 and not _holds(member, fixed):  # in no placement: drawn on its own
            statement, made = self.member_statement(member, param, depth)
            return [statement if noted else statement.split("    #")[0]], made
        draw = None
        if index is None or index < 0:  # above members of the joint: one, placed as drawn
            bound = self.binding(member.type, taken)
            if len(member.placements) > 1:
                places = self.placement_production(member)
                first = f"{places}({param}) as {bound}"
            else:
                labels = member.placements[0].labels if member.placements else ()
                words = self.relation_words(labels, param)
                first = f"{member.type} as {bound} {words}".rstrip() + wall
                draw = self.wall_draw(member)
        else:
            labels = member.placements[index].labels
            words = self.relation_words(labels, param)
            draw = self.wall_draw(member, index)
            if not member.children:
                if draw is None:
                    return [f"{prefix}{member.type} {words}".rstrip() + wall + note], 1
                bound = self.binding(member.type, taken)
                first = f"{prefix}{member.type} as {bound} {words}".rstrip()
                return [first + note, self.draw_line(member.type, draw, bound, noted)], 1
            if prefix:  # made or not as drawn: a production of its own for this placement
                return self.optional_placed(member, index, param, depth, prefix, note)
            bound = self.binding(member.type, taken)
            first = f"{member.type} as {bound} {words}".rstrip() + wall
        body, most = self.statements(
            member.children, member.joints, bound, depth + 1, fixed, taken, noted
        )
        drawn = [] if draw is None else [self.draw_line(member.type, draw, bound, noted)]
        return [first + note] + drawn + [line[len(self.INDENT) :] for line in body], 1 + most

    def optional_placed(
        self, member: Member, index: int, param: str, depth: int, prefix: str, note: str
    ) -> tuple[list[str], int]:
        """The call making ``member`` (optional, with members of its own, none of them
        in the joint) in its placement ``index``, its production written once."""
        key = (id(member), index)
        labels = member.placements[index].labels
        if key not in self.written:
            own = unique_name(f"{camel(member.type)}{labels[0] if labels else ''}", self.rule_names)
            bound = self.binding(member.type, {param})
            noun = self.induction.catalog[member.type].noun
            body_lines = comment_lines(
                f"{own}: {with_article(noun)} {labels[0] if labels else 'by'} its "
                f"{self.induction.catalog[member.parent].noun}, and what stands by it"
            )
            body_lines.append(f"{own}({param}) -> {{")
            body_lines.append(
                f"{self.INDENT}{member.type} as {bound} {self.relation_words(labels, param)}".rstrip()
                + self.placed_wall(member, index)
            )
            if (draw := self.wall_draw(member, index)) is not None:
                body_lines.append(self.INDENT + self.draw_line(member.type, draw, bound))
            body, most = self.members_body(member.children, bound, member.joints, depth + 1)
            self.productions.append(body_lines + body)
            self.written[key] = (own, most)
        own, most = self.written[key]
        return [f"{prefix}{own}({param}){note}"], most

    def placement_lines(self, member: Member) -> tuple[str, list[str]]:
        """The name and lines of the production of ``member``'s placements (two or
        more), weighted alternatives taking its parent."""
        param = self.binding(member.parent, set())
        placed = member.placements
        total = sum(p.weight for p in placed)
        noun, parent_noun = (
            self.induction.catalog[member.type].noun,
            self.induction.catalog[member.parent].noun,
        )
        places = unique_name(f"{camel(member.type)}At{camel(member.parent)}", self.rule_names)
        lines = comment_lines(
            f"{places}: how {with_article(noun)} stands by its {parent_noun}: "
            f"{total} of them in {len(placed)} ways"
        )
        head = f"{places}({param}) -> "
        bound = self.binding(member.type, {param})
        for k, placement in enumerate(placed):
            if self.wall_draw(member, k) is None:
                body = f"{{ {member.type} {self.relation_words(placement.labels, param)}".rstrip()
                body += self.placed_wall(member, k) + " }"
            else:  # the alternative's own comment says how many
                words = self.relation_words(placement.labels, param)
                draw = self.draw_line(member.type, placement, bound, noted=False)
                body = f"{{ {member.type} as {bound} {words}".rstrip() + f"; {draw} }}"
            lead = head if k == 0 else " " * (len(head) - 2) + "| "
            lines.append(f"{lead}{placement.weight}: {body}    # {placement.weight} of {total}")
        lines.append("")
        return places, lines

    def placement_production(self, member: Member) -> str:
        """The production of ``member``'s placements, written once."""
        key = ("places", id(member))
        if key not in self.written:
            places, lines = self.placement_lines(member)
            self.productions.append(lines)
            self.written[key] = (places, 1)
        return self.written[key][0]

    def member_statement(self, member: Member, target: str, depth: int) -> tuple[str, int]:
        """The statement that makes ``member``'s objects by one parent object bound to
        ``target``, and the most objects it can make."""
        self.depth = max(self.depth, depth)
        counts, seen, detail = count_parts(member.per_parent, member.parents)
        prefix = (counts + " ") if counts else ""
        note = self.member_note(member)
        if member.outliers:
            note += f", {member.outliers} outlier{'s' * (member.outliers != 1)} left out"
        unplaced = sum(c.size for c in member.clusters if not c.labels)
        if unplaced:
            note += f", {unplaced} in a cluster no label fits"
        largest = max(member.per_parent) if member.per_parent else 0
        if member.children or len(member.placements) > 1 or self.wall_draw(member):
            if id(member) not in self.written:
                self.written[id(member)] = self.member_production(member, depth + 1)
            name, below = self.written[id(member)]
            return f"{prefix}{name}({target})    # {note}", largest * below
        labels = member.placements[0].labels if member.placements else ()
        if member.placements:
            note += f"; {member.placements[0].weight} of {member.instances} in one cluster of poses"
        text = (
            f"{prefix}{member.type} {self.relation_words(labels, target)}".rstrip()
            + self.placed_wall(member)
        )
        return f"{text}    # {note}", largest

    def member_production(self, member: Member, depth: int) -> tuple[str, int]:
        """Write the production(s) of a member with several placements or with
        children of its own; returns the production to call with the parent's binding
        and the most objects one call makes."""
        self.depth = max(self.depth, depth)
        param = self.binding(member.parent, set())
        placed = member.placements or [Placement((), member.instances)]
        noun, parent_noun = (
            self.induction.catalog[member.type].noun,
            self.induction.catalog[member.parent].noun,
        )
        lines: list[str] = []
        places = None
        if len(placed) > 1:
            places, lines = self.placement_lines(member)
            self.written[("places", id(member))] = (places, 1)
            if not member.children:
                self.productions.append(lines)
                return places, 1
            self.depth = max(self.depth, depth + 1)
        own = unique_name(camel(member.type), self.rule_names)
        bound = self.binding(member.type, {param})
        body_lines = comment_lines(
            f"{own}: {with_article(noun)} by its {parent_noun}, and what stands by it"
        )
        body_lines.append(f"{own}({param}) -> {{")
        if places:
            body_lines.append(f"{self.INDENT}{places}({param}) as {bound}")
        else:
            words = self.relation_words(placed[0].labels, param)
            body_lines.append(
                f"{self.INDENT}{member.type} as {bound} {words}".rstrip() + self.placed_wall(member)
            )
            if (draw := self.wall_draw(member)) is not None:
                body_lines.append(self.INDENT + self.draw_line(member.type, draw, bound))
        body, made = self.statements(member.children, member.joints, bound, depth + 1)
        body_lines += body + ["}", ""]
        self.productions.append(lines + body_lines)
        return own, 1 + made

    def alone_production(self, member: Member, wall: str | None) -> tuple[str, int]:
        """Write the production of ``member``'s type made without its parent (objects
        seen without one) with its own members by it; returns its name and the most
        objects it makes."""
        name = unique_name(f"{camel(member.type)}Alone", self.rule_names)
        bound = self.binding(member.type, set())
        noun = self.induction.catalog[member.type].noun
        lines = comment_lines(
            f"{name}: {with_article(noun)} seen without {with_article(self.induction.catalog[member.parent].noun)}, "
            "and what stands by it"
        )
        lines += [f"{name} -> {{", f"{self.INDENT}{member.type} as {bound}{self.wall_words(wall)}"]
        body, most = self.members_body(member.children, bound, member.joints)
        self.productions.append(lines + body)
        return name, most

    def members_body(
        self, members: Sequence[Member], bound: str, joints: Sequence[Joint], depth: int = 2
    ) -> tuple[list[str], int]:
        """The statements making ``members`` by the object bound to ``bound`` (``joints``:
        those placed together), closing a production's body; and the most objects the
        body makes with that object."""
        lines, most = self.statements(members, joints, bound, depth)
        return lines + ["}", ""], 1 + most

    def group_lines(self, group: Group) -> tuple[list[str], int]:
        taken: set[str] = set()
        bound = self.binding(group.anchor, taken)
        ind = self.induction
        related = [
            p
            for p in ind.relations.pairs
            if p.related and p.a in group.types and p.b in group.types and p.a != p.b
        ]
        pairs = ", ".join(
            f"{p.a}-{p.b} (" + ("a fixed arrangement" if p.fixed else f"p {p.p_value:.3g}") + ")"
            for p in related
            if p.p_value is not None
        )
        lines = comment_lines(
            f"{group.rule}: {with_article(ind.catalog[group.anchor].noun)} and what stands by it."
        )
        if pairs:
            lines += comment_lines(f"Related pairs ({ind.relations.test} test): {pairs}.")
        supports = sorted(
            (upper, lower)
            for upper, lower in ind.resting
            if upper in group.types and lower in group.types
        )
        if supports:
            lines += comment_lines(
                "Resting: "
                + ", ".join(
                    f"{upper} on {lower} in {ind.resting_counts[(upper, lower)][0]} of {ind.resting_counts[(upper, lower)][1]} scenes holding both"
                    for upper, lower in supports
                )
                + "."
            )
        lines.append(f"{group.rule} -> {{")
        share = ind.walls.get(group.anchor)
        drawn = share.drawn() if share is not None and ind.room is not None else None
        words, draw = self.by_no_parent(group.anchor, drawn)
        note = ""
        if drawn is not None:
            assert share is not None  # drawn from it
            wall = drawn[0]
            note = f"    # {wall}: {share.held[wall]} of {share.objects} {self.noun_plural(group.anchor)}"
        lines.append(f"{self.INDENT}{group.anchor} as {bound}{words}{note}")
        if draw is not None:
            lines.append(self.INDENT + self.wall_draw_words(group.anchor, *draw, bound))
        body, most = self.members_body(group.members, bound, group.joints)
        return lines + body, most

    def by_no_parent(
        self, type_name: str, drawn: tuple[str, float] | None
    ) -> tuple[str, tuple[str, float] | None]:
        """For a type standing by no parent (a group's anchor, a type related to no
        other), given its wall label and the share it held for (``WallShare.drawn``): the
        words its statement ends with (the label where it held for all; kept off the
        walls where, in a room, none of its standing objects stood at one), and the label
        and share to draw where it held for some only (``wall_draw_words``)."""
        if drawn is None:
            share = self.induction.walls.get(type_name)
            kept_off = self.induction.room is not None and share is not None and share.kept_off()
            return (f" {AWAY} some wall" if kept_off else ""), None
        if drawn_share(drawn[1]):
            return "", drawn
        return self.wall_words(drawn[0]), None

    def text(self) -> str:
        ind = self.induction
        start = ["# -- the scene " + "-" * 74, "", "Scene -> {"]
        taken: set[str] = set()  # the names bound in Scene
        most = 0
        group_blocks = []
        for group in ind.groups:
            counts, seen, detail = count_parts(group.per_scene, ind.scenes)
            block, per_group = self.group_lines(group)
            group_blocks.append(block)
            noun = ind.catalog[group.anchor].noun
            start.append(
                f"{self.INDENT}{(counts + ' ') if counts else ''}{group.rule}    # {with_article(noun)} "
                f"in {seen} examples" + (f" ({detail})" if detail else "")
            )
            most += max(group.per_scene) * per_group
        for item in ind.loose:
            counts, seen, detail = count_parts(item.per_scene, ind.scenes)
            if item.unsupported:
                why = "resting on no " + " or ".join(
                    ind.catalog[t].noun for t in item.without.split(" or ")
                )
            elif item.without:
                why = f"seen without {with_article(ind.catalog[item.without].noun)}"
            else:
                why = "related to no other type"
            seen += " examples" + (f" ({detail})" if detail else "")
            wall = ""
            if item.wall:
                share = ind.walls[item.type]
                wall = f"; {item.wall} {share.held[item.wall]} of {share.objects} times"
            if item.member is not None and item.member.children:
                # Seen without its parent, it still brings what stands by it.
                name, made = self.alone_production(item.member, item.wall)
                start.append(
                    f"{self.INDENT}{(counts + ' ') if counts else ''}{name}    # {why}: in {seen}{wall}"
                )
                most += max(item.per_scene) * made
                continue
            most += max(item.per_scene)
            words, draw = self.by_no_parent(
                item.type, (item.wall, item.wall_share) if item.wall else None
            )
            if draw is not None:  # at the wall by a draw
                bound = self.binding(item.type, taken)
                start.append(
                    f"{self.INDENT}{(counts + ' ') if counts else ''}{item.type} as {bound}"
                    f"    # {why}: in {seen}{wall}"
                )
                start.append(self.INDENT + self.wall_draw_words(item.type, *draw, bound))
                continue
            start.append(
                f"{self.INDENT}{(counts + ' ') if counts else ''}{item.type}{words}"
                f"    # {why}: in {seen}{wall}"
            )
        start += ["}", ""]
        body: list[str] = []
        for block in group_blocks:
            body += block
        for production in self.productions:
            body += production
        lines = self.header() + self.scene_block(most) + self.catalog_lines() + start + body
        return "\n".join(lines).rstrip() + "\n"
