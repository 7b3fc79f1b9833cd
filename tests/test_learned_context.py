"""The learned layout part (``learned_term``), its fit by iterative scaling
(``learning.context``) and ``fit --what context`` / ``generate --context``."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from scenewright.api import build_scene
from scenewright.cli import main
from scenewright.core.errors import InputError
from scenewright.core.frames import to_world
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.learned_term import (
    BALANCE_BINS,
    BINS,
    YAW_BINS,
    BalanceContext,
    LearnedContext,
    LearnedMoves,
    PairContext,
    balance_offset,
    compile_learned,
    related_pairs,
    relative_pose,
)
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.sampler import start_chain
from scenewright.learning.context import (
    ContextFit,
    example_layout,
    fit_context,
    held_out_split,
    scaling_step,
    total_variation,
)

DINING = Path(__file__).resolve().parents[1] / "examples" / "sets" / "dining" / "dining.rules"


def random_context(
    graph, seed: int = 0, bounds=(-1.5, -1.2, 1.5, 1.2), balance: bool = False
) -> LearnedContext:
    """Random weights for every pair kind of a graph, over a grid around the target
    (and, with ``balance``, for the visual-balance term)."""
    problem = compile_problem(graph)
    types = [graph.node(i).type for i in problem.ids]
    rng = np.random.default_rng(seed)
    kinds = sorted({kind for _, _, kind in related_pairs(problem, types)})
    pairs = tuple(
        PairContext(
            *kind, bounds, rng.uniform(0, 5, BINS * BINS + 1), rng.uniform(0, 3, YAW_BINS), 1
        )
        for kind in kinds
    )
    table = BalanceContext(rng.uniform(0, 4, BALANCE_BINS), 1) if balance else None
    return LearnedContext(pairs, balance=table)


def learned_problem(rules, seed: int = 0, bounds=(-1.5, -1.2, 1.5, 1.2), balance: bool = False):
    graph = expand(load_rules(rules), seed)
    problem = compile_problem(graph)
    types = [graph.node(i).type for i in problem.ids]
    context = random_context(graph, seed, bounds, balance)
    problem.learned = compile_learned(context, problem, types)
    return problem


# A grid that holds the chairs at the table's sides but not the one at either end
# (1.15 m out), so that pairs stand both on and off their grids.
@pytest.mark.parametrize("incremental, balance", [(True, False), (False, False), (True, True)])
def test_learned_deltas_match_the_full_energy_on_random_moves(incremental, balance):
    problem = learned_problem(DINING, 1, (-0.9, -1.2, 0.9, 1.2), balance)
    assert (problem.learned.balance is not None) == balance
    assert len(problem.learned.pairs) == 6 and problem.learned.tempered and problem.learned.swaps
    params = LayoutParams(incremental=incremental)
    rng = np.random.default_rng(5)
    energy, mover = start_chain(problem, params, rng)
    learned = LearnedMoves(problem.learned, problem, energy.state, rng, mover.movable_box, 1)
    checked, swaps, grid_sides = 0, 0, set()
    for step in range(300):
        drawn = learned.propose() if step % 2 else None
        proposal = (drawn[0], {}) if drawn else mover.propose(energy.relation)
        if proposal is None:
            continue
        if not drawn:  # as the sampler makes it: now and then the table takes its chairs along
            proposal = (learned.carry(proposal[0]), proposal[1])
        before, soft_before, sides = energy.full(), _soft_relations(energy), _grid_sides(energy)
        delta = energy.propose(*proposal)
        after, soft_after = energy.full(), _soft_relations(energy)
        grid_sides |= sides & _grid_sides(energy)
        assert delta == pytest.approx(sum(after.values()) - sum(before.values()), abs=1e-9)
        assert energy.learned_delta == pytest.approx(after["learned"] - before["learned"], abs=1e-9)
        assert energy.soft_delta - energy.learned_delta == pytest.approx(
            soft_after - soft_before, abs=1e-9
        )
        if drawn and drawn[2] is None:  # an exchange of two interchangeable chairs
            assert drawn[1] == 0.0
            swaps += 1
        elif drawn:  # the Hastings correction is the moved pair's own change
            pair = drawn[2]
            source, target, table = problem.learned.pairs[pair]
            old = energy.learned[pair]
            new = problem.learned.value(pair, energy.state)
            assert drawn[1] == pytest.approx(new - old, abs=1e-9)
        if rng.random() < 0.5:
            energy.accept()
        else:
            energy.reject()
        assert energy.total == pytest.approx(sum(energy.full().values()), abs=1e-7)
        checked += 1
    assert checked > 250 and swaps > 10
    assert grid_sides == {True, False}  # some pair stayed on its grid and some off it across a move


def _soft_relations(energy) -> float:
    """The tempered relation terms that are sampled with the learned part, recomputed:
    those of pairs whose source stands on the pair's grid."""
    learned, pose = energy.problem.learned, energy.state.pose
    return sum(
        energy.relation_energy(t)
        for t, pair in learned.tempered.items()
        if learned.on_grid(pair, pose(learned.pairs[pair][0]), pose(learned.pairs[pair][1]))
    )


