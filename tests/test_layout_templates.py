"""Template initialisation (``generator.layout.pose_templates``): the constructive placement of
a learned pair's source drawn from the pair's learned template."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from scenewright.generator import expand, load_rules
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.learned_term import (
    BINS,
    YAW_BINS,
    LearnedContext,
    PairContext,
    compile_learned,
    related_pairs,
    relative_pose,
)
from scenewright.generator.layout.pose_templates import template_draw
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.sampler import start_chain

ROOT = Path(__file__).resolve().parents[1]
DINING = ROOT / "examples" / "sets" / "dining" / "dining.rules"
BOUNDS = (-1.5, -1.2, 1.5, 1.2)
#: Per side label, the band (x0, z0, x1, z1) of the table's frame where the peaked
#: context wants the chairs of that side: narrower than the rules' "in front of".
BANDS = {
    "NextToFront": (-0.6, 0.85, 0.6, 1.0),
    "NextToBehind": (-0.6, -1.0, 0.6, -0.85),
    "NextToLeft": (1.1, -0.2, 1.3, 0.2),
    "NextToRight": (-1.3, -0.2, -1.1, 0.2),
}
#: Every chair turned a quarter turn from facing the table: a yaw no rule asks for.
TURN_BIN = YAW_BINS // 4  # [-pi/2, -pi/2 + 2 pi / YAW_BINS)
HIGH, LOW = 0.0, 9.0


def band_cells(band: tuple[float, float, float, float]) -> np.ndarray:
    """(BINS * BINS,) True for the cells of BOUNDS whose centre lies in ``band``."""
    x0, z0, x1, z1 = BOUNDS
    centres_x = x0 + (np.arange(BINS) + 0.5) * (x1 - x0) / BINS
    centres_z = z0 + (np.arange(BINS) + 0.5) * (z1 - z0) / BINS
    inside_x = (centres_x >= band[0]) & (centres_x <= band[2])
    inside_z = (centres_z >= band[1]) & (centres_z <= band[3])
    return (inside_z[:, None] & inside_x[None, :]).ravel()


def side_of(kind) -> str:
    return next(label for label in kind[2] if label in BANDS)


def peaked_context(graph) -> LearnedContext:
    """Per pair kind of the dining graph: weight HIGH on its side's band and on TURN_BIN,
    LOW elsewhere (outside the grid too)."""
    problem = compile_problem(graph)
    kinds = sorted(
        {kind for _, _, kind in related_pairs(problem, [graph.node(i).type for i in problem.ids])}
    )
    pairs = []
    for kind in kinds:
        position = np.full(BINS * BINS + 1, LOW)
        position[:-1][band_cells(BANDS[side_of(kind)])] = HIGH
        yaw = np.full(YAW_BINS, LOW)
        yaw[TURN_BIN] = HIGH
        pairs.append(PairContext(*kind, BOUNDS, position, yaw, 1))
    return LearnedContext(tuple(pairs))


def peaked_problem(seed: int):
    graph = expand(load_rules(DINING), seed)
    problem = compile_problem(graph)
    problem.learned = compile_learned(
        peaked_context(graph), problem, [graph.node(i).type for i in problem.ids]
    )
    return problem


def landed(problem, energy) -> list[tuple[bool, bool]]:
    """Per learned pair: whether its source stands in its band's cells, and in TURN_BIN."""
    out = []
    for source, target, table in problem.learned.pairs:
        x, z, turn = relative_pose(energy.state.pose(source), energy.state.pose(target))
        cell = table.cell(x, z)
        out.append(
            (
                cell < BINS * BINS and bool(band_cells(BANDS[side_of(table.kind)])[cell]),
                table.yaw_bin(turn) == TURN_BIN,
            )
        )
    return out


def test_the_template_draw_follows_the_learned_shares():
    """Drawn alone (no energy choosing), a source lands in the high cells and yaw bin at
    the rate their shares give: e^-HIGH per high cell against e^-LOW per other."""
    problem = peaked_problem(0)
    energy, _ = start_chain(problem, LayoutParams(template_init=True), np.random.default_rng(1))
    rng = np.random.default_rng(2)
    source, target, table = problem.learned.pairs[0]
    draw = template_draw(energy, rng, source)
    high = band_cells(BANDS[side_of(table.kind)])
    expected_cells = high.sum() / (high.sum() + (~high).sum() * np.exp(HIGH - LOW))
    expected_turn = 1.0 / (1.0 + (YAW_BINS - 1) * np.exp(HIGH - LOW))
    cells = turns = 0
    count = 2000
    for _ in range(count):
        boxes, paths = draw()
        assert paths == {} and source in boxes
        x, z, turn = relative_pose(boxes[source], energy.state.pose(target))
        cell = table.cell(x, z)
        cells += bool(cell < BINS * BINS and high[cell])
        turns += table.yaw_bin(turn) == TURN_BIN
    # Binomial standard errors are below 0.011; four of them either way.
    assert abs(cells / count - expected_cells) < 0.045
    assert abs(turns / count - expected_turn) < 0.045


def test_template_init_places_sources_in_the_high_share_cells():
    """After the constructive placement, most chairs stand in their band, turned as the
    template says; the rules' own placement turns almost none so (it may find the band
    by choosing among its candidates by the learned energy, but it turns every chair to
    face the table)."""
    rates = {}
    for on in (True, False):
        hits = []
        for seed in range(6):
            problem = peaked_problem(seed)
            energy, _ = start_chain(
                problem, LayoutParams(template_init=on), np.random.default_rng(seed)
            )
            hits += landed(problem, energy)
        rates[on] = (np.mean([h[0] for h in hits]), np.mean([h[1] for h in hits]))
    assert rates[True][0] >= 0.8 and rates[True][1] >= 0.8
    assert rates[False][1] <= 0.1


def test_template_init_is_deterministic():
    graph = expand(load_rules(DINING), 3)
    context = peaked_context(graph)
    params = LayoutParams(template_init=True)
    first = layout_scene(graph, 3, params=params, context=context)
    assert (
        replace(layout_scene(graph, 3, params=params, context=context), seconds=first.seconds)
        == first
    )


@pytest.mark.parametrize("rules", [DINING, ROOT / "grammar_rules" / "bedroom.rules"])
def test_without_a_context_the_option_changes_nothing(rules):
    graph = expand(load_rules(rules), 1)
    plain = layout_scene(graph, 1, params=LayoutParams(template_init=False))
    templated = layout_scene(graph, 1, params=LayoutParams(template_init=True))
    assert replace(templated, seconds=plain.seconds) == plain


def test_the_option_switches_the_draw():
    problem = peaked_problem(0)
    source, target, _ = problem.learned.pairs[0]
    starts = {}
    for on in (True, False):
        energy, _ = start_chain(problem, LayoutParams(template_init=on), np.random.default_rng(4))
        drawer = template_draw(energy, np.random.default_rng(0), source)
        assert (drawer is not None) == on
        starts[on] = [energy.state.pose(box) for box in range(problem.n_boxes)]
    assert starts[True] != starts[False]
    # Without a context nothing is drawn from a template.
    problem.learned = None
    energy, _ = start_chain(problem, LayoutParams(template_init=True), np.random.default_rng(4))
    assert template_draw(energy, np.random.default_rng(0), source) is None
