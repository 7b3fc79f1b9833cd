"""The learning commands (``scenewright.learning``): ``fit`` a rule set's numbers
to examples, find the ``relations`` of example scenes, ``learn`` a rule set from them."""

from __future__ import annotations

import argparse
import json
import os
import sys
from functools import partial
from pathlib import Path

from .common import (
    note_progress,
    output_file,
    read_scene_data,
    say,
)
from .options import (
    MAX_CHECK_SCENES,
    MAX_LAYOUTS,
    MAX_ROUNDS,
    add_command,
    allow_option,
    count_at_least,
    prior_value,
    seed_value,
)

HELP = {
    "fit": """\
examples:
  scenewright dataset study -n 500 -o data/study --size 64x64
  scenewright fit study data/study/scenes/*.json -o fitted/study.rules --report fitted/fit.json
  scenewright fit my.rules liked/*.json -o my_fitted.rules
  scenewright fit bedroom my_rooms/ -o my_bedroom.rules   # hand-written examples or GLB, a folder of them
  scenewright fit bedroom my_rooms/ -o my_bedroom.rules --what weights,context   # and spatial priors

Re-estimates the rule set's numbers from what the example scenes drew: alternative
weights, optional probabilities, count distributions (a range becomes a weighted range
'2..4 {0.2 0.5 0.3}') and style weights. Each is the posterior mean under a Dirichlet
prior of --prior pseudo-draws per option; the report gives every parameter with its
draws, estimate, standard error and the value written before. A parameter no example
drew keeps its number and is listed as unidentified. The output is the input with only
its numbers changed; files it includes are written beside it at the same relative paths.
Examples are scene.json files of this rule set. Those made by scenewright keep their
derivation (the draws fit counts); for one without, fit searches for the derivations
that could have made it and fits by expectation-maximisation (docs/learning.md).
Hand-written examples and GLB files (their types named as in the rules) are fitted the
same way, the derivations told apart by which of their relations the geometry holds;
for --what context their objects are related as their derivation relates them.""",
    "relations": """\
examples:
  scenewright dataset bedroom -n 500 -o data/bedroom --no-images
  scenewright relations data/bedroom/scenes/*.json
  scenewright relations rooms/*.json room.glb --json
  scenewright relations data/bedroom/scenes/*.json --test angle --seed 3

finds which pairs of object types stand in a pattern relative to each other in the
example scenes (scene.json or its folder, the hand-written example format, GLB). The
default test compares where a b stands in an a's frame (position and turn) within a
scene with an a and a b of two different scenes, whose placements are independent
(energy distance, 199 permutations, related at p <= 0.01; a pair in 3 to 9 scenes that
this misses is tried again with either side of a alike: related at p <= 0.01, or when b
stands next to a at one such pose in 3 scenes of 4, as 3 or 4 scenes never reach 0.01);
--test angle is the test of complete spatial randomness by angles of Zhang et al. (related at d >= 1.628);
--test cooccurrence calls a pair related when most scenes hold both. Of a triangle of
related types a pair that holds only through the third type is reported as indirect
(a lamp on a nightstand by a bed relates to the bed through the nightstand): one
resting on another, else for the default test a pair whose poses are no tighter than
their composition through the third type (of such, the least direct in the
coordinates that hold its relation, or of those about as direct the one standing
farthest apart; roads close triangles too), else the pair standing farthest apart,
then the weakest; a third type in fewer than 3 of 4 of a pair's scenes carries nothing; --no-prune keeps them. A type
resting on another in half the scenes holding both or more (measured from the boxes)
is related to it whatever the p-value, from 5 scenes. A pair the room fixes side by
side in most scenes (a stove beside a sink under the one window), which no test of
poses can contrast, is related as "fixed". In scenes with
groups (a home, a market stand) each type is tested in each kind of group it stands in
(a bush in a home, a bush in a park), and a type pair takes the verdict of its most
related pair of such roles ("in groups"); a triangle of parts of one kind of group is
judged within each group. Prints a table of every pair of types that share a scene,
or with --json the same fields (a, b, related, statistic, p_value, pairs, scenes,
strength, tested, fixed, pruned, groups). The same examples and seed
print the same result. See docs/learning.md.""",
    "learn": """\
examples:
  scenewright learn examples/sets/desks/*.json -o desks.rules --report learn.json
  scenewright learn data/bedroom/scenes/*.json -o bedroom_learned.rules --seed 3 --check 0
  scenewright learn examples/sets/bedrooms -o bedrooms.rules   # a folder; writes bedrooms.context.json too
  scenewright learn examples/sets/desks/*.json -o desks.rules --no-context   # the rules alone
  scenewright validate desks.rules && scenewright generate desks.rules --seed 1 -o out/
  (examples/sets/ is in the repository: run these from its root, or name your own files)

induces a rule set from example scenes alone (scene.json or its folder, the
hand-written example format, GLB; a folder of such files): a catalog of the types seen (median sizes, styles
weighted by how often each was seen), the type pairs related by --test (and what rests
on what, measured from the boxes) grouped around an anchor object, each member placed
relative to its parent by the labels that hold at the density-peak clusters of its
relative poses (several clusters: weighted alternatives), and how often and how many
of each were seen ('0.85? 1..3 {6 4 1}'). The file is checked like 'validate' does,
then --check N scenes (50) are generated from it and compared with the examples: each
type's count per scene, the share of scenes holding each related pair, the share of
objects for which the written placement holds. Unless --no-context, a context (spatial
priors, as 'fit --what context' learns them) is fitted to the same examples against the
induced rules and written beside them as NAME.context.json; when no related pair occurs
in two examples, the rules are written without one and a line says why. --report gives
every type pair (test statistic, p-value, the labels chosen and their clusters), the
catalog, the groups, that comparison and the context's fit. The same examples and seed
give the same files. See docs/learning.md.""",
}


