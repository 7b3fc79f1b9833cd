"""Markov chain Monte Carlo placement of objects and paths (the paper's energy).

``layout_scene(graph, seed, params=None) -> LayoutResult`` places every object and
junction and routes every path of a scene graph. The energy (``energy``) follows the
supplement of the paper: relation terms from Table 1 (``relation_terms``), collision
penalties between boxes and between boxes and paths, path shape terms, plus keeping
everything inside the scene extent. The sampler (``sampler``) starts from a
constructive placement (``initial``) and runs annealed Metropolis-Hastings with local,
group and data-driven moves (``moves``) on incremental energy deltas. The result
reports honestly (``report``): per relation its log factor and whether it holds under
the documented thresholds; ``ok`` only when every relation holds, nothing overlaps by
more than 1 % and everything is inside the extent.

Randomness: chain k draws from the layout stage's child stream k of the scene's seed
(``core.seeds``), so restarts never share numbers with expansion, with the describer or
with each other.

``layout_scene`` can keep some objects, junctions and paths exactly where they are
(``pinned``, ``pinned_paths``) and start its chains from given poses (``start``); the
rules are in ``pinning``. A layout mask (``mask``, see ``mask_term``) adds a preference
for where some boxes stand; a learned context (``context``, see ``learned_term``) adds
spatial priors learned from examples, sampled at temperature 1 (``sampler``).
``measure_layout(graph, poses, paths)`` (``measure``) reports
on a layout that already exists (an imported scene) without sampling.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np

from scenewright.core.poses import LayoutResult, Pose
from scenewright.core.scene_graph import SceneGraph
from scenewright.core.seeds import SeedLike, stage_stream

from .decompose import (
    MIN_BOXES,
    decomposes,
    frame_streams,
    large_scene_params,
    lay_out_frames,
    run_decomposed_chain,
)
from .learned_term import LearnedContext, compile_learned
from .lots import wrap_clusters
from .mask_term import FloorMask, compile_mask
from .measure import measure_layout
from .params import LayoutParams
from .pinning import compile_pins
from .problem import compile_problem
from .repair import repair_pins
from .sampler import Run, run_chain

__all__ = [
    "FloorMask",
    "LayoutParams",
    "LearnedContext",
    "LayoutResult",
    "Pose",
    "layout_scene",
    "measure_layout",
]


def layout_scene(
    graph: SceneGraph,
    seed: SeedLike,
    *,
    params: LayoutParams | None = None,
    pinned: Mapping[str, Pose] | None = None,
    pinned_paths: Mapping[str, object] | None = None,
    start: Mapping[str, object] | None = None,
    mask: FloorMask | Sequence[FloorMask] | None = None,
    context: LearnedContext | None = None,
) -> LayoutResult:
    """Lay out a scene graph: poses for objects and junctions, control points for paths.

    Deterministic: the same graph, seed and params give the same result. ``seed`` is
    the scene's seed (an int: chain k uses the layout's child stream k), a Generator
    (each chain uses a child spawned from it) or None (fresh entropy). Runs up to
    ``1 + params.restarts`` chains, each on its own stream, until one is ok, and returns
    the best: ok first, then fewest problems, then lowest energy. The first starts from
    the constructive placement; outdoors the others but the last start from the best so
    far with its troubled items placed anew (``repair``), the last (and in a room every
    one) from a fresh placement. In a
    large scene of groups (``decompose``) every chain places the groups' frames, laid
    out once, anew. Raises ``InputError`` for relations that cannot
    be laid out (an OnTopOf between non-objects, a cycle of supports, a malformed
    PathConnectedTo).

    ``pinned`` (object or junction id -> Pose) and ``pinned_paths`` (path id -> control
    points, segments + 1 of them) stay exactly as given in every chain; the rest is placed
    around them. The supports beneath a pinned object, and the junction a pinned path
    starts at, must be pinned too. ``start`` (id -> Pose, or path id -> points) is where
    every chain starts instead of the constructive placement (a warm start; those may
    move, and what it leaves out is placed around them). Unknown ids, group ids and
    malformed poses are an ``InputError``. See ``pinning`` for the details.

    ``mask`` (``mask_term.FloorMask``, or a sequence of them for different boxes) adds
    the energy part ``mask``: the boxes each names prefer to stand where its grid is
    high. It is a preference the verdict (``ok``, the problems) does not read, except
    for a mask that confines its boxes (a composite room's part): a box whose centre
    leaves it is a problem. Without it the layout is exactly the one it was before.

    ``context`` (``learned_term.LearnedContext``, from ``scenewright fit --what
    context``) adds the energy part ``learned`` for every related pair of a kind it has,
    and the chain then samples those pairs at temperature 1 (``sampler``). A context with
    no kind of this graph, or None, leaves the layout exactly as it was.
    """
    params = params or LayoutParams()
    started = time.perf_counter()
    problem = compile_problem(graph)
    if (
        params.decompose
        and problem.room is None
        and problem.n_boxes >= MIN_BOXES
        and mask is None
        and context is None
        and not (pinned or pinned_paths or start)
    ):
        # Loose objects tied by relations (a house and its garden) laid out as groups when
        # that makes the scene one the group decomposition lays out (``lots``).
        wrapped = wrap_clusters(graph)
        if wrapped is not graph:
            grouped = compile_problem(wrapped)
            if decomposes(grouped, compile_pins(grouped, None, None, None)):
                graph, problem = wrapped, grouped
    if mask is not None:
        problem.mask = compile_mask(mask, problem.ids)
    if context is not None:
        learned = compile_learned(
            context, problem, [graph.node(box_id).type for box_id in problem.ids]
        )
        problem.learned = learned if learned.pairs else None
    pins = compile_pins(problem, pinned, pinned_paths, start)
    best: Run | None = None
    total_steps = total_accepted = 0
    frames = None
    # Repairing restarts outdoors, without a given start (every chain starts there then);
    # in a room the walls tie items together, and fresh chains did better (docs/layout.md).
    repairs = problem.room is None and not (pins.start_poses or pins.start_points)
    if params.decompose and decomposes(problem, pins):
        params = large_scene_params(params)
        frames = lay_out_frames(
            graph, problem, params, frame_streams(_chain_stream(seed, 0), problem)
        )
        total_steps += frames.steps
    for attempt in range(1 + params.restarts):
        rng = _chain_stream(seed, attempt)
        # A chain that a repairing restart follows gives up sooner: the repair mends a
        # stuck item in far fewer steps than waiting it out (docs/layout.md).
        chain_params = params
        if attempt > 0 and params.restart_patience is not None:
            chain_params = replace(params, patience=params.restart_patience)
        if repairs and attempt + 1 < params.restarts:
            chain_params = replace(chain_params, patience=params.repair_patience)
        if frames is not None:  # the groups' frames do not depend on the rest: computed once
            run = run_decomposed_chain(problem, params, rng, frames)
        elif (
            best is not None and attempt < params.restarts and repairs
        ):  # keep what was fine, redo the rest
            run = run_chain(problem, chain_params, rng, repair_pins(problem, best, pins))
        else:
            run = run_chain(problem, chain_params, rng, pins)
        total_steps += run.steps
        total_accepted += run.accepted
        if best is None or _rank(run) > _rank(best):
            best = run
        if best.ok:
            break
    assert best is not None  # one chain at least ran
    state, energy = best.energy.state, best.energy
    poses = {
        box_id: Pose(state.x[box], state.y[box], state.z[box], state.yaw[box])
        for box, box_id in enumerate(problem.ids)
    }
    paths = {
        path_id: np.array(state.points[p], dtype=float)
        for p, path_id in enumerate(problem.path_ids)
    }
    parts = energy.full()  # exact, free of the rounding the running sums gather
    return LayoutResult(
        poses=poses,
        paths=paths,
        relations=best.relations,
        energy=float(sum(parts.values())),
        parts=parts,
        steps=total_steps,
        acceptance=total_accepted / total_steps if total_steps else 0.0,
        seconds=time.perf_counter() - started,
        ok=best.ok,
        problems=list(best.problems),
    )


def _chain_stream(seed: SeedLike, attempt: int) -> np.random.Generator:
    """Chain ``attempt``'s stream: the layout's child stream ``attempt`` of an int seed, or
    a child spawned from a Generator."""
    return (
        seed.spawn(1)[0]
        if isinstance(seed, np.random.Generator)
        else stage_stream(seed, "layout", attempt)
    )


def _rank(run: Run) -> tuple:
    """Higher is better: ok, then fewer problems, then lower energy."""
    return (run.ok, -len(run.problems), -run.energy.total)
