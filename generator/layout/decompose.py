"""Group decomposition: large scenes laid out group by group, then as a whole.

After section 6 of Zhang et al., "Fast 3D Indoor Scene Synthesis by Learning Spatial
Relation Priors of Objects" (IEEE TVCG 2021): the input objects are split into disjoint
groups, each group is arranged on its own, and one global optimisation then adjusts the
whole layout. The paper forms groups as connected components of a graph of learnt
spatial strengths and arranges each group by sampling learnt templates; here the groups
are the grammar's own (its top-level ``group`` nodes: a home with its garden, a market,
a park), whose relations among their members play the part of the templates, and each
group is arranged by the same annealed sampler as the whole scene. The paper's global
step (template matching by position-based dynamics against collisions) becomes the
layout's own energy, in two phases:

1. **Frames.** Every top-level group of two or more boxes is laid out alone, in a frame
   of its own: a scene holding only its nodes and the relations among them, on an
   extent sized to its members (``frame_extent``). What it relates to outside (its road)
   is left out. Group g draws from child g of the layout's stream 0, so the frames do
   not depend on each other, on the order they are computed in, or on how many
   processes compute them (``LayoutParams.workers``).
2. **Rigid placement.** The scene is placed with each such group a rigid footprint:
   its members keep their relative poses and the group is placed, turned and moved as
   one (``Mover(rigid_groups=...)``), by its relations to roads and other items and
   against collisions, with the free objects and the paths around them; annealed for
   ``RIGID_STEPS_PER_UNIT`` steps per top-level item.
3. **Joint refinement.** A short chain with every move (members one by one too),
   ``REFINE_STEPS_PER_BOX`` steps per box, from where phase 2 ended, mends what the
   rigid footprints could not (a garden bush in a neighbour's way).

The result is an ordinary layout: ``report.assess`` gives its verdicts and problems as
for any other, and a restart (``LayoutParams.restarts``) redoes phases 2 and 3 from a
fresh stream but keeps the frames, which do not depend on the rest of the scene.

When (``decomposes``): without pins or a warm start, outdoors, when the scene has at
least ``MIN_BOXES`` objects and at least ``MIN_GROUPED_SHARE`` of them are in top-level
groups of two or more. Below that one chain over the whole scene is as fast (its cost
per step does not grow with the scene, and a small scene's chain is short); a room's
furniture is tied to walls that a group's own frame does not have.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field, replace

import networkx as nx
import numpy as np

from scenewright.core.scene_graph import SceneGraph

from .energy import Energy
from .initial import place_initial
from .lots import settle, shortage
from .moves import Mover
from .params import LayoutParams
from .pinning import Pins
from .problem import Problem, compile_problem
from .report import assess
from .sampler import Run, anneal, run_chain
from .state import State

#: The rule: decompose scenes with at least this many objects ...
MIN_BOXES = 80
#: ... of which at least this share stand in top-level groups of two or more boxes.
MIN_GROUPED_SHARE = 0.5
#: Phase 2's budget, per top-level item (group or free object).
RIGID_STEPS_PER_UNIT = 40
#: Phase 3's budget, per box.
REFINE_STEPS_PER_BOX = 10
#: A frame's extent: this many times the summed footprint diagonals of its ground boxes
#: (at least FRAME_MIN_SIDE metres a side), room for any arrangement of them.
FRAME_SPREAD = 1.0
FRAME_MIN_SIDE = 10.0
#: A decomposed scene's chains test the stop rule at least this rarely and from this step
#: on, and place each item as the best of at least this many candidates: assessing 200
#: boxes costs as much as hundreds of steps, and a group's footprint, placed once with all
#: its members, is rarely moved out of a poor spot. With the small scenes' 25, 50 and 8
#: the town's slowest layouts took several times its median, and some failed (the
#: figures: docs/notes/measurements.md).
LARGE_CHECK_EVERY = 200
LARGE_MIN_STEPS = 200
LARGE_CANDIDATES = 16
#: A group's own chain tests its stop rule this often (steps): a group of a few boxes is
#: often ok after a few dozen steps, and assessing it is cheap.
FRAME_CHECK_EVERY = 25

#: A group's frame: {box index in the scene: (x, z, yaw)} about the group's centre.
Frame = dict[int, tuple[float, float, float]]


@dataclass
class Frames:
    """The groups laid out in their own frames (phase 1)."""

    poses: dict[int, Frame]  # by group index of the scene's problem
    ok: dict[int, bool]  # whether the group's own layout was ok
    steps: int
    nouns: dict[str, tuple[str, str]] = field(default_factory=dict)  # type -> noun, plural


def framed_groups(problem: Problem) -> list[int]:
    """The top-level groups of two or more boxes, in creation order."""
    return [g for g in problem.top_groups if len(problem.group_members[g]) >= 2]


def decomposes(problem: Problem, pins: Pins) -> bool:
    """The documented rule (module docstring): large outdoor scenes mostly made of groups,
    without pins or a warm start."""
    if pins.preset or problem.room is not None:
        return False
    objects = sum(1 for b in range(problem.n_boxes) if not problem.is_junction[b])
    grouped = sum(len(problem.group_members[g]) for g in framed_groups(problem))
    return objects >= MIN_BOXES and grouped >= MIN_GROUPED_SHARE * objects


def large_scene_params(params: LayoutParams) -> LayoutParams:
    """``params`` for a decomposed scene: the stop rule tested and items placed as the
    ``LARGE_*`` constants say, or as ``params`` says where it asks for more."""
    return replace(
        params,
        check_every=max(params.check_every, LARGE_CHECK_EVERY),
        min_steps=max(params.min_steps, LARGE_MIN_STEPS),
        initial_candidates=max(params.initial_candidates, LARGE_CANDIDATES),
    )


def frame_extent(problem: Problem, members: tuple[int, ...]) -> float:
    """The side (metres) of a square frame with room for a group's members."""
    spread = sum(problem.size[b] for b in members if problem.support[b] < 0)
    return max(FRAME_MIN_SIDE, FRAME_SPREAD * spread)