def add_commands(commands) -> None:
    """Add the commands fit, relations, learn to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    fit = command("fit", "re-estimate a rule set's weights from example scenes", run_fit)
    fit.add_argument("rules", help="shipped rule set name or path to a .rules file")
    fit.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes of the rule set (scene.json, the hand-written format, GLB, or a folder of them)",
    )
    fit.add_argument(
        "-o", "--output", required=True, metavar="RULES", help="the fitted rules file to write"
    )
    fit.add_argument(
        "--report", metavar="JSON", help="also write every parameter with its standard error here"
    )
    fit.add_argument(
        "--prior",
        type=prior_value,
        default=0.5,
        metavar="A",
        help="Dirichlet pseudo-draws per option (0.5: Jeffreys' prior; more pulls rarely drawn parameters "
        "towards uniform)",
    )
    fit.add_argument(
        "--what",
        default="weights",
        metavar="WHAT[,WHAT]",
        help="what to fit: weights (the rules' numbers, the default), context (spatial priors learned from the "
        "examples' layouts, written beside the rules as NAME.context.json), or weights,context",
    )
    fit.add_argument(
        "--seed", type=seed_value, default=0, help="seed of the context fit's layouts (0)"
    )
    context_fit_options(fit)
    allow_option(fit)

    relations = command(
        "relations",
        "find which object type pairs are spatially related in example scenes",
        run_relations,
    )
    relations.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes (scene.json or its folder, .json, .glb)",
    )
    relations.add_argument("--json", action="store_true", help="print the result as JSON")
    relations.add_argument(
        "--test",
        choices=("permutation", "angle", "cooccurrence"),
        default="permutation",
        help="permutation (default: within- vs across-scene poses), angle (complete spatial randomness by "
        "angles) or cooccurrence (a baseline)",
    )
    relations.add_argument(
        "--seed", type=seed_value, default=0, help="seed of the tests' random draws (0)"
    )
    relations.add_argument(
        "--no-prune",
        dest="prune",
        action="store_false",
        help="keep indirect relations (a pair of a triangle that holds through the third type)",
    )

    learn = command("learn", "induce a rule set from example scenes alone", run_learn)
    learn.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes (scene.json or its folder, .json, .glb)",
    )
    learn.add_argument(
        "-o", "--output", required=True, metavar="RULES", help="the rules file to write"
    )
    learn.add_argument(
        "--report",
        metavar="JSON",
        help="also write the pairs, catalog, groups, the check and the context's fit here",
    )
    learn.add_argument(
        "--seed",
        type=seed_value,
        default=0,
        help="seed of the relation test, the check scenes and the context fit (0)",
    )
    learn.add_argument(
        "--test",
        choices=("permutation", "angle", "cooccurrence"),
        default="permutation",
        help="which test finds the related type pairs (permutation; see 'relations --help')",
    )
    learn.add_argument(
        "--check",
        type=count_at_least(0, MAX_CHECK_SCENES),
        default=50,
        metavar="N",
        help="scenes to generate from the induced rules and compare with the examples (50; 0: none)",
    )
    learn.add_argument(
        "--no-context",
        dest="context",
        action="store_false",
        help="write no context: by default spatial priors are learned from the examples' layouts against the "
        "induced rules and written beside them as NAME.context.json, which generate uses",
    )
    context_fit_options(learn)


def context_fit_options(parser: argparse.ArgumentParser) -> None:
    """The options of a context's iterative scaling, which fit and learn share."""
    parser.add_argument(
        "--rounds",
        type=count_at_least(0, MAX_ROUNDS),
        default=2,
        metavar="N",
        help="context: rounds of iterative scaling (2)",
    )
    parser.add_argument(
        "--layouts",
        type=count_at_least(1, MAX_LAYOUTS),
        default=40,
        metavar="N",
        help="context: scenes laid out per round (40)",
    )
    parser.add_argument(
        "--balance",
        action="store_true",
        help="context: also fit the visual-balance term (off: it slows layouts, docs/learning.md)",
    )