def _grid_sides(energy) -> set[bool]:
    """Whether each learned pair's source stands on its grid, as a set."""
    learned, pose = energy.problem.learned, energy.state.pose
    return {
        learned.on_grid(k, pose(source), pose(target))
        for k, (source, target, _) in enumerate(learned.pairs)
    }


def test_an_off_grid_pair_anneals_its_relations_and_an_on_grid_one_samples_them():
    problem = learned_problem(DINING, 1, (-0.9, -1.2, 0.9, 1.2))
    energy, _ = start_chain(problem, LayoutParams(), np.random.default_rng(2))
    learned, state = problem.learned, energy.state
    for pair, (source, target, _) in enumerate(learned.pairs):
        terms = [t for t, k in learned.tempered.items() if k == pair]
        tx, tz, tyaw = state.pose(target)
        start = state.pose(source)
        for first, second, on_grid in (
            (0.0, 0.2, True),
            (3.0, 3.5, False),
        ):  # beside the table, or metres off
            for lx in (first, second):
                x, z = to_world(tx, tz, tyaw, lx, 0.8)
                energy.propose({source: (x, z, state.yaw[source])}, {})
                if lx == first:
                    energy.accept()
            assert learned.on_grid(pair, state.pose(source), state.pose(target)) is on_grid
            relations = sum(energy.relation_energy(t) - energy.relation[t] for t in terms)
            if on_grid:  # sampled with the learned part
                assert energy.soft_delta == pytest.approx(
                    energy.learned_delta + relations, abs=1e-12
                )
            else:  # annealed with the rest: the further off, the more broken its NextTo
                assert relations > 0.1 and energy.soft_delta == energy.learned_delta
            energy.reject()
        energy.propose({source: start}, {})
        energy.accept()


def test_interchangeable_boxes_swap_with_what_rests_on_them_and_a_swap_undoes_itself():
    problem = learned_problem("bedroom", 2)
    ids, learned = problem.ids, problem.learned
    swaps = {(ids[a], ids[b]) for a, b in learned.swaps}
    # The lamps are of one type too, but each rests on its own nightstand.
    assert swaps == {("nightstand_1", "nightstand_2"), ("book_1", "book_2")}
    energy, mover = start_chain(problem, LayoutParams(), np.random.default_rng(4))
    state = energy.state
    moves = LearnedMoves(learned, problem, state, np.random.default_rng(0), mover.movable_box, 2)
    a, b = ids.index("nightstand_1"), ids.index("nightstand_2")
    lamp = ids.index("lamp_1")
    assert problem.support[lamp] == a
    start = {box: state.pose(box) for box in range(problem.n_boxes)}
    on_a = relative_pose(state.pose(lamp), state.pose(a))
    for _ in range(2):
        before = energy.full()
        delta = energy.propose(moves.swap(a, b), {})
        assert delta == pytest.approx(sum(energy.full().values()) - sum(before.values()), abs=1e-9)
        energy.accept()
    swapped = {box: state.pose(box) for box in range(problem.n_boxes)}
    # Twice is once there and back: the move is its own inverse.
    for box, pose in start.items():
        assert swapped[box] == pytest.approx(pose, abs=1e-12)
    energy.propose(moves.swap(a, b), {})
    assert state.pose(a) == start[b] and state.pose(b) == start[a]
    assert relative_pose(state.pose(lamp), state.pose(a)) == pytest.approx(on_a, abs=1e-12)
    others = set(range(problem.n_boxes)) - set(problem.carried(a)) - set(problem.carried(b))
    assert all(state.pose(box) == start[box] for box in others)