def group_scenes(graph: SceneGraph, problem: Problem, groups: list[int]) -> list[SceneGraph]:
    """For each of ``groups`` (top-level group indices) a scene of that group alone: the
    group, its nodes and the relations among them, on a square extent of side
    ``frame_extent``. One pass over the scene's nodes and edges for all of them."""
    whole = graph.graph
    group_of: dict[str, int] = {}
    for position, group in enumerate(groups):
        group_of[problem.group_ids[group]] = position
    for node_id, data in whole.nodes(data=True):  # creation order: parents come first
        if data["parent"] in group_of:
            group_of.setdefault(node_id, group_of[data["parent"]])
    own = [nx.MultiDiGraph() for _ in groups]
    # In the scene's own order (a networkx subgraph would list them in a set's order,
    # which changes from run to run), so a group's layout is the same every time.
    for node_id, data in whole.nodes(data=True):
        if node_id in group_of:
            own[group_of[node_id]].add_node(node_id, **data)
    for source, target, data in whole.edges(data=True):
        shared = group_of.get(source)
        if shared is not None and group_of.get(target) == shared:
            own[shared].add_edge(source, target, **data)
    return [
        SceneGraph(params=replace(graph.params, extent=(side, side)), graph=members)
        for members, side in zip(
            own, (frame_extent(problem, problem.group_members[g]) for g in groups), strict=False
        )
    ]


