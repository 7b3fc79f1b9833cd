"""The errors learning raises for a user to see, each on its side of the input /
generation split (``core.errors``).

Input: examples with no pair kind to learn a context from (``NoRelatedPairs``), an
example with more derivations than the search may try (``AmbiguousExample``, and
``BudgetSpent`` when a shared budget ran out), a fitted rule set that cannot be written
where it was asked for (``FitOutputError``). Generation: induced rules that do not
pass the static checks (``InducedRulesError``), which no input should cause.
"""

from __future__ import annotations

from scenewright.core.errors import GenerationError, InputError


class NoRelatedPairs(InputError):
    """The examples hold no pair kind in MIN_EXAMPLES of them: there is no context to learn."""


class AmbiguousExample(InputError):
    """An example with more possible derivations than the search may try."""


class BudgetSpent(AmbiguousExample):
    """The replays shared by several searches (``ReplayBudget``) ran out during this one."""


class FitOutputError(InputError):
    """The fitted rule set cannot be written where it was asked for."""


class InducedRulesError(GenerationError):
    """The induced text did not pass the static checks: a fault of ``induce``, not of the input."""