def run_fit(args: argparse.Namespace) -> int:
    from scenewright.core.atomic import staged_files
    from scenewright.examples.formats import example_paths
    from scenewright.learning.fit import fit_rule_set, parse_what

    what = parse_what(args.what)
    examples = [(str(path), read_fit_example(path)) for path in example_paths(args.examples)]
    output = output_file(args.output, "fitted.rules")
    report = output_file(args.report, "fit.json") if args.report else None
    with staged_files() as staged:  # the rules, their includes, context and report: all or none
        fit, context, written = fit_rule_set(
            args.rules,
            examples,
            output,
            report=report,
            allow=args.allow_outside,
            prior=args.prior,
            write=staged.write,
            commit=staged.commit,
            what=what,
            seed=args.seed,
            rounds=args.rounds,
            layouts=args.layouts,
            balance=args.balance,
        )
    unidentified = fit.unidentified
    if "weights" in what:
        say(
            args,
            f"fitted {len(fit.parameters)} parameters from {fit.examples} example"
            f"{'s' if fit.examples != 1 else ''}"
            + (
                f"; {len(unidentified)} no example drew kept their numbers: "
                + ", ".join(f"{p.kind} {p.name}" for p in unidentified)
                if unidentified
                else ""
            ),
        )
    if context is not None:
        held = context.held_out_summary()
        fitted = (
            f"a context of {len(context.context.pairs)} pair kind"
            f"{'s' * (len(context.context.pairs) != 1)} from {len(examples)} examples "
            f"(divergence {context.divergence[0]:.3f} at the start, "
            f"{context.divergence[context.kept]:.3f} kept{'; ' + held if held else ''})"
        )
        if context.rules_alone_better:
            say(
                args,
                f"no context written: the rules alone come as near the examples held out; {fitted}",
            )
        else:
            say(args, f"fitted {fitted}")
    say(args, "wrote " + ", ".join(str(path) for path in written))
    return 0