def lay_out_frames(
    graph: SceneGraph, problem: Problem, params: LayoutParams, rngs: list[np.random.Generator]
) -> Frames:
    """Phase 1: every framed group laid out alone, group k on ``rngs[k]``; in
    ``params.workers`` processes when more than one (same results either way)."""
    groups = framed_groups(problem)
    tasks = [
        (scene, params, rng)
        for scene, rng in zip(group_scenes(graph, problem, groups), rngs, strict=False)
    ]
    if params.workers > 1 and len(tasks) > 1:
        with ProcessPoolExecutor(max_workers=params.workers) as pool:
            results = list(
                pool.map(_frame, tasks, chunksize=max(1, len(tasks) // (4 * params.workers)))
            )
    else:
        results = [_frame(task) for task in tasks]
    index = {box_id: box for box, box_id in enumerate(problem.ids)}
    frames = Frames({}, {}, 0)
    for node in graph.nodes():
        if node.type not in frames.nouns:  # a type with styles is named by its type
            noun = node.type.replace("_", " ") if node.style else node.noun
            plural = noun + "s" if node.style or not node.plural else node.plural
            frames.nouns[node.type] = (noun, plural)
    for g, (poses, ok, steps) in zip(groups, results, strict=False):
        frames.poses[g] = {index[box_id]: pose for box_id, pose in poses.items()}
        frames.ok[g] = ok
        frames.steps += steps
    return frames


def _frame(task: tuple[SceneGraph, LayoutParams, np.random.Generator]) -> tuple[dict, bool, int]:
    """One group's own layout: its poses about its centre, whether it was ok, its steps.

    Chains stop as soon as the group is ok, tested every ``FRAME_CHECK_EVERY`` steps (no
    minimum of polishing steps: the joint refinement polishes); up to
    ``params.restarts`` more run while it is not.
    """
    graph, params, rng = task
    sub = compile_problem(graph)
    own = replace(params, min_steps=0, check_every=FRAME_CHECK_EVERY)
    best, steps = None, 0
    for _ in range(1 + params.restarts):
        run = run_chain(sub, own, rng)
        steps += run.steps
        if best is None or (run.ok, -len(run.problems)) > (best.ok, -len(best.problems)):
            best = run
        if best.ok:
            break
    assert best is not None  # one chain at least ran
    state = best.energy.state
    ground = [b for b in range(sub.n_boxes) if sub.support[b] < 0]
    cx = sum(state.x[b] for b in ground) / len(ground)
    cz = sum(state.z[b] for b in ground) / len(ground)
    poses = {
        box_id: (state.x[b] - cx, state.z[b] - cz, state.yaw[b]) for b, box_id in enumerate(sub.ids)
    }
    return poses, best.ok, steps


def run_decomposed_chain(
    problem: Problem, params: LayoutParams, rng: np.random.Generator, frames: Frames
) -> Run:
    """Phases 2 and 3 on one stream: the framed groups placed and annealed as rigid
    footprints, then a short joint refinement of everything."""
    if problem.free_paths:  # the lots may give relations to "some road" another road
        problem = problem.with_own_relations()
    state = State(problem)
    energy = Energy(problem, state, params)
    # The roads are fitted to the scene and the lots planned along them: they stay put.
    roads = Pins(
        box=list(problem.is_junction),
        anchored=[False] * problem.n_boxes,
        path=[True] * problem.n_paths,
    )
    rigid = Mover(problem, state, rng, params, roads, rigid_groups=list(frames.poses))
    plan = place_initial(energy, rigid, rng, frames=frames.poses, lots=True)
    placed = anneal(
        energy, rigid, params, rng, max(params.steps, RIGID_STEPS_PER_UNIT * len(problem.units))
    )
    joint = Mover(problem, state, rng, params, roads)
    refined = anneal(
        energy, joint, params, rng, max(params.min_steps, REFINE_STEPS_PER_BOX * problem.n_boxes)
    )
    relations, problems = refined.relations, list(refined.problems)
    if settle(energy):  # the few centimetres of overlap the verdict lets pass, mended
        relations, problems = assess(energy)
    missing = (
        shortage(plan, frames.nouns, problem.path_ids) if plan is not None and problems else None
    )
    if missing:  # what the rule set asked for too much of, before what went wrong
        problems.insert(0, missing)
    return Run(
        energy,
        relations,
        problems,
        placed.steps + refined.steps,
        placed.accepted + refined.accepted,
    )


def frame_streams(root: np.random.Generator, problem: Problem) -> list[np.random.Generator]:
    """One independent stream per framed group, children of ``root`` (spawned, so no
    number of ``root``'s own is drawn)."""
    return root.spawn(len(framed_groups(problem)))
