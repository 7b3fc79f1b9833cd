"""Static checks of a rule set's productions, statement by statement.

Relation labels, types, names in scope, calls and their arguments, counts,
probabilities and weights, blocks on groups only, wall relations in a room only,
PathConnectedTo from a path to a junction or a path, and - as a warning - a ``some T`` that may
find none because every statement making a T may make none.
"""

from __future__ import annotations

from scenewright.core.limits import MAX_NODES, MAX_WEIGHT
from scenewright.core.relations import RELATIONS

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_check_scene import ROOM_TYPES
from .rules_check_state import CheckState
from .rules_check_values import LIMITS_DOC, is_whole, number_text, too_large, with_article
from .rules_errors import case_mix_up, did_you_mean


class ProductionChecks(CheckState):
    """The checks of productions and the statements in their alternatives."""

    def note_makers(self, production: ast.Production) -> None:
        """Record in ``makers`` each statement of ``production`` that creates a type."""
        for statement in ast.production_statements(production):
            subject = statement.subject
            if (
                isinstance(subject, ast.Reference)
                and subject.kind == "name"
                and subject.name in self.kinds
            ):
                optional = (statement.probability is not None and statement.probability < 1) or (
                    statement.count is not None and statement.count.low == 0
                )
                self.makers.setdefault(subject.name, []).append((optional, statement.location))

    def check_production(self, production: ast.Production) -> None:
        scope: dict[str, str | None] = {}
        for param in production.params:
            if param.name in scope:
                self.error(param.location, f"duplicate parameter '{param.name}'")
            elif param.name in self.kinds:
                self.error(
                    param.location,
                    f"parameter '{param.name}' has the name of a type; choose another name",
                )
            scope[param.name] = None  # what an argument is, is known only at the call
        for alternative in production.alternatives:
            if alternative.weight is not None and alternative.weight <= 0:
                self.error(
                    alternative.location,
                    f"alternative weight must be positive, not {number_text(alternative.weight)}",
                )
            elif alternative.weight is not None and alternative.weight > MAX_WEIGHT:
                self.error(
                    alternative.location,
                    too_large("an alternative weight", alternative.weight, MAX_WEIGHT, ""),
                )
            self.check_block(alternative.statements, dict(scope))

    def check_block(
        self, statements: tuple[ast.Statement, ...], scope: dict[str, str | None]
    ) -> None:
        """Check statements in order; ``scope`` (bound name -> kind of its nodes, if
        known) gains each statement's binding."""
        for statement in statements:
            self.check_statement(statement, scope)
            if statement.binding:
                scope[statement.binding] = self.subject_kind(statement.subject, scope)

    def check_statement(self, statement: ast.Statement, scope: dict[str, str | None]) -> None:
        subject = statement.subject
        self.check_count(statement.count)
        if statement.probability is not None and not 0 <= statement.probability <= 1:
            assert statement.probability_location is not None  # the parser sets both
            self.error(
                statement.probability_location,
                f"probability must be between 0 and 1, not {number_text(statement.probability)}",
            )
        created_kind = self.check_subject(subject, scope)
        if statement.binding and statement.binding in self.kinds:
            assert statement.binding_location is not None  # the parser sets both
            self.error(
                statement.binding_location,
                f"'{statement.binding}' is a type; bind the nodes to another name",
            )
        for relation in statement.relations:
            if relation.label not in RELATIONS:
                self.error(
                    relation.location,
                    f"unknown relation label '{relation.label}'"
                    + (
                        case_mix_up(
                            relation.label, RELATIONS.names(), "relation labels are CamelCase"
                        )
                        or did_you_mean(relation.label, RELATIONS.names())
                    ),
                )
            spec = RELATIONS[relation.label] if relation.label in RELATIONS else None
            by_room = spec is not None and spec.by_room
            if not by_room or self.has_room:  # outdoors, the wall label's own error says it all
                self.check_target(relation.target, scope)
            if spec is not None and spec.family == "structural":
                self.check_path_connection(subject, relation.target, scope)
            if by_room:
                self.check_wall_relation(relation)
        if statement.block is not None:
            self.check_group_block(statement, statement.block, created_kind, scope)

    def check_wall_relation(self, relation: ast.Relation) -> None:
        """A label by the room (a wall label, ``AwayFromWall``) needs a room, and a wall
        (or, by a window, a window) as its target."""
        label = RELATIONS[relation.label]
        wanted = "window" if label.wall in ("under_window", "beside_window") else "wall"
        target = relation.target
        if not self.has_room:
            self.error(
                relation.location,
                f"{relation.label} needs a room: give the scene block one "
                "(room W x D { door ... window ... })",
            )
        elif target.name != wanted or target.kind not in ("some", "nth"):
            self.error(
                target.location,
                f"{relation.label} stands by a {wanted}: write 'some {wanted}' "
                f"(the layout picks the {wanted} that fits) or '{wanted} #N'",
            )
        elif self.room is not None and target.kind == "nth":
            count = len(self.room.walls) if wanted == "wall" else len(self.room.windows)
            if target.index > count:
                self.error(
                    target.location,
                    f"'{wanted} #{target.index}': the room has {count} {wanted}"
                    + ("" if count == 1 else "s"),
                )

    def check_group_block(
        self,
        statement: ast.Statement,
        block: tuple[ast.Statement, ...],
        created_kind: str | None,
        scope: dict[str, str | None],
    ) -> None:
        """A block (``block``, the statement's) nests its nodes in the group its statement
        creates: only a new group takes one."""
        subject = statement.subject
        unknown_name = (
            isinstance(subject, ast.Reference)
            and subject.kind == "name"
            and subject.name not in scope
            and subject.name not in self.kinds
        )
        if created_kind != "group" and not unknown_name:  # an unknown name is reported already
            what = (
                f"'{subject.name}' is {with_article(created_kind)}"
                if created_kind and isinstance(subject, ast.Reference)  # a call creates no kind
                else _subject_words(subject)
            )
            assert statement.block_location is not None  # the parser sets it with the block
            self.error(statement.block_location, f"a block nests nodes in a new group, but {what}")
        inner = dict(scope) | ({statement.binding: "group"} if statement.binding else {})
        self.check_block(block, inner)

    def check_count(self, count: ast.Count | None) -> None:
        if count is None:
            return
        for value in (count.low, count.high):
            if value < 0 or not is_whole(value):
                self.error(
                    count.location, f"a count must be a whole number, not {number_text(value)}"
                )
                return
        if count.low > count.high:
            self.error(
                count.location,
                f"range {number_text(count.low)}..{number_text(count.high)} has min > max",
            )
        elif count.high > self.max_nodes:
            raise_it = (
                f"raise it in the scene block, e.g. max_nodes {number_text(count.high)}"
                if count.high <= MAX_NODES
                else f"max_nodes may be at most {MAX_NODES}, see {LIMITS_DOC}"
            )
            self.error(
                count.location,
                f"count {number_text(count.high)} exceeds max_nodes {self.max_nodes} ({raise_it})",
            )
        elif count.weights is not None:
            assert count.weights_location is not None  # the parser sets both
            self.check_count_weights(count, count.weights, count.weights_location)

    def check_count_weights(
        self, count: ast.Count, weights: tuple[float, ...], where: SourceLocation
    ) -> None:
        """``LOW..HIGH {W ...}`` (``weights`` written at ``where``): one weight per count,
        none negative, not all zero."""
        wanted = int(count.high - count.low) + 1
        if len(weights) != wanted:
            self.error(
                where,
                f"range {number_text(count.low)}..{number_text(count.high)} has {wanted} counts but "
                f"{len(weights)} weight{'s' if len(weights) != 1 else ''}",
            )
        elif any(weight < 0 for weight in weights):
            negative = next(weight for weight in weights if weight < 0)
            self.error(where, f"count weights may not be negative, not {number_text(negative)}")
        elif any(weight > MAX_WEIGHT for weight in weights):
            self.error(where, too_large("a count weight", max(weights), MAX_WEIGHT, ""))
        elif not any(weights):
            self.error(where, "count weights are all 0: at least one count must be possible")

    def check_path_connection(
        self, subject: ast.Reference | ast.Call, target: ast.Reference, scope: dict[str, str | None]
    ) -> None:
        """``PathConnectedTo`` starts a path at a junction, or on another path (a branch):
        check kinds where known."""
        for reference, kind, wanted in (
            (subject, self.subject_kind(subject, scope), ("path",)),
            (target, self.reference_kind(target, scope), ("junction", "path")),
        ):
            if kind is not None and kind not in wanted:
                assert isinstance(reference, ast.Reference)  # a call's kind is not known
                self.error(
                    reference.location,
                    "PathConnectedTo starts a path at a junction or on another path, "
                    f"but '{reference.name}' is {with_article(kind)}",
                )

    def subject_kind(
        self, subject: ast.Reference | ast.Call, scope: dict[str, str | None]
    ) -> str | None:
        """The kind of a subject's nodes, when known without expanding."""
        return None if isinstance(subject, ast.Call) else self.reference_kind(subject, scope)

    def reference_kind(self, reference: ast.Reference, scope: dict[str, str | None]) -> str | None:
        if reference.kind == "name" and reference.name in scope:
            return scope[reference.name]
        return self.kinds.get(reference.name)

    def check_subject(
        self, subject: ast.Reference | ast.Call, scope: dict[str, str | None]
    ) -> str | None:
        """Check a statement's subject; return the kind of type it creates, if it creates one."""
        if isinstance(subject, ast.Call):
            self.check_call(subject, scope)
            return None
        if subject.kind == "name":
            if subject.name in scope:
                return None
            if self.has_room and subject.name in ROOM_TYPES:
                self.error(
                    subject.location,
                    f"the room's {subject.name}s come from its room block and cannot be "
                    f"created; refer to them as 'some {subject.name}' or '{subject.name} #1'",
                )
                return None
            if subject.name in self.kinds:
                self.created_types.add(subject.name)
                return self.kinds[subject.name]
            self.error(
                subject.location,
                f"unknown type or name '{subject.name}'"
                + (
                    case_mix_up(subject.name, self.productions, "nonterminals are CamelCase")
                    or did_you_mean(subject.name, list(self.kinds) + sorted(scope))
                ),
            )
            return None
        self.check_type_reference(subject)
        return None

    def check_target(self, reference: ast.Reference, scope: dict[str, str | None]) -> None:
        if reference.kind != "name":
            self.check_type_reference(reference)
        elif reference.name in scope:
            return
        elif reference.name in self.kinds:
            name = reference.name
            self.error(
                reference.location,
                f"'{name}' is a type, not a bound name; write "
                f"'some {name}', 'each {name}' or '{name} #1'",
            )
        else:
            self.error(
                reference.location,
                f"unbound name '{reference.name}'" + did_you_mean(reference.name, scope),
            )

    def check_type_reference(self, reference: ast.Reference) -> None:
        if self.has_room and reference.name in ROOM_TYPES:
            return
        if reference.name not in self.kinds:
            self.error(
                reference.location,
                f"unknown type '{reference.name}'" + did_you_mean(reference.name, self.kinds),
            )
        if reference.kind == "nth" and reference.index < 1:
            self.error(reference.location, f"'#{reference.index}': ordinals count from #1")
        elif reference.kind == "nth" and reference.index > self.max_nodes:
            self.error(
                reference.location,
                f"this ordinal is larger than max_nodes {self.max_nodes}, "
                "so it can never name a node",
            )
        makers = self.makers.get(reference.name, [])
        if reference.kind in ("some", "nth") and makers and all(optional for optional, _ in makers):
            written = (
                f"some {reference.name}"
                if reference.kind == "some"
                else f"{reference.name} #{reference.index}"
            )
            self.warning(
                reference.location,
                f"'{written}' may find none: every statement that makes "
                f"{with_article(reference.name)} may make none (line {makers[0][1].line}), and where a scene "
                "has none its expansion stops here; refer to it only where one is certain",
            )

    def check_call(self, call: ast.Call, scope: dict[str, str | None]) -> None:
        for argument in call.arguments:
            self.check_target(argument, scope)
        production = self.productions.get(call.nonterminal)
        if production is None:
            self.error(
                call.location,
                f"undefined nonterminal '{call.nonterminal}'"
                + (
                    case_mix_up(call.nonterminal, self.kinds, "types are snake_case")
                    or case_mix_up(call.nonterminal, scope, "bound names are snake_case")
                    or did_you_mean(call.nonterminal, self.productions)
                ),
            )
            return
        expected, given = len(production.params), len(call.arguments)
        if expected != given:
            self.error(
                call.location,
                f"'{call.nonterminal}' takes {_parameters(expected)} "
                f"({production.location}), but {given} {'is' if given == 1 else 'are'} given",
            )


def _parameters(count: int) -> str:
    return "no parameters" if count == 0 else f"{count} parameter{'s' if count > 1 else ''}"


def _subject_words(subject: ast.Reference | ast.Call) -> str:
    if isinstance(subject, ast.Call):
        return f"'{subject.nonterminal}' is a nonterminal call"
    return "the subject refers to existing nodes"
