"""The derivation trace: one record per random draw of grammar expansion, and their tally.

Expansion (``generator.expand``) appends a record to ``SceneGraph.derivation`` each
time it draws from its random stream, in the order it draws, and scene.json keeps the
list as ``"derivation"`` (schema: ``$defs/choice``). It is what learning rule weights
from example scenes reads: ``choice_counts`` tallies, per random parameter of a rule
set, how often each option was drawn.

A record is a plain JSON-ready dict, with keys in this order:

``kind``
    ``"alternative"`` (which alternative of a production), ``"count"`` (how many
    repetitions a range ``2..4`` gave), ``"optional"`` (whether a statement written
    with a probability ``0.5?`` was carried out), ``"style"`` (which style of a
    catalog type a new node got) or ``"some"`` (which existing node ``some TYPE``
    picked).
``rule``
    The production being expanded: for an alternative, the production whose
    alternative was drawn; otherwise the one holding the statement or making the node.
``at``, ``file``
    Where the parameter is written, ``[line, column]`` in ``file``, the rules file's
    name without folders (so traces are byte-identical across machines): the
    production (alternative), the range (count), the probability (optional), the
    catalog entry (style), the ``some`` (some). (Two included files of the same name in
    different folders are told apart by line and column only.)
``options``
    alternative, style, some: how many there were to draw from.
``low``, ``high``
    count: the range.
``probability``
    optional: the probability as written.
``type``
    style, some: the catalog type.
``value``
    The draw: the alternative's, style's or candidate's 0-based index (alternatives
    and styles in the order written; candidates the type's nodes in creation order,
    less the subject when ``some`` is a relation's target), the count, or ``true`` when
    the optional statement was carried out.
``nodes``
    The node ids the choice made, in creation order: every node created while the
    drawn alternative was expanded (nested ones included); every node created over
    all the repetitions of a count; every node the optional statement created (none
    when it was skipped); the new node of a style; the node ``some`` picked.

Only real draws are recorded: a production with one alternative, a count without a
range (``3``) and a type with a single style draw nothing, so they leave no record. An
optional statement always draws, even with probability 0 or 1, and so does ``some``,
even among a single candidate.

Reading it: records nest as the derivation does. An alternative's record comes before
the records of the draws made while its statements ran, and its nodes include theirs; a
statement's optional record comes before its count record, which comes before the
draws of its repetitions. Answering each draw with the recorded value, in order,
rebuilds the same graph from the same rules.

Two records of the village, seed 7: ``Roads -> 3: {...} | 2: {...} | 1: {...}`` drew
its second alternative, whose ``2..3 road`` drew 2::

    {"kind": "alternative", "rule": "Roads", "at": [100, 1], "file": "village.rules", "options": 3,
     "value": 1, "nodes": ["intersection_1", "road_1", "road_2", "street_lamp_1"]}
    {"kind": "count", "rule": "Roads", "at": [101, 34], "file": "village.rules", "low": 2, "high": 3,
     "value": 2, "nodes": ["road_1", "road_2"]}
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import PurePath
from typing import NamedTuple, NoReturn

from .catalog import SourceLocation
from .rules import Rules
from .rules_ast import all_statements


class Site(NamedTuple):
    """Where a parameter is written: file name (no folders), line and column."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


def site_of(location: SourceLocation) -> Site:
    """The site of a parsed location, as a record names it."""
    return Site(_file_name(location.file), location.line, location.column)


@functools.cache
def _file_name(file: str) -> str:
    """A file's name without its folders (a rule set has a handful of files)."""
    return PurePath(file).name


def choice(
    kind: str,
    rule: str,
    location: SourceLocation | None,
    value: int | bool,
    nodes: list[str] | None = None,
    *,
    options: int | None = None,
    low: int | None = None,
    high: int | None = None,
    probability: float | None = None,
    type: str | None = None,
) -> dict:
    """One record, its keys in the format's order (the details given, none of them None)."""
    record: dict = {"kind": kind, "rule": rule}
    if location is not None:
        site = site_of(location)
        record["at"] = [site.line, site.column]
        record["file"] = site.file
    details = {
        "options": options,
        "low": low,
        "high": high,
        "probability": probability,
        "type": type,
    }
    record.update((name, detail) for name, detail in details.items() if detail is not None)
    record["value"] = value
    record["nodes"] = [] if nodes is None else nodes
    return record


