"""Grounded captions of the image, measured on the shipped rule sets.

For N scenes of each rule set (256x256 perspective pictures, the default thresholds,
two caption variants in each frame), checks and counts:

- spans: every mention of the captions and of the full text holds the noun (or
  plural) of each entity it names, or is the pronoun "it" (counted apart); every
  grounding record's boxes are the rendered boxes of its ids;
- visibility: mentions in the image's captions of objects below the thresholds (must
  be 0), and how many objects the layout-true caption names that the image's would not;
- referring expressions: how many, how many of the seen objects have one, and how many
  programs, executed again on the picture's objects, do not give exactly their object
  (must be 0);
- questions (``describer.questions``): how many per family, the answers' spread per
  family, and how many programs, executed again on the picture's objects, do not give
  their stored answer (must be 0);
- grammar: caption sentences and questions link-grammar's ``link-parser`` finds no
  linkage for (needs the Debian package link-grammar);
- cost: CPU seconds (``time.process_time``; the machine is shared) per scene of the
  work one dataset scene does: layout, full text, render, and the captions, the old
  way (layout-true captions) and the new (the image's captions plus the grounding and
  refexps columns), and the questions column apart. Throughput with grounding relative
  to without is the ratio of the totals, and so is throughput with questions relative
  to without (both with the grounding).

    .venv/bin/python benchmarks/bench_grounding.py -n 200
    .venv/bin/python benchmarks/bench_grounding.py -n 20 --rules village desk
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from pathlib import Path

from scenewright.api import build_scene, describe, load_rules
from scenewright.dataset.produce import PictureCaptions, picture_captions
from scenewright.dataset.spec import scene_seed
from scenewright.describer.errors import ProgramError
from scenewright.describer.programs import PictureFacts, answer_text, execute
from scenewright.describer.questions import picture_questions, vocabulary_of
from scenewright.describer.view import describe_view
from scenewright.describer.world import world_of
from scenewright.generator.rules import shipped_rule_sets
from scenewright.render.offscreen import Renderer
from scenewright.render.visibility import PictureView

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from test_describer_e2e import split_sentences, ungrammatical  # noqa: E402  (the suite's grammar check)
from test_grounding import names_its_entities  # noqa: E402  (the suite's noun check)

CAPTIONS = 2


class Tally:
    """What one rule set's scenes gave."""

    #: The counts the targets are about, reported even when 0.
    TARGETS = (
        "text spans without their noun",
        "caption spans without their noun",
        "records whose boxes are not the rendered ones",
        "caption mentions of objects below the thresholds",
        "refexp programs that do not give exactly their object",
        "question programs that do not give their answer",
    )

    def __init__(self) -> None:
        self.counts: Counter[str] = Counter(dict.fromkeys(self.TARGETS, 0))
        self.seconds: Counter[str] = Counter()
        self.sentences: list[str] = []
        self.questions: list[str] = []
        #: family -> answer -> how many questions
        self.answers: dict[str, Counter[str]] = {}

    def clock(self, stage: str, started: float) -> float:
        now = time.process_time()
        self.seconds[stage] += now - started
        return now


def check_mentions(description, world, tally: Tally, kind: str) -> None:
    for mention in description.mentions:
        phrase = description.text[mention.start : mention.end]
        tally.counts[f"{kind} spans"] += 1
        if phrase.lower() == "it":
            tally.counts[f"{kind} pronoun spans"] += 1
        elif not names_its_entities(phrase, mention.entities, world):
            tally.counts[f"{kind} spans without their noun"] += 1
            print(f"  no noun: {phrase!r} -> {mention.entities}", file=sys.stderr)


