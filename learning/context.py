"""Learning a context: the ``learned`` layout part's weights, fitted by iterative scaling.

``fit_context(examples, seed)`` measures, in every example scene, the related pairs
(``learned_term.related_pairs``: objects joined by relation edges of the rules) and per
pair kind builds the two histograms of the maximum-entropy framework of Dema and
Sari-Sarraf (Entropy 2014): where the source stands in the target's frame (BINS x BINS cells
over the examples' range grown by ``PAD`` on each side, plus one bin for outside) and
its yaw relative to the target's (YAW_BINS bins).

Histograms are *shares* made comparable between a few dozen examples and a few dozen
generated scenes: counts blurred by a Gaussian of ``SMOOTH`` bins (the position grid
with zeros beyond its edge, the yaw circularly), divided by their total, plus ``FLOOR``
in every bin and normalised again, so every bin has a share and a log.

The weights start at lambda = -log(observed share): the exact answer when nothing but
the learned terms acts on a pair (the outside bin's weight is raised by the log of how
many grid cells the scene's floor would hold, as its share is spread over all of it).
The layout adds collisions, the room and the rules'
own relation terms, so the weights are then corrected by iterative scaling: each round
lays out ``layouts`` scenes (the examples' own scene graphs in turn, each on its stream
``core.seeds.stream(seed, "context", k)``) with the current weights, at temperature 1
(``sampler``), measures their shares, and moves every weight by

    lambda += RATE * log(generated share / observed share)     (clipped to +-MAX_STEP)

the multiplicative form of iterative scaling (Darroch and Ratcliff's generalised
iterative scaling, step 1/C with C = 2 histograms per pair): a bin the generated
scenes visit too often gets costlier in proportion. The paper updates additively,
lambda += eta (generated - observed) with eta = 1, on 32-bin histograms whose shares are
tenths; on a 1024-cell grid the shares are thousandths and that step would not move.

Each round's *divergence* is the mean over pair kinds of the total variation distance
between observed and generated shares (position and yaw averaged). A round whose
divergence is not below the best so far made the fit worse: the next weights are taken
from the best round's instead, with half the step (a backtracking line search on the
step length, so a step that overshoots is not built on). The weights kept are those of
the round with the smallest divergence (after the last update one more round is laid
out to measure it), so the figure reported is the one measured for the weights
written, and it is never above the first round's.

With HOLDOUT_FROM examples or more, HOLDOUT of them are held out (``held_out_split``):
the weights are fitted to the rest, each round's scenes are also compared with the
held-out examples, and the round nearest them says how many rounds to fit
(``ContextFit.selected``); the rules alone (no context) are laid out and compared too,
and ``ContextFit.rules_alone_better`` says when the context would make scenes worse
than none (``fit`` and ``learn`` then write none). The context written is then fitted
again, to every example, for the rounds chosen: the held-out check chooses how far to
fit, and no example is left out of what is fitted (with nine examples, two held out
would move a two-to-one split of the rest by a tenth).

The visual-balance term (``learned_term.BalanceContext``): one histogram per scene of
the balance offset (``graph_balance``), fitted like a pair kind's with starting weights
capped at BALANCE_CAP, and one more term of every divergence.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.ndimage import gaussian_filter, gaussian_filter1d

from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS
from scenewright.core.scene import Scene
from scenewright.core.scene_graph import SceneGraph
from scenewright.core.seeds import stream
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.learned_term import (
    BALANCE_BINS,
    BINS,
    YAW_BINS,
    BalanceContext,
    LearnedContext,
    PairContext,
    balance_boxes,
    balance_offset,
    pair_kind_name,
    related_pairs,
    relative_pose,
)
from scenewright.generator.layout.problem import compile_problem

from .derivations import closest_derivation, measured_relations
from .errors import NoRelatedPairs

#: Blur of the histograms, in bins (standard deviation of the Gaussian): SMOOTH for the
#: starting weights, UPDATE_SMOOTH for the comparisons iterative scaling makes (a few
#: dozen generated pairs per round give a noisy fine histogram; what the weights must
#: correct, the pull of collisions and of the rules' own relation terms, is smooth).
SMOOTH = 1.0
UPDATE_SMOOTH = 3.0
#: Share added to every bin before normalising, so that every bin has a finite log.
FLOOR = 1e-6
#: The position grid reaches this share of the examples' range (at least MIN_PAD metres)
#: beyond their extreme positions on each side.
PAD = 0.25
MIN_PAD = 0.1
#: Iterative scaling's step (1 / C, C = 2 histograms per pair) and its largest change
#: of one weight in one round.
RATE = 0.5
MAX_STEP = 2.0
#: Defaults: rounds of iterative scaling and scenes laid out per round.
ROUNDS = 2
LAYOUTS = 40
#: Fewest examples holding a pair kind for it to get a histogram (one scene shows no spread).
MIN_EXAMPLES = 2
#: The held-out check: with at least HOLDOUT_FROM examples, this share of them (rounded,
#: at least 2) is held out, the weights are fitted to the rest, and the round kept is the
#: one whose scenes come nearest the held-out examples; the rules alone are measured too.
HOLDOUT = 0.25
HOLDOUT_FROM = 8
#: The child of the context stage's stream that draws the examples held out: beyond
#: any round's layouts (round * layouts + k).
HOLDOUT_STREAM = 2**32

Kind = tuple[str, str, tuple[str, ...]]
#: The key of the visual-balance histogram among the generated shares.
BALANCE = "balance"
#: Blur of the balance histogram, in bins, and the largest weight a balance bin starts
#: with: the offset is one number for the whole scene, so a bin no example showed, at
#: -log(FLOOR), would hold every piece of a scene still at temperature 1; capped, it is
#: e^BALANCE_CAP times less likely than the examples' own offsets, and the rounds move it.
BALANCE_SMOOTH = 2.0
BALANCE_CAP = 2.0


@dataclass
class ExampleLayout:
    """One example's scene graph, its related pairs' relative poses (kind, (x, z, turn))
    and its floor's area (m^2, the extent's)."""

    graph: SceneGraph
    poses: list[tuple[Kind, tuple[float, float, float]]]
    area: float
    #: The example's balance offset (``learned_term.balance_offset``; None: no floor piece).
    balance: float | None = None


def graph_pair_poses(
    graph: SceneGraph,
    poses: dict[str, tuple[float, float, float]],
    broken: frozenset[tuple[str, str]] = frozenset(),
) -> list[tuple[Kind, tuple]]:
    """The relative pose of every related pair of ``graph`` at ``poses`` (id -> (x, z,
    yaw)), but the pairs in ``broken`` ((source id, target id): a relation between them
    does not hold at these poses)."""
    problem = compile_problem(graph)
    types = [graph.node(box_id).type for box_id in problem.ids]
    found = []
    for source, target, kind in related_pairs(problem, types):
        if (problem.ids[source], problem.ids[target]) not in broken:
            found.append(
                (kind, relative_pose(poses[problem.ids[source]], poses[problem.ids[target]]))
            )
    return found


def graph_balance(
    graph: SceneGraph, poses: dict[str, tuple[float, float, float]], extent=None
) -> float | None:
    """The balance offset of ``graph``'s floor pieces at ``poses`` (id -> (x, z, yaw)) in
    a scene of ``extent`` (default: the graph's); None when no floor piece has a pose."""
    problem = compile_problem(graph)
    boxes, areas = balance_boxes(problem)
    keep = [k for k, box in enumerate(boxes) if problem.ids[box] in poses]
    if not keep:
        return None
    ids = [problem.ids[boxes[k]] for k in keep]
    xs = np.array([poses[i][0] for i in ids])
    zs = np.array([poses[i][1] for i in ids])
    return balance_offset(tuple(extent or problem.extent), xs, zs, areas[keep])


def _floor_area(extent) -> float:
    return float(np.prod(extent or [1.0, 1.0]))


def example_layout(name: str, document: dict) -> ExampleLayout:
    """An example scene.json document's graph and pair poses; ``InputError`` naming it when
    it is not a scene graph."""
    try:
        scene = Scene.from_dict(document)
        graph = scene.graph()
    except InputError as error:
        raise InputError(f"{name}: {error}") from None
    except (KeyError, ValueError, TypeError) as error:
        raise InputError(f"{name}: not a valid scene graph: {error}") from None
    poses = {
        o.id: (float(o.position[0]), float(o.position[2]), float(o.yaw)) for o in scene.objects
    }
    return ExampleLayout(
        graph,
        graph_pair_poses(graph, poses),
        _floor_area(document.get("extent")),
        graph_balance(graph, poses, document.get("extent")),
    )


def measured_example_layout(
    name: str, scene: Scene, derivations: Sequence[SceneGraph]
) -> ExampleLayout:
    """An example read from geometry alone (``scene``: no relation edges but what rests on
    what), related as one of its best derivations relates its objects: ``derivations``
    are their scene graphs (``derivations.measured_derivation_graphs``), of which the one
    the example comes nearest to holding is taken (``derivations.closest_derivation``),
    each of its object nodes standing for the example object assigned to it, at that
    object's pose; the graph laid out in the fit's rounds is that derivation's. A pair
    whose relation the example breaks (measured as the layout's verdict would) gives no
    pose: the learned term would pull towards poses the verdict refuses."""
    try:
        derivation, chosen = closest_derivation(derivations, scene)
    except InputError as error:
        raise InputError(f"{name}: {error}") from None
    objects = {o.id: o for o in scene.placed_objects()}
    poses = {
        node: (float(objects[o].position[0]), float(objects[o].position[2]), float(objects[o].yaw))
        for node, o in chosen.items()
    }
    # A hand-placed pair that breaks the rules' own relation (a nightstand 46 degrees off
    # "right of the bed") would teach the learned term poses the layout's verdict refuses.
    # So would a vase on a sideboard's end taught to "in the middle of" it: a support
    # with a placement is measured in the plane, the object set on its support's top (the
    # stacking that found the support allows 3 cm, the verdict's height 1 cm).
    pairs = [
        (chosen[e.source], e.label, chosen[e.target])
        for e in derivation.edges()
        if e.source in chosen and e.target in chosen
    ]
    wanted = [pair for pair in pairs if not RELATIONS[pair[1]].support]
    placed = [
        pair
        for pair in pairs
        if RELATIONS[pair[1]].support and RELATIONS[pair[1]].placement != "anywhere"
    ]
    verdicts = {
        **measured_relations(scene, wanted),
        **measured_relations(set_on_supports(scene, placed), placed),
    }
    node_of = {o: node for node, o in chosen.items()}
    broken = frozenset(
        (node_of[a], node_of[b]) for (a, _, b), verdict in verdicts.items() if not verdict.satisfied
    )
    return ExampleLayout(
        derivation,
        graph_pair_poses(derivation, poses, broken),
        _floor_area(scene.extent),
        graph_balance(derivation, poses, scene.extent),
    )


def set_on_supports(scene: Scene, supports: Sequence[tuple[str, str, str]]) -> Scene:
    """A copy of ``scene`` with the subject of each (subject id, label, support id) set
    on its support's top."""
    objects = {o.id: o for o in scene.objects}
    tops = {
        subject: objects[below].position[1] + objects[below].size[1]
        for subject, _, below in supports
    }
    moved = [
        replace(o, position=[o.position[0], tops[o.id], o.position[2]]) if o.id in tops else o
        for o in scene.objects
    ]
    return replace(scene, objects=moved)


def grid_bounds(points: np.ndarray) -> tuple[float, float, float, float]:
    """The position grid (x0, z0, x1, z1) around relative positions ``points`` (n, 2)."""
    low, high = points.min(axis=0), points.max(axis=0)
    pad = np.maximum(PAD * (high - low), MIN_PAD)
    return (
        float(low[0] - pad[0]),
        float(low[1] - pad[1]),
        float(high[0] + pad[0]),
        float(high[1] + pad[1]),
    )


def counts(
    table: PairContext, poses: Sequence[tuple[float, float, float]]
) -> tuple[np.ndarray, np.ndarray]:
    """Raw histograms of relative poses in ``table``'s bins: position (BINS * BINS + 1,), yaw (YAW_BINS,)."""
    position, yaw = np.zeros(BINS * BINS + 1), np.zeros(YAW_BINS)
    for pose in poses:
        position[table.cell(pose[0], pose[1])] += 1.0
        yaw[table.yaw_bin(pose[2])] += 1.0
    return position, yaw


def shares(
    position: np.ndarray, yaw: np.ndarray, smooth: float = SMOOTH
) -> tuple[np.ndarray, np.ndarray]:
    """Shares of raw histograms blurred by ``smooth`` bins and floored (module
    docstring); same shapes."""
    grid = gaussian_filter(
        position[:-1].reshape(BINS, BINS), smooth, mode="constant", cval=0.0
    ).ravel()
    inside = position[:-1].sum()
    if grid.sum() > 0.0:
        grid *= inside / grid.sum()  # the blur keeps what was inside the grid inside it
    blurred = np.append(grid, position[-1])
    turns = gaussian_filter1d(yaw, smooth, mode="wrap")
    return _floored(blurred), _floored(turns)


def balance_shares(offsets: Sequence[float]) -> np.ndarray:
    """Shares of balance offsets in BALANCE_BINS bins, blurred by BALANCE_SMOOTH bins
    (the edges reflect) and floored (module docstring)."""
    raw = np.zeros(BALANCE_BINS)
    for offset in offsets:
        raw[BalanceContext.bin(offset)] += 1.0
    return _floored(gaussian_filter1d(raw, BALANCE_SMOOTH, mode="reflect"))


def _floored(values: np.ndarray) -> np.ndarray:
    total = values.sum()
    values = values / total if total > 0.0 else np.full(len(values), 1.0 / len(values))
    values = values + FLOOR
    return values / values.sum()


def _cell_area(bounds: tuple[float, float, float, float]) -> float:
    return (bounds[2] - bounds[0]) * (bounds[3] - bounds[1]) / (BINS * BINS)


def scaling_step(
    weights: np.ndarray, observed: np.ndarray, generated: np.ndarray, rate: float = RATE
) -> np.ndarray:
    """One iterative-scaling update of a histogram's weights (module docstring)."""
    step = np.clip(rate * np.log(generated / observed), -MAX_STEP, MAX_STEP)
    updated = weights + step
    return updated - updated.min()


def total_variation(first: np.ndarray, second: np.ndarray) -> float:
    return 0.5 * float(np.abs(first - second).sum())


def share_distance(
    first: tuple[np.ndarray, np.ndarray], second: tuple[np.ndarray, np.ndarray]
) -> float:
    """The divergence of one pair kind: the total variation distance of two (position,
    yaw) shares, position and yaw averaged."""
    return 0.5 * (total_variation(first[0], second[0]) + total_variation(first[1], second[1]))


@dataclass
class ContextFit:
    """A fitted context with its record: divergence per round, the round kept, the
    pair kinds and how many example pairs each had."""

    context: LearnedContext
    divergence: list[float]
    kept: int
    layouts: int
    skipped: list[str]
    #: The held-out check (``held_out_split``): the examples held out (indices), per round
    #: the divergence from them, and that of the rules alone (no context); empty and None
    #: without a check (fewer than HOLDOUT_FROM examples, or ``holdout`` 0).
    held: tuple[int, ...] = ()
    held_out: list[float] = field(default_factory=list)
    rules_alone: float | None = None
    #: The round nearest the held-out examples: how many rounds the context written was
    #: fitted for, to every example (None without a check).
    selected: int | None = None

    @property
    def rules_alone_better(self) -> bool:
        """Whether the rules alone came nearer the held-out examples than the round
        chosen (then the context would make scenes worse, and is not written)."""
        if self.rules_alone is None or self.selected is None:
            return False
        return self.rules_alone <= self.held_out[self.selected]

    def held_out_summary(self) -> str:
        """The held-out check in words (empty without one)."""
        if self.rules_alone is None or self.selected is None:
            return ""
        return (
            f"held out {len(self.held)}: divergence from them {self.held_out[self.selected]:.3f} "
            f"with the context, {self.rules_alone:.3f} with the rules alone"
        )


def fit_context(
    examples: Sequence[tuple[str, dict]],
    *,
    seed: int = 0,
    rounds: int = ROUNDS,
    layouts: int = LAYOUTS,
    params: LayoutParams | None = None,
    holdout: float = HOLDOUT,
    balance: bool = False,
) -> ContextFit:
    """Fit a context to example scene.json documents ((name, document) pairs); see the
    module docstring. ``NoRelatedPairs`` (an ``InputError``) when no pair kind is held by
    MIN_EXAMPLES examples."""
    laid = [example_layout(name, document) for name, document in examples]
    return fit_example_layouts(
        laid,
        seed=seed,
        rounds=rounds,
        layouts=layouts,
        params=params,
        holdout=holdout,
        balance=balance,
    )


def held_out_split(count: int, seed: int, share: float = HOLDOUT) -> tuple[int, ...]:
    """The indices of the examples held out of a fit to ``count`` examples: none below
    HOLDOUT_FROM examples (or with ``share`` 0), else ``share`` of them (rounded, at
    least 2), drawn from ``core.seeds.stream(seed, "context", HOLDOUT_STREAM)``, sorted."""
    if share <= 0.0 or count < HOLDOUT_FROM:
        return ()
    size = max(2, int(round(share * count)))
    order = stream(seed, "context", HOLDOUT_STREAM).permutation(count)
    return tuple(sorted(int(k) for k in order[:size]))


def fit_example_layouts(
    laid: Sequence[ExampleLayout],
    *,
    seed: int = 0,
    rounds: int = ROUNDS,
    layouts: int = LAYOUTS,
    params: LayoutParams | None = None,
    holdout: float = HOLDOUT,
    balance: bool = False,
) -> ContextFit:
    """Fit a context to examples' layouts (``example_layout``, ``measured_example_layout``);
    see the module docstring. With the held-out check (``held_out_split``: ``holdout``
    of the examples, from HOLDOUT_FROM of them) the round nearest the held-out examples,
    of a fit to the rest, says how many rounds the context is then fitted to them all.
    With ``balance`` (and MIN_EXAMPLES examples with a floor piece) the visual-balance
    term is fitted too, as one more histogram. ``NoRelatedPairs`` (an ``InputError``)
    when no pair kind is held by MIN_EXAMPLES examples (of those fitted to)."""
    options = {"seed": seed, "layouts": layouts, "params": params, "balance": balance}
    held = held_out_split(len(laid), seed, holdout)
    selection = _fit_rounds(laid, held, rounds=rounds, **options)
    if not held or selection.rules_alone_better:
        return selection
    refit = _fit_rounds(laid, (), rounds=selection.kept, **options)
    record = dict(refit.context.fit)
    record["held_out"] = selection.context.fit["held_out"]
    record["rounds_chosen"] = selection.kept
    return replace(
        refit,
        context=replace(refit.context, fit=record),
        held=selection.held,
        held_out=selection.held_out,
        rules_alone=selection.rules_alone,
        selected=selection.kept,
    )


def _fit_rounds(
    laid: Sequence[ExampleLayout],
    held: tuple[int, ...],
    *,
    seed: int,
    rounds: int,
    layouts: int,
    params: LayoutParams | None,
    balance: bool,
) -> ContextFit:
    """Iterative scaling for ``rounds`` rounds to the examples but those ``held`` out,
    keeping the round nearest the held-out examples (with some) or the fitted ones."""
    if held:
        check = [laid[k] for k in held]
        laid = [example for k, example in enumerate(laid) if k not in held]
    observed_poses: dict[Kind, list[tuple]] = {}
    extents: dict[Kind, float] = {}  # the largest scene area a kind is seen in (m^2)
    holding: dict[Kind, int] = {}  # examples holding the kind
    for example in laid:
        for kind, pose in example.poses:
            observed_poses.setdefault(kind, []).append(pose)
            extents[kind] = max(extents.get(kind, 0.0), example.area)
        for kind in {kind for kind, _ in example.poses}:
            holding[kind] = holding.get(kind, 0) + 1
    kinds = sorted(kind for kind in observed_poses if holding[kind] >= MIN_EXAMPLES)
    skipped = sorted(pair_kind_name(*kind) for kind in observed_poses if kind not in kinds)
    if not kinds:
        raise NoRelatedPairs(
            "no related pair of objects (two objects joined by a relation of the rules) occurs in at least "
            f"{MIN_EXAMPLES} examples, so there is no context to learn"
        )
    tables: dict[Kind, PairContext] = {}
    raw: dict[Kind, tuple[np.ndarray, np.ndarray]] = {}
    observed: dict[Kind, tuple[np.ndarray, np.ndarray]] = {}  # shares at UPDATE_SMOOTH
    for kind in kinds:
        poses = observed_poses[kind]
        bounds = grid_bounds(np.array([(x, z) for x, z, _ in poses]))
        blank = PairContext(
            *kind, bounds, np.zeros(BINS * BINS + 1), np.zeros(YAW_BINS), len(poses)
        )
        raw[kind] = counts(blank, poses)
        observed[kind] = shares(*raw[kind], UPDATE_SMOOTH)
        position, yaw = (-np.log(share) for share in shares(*raw[kind]))
        # The outside bin stands for all the floor beyond the grid, so its weight holds
        # the log of how many cells that floor would make: without it, a share of FLOOR
        # spread over the whole scene outweighs the grid (module docstring).
        position[-1] += np.log(max(extents[kind] / _cell_area(bounds), 1.0))
        tables[kind] = PairContext(
            *kind, bounds, position - position.min(), yaw - yaw.min(), len(poses)
        )

    offsets = [example.balance for example in laid if example.balance is not None]
    balance_table: BalanceContext | None = None
    balance_observed = None
    if balance and len(offsets) >= MIN_EXAMPLES:
        balance_observed = balance_shares(offsets)
        start = -np.log(balance_observed)
        balance_table = BalanceContext(np.minimum(start - start.min(), BALANCE_CAP), len(offsets))
    graphs = [example.graph for example in laid]
    held_shares: dict[Kind, tuple[np.ndarray, np.ndarray]] = {}
    if held:
        held_poses: dict[Kind, list[tuple]] = {}
        for example in check:
            for kind, pose in example.poses:
                if kind in tables:
                    held_poses.setdefault(kind, []).append(pose)
        held_shares = {
            kind: shares(*counts(tables[kind], poses), UPDATE_SMOOTH)
            for kind, poses in sorted(held_poses.items())
        }
        held_offsets = [example.balance for example in check if example.balance is not None]
        held_balance = (
            balance_shares(held_offsets) if balance_table is not None and held_offsets else None
        )

    def held_divergence(generated: dict) -> float:
        found = [share_distance(generated[kind], held_shares[kind]) for kind in held_shares]
        if held_balance is not None:
            found.append(total_variation(generated[BALANCE], held_balance))
        return float(np.mean(found))

    def fitted_divergence(generated: dict) -> float:
        found = [share_distance(generated[kind], observed[kind]) for kind in kinds]
        if balance_observed is not None:
            found.append(total_variation(generated[BALANCE], balance_observed))
        return float(np.mean(found))

    def generate(context: LearnedContext | None, index: int) -> dict:
        """Shares of the pair kinds in ``layouts`` scenes laid out with ``context``."""
        generated_poses: dict[Kind, list[tuple]] = {kind: [] for kind in kinds}
        generated_offsets = []
        for k in range(layouts):
            graph = graphs[k % len(graphs)]
            rng = stream(seed, "context", index * layouts + k)
            result = layout_scene(graph, rng, params=params, context=context)
            poses = {box_id: (pose.x, pose.z, pose.yaw) for box_id, pose in result.poses.items()}
            for kind, pose in graph_pair_poses(graph, poses):
                if kind in generated_poses:
                    generated_poses[kind].append(pose)
            if balance_table is not None:
                offset = graph_balance(graph, poses)
                if offset is not None:
                    generated_offsets.append(offset)
        found: dict = {
            kind: shares(*counts(tables[kind], generated_poses[kind]), UPDATE_SMOOTH)
            for kind in kinds
        }
        if balance_table is not None:
            found[BALANCE] = balance_shares(generated_offsets)
        return found

    rules_alone = held_divergence(generate(None, rounds + 1)) if held_shares else None
    divergence: list[float] = []
    held_out: list[float] = []
    # (divergence, round, weights, generated shares per kind, balance) of the best round so far
    # (by the fitted examples' divergence: the line search's), and the round nearest the
    # held-out examples
    best: tuple[float, int, dict[Kind, PairContext], dict, BalanceContext | None] | None = None
    nearest: tuple[float, int, dict[Kind, PairContext], BalanceContext | None] | None = None
    rate = RATE
    for round_index in range(rounds + 1):
        context = LearnedContext(tuple(tables[kind] for kind in kinds), balance=balance_table)
        generated = generate(context, round_index)
        divergence.append(fitted_divergence(generated))
        if held_shares:
            held_out.append(held_divergence(generated))
            if nearest is None or held_out[-1] < nearest[0]:
                nearest = (held_out[-1], round_index, dict(tables), balance_table)
        if best is None or divergence[-1] < best[0]:
            best = (divergence[-1], round_index, dict(tables), generated, balance_table)
        else:
            # The step made the fit worse: go back to the best weights and take half of
            # the step from there (a backtracking line search on the step length).
            rate /= 2.0
        _, _, base, measured, base_balance = best
        if base_balance is not None and balance_observed is not None:
            balance_table = BalanceContext(
                scaling_step(base_balance.weights, balance_observed, measured[BALANCE], rate),
                base_balance.examples,
            )
        tables = {
            kind: PairContext(
                *kind,
                base[kind].bounds,
                scaling_step(base[kind].position, observed[kind][0], measured[kind][0], rate),
                scaling_step(base[kind].yaw, observed[kind][1], measured[kind][1], rate),
                base[kind].examples,
            )
            for kind in kinds
        }
    _, kept, chosen, _, chosen_balance = best
    record = {
        "seed": seed,
        "rounds": rounds,
        "layouts_per_round": layouts,
        "kept_round": kept,
        "divergence": [round(d, 6) for d in divergence],
        "skipped": skipped,
    }
    if nearest is not None:
        _, kept, chosen, chosen_balance = nearest
        record["kept_round"] = kept
        record["held_out"] = {
            "examples": list(held),
            "divergence": [round(d, 6) for d in held_out],
            "rules_alone": round(float(rules_alone or 0.0), 6),
        }
    return ContextFit(
        LearnedContext(tuple(chosen[kind] for kind in kinds), record, balance=chosen_balance),
        divergence,
        kept,
        layouts,
        skipped,
        held,
        held_out,
        rules_alone,
        kept if held else None,
    )
