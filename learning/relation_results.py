"""What relation finding reports: ``PairRelation``, the verdict on one pair of roles (or
of types), and ``RelationsResult``, every pair's verdict with the test and its settings,
as ``scenewright relations`` prints it and the induced rule set records it.
Design notes: docs/notes/design.md, "Relation finding".
"""

from __future__ import annotations

from dataclasses import dataclass

from .relation_tests import TESTS
from .relation_thresholds import ANGLE_SAMPLE, ANGLE_THRESHOLD, PERMUTATIONS


@dataclass(frozen=True)
class PairRelation:
    """The verdict on the type pair (``a``, ``b``), a <= b: ``related``; the test's
    ``statistic`` and ``p_value`` (None when not tested or, for co-occurrence, no
    p-value); ``pairs``, the relative poses the test used; ``scenes``, the scenes that
    hold both; ``strength``, what ranks related pairs for pruning (the permutation
    test's tightness, the angle test's d, the co-occurrence share); ``fixed``: found
    related as a fixed arrangement, which the test itself did not find (design notes);
    ``pruned``: found related but pruned as indirect; ``groups``: the kinds of group
    holding the a and the b of the pair of roles the verdict is that of ("" at the top
    level; design notes, "Roles")."""

    a: str
    b: str
    related: bool
    statistic: float | None
    p_value: float | None
    pairs: int
    scenes: int
    strength: float | None = None
    tested: bool = True
    fixed: bool = False
    pruned: bool = False
    groups: tuple[str, str] = ("", "")

    def to_dict(self) -> dict:
        return {
            "a": self.a,
            "b": self.b,
            "related": self.related,
            "statistic": None if self.statistic is None else round(self.statistic, 6),
            "p_value": None if self.p_value is None else round(self.p_value, 6),
            "pairs": self.pairs,
            "scenes": self.scenes,
            "strength": None if self.strength is None else round(self.strength, 6),
            "tested": self.tested,
            "fixed": self.fixed,
            "pruned": self.pruned,
            "groups": [group or None for group in self.groups],
        }

    @property
    def verdict(self) -> str:
        """How the table says it: yes, fixed (related as a fixed arrangement), no,
        indirect (pruned) or untested."""
        if not self.tested:
            return "untested"
        if self.related:
            return "fixed" if self.fixed else "yes"
        return "indirect" if self.pruned else "no"


@dataclass(frozen=True)
class RelationsResult:
    """Every type pair that occurs together in some scene, in (a, b) order, with the
    test, its level, the seed and the number of example scenes."""

    test: str
    examples: int
    seed: int
    alpha: float
    pairs: tuple[PairRelation, ...]

    def related(self) -> list[tuple[str, str]]:
        return [(pair.a, pair.b) for pair in self.pairs if pair.related]

    def to_dict(self) -> dict:
        test = TESTS[self.test]
        settings: dict = (
            {"alpha": self.alpha, "permutations": PERMUTATIONS}
            if self.test == "permutation"
            else {}
        )
        if self.test == "angle":
            settings = {"threshold": ANGLE_THRESHOLD, "sample": ANGLE_SAMPLE}
        return {
            "test": self.test,
            "statistic": test.statistic,
            **settings,
            "examples": self.examples,
            "seed": self.seed,
            "pruned_indirect": test.prunes,
            "pairs": [pair.to_dict() for pair in self.pairs],
        }

    def table(self) -> str:
        """A table for people: one line per pair, related ones marked."""
        test = TESTS[self.test]
        header = ("a", "b", "related", test.statistic, "p-value", "n pairs", "scenes")
        if test.strength:
            header += (test.strength,)
        grouped = any(any(pair.groups) for pair in self.pairs)
        if grouped:  # scenes with groups: in which the verdict's a and b stand
            header += ("in groups",)
        rows = [
            (
                pair.a,
                pair.b,
                pair.verdict,
                "-" if pair.statistic is None else f"{pair.statistic:.3f}",
                "-" if pair.p_value is None else f"{pair.p_value:.3g}",
                str(pair.pairs),
                str(pair.scenes),
                *(
                    ["-" if pair.strength is None else f"{pair.strength:.3f}"]
                    if test.strength
                    else []
                ),
                *([" / ".join(group or "-" for group in pair.groups)] if grouped else []),
            )
            for pair in self.pairs
        ]
        widths = [max(len(row[k]) for row in [header, *rows]) for k in range(len(header))]
        found = sum(pair.related for pair in self.pairs)
        lines = [
            f"{self.test} test ({test.summary}) on {self.examples} scenes, seed {self.seed}: "
            f"{found} of {len(self.pairs)} type pairs related"
        ]
        for k, row in enumerate([header, *rows]):
            cells = [
                cell.ljust(width)
                if column < 3 or column == len(row) - 1 and grouped
                else cell.rjust(width)
                for column, (cell, width) in enumerate(zip(row, widths, strict=False))
            ]
            lines.append("  ".join(cells).rstrip())
            if k == 0:
                lines.append("  ".join("-" * width for width in widths))
        return "\n".join(lines) + "\n"