def read_fit_example(path: str | os.PathLike):
    """A scene.json document (checked; its derivation, when kept, is what is fitted), or
    the Scene of an example read from geometry alone (the hand-written format, GLB)."""
    from scenewright.examples import load_example
    from scenewright.examples.formats import is_scene_json_file

    if is_scene_json_file(path):
        folder = Path(path)
        return read_scene_data(str(folder / "scene.json" if folder.is_dir() else folder))
    return load_example(path).scene


def run_relations(args: argparse.Namespace) -> int:
    from scenewright.examples import load_examples
    from scenewright.learning.relation_finding import find_relations

    examples = load_examples(args.examples)
    result = find_relations(
        [e.scene for e in examples], test=args.test, seed=args.seed, prune=args.prune
    )
    sys.stdout.write(json.dumps(result.to_dict(), indent=1) + "\n" if args.json else result.table())
    return 0


def run_learn(args: argparse.Namespace) -> int:
    from scenewright.api import build_scene
    from scenewright.core.atomic import staged_files
    from scenewright.examples import load_examples
    from scenewright.generator.layout.learned_term import context_path
    from scenewright.learning.learn import CONTEXT_REPLAYS, learn_rule_set

    examples = load_examples(args.examples)
    output = output_file(args.output, "induced.rules")
    report = output_file(args.report, "learn.json") if args.report else None
    sidecar = context_path(output)
    stale = sidecar.is_file()
    with staged_files() as staged:  # the rules, context and report: all or none
        learned = learn_rule_set(
            examples,
            output,
            report=report,
            seed=args.seed,
            test=args.test,
            check=args.check,
            context=args.context,
            rounds=args.rounds,
            layouts=args.layouts,
            balance=args.balance,
            write=staged.write,
            build_scene=build_scene,
            progress=lambda message: note_progress(args, message),
        )
    induction = learned.induction
    warning = learned.check.warning() if learned.check is not None else None
    if warning:  # first, where it is seen; not silenced by --quiet
        print(warning, flush=True, file=sys.stderr if args.quiet else sys.stdout)
    related = sum(pair.related for pair in induction.relations.pairs)
    say(
        args,
        f"induced {len(induction.catalog)} types, {len(induction.groups)} group"
        f"{'s' * (len(induction.groups) != 1)} and {len(induction.written_pairs())} relations from "
        f"{induction.scenes} examples ({related} related type pairs by the {induction.relations.test} test)",
    )
    if learned.check is not None:
        say(args, learned.check.summary())
    context = learned.context
    if context is not None:
        left_out = "".join(
            f"; {len(names)} example{'s' * (len(names) != 1)} {why} left out ({', '.join(names)})"
            for names, why in (
                (context.left_out, "no derivation of the induced rules makes"),
                (context.ambiguous, "the induced rules make in too many ways to search"),
            )
            if names
        )
        if context.unsearched:
            left_out += (
                f"; {len(context.unsearched)} not searched (the searches before them spent the "
                f"{CONTEXT_REPLAYS} replays all share)"
            )
        if context.fit is not None:
            pairs = context.fit.context.pairs
            say(
                args,
                f"fitted a context of {len(pairs)} pair kind{'s' * (len(pairs) != 1)} from {context.used} "
                f"examples (divergence {context.fit.divergence[0]:.3f} at the start, "
                f"{context.fit.divergence[context.fit.kept]:.3f} kept"
                + (f"; {context.fit.held_out_summary()}" if context.fit.held_out_summary() else "")
                + f"){left_out}",
            )
        else:
            say(args, f"no context learned: {context.why_not}{left_out}")
    if sidecar not in learned.written and stale:
        say(
            args,
            f"note: {sidecar} beside the rules is not from this run; generate refuses it when it "
            "records other rules, and uses it otherwise (--no-context leaves it out)",
        )
    say(args, "wrote " + ", ".join(str(path) for path in learned.written))
    return 0
