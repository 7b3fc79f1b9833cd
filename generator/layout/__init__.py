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
more than 1 % and everything is inside the extent. ``plan.draw_plan`` draws a top-down
plan of a laid-out scene.
"""

from __future__ import annotations

import time

import numpy as np

from ..scene_graph import SceneGraph
from .params import LayoutParams
from .problem import compile_problem
from .result import LayoutResult, Pose, RelationResult
from .sampler import Run, run_chain

__all__ = ["LayoutParams", "LayoutResult", "Pose", "RelationResult", "layout_scene"]


def layout_scene(graph: SceneGraph, seed: int, *, params: LayoutParams | None = None) -> LayoutResult:
    """Lay out a scene graph: poses for objects and junctions, control points for paths.

    Deterministic: the same graph, seed and params give the same result. Runs up to
    ``1 + params.restarts`` chains (each from a fresh initial placement, on its own
    stream derived from ``seed``) until one is ok, and returns the best: ok first, then
    fewest problems, then lowest energy. Raises ``InputError`` for relations that cannot
    be laid out (an OnTopOf between non-objects, a cycle of supports, a malformed
    PathConnectedTo).
    """
    params = params or LayoutParams()
    started = time.perf_counter()
    problem = compile_problem(graph)
    best: Run | None = None
    total_steps = total_accepted = 0
    for attempt in range(1 + params.restarts):
        run = run_chain(problem, params, np.random.default_rng([seed, attempt]))
        total_steps += run.steps
        total_accepted += run.accepted
        if best is None or _rank(run) > _rank(best):
            best = run
        if best.ok:
            break
    state, energy = best.energy.state, best.energy
    poses = {
        box_id: Pose(state.x[box], state.y[box], state.z[box], state.yaw[box])
        for box, box_id in enumerate(problem.ids)
    }
    paths = {path_id: np.array(state.points[p], dtype=float) for p, path_id in enumerate(problem.path_ids)}
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


def _rank(run: Run) -> tuple:
    """Higher is better: ok, then fewer problems, then lower energy."""
    return (run.ok, -len(run.problems), -run.energy.total)