def measure_scene(rules, seed: int, renderer: Renderer, tally: Tally) -> None:
    started = time.process_time()
    scene = build_scene(rules, seed)
    started = tally.clock("layout", started)
    if not scene.layout.ok:
        tally.counts["failed layouts"] += 1
        return
    tally.counts["scenes"] += 1
    full = describe(scene, style="full")
    started = tally.clock("full text", started)
    result = renderer.render(scene)
    started = tally.clock("render", started)
    old = [describe(scene, style="short", variant=k) for k in range(CAPTIONS)]
    started = tally.clock("layout-true captions", started)
    columns, _ = picture_captions(WITHOUT_QUESTIONS, scene, result, full)
    grounding = columns["grounding"]
    facts = PictureFacts.of(scene, PictureView.from_render(result, scene))
    tally.counts["seen objects"] += len(facts.objects)
    for expression in columns["refexps"]:
        tally.counts["refexps"] += 1
        try:
            picked = execute(expression["program"], facts)
        except ProgramError:
            picked = None
        tally.counts["refexp programs that do not give exactly their object"] += (
            picked != expression["id"]
        )
    started = tally.clock("image captions + grounding + refexps", started)
    picture = PictureView.from_render(result, scene)
    asked = picture_questions(
        PictureFacts.of(scene, picture), vocabulary_of(rules, scene), scene.seed
    )
    tally.clock("questions", started)
    for question in asked:
        tally.counts["questions"] += 1
        tally.answers.setdefault(question["family"], Counter())[question["answer"]] += 1
        tally.questions.append(question["question"])
        try:
            answer = answer_text(execute(question["program"], facts))
        except ProgramError:
            answer = None
        tally.counts["question programs that do not give their answer"] += (
            answer != question["answer"]
        )

    world = world_of(scene)
    for _column, records in grounding.items():
        for record in records:
            tally.counts["grounding records"] += 1
            if record["boxes"] != [result.boxes.get(i) for i in record["ids"]]:
                tally.counts["records whose boxes are not the rendered ones"] += 1
    check_mentions(full, world, tally, "text")
    for frame in ("scene", "camera"):
        for variant in range(CAPTIONS):
            caption = describe_view(scene, picture, frame=frame, variant=variant)
            check_mentions(caption, world, tally, "caption")
            tally.sentences += split_sentences(caption.text)
            for mention in caption.mentions:
                tally.counts["caption mentions of objects below the thresholds"] += sum(
                    not picture.seen(i) for i in mention.ids
                )
            tally.counts["captions too small to make out"] += (
                "too small to make out" in caption.text
            )
    layout_true = {i for m in old[0].mentions for i in m.ids}
    tally.counts["objects named by the layout-true caption"] += len(layout_true)
    tally.counts["...of which below the thresholds"] += sum(
        not picture.seen(i) for i in layout_true
    )


#: The dataset defaults for ``picture_captions`` but two captions and no questions (timed apart).
WITHOUT_QUESTIONS = PictureCaptions(
    rules="", rules_digest="", count=0, captions=CAPTIONS, questions=False
)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("-n", "--count", type=int, default=200, help="scenes per rule set (200)")
    parser.add_argument("--rules", nargs="+", default=None, help="rule sets (all shipped)")
    args = parser.parse_args()
    renderer = Renderer(256, 256)
    totals = Tally()
    for name in args.rules or shipped_rule_sets():
        tally = Tally()
        rules = load_rules(name)
        for index in range(args.count):
            measure_scene(rules, scene_seed(0, index), renderer, tally)
        check_grammar(tally.sentences, tally, "caption sentences")
        check_grammar(tally.questions, tally, "questions")
        report(name, args.count, tally)
        totals.counts.update(tally.counts)
        totals.seconds.update(tally.seconds)
        for family, answers in tally.answers.items():
            totals.answers.setdefault(family, Counter()).update(answers)
    report("all", args.count, totals)


def check_grammar(sentences: list[str], tally: Tally, kind: str) -> None:
    """Count the distinct ``sentences`` and those link-grammar finds no linkage for."""
    distinct = list(dict.fromkeys(sentences))
    bad = ungrammatical(distinct)
    tally.counts[f"{kind} (distinct)"] += len(distinct)
    tally.counts[f"{kind} link-grammar rejects"] += len(bad)
    for sentence in bad[:5]:
        print(f"  unparsed: {sentence}", file=sys.stderr)


def report(name: str, count: int, tally: Tally) -> None:
    scenes = max(tally.counts["scenes"], 1)
    per_scene = {stage: seconds / scenes for stage, seconds in tally.seconds.items()}
    common = per_scene["layout"] + per_scene["full text"] + per_scene["render"]
    before = common + per_scene["layout-true captions"]
    after = common + per_scene["image captions + grounding + refexps"]
    print(f"== {name}: {tally.counts['scenes']} scenes laid out of {count} seeds")
    for key, value in sorted(tally.counts.items()):
        if key != "scenes":
            print(f"  {key}: {value}")
    print(
        "  CPU s/scene: "
        + ", ".join(f"{stage} {seconds:.4f}" for stage, seconds in per_scene.items())
    )
    print(f"  throughput with grounding / without: {before / after:.3f}")
    print(f"  throughput with questions / without: {after / (after + per_scene['questions']):.3f}")
    for family, answers in tally.answers.items():
        total = sum(answers.values())
        spread = ", ".join(f"{answer} {n / total:.0%}" for answer, n in answers.most_common(6))
        print(
            f"  {family}: {total} questions; answers {spread}"
            + (" ..." if len(answers) > 6 else "")
        )


if __name__ == "__main__":
    main()