@dataclass
class ChoiceCounts:
    """How often each option of each random parameter of a rule set was drawn.

    Every parameter of the rules is present, options never drawn with 0, so a fit sees
    what was possible as well as what happened. ``some`` draws are uniform and have no
    parameter: they are not counted.
    """

    #: production (with more than one alternative) -> times each alternative was drawn, by index
    alternatives: dict[str, list[int]] = field(default_factory=dict)
    #: site of a range ``LOW..HIGH`` -> times each count from LOW to HIGH was drawn
    counts: dict[Site, dict[int, int]] = field(default_factory=dict)
    #: site of an optional statement's probability -> times it was skipped (False) and carried out (True)
    optional: dict[Site, dict[bool, int]] = field(default_factory=dict)
    #: type (with more than one style) -> times each style was drawn, by name
    styles: dict[str, dict[str, int]] = field(default_factory=dict)


def choice_counts(rules: Rules, *derivations: list[dict]) -> ChoiceCounts:
    """Tally the draws of one or more derivations of ``rules`` per parameter.

    Raises ``ValueError`` for a record that is not a draw these rules can make (another
    rule set's trace, or a value out of range).
    """
    tally = _parameters(rules)
    for derivation in derivations:
        for record in derivation:
            _count(tally, rules, record)
    return tally


def _parameters(rules: Rules) -> ChoiceCounts:
    """Every random parameter of ``rules``, each option counted 0 times."""
    tally = ChoiceCounts()
    for production in rules.productions.values():
        if len(production.alternatives) > 1:
            tally.alternatives[production.name] = [0] * len(production.alternatives)
        for alternative in production.alternatives:
            for statement in all_statements(alternative.statements):
                count = statement.count
                if count is not None and count.low != count.high:
                    drawn = range(int(count.low), int(count.high) + 1)
                    tally.counts[site_of(count.location)] = dict.fromkeys(drawn, 0)
                if statement.probability is not None:
                    assert statement.probability_location is not None  # the parser sets both
                    tally.optional[site_of(statement.probability_location)] = {False: 0, True: 0}
    for entry in rules.catalog:
        if len(entry.styles) > 1:
            tally.styles[entry.name] = {style.name: 0 for style in entry.styles}
    return tally


def _count(tally: ChoiceCounts, rules: Rules, record: dict) -> None:
    kind, value = record["kind"], record["value"]
    root = _file_name(str(rules.path))
    if kind == "alternative":
        options = tally.alternatives.get(record["rule"])
        if options is None or not (_is_whole(value) and 0 <= value < len(options)):
            _refuse(record)
        options[value] += 1
    elif kind == "count":
        site = _site_in(tally.counts, record, root)
        counts = tally.counts.get(site) if site is not None else None
        if counts is None or not (_is_whole(value) and value in counts):
            _refuse(record)
        counts[value] += 1
    elif kind == "optional":
        site = _site_in(tally.optional, record, root)
        taken = tally.optional.get(site) if site is not None else None
        if taken is None or not isinstance(value, bool):
            _refuse(record)
        taken[value] += 1
    elif kind == "style":
        styles = tally.styles.get(record["type"])
        if styles is None or not (_is_whole(value) and 0 <= value < len(styles)):
            _refuse(record)
        styles[rules.catalog[record["type"]].styles[value].name] += 1
    elif kind != "some":
        _refuse(record)


def _site_in(sites: Mapping[Site, object], record: dict, root: str) -> Site | None:
    """The parameter site of ``sites`` that a count or optional record was drawn at: its
    own site, or else the only one on its line. A scene made before the rule set's
    numbers were edited (by ``scenewright fit``, say) has the old columns: an edit of
    numbers moves what follows on the line but never changes the lines. A file name
    the rules do not have is taken for the root file (``root``) under another name."""
    site = _record_site(record)
    if site is None or site in sites:
        return site
    if all(other.file != site.file for other in sites):
        site = site._replace(file=root)  # made by a copy of the root file under another name
        if site in sites:
            return site
    same_line = [other for other in sites if other.file == site.file and other.line == site.line]
    return same_line[0] if len(same_line) == 1 else None


def _record_site(record: dict) -> Site | None:
    if "at" not in record or "file" not in record:
        return None
    line, column = record["at"]
    return Site(record["file"], line, column)


def _is_whole(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _refuse(record: dict) -> NoReturn:
    """Refuse a record of a draw that these rules do not have."""
    what = record.get("kind", "?")
    of = record.get("type") or record.get("rule", "?")
    site = _record_site(record)
    at = f" at {site}" if site else ""
    raise ValueError(
        f"it draws {what} {of!r}{at} (value {record.get('value')!r}), which these rules do not have"
    )
