"""Text -> request -> rule set -> laid-out scene, with a report of what was used.

``plan`` reads the text and writes the rule set (no layout); ``compose_scene`` loads
that rule set, expands it and lays it out. A layout that leaves a stated relation
unsatisfied, or puts a thing in another corner than the one named, is tried again with
the next retry seed (``core.seeds.retry_seed``), up to ``ATTEMPTS`` layouts; the best
one is kept and the statements it could not satisfy are reported as conflicting.
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from scenewright.core.errors import InputError
from scenewright.generator.catalog import CatalogEntry

from .outdoor import Ground
from .outdoor import synonyms as outdoor_synonyms
from .parse import parse
from .plan import FIRST_CORNER, corner_starts, rules_text
from .request import Issue, Place, Request, Statement
from .vocabulary import vocabulary

#: Layouts tried before the best one is kept.
ATTEMPTS = 3
#: How scene.json names the rule set of a composed scene without ``--rules-out``.
RULES_LABEL = "composed"


@dataclass
class Report:
    """What composing did with a text: ``used`` character spans, ``unused`` issues (each
    with its span and message), the statements made and, after layout, the statements
    the layout could not satisfy (``conflicts``, as pairs of spans where two clash)."""

    text: str
    used: list[tuple[int, int]]
    unused: list[Issue]
    statements: list[Statement]
    unsatisfied: list[Statement] = field(default_factory=list)
    #: Spans of the statements (or, where a thing has none, the noun phrases) about the
    #: things the layout's problems name, when the layout is not ok.
    crowded: list[tuple[int, int]] = field(default_factory=list)
    rules: str = ""

    def position(self, offset: int) -> tuple[int, int]:
        """1-based line and column of a character offset."""
        line = self.text.count("\n", 0, offset) + 1
        column = offset - (self.text.rfind("\n", 0, offset) + 1) + 1
        return line, column

    def where(self, start: int, end: int) -> str:
        line, col = self.position(start)
        _, last = self.position(max(start, end - 1))
        return f"{line}:{col}-{last}"

    def messages(self) -> list[str]:
        """One line per unused word or phrase, ``LINE:COL-COL: message``, in text order."""
        return [f"{self.where(i.start, i.end)}: {i.message}" for i in self.unused]

    def conflicts(self) -> list[str]:
        """One line per statement the layout could not satisfy, with what it clashes with."""
        out = []
        for s in self.unsatisfied:
            others = [
                o
                for o in self.statements
                if o is not s
                and (o.source == s.source or o.target == s.source or o.source == s.target)
                and not o.label.startswith("Implicit")
            ]
            said = self.text[s.start : s.end]
            clash = "; ".join(
                f"{self.where(o.start, o.end)} '{self.text[o.start : o.end]}'" for o in others[:3]
            )
            tail = f" (it shares things with {clash})" if clash else ""
            out.append(f"{self.where(s.start, s.end)}: could not lay out '{said}'{tail}")
        if self.crowded:
            spans = "; ".join(f"{self.where(a, b)} '{self.text[a:b]}'" for a, b in self.crowded)
            out.append(f"these could not be laid out together (see the layout's problems): {spans}")
        return out


def plan(
    text: str,
    entries: Mapping[str, CatalogEntry],
    prefer: Iterable[str] = (),
    ground: Ground | None = None,
) -> tuple[Request, str]:
    """The request read from ``text`` and the rule set that makes it (``prefer``: the
    types that name a noun several types share, ``vocabulary``; ``ground``: outdoors,
    ``composer.outdoor``; ``catalog_for`` gives all three for a text)."""
    if not text.strip():
        raise InputError("nothing to compose: the text is empty")
    if ground is not None:
        request = parse(text, vocabulary(entries, prefer, outdoor_synonyms()))
        return request, rules_text(request, entries, ground)
    request = parse(text, vocabulary(entries, prefer))
    rules = rules_text(request, entries)
    request.starts = corner_starts(request, entries, request.planned_size)
    return request, rules


def lay_out(
    rules: str,
    request: Request,
    seed: int,
    *,
    label: str = RULES_LABEL,
    allow: tuple[str, ...] = (),
):
    """Load, expand and lay out a composed rule set: (scene, the statements it left
    unsatisfied, the spans about the things its problems name)."""
    from scenewright.core.scene import assemble_scene
    from scenewright.core.seeds import check_seed, retry_seed
    from scenewright.core.timing import timed
    from scenewright.generator import expand, load_rules
    from scenewright.generator.layout import layout_scene

    seed = check_seed(seed)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "composed.rules"
        path.write_text(rules, encoding="utf-8")
        loaded = load_rules(path, allow=allow)
    timings: dict[str, float] = {}
    with timed(timings, "expand"):
        graph = expand(loaded, seed)
    # The expansion names the things by type and number; the k-th thing (object or group)
    # it makes is the k-th of the production's order (``request.made``).
    made = [n.id for n in graph.nodes() if n.kind in ("object", "group", "path", "junction")]
    ids = dict(zip(request.made, made, strict=True))
    from scenewright.core.poses import Pose

    def held(k: int) -> dict[str, Pose]:
        return {
            ids[eid]: Pose(poses[k][0], 0.0, poses[k][1], poses[k][2])
            for eid, poses in request.starts.items()
        }

    best = None
    for attempt in range(ATTEMPTS):
        with timed(timings, "layout"):
            # A thing asked for in a named corner is held there for the first layouts,
            # back to one wall of the corner and then the other (InCorner holds in
            # any corner, and the chain would wander between them); the last layout
            # only starts it there.
            hold = attempt < ATTEMPTS - 1
            poses = held(attempt if hold else 0) or None
            layout = layout_scene(
                graph,
                retry_seed(seed, attempt) if attempt else seed,
                pinned=poses if hold else None,
                start=None if hold else poses,
            )
        scene = assemble_scene(graph, layout, rules=label, seed=seed)
        failed = _unsatisfied(scene, request, ids)
        score = (len(failed), not scene.layout.ok)
        if best is None or score < best[2]:
            best = (scene, failed, score)
        if score == (0, False):
            break
    assert best is not None
    scene, failed, _ = best
    scene.timings.update(timings)
    return scene, failed, _crowded(scene, request, ids)


def _crowded(scene, request: Request, ids: Mapping[str, str]) -> list[tuple[int, int]]:
    """The text's spans about the things the layout's problems name (none when ok)."""
    if scene.layout.ok:
        return []
    said = " ".join(scene.layout.problems)
    named = {eid for eid, node in ids.items() if re.search(rf"\b{re.escape(node)}\b", said)}
    spans: list[tuple[int, int]] = []
    for e in request.entities:
        if e.id not in named:
            continue
        own = [
            (st.start, st.end)
            for st in request.statements
            if st.source == e.id and not st.label.startswith("Implicit")
        ]
        for span in own or [(e.start, e.end)]:
            if span not in spans:
                spans.append(span)
    return sorted(spans)


def _unsatisfied(scene, request: Request, ids: Mapping[str, str]) -> list[Statement]:
    verdicts: dict[tuple[str, str, str], bool] = {}
    for r in scene.relations:
        verdicts[(r.source, r.label, r.target)] = bool(r.satisfied)
    failed = []
    for s in request.statements:
        if s.label.startswith("Implicit"):
            continue
        source = ids[s.source]
        if isinstance(s.target, Place):
            ok = any(v for (a, label, _), v in verdicts.items() if a == source and label == s.label)
            corner = s.target.corner
            if s.target.by_door:
                corner = FIRST_CORNER[request.door_walls[0]]
            if ok and corner is not None:
                obj = next(o for o in scene.objects if o.id == source)
                x, z = obj.position[0], obj.position[2]
                want = {"north": z < 0, "south": z > 0, "east": x > 0, "west": x < 0}
                ok = all(want[side] for side in corner)
        else:
            ok = verdicts.get((source, s.label, ids[s.target]), False)
        if not ok:
            failed.append(s)
    return failed


def report_of(text: str, request: Request, rules: str) -> Report:
    return Report(text, request.used, request.issues, request.statements, rules=rules)


def write_rules(rules: str, path: str | os.PathLike[str]) -> None:
    """Write a composed rule set where the user asked (whole, or not at all)."""
    from scenewright.core.atomic import write_atomic

    write_atomic(Path(path), rules)
