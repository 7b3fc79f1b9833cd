"""Parameter recovery of ``scenewright fit``: known weights in, the same weights out.

    .venv/bin/python benchmarks/bench_fit.py                      # every shipped rule set, 500 scenes
    .venv/bin/python benchmarks/bench_fit.py study --scenes 200   # these rule sets (names or paths)
    .venv/bin/python benchmarks/bench_fit.py --cli 500            # also time the command on 500 scene.json files
    .venv/bin/python benchmarks/bench_fit.py desk --em 200        # also fit 200 scenes without their derivations

For each rule set (the truth): draw ``--scenes`` derivations from it, write a *flat*
copy (every alternative and style weight equal, every optional 0.5, every range
uniform), fit the flat copy to the truth's derivations, and print

- recovered: of the identified parameter values, the share within max(3 standard
  errors, 0.03) of the truth, and the worst one;
- regenerated scenes against a fresh truth sample, on three families of statistics:
  per-type count distributions, style shares, and the share of scenes holding each
  (type, label, type) relation. The distance of two samples is the mean over the
  statistics of a family of the total variation distance (counts, styles) or the
  absolute difference (relations). The noise floor is the distance between two truth
  samples of the same size; the fitted rules should come within 1.5x of it, and the
  flat rules should not;
- CPU seconds of the fit itself.

Scenes here are grammar expansions (what the weights decide); the layout does not
change them. ``--cli N`` also generates N laid-out scenes of the first rule set and
times ``scenewright fit`` on their scene.json files, start to end (reading, checking,
fitting, writing). Prints figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

from scenewright.generator import expand, load_rules
from scenewright.generator.rules import parse_rules_tree, shipped_rule_sets
from scenewright.learning.derivations import derivations_of
from scenewright.learning.errors import AmbiguousExample
from scenewright.learning.rewrite import fitted_files, rewrite_rules
from scenewright.learning.weights import Parameter, WeightFit, fit_weights, fit_weights_em

FAMILIES = ("counts", "styles", "relations")


def flat_fit(fit: WeightFit) -> WeightFit:
    """A fit that writes every parameter flat: uniform options (optional 0.5)."""
    flat = []
    for p in fit.parameters:
        uniform = tuple(1.0 / len(p.options) for _ in p.options)
        flat.append(
            Parameter(
                p.kind,
                p.name,
                p.site,
                p.options,
                (1,) * len(p.options),
                uniform,
                uniform,
                p.written,
            )
        )
    return WeightFit(tuple(flat), 1, fit.prior)


def write_rules(source: str, fit: WeightFit, output: Path) -> Path:
    """``source`` rewritten with ``fit``'s numbers at ``output`` (includes beside it)."""
    tree = parse_rules_tree(source)
    for path, text in fitted_files(tree, rewrite_rules(tree, fit), output):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return output


def statistics_of(rules, seeds) -> dict[str, dict]:
    """Per family, per statistic, the sample's distribution (counts: a Counter of the
    number per scene; styles: a Counter of style names per type; relations: the share
    of scenes that hold the triple)."""
    counts: dict[str, Counter] = {}
    styles: dict[str, Counter] = {}
    relations: Counter = Counter()
    graphs = [expand(rules, seed) for seed in seeds]
    types = sorted({node.type for graph in graphs for node in graph.nodes()})
    for graph in graphs:
        per_type = Counter(node.type for node in graph.nodes())
        for type_name in types:
            counts.setdefault(type_name, Counter())[per_type[type_name]] += 1
        for node in graph.nodes():
            if node.style:
                styles.setdefault(node.type, Counter())[node.style] += 1
        nodes = {node.id: node.type for node in graph.nodes()}
        held = {(nodes[e.source], e.label, nodes.get(e.target, e.target)) for e in graph.edges()}
        relations.update(held)
    shares = {triple: number / len(graphs) for triple, number in relations.items()}
    return {"counts": counts, "styles": styles, "relations": shares}


def tvd(first: Counter, second: Counter) -> float:
    keys = set(first) | set(second)
    a, b = sum(first.values()) or 1, sum(second.values()) or 1
    return 0.5 * sum(abs(first[k] / a - second[k] / b) for k in keys)


def distance(first: dict, second: dict) -> dict[str, float]:
    out = {}
    for family in FAMILIES:
        keys = set(first[family]) | set(second[family])
        if family == "relations":
            values = [abs(first[family].get(k, 0.0) - second[family].get(k, 0.0)) for k in keys]
        else:
            values = [
                tvd(first[family].get(k, Counter()), second[family].get(k, Counter())) for k in keys
            ]
        out[family] = float(np.mean(values)) if values else 0.0
    return out


def recovery(truth_fit: WeightFit, fit: WeightFit) -> tuple[int, int, str]:
    """(values within tolerance, values, the worst value's description)."""
    truth = {(p.kind, p.name, p.site.line): p.written for p in truth_fit.parameters}
    within = total = 0
    worst, worst_ratio = "", -1.0
    for p in fit.parameters:
        if not p.identified:
            continue
        for option, estimate, error, true in zip(
            p.options,
            p.estimate,
            p.standard_error,
            truth[(p.kind, p.name, p.site.line)],
            strict=False,
        ):
            tolerance = max(3 * error, 0.03)
            total += 1
            within += abs(estimate - true) <= tolerance
            ratio = abs(estimate - true) / tolerance
            if ratio > worst_ratio:
                worst_ratio = ratio
                worst = f"{p.kind} {p.name} [{option}]: {estimate:.3f} vs {true:.3f} (tolerance {tolerance:.3f})"
    return within, total, worst