def test_a_share_of_learned_moves_are_swaps_and_they_are_not_counted_as_redraws():
    problem = learned_problem("bedroom", 2)
    energy, mover = start_chain(problem, LayoutParams(), np.random.default_rng(4))
    moves = LearnedMoves(
        problem.learned, problem, energy.state, np.random.default_rng(1), mover.movable_box, 2
    )
    kinds = [moves.propose() for _ in range(400)]
    swaps = [drawn for drawn in kinds if drawn[2] is None]
    assert 0.15 < len(swaps) / len(kinds) < 0.35  # SWAP_SHARE of the learned moves
    assert sum(moves.tried) == len(kinds) - len(swaps)


def test_a_learned_target_carries_its_sources_in_half_its_ordinary_moves():
    problem = learned_problem("bedroom", 2)
    ids = problem.ids
    energy, mover = start_chain(problem, LayoutParams(), np.random.default_rng(4))
    state = energy.state
    moves = LearnedMoves(
        problem.learned, problem, state, np.random.default_rng(6), mover.movable_box, 2
    )
    bed = ids.index("bed_1")
    followers = {ids[box] for box in moves.followers[bed]}
    assert {
        "nightstand_1",
        "nightstand_2",
        "lamp_1",
        "lamp_2",
    } <= followers and "bed_1" not in followers
    x, z, yaw = state.pose(bed)
    turned = {bed: (x + 0.3, z - 0.2, yaw + 0.5)}
    carried = 0
    for _ in range(200):
        proposal = moves.carry(turned)
        assert proposal[bed] == turned[bed]
        if len(proposal) == 1:
            continue
        carried += 1
        assert {ids[box] for box in proposal} == {"bed_1"} | followers
        for box in moves.followers[bed]:  # each follower keeps its pose in the bed's frame
            assert relative_pose(proposal[box], proposal[bed]) == pytest.approx(
                relative_pose(state.pose(box), state.pose(bed)), abs=1e-9
            )
    assert 70 < carried < 130  # CARRY_SHARE of the calls
    # A follower the proposal moves itself keeps the proposal's pose.
    a = ids.index("nightstand_1")
    own = {bed: turned[bed], a: (0.0, 0.0, 0.0)}
    assert all(moves.carry(own)[a] == (0.0, 0.0, 0.0) for _ in range(20))


def test_iterative_scaling_matches_the_observed_shares_on_a_known_model():
    # A pair's model: base measure b over (position bin, yaw bin), times exp(-lambda_p - lambda_y).
    rng = np.random.default_rng(0)
    base = rng.uniform(0.2, 3.0, (8, 5))
    observed_p, observed_y = rng.dirichlet(np.ones(8)), rng.dirichlet(np.ones(5))
    weights_p, weights_y = np.zeros(8), np.zeros(5)

    def model():
        joint = base * np.exp(-weights_p)[:, None] * np.exp(-weights_y)[None, :]
        joint /= joint.sum()
        return joint.sum(axis=1), joint.sum(axis=0)

    start = total_variation(model()[0], observed_p) + total_variation(model()[1], observed_y)
    for _ in range(60):
        generated_p, generated_y = model()
        weights_p = scaling_step(weights_p, observed_p, generated_p)
        weights_y = scaling_step(weights_y, observed_y, generated_y)
    generated_p, generated_y = model()
    assert start > 0.1
    assert (
        total_variation(generated_p, observed_p) < 1e-4
        and total_variation(generated_y, observed_y) < 1e-4
    )
    assert weights_p.min() == 0.0  # normalised to start at 0


