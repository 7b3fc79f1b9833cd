"""Composing requests written in everyday English (benchmarks/data/compose_prompts.tsv):
does the scene hold what each one asks for?

For each prompt (seed 1000 + its line number among the prompts):

- objects: each type the prompt names is in the scene with the count written beside it
  in the file (0: the prompt asks for none);
- relations held: every relation composing made of the prompt's words, measured again on
  the composed layout (``measure_layout``) rather than taken from the report;
- contradictions: relations the composed scene's description states that contradict a
  relation of the prompt (another wall than the one named, left for right, close beside
  or not, front for behind, north for south, east for west);
- reported: every word of the prompt is either used or reported unused (no word is
  dropped silently), and how many prompts had every word used.

    python benchmarks/bench_compose_prompts.py [--file PROMPTS.tsv]
    python benchmarks/bench_compose_prompts.py --file benchmarks/data/compose_prompts_outdoor.tsv

(the outdoor requests' counts take in roads and lanes, which are paths, not objects).
"""

from __future__ import annotations

import argparse
import re
from collections import Counter
from pathlib import Path

from scenewright.api import compose, describe
from scenewright.composer.vocabulary import FUNCTION_WORDS
from scenewright.generator.layout.measure import measure_layout
from scenewright.generator.layout.pinning import scene_layout

DEFAULT = Path(__file__).parent / "data" / "compose_prompts.tsv"
_OPPOSITE = {
    "NextToLeft": {"NextToRight", "BesideRight"},
    "NextToRight": {"NextToLeft", "BesideLeft"},
    "BesideLeft": {"NextToRight", "BesideRight"},
    "BesideRight": {"NextToLeft", "BesideLeft"},
    "NextToFront": {"NextToBehind"},
    "NextToBehind": {"NextToFront"},
    "NextToNorth": {"NextToSouth"},
    "NextToSouth": {"NextToNorth"},
    "NextToEast": {"NextToWest"},
    "NextToWest": {"NextToEast"},
    "FacingTowards": {"FacingAwayFrom"},
    "FacingAwayFrom": {"FacingTowards"},
}


def _contradictions(scene, facts) -> int:
    """Facts of the description that deny a relation the scene was asked for."""
    asked = [r for r in scene.relations if not r.label.startswith("Implicit")]
    count = 0
    for source, label, target in facts:
        for r in asked:
            if r.source != source:
                continue
            if label in _OPPOSITE.get(r.label, ()) and r.target == target:
                count += 1
            elif (
                r.label == label == "AgainstWall"
                and r.target.startswith("wall_")
                and target.startswith("wall_")
                and r.target != target
            ):
                count += 1
    return count


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", default=str(DEFAULT))
    args = parser.parse_args()
    rows = [
        line.split("\t")
        for line in Path(args.file).read_text(encoding="utf-8").splitlines()
        if line.strip() and not line.startswith("#")
    ]
    totals: Counter = Counter()
    for k, (prompt, expected) in enumerate(rows):
        scene, report = compose(prompt, 1000 + k)
        have = Counter(o.type for o in scene.objects) + Counter(p.type for p in scene.paths)
        want = {t: int(n) for t, n in (item.split("=") for item in expected.split())}
        right = sum(have[t] == n for t, n in want.items())
        poses, points = scene_layout(scene)
        measured = measure_layout(scene.graph(), poses, points)
        stated = [r for r in measured.relations if not r.label.startswith("Implicit")]
        held = sum(bool(r.satisfied) for r in stated)
        facts = describe(scene).facts
        contra = _contradictions(scene, facts)
        covered = [
            (m.start(), m.end())
            for m in re.finditer(r"[A-Za-z0-9][A-Za-z0-9'-]*", prompt)
            if m.group().lower() not in FUNCTION_WORDS
        ]
        spans = report.used + [(i.start, i.end) for i in report.unused]
        silent = [prompt[a:b] for a, b in covered if not any(s <= a and b <= e for s, e in spans)]
        totals.update(
            objects=len(want),
            right=right,
            stated=len(stated),
            held=held,
            contra=contra,
            silent=len(silent),
            unused=len(report.unused),
            whole=not report.unused,
        )
        wrong = {t: (have[t], n) for t, n in want.items() if have[t] != n}
        flag = "" if not (wrong or held < len(stated) or contra or silent) else "  <-"
        print(f"{k + 1:2d} objects {right}/{len(want)} held {held}/{len(stated)}{flag}")
        for line in report.messages():
            print(f"     {line}")
        if wrong:
            print(f"     counts (have, want): {wrong}")
        if silent:
            print(f"     dropped silently: {silent}")
    print(
        f"prompts {len(rows)}: objects with the right count {totals['right']}/{totals['objects']}"
        f" = {totals['right'] / totals['objects']:.1%}; relations held {totals['held']}/{totals['stated']}"
        f" = {totals['held'] / max(totals['stated'], 1):.1%}; contradicting relations {totals['contra']};"
        f" words dropped without a report {totals['silent']}; unused words reported {totals['unused']}"
        f"; prompts with every word used {totals['whole']}/{len(rows)}"
    )


if __name__ == "__main__":
    main()