def bench(name: str, scenes: int, folder: Path) -> None:
    truth = load_rules(name)
    truth_fit = fit_weights(truth, [])  # its parameters, with the written values
    if not truth_fit.parameters:
        print(f"{name}: no random parameters")
        return
    flat_path = write_rules(name, flat_fit(truth_fit), folder / name / "flat.rules")
    flat = load_rules(flat_path)
    derivations = [expand(truth, seed).derivation for seed in range(scenes)]
    start = time.process_time()
    fit = fit_weights(flat, derivations)
    seconds = time.process_time() - start
    fitted = load_rules(write_rules(str(flat_path), fit, folder / name / "fitted" / "fitted.rules"))
    within, total, worst = recovery(truth_fit, fit)
    samples = {
        "truth": statistics_of(truth, range(10**6, 10**6 + scenes)),
        "truth again": statistics_of(truth, range(2 * 10**6, 2 * 10**6 + scenes)),
        "fitted": statistics_of(fitted, range(3 * 10**6, 3 * 10**6 + scenes)),
        "flat": statistics_of(flat, range(4 * 10**6, 4 * 10**6 + scenes)),
    }
    floor = distance(samples["truth"], samples["truth again"])
    print(
        f"{name}: {len(fit.parameters)} parameters, {len(fit.unidentified)} unidentified; "
        f"recovered {within}/{total} values within max(3 se, 0.03); fit {seconds:.3f} CPU s for {scenes} scenes"
    )
    print(f"  worst: {worst}")
    for label in ("fitted", "flat"):
        d = distance(samples["truth"], samples[label])
        ratios = ", ".join(
            f"{family} {d[family]:.4f} ({d[family] / floor[family]:.2f}x floor {floor[family]:.4f})"
            if floor[family]
            else f"{family} {d[family]:.4f} (floor 0)"
            for family in FAMILIES
        )
        print(f"  {label:6s} vs truth: {ratios}")


def bench_em(name: str, scenes: int, folder: Path) -> None:
    """Fit the flat copy to ``scenes`` truth scenes without their derivations (EM)."""
    truth = load_rules(name)
    truth_fit = fit_weights(truth, [])
    if not truth_fit.parameters:
        return
    flat = load_rules(folder / name / "flat.rules")
    start = time.process_time()
    try:
        candidates = [derivations_of(flat, expand(truth, seed)) for seed in range(scenes)]
    except AmbiguousExample as error:
        print(f"{name} without derivations: {error} ({time.process_time() - start:.1f} CPU s)")
        return
    searched = time.process_time() - start
    fit = fit_weights_em(flat, candidates)
    within, total, worst = recovery(truth_fit, fit)
    print(
        f"{name} without derivations: {scenes} scenes, {fit.ambiguous} with more than one derivation "
        f"(at most {max(map(len, candidates))}); search {searched / scenes:.3f} CPU s per scene, "
        f"EM {fit.iterations} rounds; recovered {within}/{total} within max(3 se, 0.03); worst: {worst}"
    )


def time_cli(name: str, scenes: int, folder: Path) -> None:
    from scenewright.api import generate, reproducible_json

    examples = folder / "cli"
    examples.mkdir(parents=True, exist_ok=True)
    for seed in range(scenes):
        path = examples / f"{seed:06d}.json"
        if not path.exists():
            path.write_text(reproducible_json(generate(name, seed)))
    command = [
        sys.executable,
        "-m",
        "scenewright.cli",
        "fit",
        name,
        *map(str, sorted(examples.glob("*.json"))),
        "-o",
        str(folder / "cli-out" / "fitted.rules"),
    ]
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    print(
        f"cli: scenewright fit {name} on {scenes} scene.json files: {seconds:.1f} s wall, exit {result.returncode}"
    )
    print("  " + (result.stdout.strip().splitlines() or [result.stderr.strip()])[0])


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("rules", nargs="*", help="rule sets (default: every shipped one)")
    parser.add_argument("--scenes", type=int, default=500, help="scenes per sample (500)")
    parser.add_argument(
        "--cli",
        type=int,
        default=0,
        metavar="N",
        help="also time the command on N scene.json files",
    )
    parser.add_argument(
        "--em",
        type=int,
        default=0,
        metavar="N",
        help="also fit N scenes without their derivations (expectation-maximisation)",
    )
    args = parser.parse_args()
    names = args.rules or shipped_rule_sets()
    with tempfile.TemporaryDirectory() as folder:
        for name in names:
            bench(name, args.scenes, Path(folder))
            if args.em:
                bench_em(name, args.em, Path(folder))
        if args.cli:
            time_cli(names[0], args.cli, Path(folder))


if __name__ == "__main__":
    main()