def dining_examples(count: int, seed: int = 0) -> list[tuple[str, dict]]:
    """``count`` dining scenes, the chairs' layouts jittered around one arrangement."""
    template = build_scene(load_rules(DINING), 0).to_dict()
    side = {
        r["source"]: r["label"] for r in template["relations"] if r["label"].startswith("NextTo")
    }
    places = {
        "NextToFront": [(-0.4, 0.8), (0.4, 0.8)],
        "NextToBehind": [(-0.4, -0.8), (0.4, -0.8)],
        "NextToLeft": [(1.15, 0.0)],
        "NextToRight": [(-1.15, 0.0)],
    }
    yaws = {
        "NextToFront": math.pi,
        "NextToBehind": 0.0,
        "NextToLeft": -math.pi / 2,
        "NextToRight": math.pi / 2,
    }
    rng = np.random.default_rng(seed)
    examples = []
    for k in range(count):
        used: dict[str, int] = {}
        objects = []
        for o in template["objects"]:
            o = dict(o)
            if o["type"] == "table":
                o["position"], o["yaw"] = [0.0, 0.0, 0.0], 0.0
            elif o["id"] in side:
                label = side[o["id"]]
                x, z = places[label][used.get(label, 0)]
                used[label] = used.get(label, 0) + 1
                o["position"] = [x + rng.normal(0, 0.05), 0.0, z + rng.normal(0, 0.05)]
                o["yaw"] = yaws[label]
            objects.append(o)
        examples.append((f"example_{k}", {**template, "objects": objects}))
    return examples


def test_fit_context_is_deterministic_and_learns_every_pair_kind():
    examples = dining_examples(6)
    first = fit_context(examples, seed=3, rounds=1, layouts=4)
    again = fit_context(examples, seed=3, rounds=1, layouts=4)
    assert first.context.to_json() == again.context.to_json()
    assert len(first.context.pairs) == 4 and len(first.divergence) == 2
    # Each weight vector starts at 0 and the lowest cells hold the examples.
    front = next(p for p in first.context.pairs if "NextToFront" in p.labels)
    assert front.position.min() == 0.0
    assert front.position[front.cell(0.4, 0.8)] < front.position[front.cell(0.0, 0.8)]
    assert front.position[-1] > front.position[:-1].max() - 1e-9 or front.position[-1] > 10.0


def test_a_share_of_eight_examples_or_more_is_held_out_the_same_way_each_time():
    assert held_out_split(7, 0) == () and held_out_split(12, 0, share=0.0) == ()
    eight = held_out_split(8, 0)
    assert len(eight) == 2 and eight == held_out_split(8, 0) and list(eight) == sorted(eight)
    assert len(held_out_split(12, 5)) == 3 and all(0 <= k < 12 for k in held_out_split(12, 5))
    assert {held_out_split(20, seed) for seed in range(4)} != {held_out_split(20, 0)}


def test_the_round_kept_is_the_one_nearest_the_held_out_examples():
    fit = fit_context(dining_examples(8), seed=1, rounds=2, layouts=4, balance=True)
    assert fit.context.balance is not None and len(fit.held) == 2 and len(fit.held_out) == 3
    assert fit.selected is not None and fit.held_out[fit.selected] == min(fit.held_out)
    assert fit.selected == fit.held_out.index(min(fit.held_out))  # the first of equals
    record = fit.context.fit["held_out"]
    assert record["examples"] == list(fit.held) and record["divergence"][fit.selected] == round(
        fit.held_out[fit.selected], 6
    )
    assert fit.rules_alone is not None and record["rules_alone"] == round(fit.rules_alone, 6)
    # The jittered chairs: the rules alone put them anywhere their tolerances allow.
    assert fit.rules_alone > fit.held_out[fit.selected] and not fit.rules_alone_better
    # The context written is fitted to all eight, for the rounds the check chose.
    assert fit.context.fit["rounds_chosen"] == fit.selected
    assert len(fit.divergence) == fit.selected + 1
    assert fit.divergence[fit.kept] == min(fit.divergence)
    alone = fit_context(
        dining_examples(8), seed=1, rounds=fit.selected, layouts=4, balance=True, holdout=0.0
    )
    assert [p.position.tolist() for p in alone.context.pairs] == [
        p.position.tolist() for p in fit.context.pairs
    ]
    # Without the check every example is fitted and the kept round is the fitted ones' best.
    plain = fit_context(dining_examples(8), seed=1, rounds=2, layouts=4, holdout=0.0)
    assert plain.held == () and plain.rules_alone is None and plain.held_out_summary() == ""
    assert plain.divergence[plain.kept] == min(plain.divergence)


