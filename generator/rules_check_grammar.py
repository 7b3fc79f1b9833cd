"""Static checks of a rule set's grammar as a whole.

The start symbol must have a production that takes no parameters; every nonterminal
must be able to finish expanding (a fixpoint over the alternatives); a nonterminal the
start symbol never reaches is a warning.
"""

from __future__ import annotations

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_check_state import CheckState
from .rules_errors import did_you_mean


class GrammarChecks(CheckState):
    """The checks of the grammar: termination and reachability."""

    def check_start(self, start: str, location: SourceLocation) -> None:
        if start not in self.productions:
            self.error(
                location,
                f"start symbol '{start}' has no production" + did_you_mean(start, self.productions),
            )
            return
        if self.productions[start].params:
            self.error(location, f"start symbol '{start}' takes parameters; it must take none")
        reached = self.reachable(start)
        for name, production in self.productions.items():
            if name not in reached:
                self.warning(
                    production.location,
                    f"nonterminal '{name}' is never used (start '{start}' does not reach it)",
                )

    def reachable(self, start: str) -> set[str]:
        reached, pending = {start}, [start]
        while pending:
            for name in _calls(self.productions[pending.pop()]):
                if name in self.productions and name not in reached:
                    reached.add(name)
                    pending.append(name)
        return reached

    def check_termination(self) -> None:
        """Error for each nonterminal none of whose alternatives can ever finish.

        A nonterminal terminates when one of its alternatives makes only calls that
        terminate, not counting calls it may skip (optional, or a count that may be 0).
        Fixpoint: keep adding terminating nonterminals until nothing changes.
        """
        terminating: set[str] = set()
        changed = True
        while changed:
            changed = False
            for name, production in self.productions.items():
                if name in terminating:
                    continue
                if any(
                    all(
                        call in terminating or call not in self.productions
                        for call in _required_calls(alt.statements)
                    )
                    for alt in production.alternatives
                ):
                    terminating.add(name)
                    changed = True
        for name, production in self.productions.items():
            if name in terminating:
                continue
            blocking = next(
                call
                for call in _required_calls(production.alternatives[0].statements)
                if call not in terminating and call in self.productions
            )
            reason = (
                "it always calls itself"
                if blocking == name
                else f"it always calls '{blocking}', which never finishes"
            )
            self.error(
                production.location,
                f"'{name}' can never finish expanding: {reason} "
                f"(make the call optional, e.g. '0.5? {blocking}' or '0..2 {blocking}', "
                "or add an alternative without it)",
            )


def _calls(production: ast.Production) -> list[str]:
    """Every nonterminal a production may call, in order of appearance."""
    return [
        statement.subject.nonterminal
        for statement in ast.production_statements(production)
        if isinstance(statement.subject, ast.Call)
    ]


def _required_calls(statements: tuple[ast.Statement, ...]) -> list[str]:
    """The calls an alternative cannot skip: not optional, count at least 1."""
    required: list[str] = []
    for statement in statements:
        optional = (statement.probability is not None and statement.probability < 1) or (
            statement.count is not None and statement.count.low < 1
        )
        if optional:
            continue
        if isinstance(statement.subject, ast.Call):
            required.append(statement.subject.nonterminal)
        if statement.block:
            required.extend(_required_calls(statement.block))
    return required