def test_a_context_the_rules_alone_beat_on_the_held_out_examples_says_so():
    def fit(rules_alone):
        return ContextFit(
            LearnedContext(()), [0.2, 0.1], 1, 4, [], (0, 3), [0.3, 0.25], rules_alone, 1
        )

    assert fit(0.25).rules_alone_better and fit(0.1).rules_alone_better
    assert not fit(0.26).rules_alone_better and not fit(None).rules_alone_better
    assert fit(0.4).held_out_summary() == (
        "held out 2: divergence from them 0.250 with the context, 0.400 with the rules alone"
    )


def test_a_context_of_other_types_leaves_the_layout_unchanged():
    graph = expand(load_rules(DINING), 2)
    other = LearnedContext(
        (
            PairContext(
                "lamp",
                "desk",
                ("OnTopOf",),
                (-1, -1, 1, 1),
                np.zeros(BINS * BINS + 1),
                np.zeros(YAW_BINS),
            ),
        )
    )
    plain = layout_scene(graph, 2)
    assert replace(layout_scene(graph, 2, context=other), seconds=plain.seconds) == plain


def test_tempered_sampling_spreads_where_annealing_collapses():
    """Where the chair at the table's left end stands in the table's frame."""
    graph = expand(load_rules(DINING), 0)
    examples = dining_examples(12)
    # The pair terms alone: the balance term holds the whole group (docs/learning.md).
    context = fit_context(examples, seed=0, rounds=0, layouts=2, holdout=0.0, balance=False).context
    spread = {}
    for tempered in (True, False):
        chairs = []
        for seed in range(8):
            result = layout_scene(
                graph,
                seed,
                context=context,
                params=replace(LayoutParams(), tempered=tempered, restarts=0),
            )
            assert "learned" in result.parts
            chair, table = result.poses["chair_5"], result.poses["table_1"]
            chairs.append(
                relative_pose((chair.x, chair.z, chair.yaw), (table.x, table.z, table.yaw))[:2]
            )
        spread[tempered] = float(np.linalg.norm(np.std(chairs, axis=0)))
    assert spread[True] > spread[False]


def write_examples(folder: Path, examples) -> list[str]:
    paths = []
    for name, scene in examples:
        path = folder / f"{name}.json"
        path.write_text(json.dumps(scene), encoding="utf-8")
        paths.append(str(path))
    return paths


def test_fit_what_context_round_trip(tmp_path, capsys):
    paths = write_examples(tmp_path, dining_examples(5))
    out = tmp_path / "out" / "fitted.rules"
    code = main(
        [
            "fit",
            str(DINING),
            *paths,
            "-o",
            str(out),
            "--what",
            "weights,context",
            "--rounds",
            "1",
            "--layouts",
            "3",
            "--report",
            str(tmp_path / "fit.json"),
        ]
    )
    assert code == 0, capsys.readouterr().err
    sidecar = tmp_path / "out" / "fitted.context.json"
    document = json.loads(sidecar.read_text())
    assert document["format"] == "scenewright-context" and len(document["pairs"]) == 4
    assert json.loads((tmp_path / "fit.json").read_text())["context"]["file"] == str(sidecar)
    first = sidecar.read_bytes()
    assert (
        main(
            [
                "fit",
                str(DINING),
                *paths,
                "-o",
                str(out),
                "--what",
                "context",
                "--rounds",
                "1",
                "--layouts",
                "3",
            ]
        )
        == 0
    )
    assert sidecar.read_bytes() == first  # deterministic
    assert out.read_text() == DINING.read_text()  # context only: the numbers as they were
    # generate picks the context up beside the rules; --no-context leaves it out.
    capsys.readouterr()
    assert (
        main(["generate", str(out), "--seed", "1", "--no-render", "-o", str(tmp_path / "g1")]) == 0
    )
    assert "context: " in capsys.readouterr().out
    scene = json.loads((tmp_path / "g1" / "scene.json").read_text())
    assert "learned" in scene["layout"]["parts"]
    assert (
        main(
            [
                "generate",
                str(out),
                "--seed",
                "1",
                "--no-render",
                "--no-context",
                "-o",
                str(tmp_path / "g2"),
            ]
        )
        == 0
    )
    assert (
        "learned" not in json.loads((tmp_path / "g2" / "scene.json").read_text())["layout"]["parts"]
    )
    assert (
        main(
            [
                "generate",
                str(DINING),
                "--seed",
                "1",
                "--no-render",
                "--context",
                str(sidecar),
                "-o",
                str(tmp_path / "g3"),
            ]
        )
        == 0
    )
    given, beside = (json.loads((tmp_path / g / "scene.json").read_text()) for g in ("g3", "g1"))
    assert given["rules"] != beside["rules"]  # the file's path
    assert {**given, "rules": None} == {**beside, "rules": None}


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys):
    paths = write_examples(tmp_path, dining_examples(2))
    out = tmp_path / "o" / "fitted.rules"
    assert main(["fit", str(DINING), *paths, "-o", str(out), "--what", "colours"]) == 2
    assert "--what" in _one_line_error(capsys)
    # Examples holding no related pair of a kind in two of them: nothing is written.
    lone = write_examples(tmp_path, dining_examples(1))
    assert main(["fit", str(DINING), *lone, "-o", str(out), "--what", "context"]) == 2
    assert "no related pair" in _one_line_error(capsys)
    assert not out.exists() and not (tmp_path / "o" / "fitted.context.json").exists()
    bad = tmp_path / "bad.context.json"
    for text, words in [
        ("{", "not JSON"),
        ('{"format": "x"}', "not a context file"),
        (
            json.dumps(
                {
                    "format": "scenewright-context",
                    "version": 1,
                    "bins": BINS,
                    "yaw_bins": YAW_BINS,
                    "pairs": [{"source": "chair"}],
                }
            ),
            "target",
        ),
    ]:
        bad.write_text(text)
        assert (
            main(
                [
                    "generate",
                    str(DINING),
                    "--no-render",
                    "--context",
                    str(bad),
                    "-o",
                    str(tmp_path / "g"),
                ]
            )
            == 2
        )
        assert words in _one_line_error(capsys)
        assert not (tmp_path / "g").exists()
    # A broken sidecar beside the rules is refused too.
    rules = tmp_path / "mine.rules"
    rules.write_text(DINING.read_text())
    (tmp_path / "mine.context.json").write_text("[]")
    assert main(["generate", str(rules), "--no-render", "-o", str(tmp_path / "g")]) == 2
    assert "mine.context.json" in _one_line_error(capsys)
    assert (
        main(
            [
                "generate",
                str(rules),
                "--no-render",
                "--no-context",
                "--context",
                str(bad),
                "-o",
                str(tmp_path / "g"),
            ]
        )
        == 2
    )
    _one_line_error(capsys)


@pytest.mark.slow
def test_dataset_lays_out_with_the_context_beside_the_rules_and_keeps_to_it(tmp_path, capsys):
    rules = tmp_path / "dining.rules"
    rules.write_text(DINING.read_text())
    sidecar = tmp_path / "dining.context.json"
    sidecar.write_text(
        fit_context(dining_examples(8), seed=0, rounds=0, layouts=2).context.to_json()
    )
    common = [str(rules), "-n", "3", "--no-images", "--workers", "1", "-q"]
    assert main(["dataset", *common, "-o", str(tmp_path / "with")]) == 0, capsys.readouterr().err
    assert main(["dataset", *common, "--no-context", "-o", str(tmp_path / "without")]) == 0
    settings = json.loads((tmp_path / "with" / "dataset.json").read_text())
    assert settings["context"] == str(sidecar.resolve()) and len(settings["context_digest"]) == 64
    assert json.loads((tmp_path / "without" / "dataset.json").read_text())["context"] is None
    with_scene, without_scene = (
        json.loads((tmp_path / name / "scenes" / "000000.json").read_text())
        for name in ("with", "without")
    )
    assert (
        "learned" in with_scene["layout"]["parts"]
        and "learned" not in without_scene["layout"]["parts"]
    )
    again = api_scene_with_context(rules, sidecar, settings)
    assert (
        with_scene["objects"] == again["objects"]
    )  # the same layout as build_scene with the context gives
    # A rerun with another context (or none) is refused, and nothing is added.
    sidecar.write_text(random_context(expand(load_rules(DINING), 0), seed=5).to_json())
    capsys.readouterr()
    assert main(["dataset", *common, "-o", str(tmp_path / "with")]) == 2
    assert "context_digest" in _one_line_error(capsys)
    assert main(["dataset", *common, "--no-context", "-o", str(tmp_path / "with")]) == 2
    _one_line_error(capsys)
    assert (
        main(
            [
                "dataset",
                *common,
                "--context",
                str(tmp_path / "missing.json"),
                "-o",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    _one_line_error(capsys)
    assert not (tmp_path / "x").exists()


def api_scene_with_context(rules: Path, sidecar: Path, settings: dict) -> dict:
    """Scene 0 of a dataset with ``settings`` made by the Python API with the context."""
    from scenewright.api import reproducible_json, rules_context
    from scenewright.dataset.spec import scene_seed

    loaded = load_rules(rules)
    seed = scene_seed(settings["base_seed"], 0)
    scene = build_scene(loaded, seed, context=rules_context(loaded, sidecar)[1])
    return json.loads(reproducible_json(scene))


def test_the_wait_for_learned_moves_ends_for_a_pair_whose_draws_are_always_refused():
    from scenewright.generator.layout.learned_term import TRIES_PER_SWEEP

    problem = learned_problem(DINING, 1)
    energy, mover = start_chain(problem, LayoutParams(), np.random.default_rng(2))
    learned = LearnedMoves(
        problem.learned, problem, energy.state, np.random.default_rng(3), mover.movable_box, 2
    )
    accepted_pair = learned.pairs[0]
    drawn = []
    while not learned.mixed():
        _, _, pair = learned.propose()
        if pair is None:  # an exchange of two chairs: no learned draw, not part of the wait
            continue
        drawn.append(pair)
        if pair == accepted_pair:  # only this pair's moves are ever accepted
            learned.redrawn[pair] += 1
        assert len(drawn) <= TRIES_PER_SWEEP * 2 * len(learned.pairs)
    refused = [pair for pair in learned.pairs if pair != accepted_pair]
    assert all(drawn.count(pair) == TRIES_PER_SWEEP * 2 for pair in refused)
    assert (
        drawn.count(accepted_pair) == 2
    )  # lagging pairs are drawn first, and it caught up at once


def test_layout_lays_a_scene_out_again_with_a_context(tmp_path, capsys):
    sidecar = tmp_path / "dining.context.json"
    sidecar.write_text(
        fit_context(dining_examples(8), seed=0, rounds=0, layouts=2).context.to_json()
    )
    assert (
        main(
            ["generate", str(DINING), "--seed", "2", "--no-render", "-q", "-o", str(tmp_path / "g")]
        )
        == 0
    )
    scene = str(tmp_path / "g" / "scene.json")
    runs = {}
    for name, extra in (
        ("a", ["--context", str(sidecar)]),
        ("b", ["--context", str(sidecar)]),
        ("c", []),
    ):
        code = main(
            [
                "layout",
                scene,
                "--pin",
                "table_1",
                "--no-render",
                "-q",
                *extra,
                "-o",
                str(tmp_path / name),
            ]
        )
        assert code == 0, capsys.readouterr().err
        runs[name] = json.loads((tmp_path / name / "scene.json").read_text())
    assert (
        "learned" in runs["a"]["layout"]["parts"] and "learned" not in runs["c"]["layout"]["parts"]
    )
    assert runs["a"] == runs["b"]
    assert (
        main(["layout", scene, "--context", str(tmp_path / "none.json"), "-o", str(tmp_path / "d")])
        == 2
    )
    _one_line_error(capsys)
    assert not (tmp_path / "d").exists()


def test_the_api_takes_a_context_by_the_path_of_its_file(tmp_path):
    from scenewright.api import reproducible_json, rules_context
    from scenewright.core.errors import InputError

    loaded = load_rules(DINING)
    sidecar = tmp_path / "dining.context.json"
    sidecar.write_text(random_context(expand(loaded, 0), seed=5).to_json())
    by_path = reproducible_json(build_scene(loaded, 1, context=sidecar))
    assert by_path == reproducible_json(build_scene(loaded, 1, context=str(sidecar)))
    assert by_path == reproducible_json(
        build_scene(loaded, 1, context=rules_context(loaded, sidecar)[1])
    )
    assert by_path != reproducible_json(build_scene(loaded, 1))  # the context moved something
    with pytest.raises(InputError, match="missing.json: cannot read"):
        build_scene(loaded, 1, context=tmp_path / "missing.json")


def test_the_balance_offset_is_the_area_weighted_centre_over_half_the_diagonal():
    # a 4 x 3 room (half diagonal 2.5); 3 m^2 at (1, 0) and 1 m^2 at (-1, 0): centre (0.5, 0)
    assert balance_offset((4.0, 3.0), np.array([1.0, -1.0]), np.zeros(2), np.array([3.0, 1.0])) == (
        pytest.approx(0.2)
    )
    assert balance_offset((4.0, 3.0), np.array([1.0]), np.array([1.0]), np.array([0.0])) == 0.0
    assert BalanceContext.bin(0.2) == int(0.2 * BALANCE_BINS) and BalanceContext.bin(3.0) == (
        BALANCE_BINS - 1
    )


def test_a_fitted_balance_term_is_written_read_back_and_learned_from_off_centre_rooms():
    examples = dining_examples(8)
    for _, document in examples[:6]:  # most examples put the dining group off centre
        for o in document["objects"]:
            o["position"] = [o["position"][0] + 1.0, *o["position"][1:]]
    fit = fit_context(examples, seed=0, rounds=0, layouts=2, holdout=0.0, balance=True)
    table = fit.context.balance
    assert table is not None and table.examples == 8
    offsets = [
        layout.balance for layout in (example_layout(name, document) for name, document in examples)
    ]
    assert all(o is not None for o in offsets)
    # The weights are -log of the blurred shares: the offsets the examples show cost
    # least, and the bins none comes near cost most.
    shown = {BalanceContext.bin(o) for o in offsets}
    cheapest = min(table.weights[b] for b in shown)
    assert cheapest == 0.0 and max(table.weights[b] for b in shown) < table.weights.max()
    assert max(offsets[:6]) > min(offsets[:6]) and min(offsets[:6]) > max(offsets[6:])
    again = LearnedContext.from_dict(json.loads(fit.context.to_json()))
    assert np.allclose(again.balance.weights, table.weights, atol=1e-6)
    assert fit_context(examples, seed=0, rounds=0, layouts=2).context.balance is None  # opt-in
    with pytest.raises(InputError, match='balance: "weights" must be 16 numbers'):
        LearnedContext.from_dict({**fit.context.to_dict(), "balance": {"weights": [1, 2]}})


def test_fit_balance_writes_the_balance_term_and_generate_lays_out_with_it(tmp_path, capsys):
    paths = write_examples(tmp_path, dining_examples(4))
    out = tmp_path / "out" / "fitted.rules"
    argv = ["fit", str(DINING), *paths, "-o", str(out), "--what", "context"]
    assert main([*argv, "--rounds", "0", "--layouts", "2", "--balance"]) == 0
    document = json.loads((tmp_path / "out" / "fitted.context.json").read_text())
    assert len(document["balance"]["weights"]) == BALANCE_BINS
    assert document["balance"]["examples"] == 4
    capsys.readouterr()
    assert (
        main(["generate", str(out), "--seed", "1", "--no-render", "-o", str(tmp_path / "g")]) == 0
    )
    scene = json.loads((tmp_path / "g" / "scene.json").read_text())
    assert "learned" in scene["layout"]["parts"]


def test_fit_writes_no_context_the_rules_alone_beat_and_says_so(tmp_path, capsys, monkeypatch):
    paths = write_examples(tmp_path, dining_examples(8))
    out = tmp_path / "out" / "fitted.rules"
    argv = ["fit", str(DINING), *paths, "-o", str(out), "--what", "context"]
    monkeypatch.setattr(ContextFit, "rules_alone_better", property(lambda self: True))
    capsys.readouterr()
    assert (
        main([*argv, "--rounds", "0", "--layouts", "2", "--report", str(tmp_path / "r.json")]) == 0
    )
    said = capsys.readouterr().out
    assert said.startswith(
        "no context written: the rules alone come as near the examples held out; a context of"
    )
    assert "held out 2: divergence from them" in said
    assert not (tmp_path / "out" / "fitted.context.json").exists()
    report = json.loads((tmp_path / "r.json").read_text())["context"]
    assert report["file"] is None and len(report["held_out"]["examples"]) == 2
