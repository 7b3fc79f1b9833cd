"""Pruning of indirect relations: in every triangle of related types, at most one pair is
carried by the other two and reported as pruned. A pair goes when one type of the
triangle rests on another, or when its within-scene poses are no tighter than their
composition through the third type (``indirect_through``, ``informative_directness``),
or, where that cannot be tested, when its two stand the farthest apart of the three
(then: the weakest).
Design notes: docs/notes/design.md, "Relation finding".
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from scenewright.core.frames import to_world_many
from scenewright.core.scene import Scene
from scenewright.examples.stacking import infer_supports

from .relation_poses import (
    TypePoses,
    fellows_held,
    footprint_gaps,
    framed,
    hand_placed_poses,
    holding_both,
    nearest_objects,
    pair_poses,
    pair_stream,
    relative_poses,
    square,
)
from .relation_results import PairRelation
from .relation_statistics import flip_test, sample_tightness
from .relation_thresholds import (
    DIRECTNESS_MARGIN,
    MAX_SCENES,
    MIN_DIRECT_TIGHTNESS,
    PAIR_SCENES,
    PERMUTATIONS,
    SCALE_FLOOR,
    STRENGTH_DRAWS,
    THIRD_SHARE,
)


def composed_poses(
    frame: TypePoses,
    middle: TypePoses,
    end: TypePoses,
    together: np.ndarray,
    rng: np.random.Generator,
    grouped: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The within- and composed poses of the test of indirectness (design notes) on
    the scenes ``together`` holding all three types, at most ``MAX_SCENES`` of them, in
    pairs of scenes as ``pair_poses`` gives them: per scene a random a, its nearest b,
    that b's nearest c -> (within, composed in b's frame, composed in the world's axes),
    (2K, 4) each. Within: c in a's frame. Composed in b's frame: the c of the other
    scene of the pair put where it stands relative to its own b, in that b's frame,
    relative to this scene's b; in the world's axes: the same offset along the world's
    axes and the same turn, for a c placed by a world direction (north of b). With
    ``grouped`` ((S, K), ``fellows_held``), the a is one whose group holds a b and a c,
    and they are that group's (design notes, "Triangles within groups")."""
    order = rng.permutation(together)[:MAX_SCENES]
    pairs = len(order) // 2
    scenes = order[: 2 * pairs]
    if grouped is None:
        chosen = np.floor(rng.random(2 * pairs) * frame.counts[scenes]).astype(int)
        holder = None
    else:  # a random a among those whose group holds the other two, as the i-th of them
        eligible = grouped[scenes]
        rank = np.floor(rng.random(2 * pairs) * eligible.sum(axis=1)).astype(int)
        chosen = np.argmax(np.cumsum(eligible, axis=1) > rank[:, None], axis=1)
        holder = frame.holders[scenes, chosen]
    a = frame.poses[scenes, chosen]
    b = nearest_objects(a, middle, scenes, holders=holder)
    c = nearest_objects(b, end, scenes, holders=holder)
    c_in_b = relative_poses(b, c[:, None])[:, 0]  # (2K, 4)
    swapped = np.roll(c_in_b, pairs, axis=0)  # the c of the pair's other scene, relative to its b
    turn = np.arctan2(swapped[:, 3], swapped[:, 2])
    moved = np.column_stack(
        [to_world_many(b[:, :2], b[:, 2], swapped[:, None, :2])[:, 0], b[:, 2] + turn]
    )
    other_c, other_b = np.roll(c, pairs, axis=0), np.roll(b, pairs, axis=0)
    along_axes = np.column_stack([b[:, :2] + other_c[:, :2] - other_b[:, :2], other_c[:, 2]])
    within = relative_poses(a, c[:, None])[:, 0]
    return (
        within,
        relative_poses(a, moved[:, None])[:, 0],
        relative_poses(a, along_axes[:, None])[:, 0],
    )


def triangle_scenes(
    poses: dict[str, TypePoses], a: str, c: str, b: str, kinds: dict[str, str] | None = None
) -> tuple[TypePoses, TypePoses, TypePoses, np.ndarray, np.ndarray | None]:
    """The scenes a test of (a, c) through b looks at: (frame type, other type, b,
    the scenes holding all three, and per object of the frame type whether its group
    holds a b and a c, or None). The pair's frame is its type with fewer objects in
    them (``framed``); where ``kinds`` (name -> the kind of group of its role) puts all
    three in one kind of group, only scenes with such a group count ("Triangles within
    groups")."""
    first, second, middle = poses[a], poses[c], poses[b]
    together = np.flatnonzero((first.counts >= 1) & (second.counts >= 1) & (middle.counts >= 1))
    first, second = framed(first, second, together)
    grouped = None
    if (
        kinds is not None
        and kinds.get(a, "") != ""
        and kinds.get(a) == kinds.get(b) == kinds.get(c)
    ):
        grouped = fellows_held(first, middle, second)
        together = together[grouped[together].any(axis=1)]
    return first, second, middle, together, grouped


def indirect_through(
    poses: dict[str, TypePoses],
    a: str,
    c: str,
    b: str,
    seed: int,
    alpha: float,
    kinds: dict[str, str] | None = None,
) -> bool | None:
    """Whether the pair (a, c) is indirect through b (design notes): its poses within
    scenes not clearly tighter than the composition of b in a's frame and c in b's from
    two scenes, in b's frame or in the world's axes (``triangle_scenes`` picks the
    scenes). None when fewer than ``PAIR_SCENES`` scenes hold all three (in one
    group)."""
    first, second, middle, together, grouped = triangle_scenes(poses, a, c, b, kinds)
    if len(together) < PAIR_SCENES:
        return None
    rng = pair_stream(seed, a, c, b)
    within, in_frame, along_axes = composed_poses(first, middle, second, together, rng, grouped)
    draws = []
    for composed in (in_frame, along_axes):
        _, p_value, strength = flip_test(within, composed, PERMUTATIONS, rng)
        if p_value > alpha:
            return True
        draws.append([strength])
    for _ in range(STRENGTH_DRAWS - 1):
        within, in_frame, along_axes = composed_poses(first, middle, second, together, rng, grouped)
        draws[0].append(sample_tightness(within, in_frame))
        draws[1].append(sample_tightness(within, along_axes))
    return min(float(np.mean(tightnesses)) for tightnesses in draws) < MIN_DIRECT_TIGHTNESS


def coordinate_spreads(values: np.ndarray) -> np.ndarray:
    """The mean absolute difference of two of the n rows of ``values`` (n, D), per
    coordinate -> (D,): from the sorted values, sum_k (2k - n - 1) x_(k) over n(n - 1)/2."""
    n = len(values)
    ordered = np.sort(values, axis=0)
    rank = np.arange(1, n + 1)[:, None]
    return 2.0 * ((2 * rank - n - 1) * ordered).sum(axis=0) / (n * (n - 1))


def informative_directness(
    poses: dict[str, TypePoses],
    a: str,
    c: str,
    b: str,
    seed: int,
    kinds: dict[str, str] | None = None,
    mirrored: bool = False,
) -> float:
    """How much tighter the pair (a, c) stands within scenes than composed through b,
    in the coordinates that hold its relation (design notes, "Choosing the
    indirect pair"): 1 - the geometric mean, over the coordinates of a pose, of the
    within-scene spread over the composed one, each coordinate weighted by the log of
    the across-scene spread over the within-scene one (0 where the within-scene poses
    are no tighter); the smaller over the two compositions (b's frame, the world's
    axes), averaged over ``STRENGTH_DRAWS`` draws (0 in a draw where no coordinate
    holds the relation). ``mirrored``: every pose with either side of its frame alike
    (``hand_placed_poses``), the same draws: a plant left of the desk in some studies and
    right in others is as direct as one always on the left."""
    first, second, middle, together, grouped = triangle_scenes(poses, a, c, b, kinds)
    rng = pair_stream(seed, a, c, b, "directness")
    values = []
    for _ in range(STRENGTH_DRAWS):
        within, in_frame, along_axes = composed_poses(first, middle, second, together, rng, grouped)
        _, across = pair_poses(first, second, False, together, rng)
        if mirrored:
            within, in_frame, along_axes, across = (
                hand_placed_poses(found, square(second))
                for found in (within, in_frame, along_axes, across)
            )
        spread = np.maximum(coordinate_spreads(within), SCALE_FLOOR)
        weight = np.log(np.maximum(coordinate_spreads(across), SCALE_FLOOR) / spread).clip(min=0.0)
        if weight.sum() <= 0.0:
            values.append(0.0)
            continue
        values.append(
            min(
                1.0
                - float(
                    np.exp(
                        weight
                        @ np.log(spread / np.maximum(coordinate_spreads(composed), SCALE_FLOOR))
                        / weight.sum()
                    )
                )
                for composed in (in_frame, along_axes)
            )
        )
    return float(np.mean(values))


def typical_gap(first: TypePoses, second: TypePoses, same: bool) -> tuple[float, float]:
    """How far apart an a and a b stand: in each scene holding both, the pair of an a
    and a b closest by the gap between their footprints (rounded to 0.1 m, as the layout
    measures boxes square to each other), then by the distance of their centres; the
    medians over the scenes of that gap and that distance."""
    gaps, centres = [], []
    for scene in holding_both(first, second, same):
        a, b = (
            first.poses[scene, : first.counts[scene]],
            second.poses[scene, : second.counts[scene]],
        )
        a_sizes, b_sizes = (
            first.footprints[scene, : first.counts[scene]],
            second.footprints[scene, : second.counts[scene]],
        )
        pose = relative_poses(np.repeat(a, len(b), axis=0), np.tile(b, (len(a), 1))[:, None])[
            :, 0
        ]  # every a with every b
        gap = np.round(
            footprint_gaps(pose, np.repeat(a_sizes, len(b), axis=0), np.tile(b_sizes, (len(a), 1))),
            1,
        )
        centre = np.hypot(pose[:, 0], pose[:, 1])
        if same:  # an object is not its own partner
            gap[:: len(b) + 1] = np.inf
        closest = np.lexsort((centre, gap))[0]
        gaps.append(gap[closest])
        centres.append(centre[closest])
    return float(np.median(gaps)), float(np.median(centres))


def resting_pairs(
    scenes: Sequence[Scene],
    poses: dict[str, TypePoses],
    names: Sequence[dict[str, str]] | None = None,
) -> set[tuple[str, str]]:
    """(upper type, lower type) for the types of which an object rests on one of the
    other (measured from the boxes, ``examples.stacking``) in at least half the scenes
    holding both; with ``names`` (per scene, object id -> name, as ``poses`` is keyed),
    the names instead of the types."""
    held: Counter = Counter()
    for index, scene in enumerate(scenes):
        objects = scene.placed_objects()
        types = {o.id: o.type for o in objects} if names is None else names[index]
        held.update(
            {(types[upper], types[lower]) for upper, lower in infer_supports(objects).items()}
        )
    return {
        (upper, lower)
        for (upper, lower), count in held.items()
        if upper != lower and 2 * count >= len(holding_both(poses[upper], poses[lower], False))
    }


def third_share(poses: dict[str, TypePoses], a: str, b: str, third: str) -> float:
    """The share of the scenes holding a and b (two a's when a == b) that hold a ``third``."""
    both = holding_both(poses[a], poses[b], a == b)
    return float(np.mean(poses[third].counts[both] >= 1)) if len(both) else 0.0


def prune_indirect(
    pairs: Sequence[PairRelation],
    resting: set[tuple[str, str]] = frozenset(),
    through: Callable[[str, str, str], bool | None] | None = None,
    apart: Callable[[str, str], tuple[float, float]] | None = None,
    present: Callable[[str, str, str], float] | None = None,
    direct: Callable[[str, str, str], float] | None = None,
) -> list[PairRelation]:
    """``pairs`` with the indirect pairs of every triangle of related pairs marked not
    related and ``pruned``: the pair of a third type with one that rests on another of
    the triangle (``resting``: (upper, lower) type pairs); else, given ``through(a, c,
    b)``, whether (a, c) is indirect through b (None: cannot tell), of the triangle's
    pairs it finds indirect the one whose objects stand farthest apart (``apart(a, c)``,
    compared as tuples; the weakest without it), and where it cannot tell for some pair
    of the triangle, likewise the pair farthest apart (a lamp and a side table on either
    side of an armchair relate through it), then the one of the smallest strength. Given ``direct(a, c, b)``, how
    direct (a, c) is against its composition through b, the farthest apart is taken only
    among the pairs found indirect within ``DIRECTNESS_MARGIN`` of the least direct of
    them. Given ``present(a, c, b)``, the share of the scenes holding a and c that hold
    a b, a pair is judged in a triangle only when that share is at least
    ``THIRD_SHARE``. A resting pair itself is never pruned (design notes)."""
    strength = {(p.a, p.b): p.strength for p in pairs if p.related}
    neighbours: dict[str, set[str]] = defaultdict(set)
    for a, b in strength:
        if a != b:
            neighbours[a].add(b)
            neighbours[b].add(a)

    def key(u: str, v: str) -> tuple[str, str]:
        return (u, v) if u < v else (v, u)

    def supported(u: str, v: str) -> bool:
        return (u, v) in resting or (v, u) in resting

    def explains(
        u: str, v: str, third: str
    ) -> bool:  # the third stands in enough of the pair's scenes
        return present is None or present(u, v, third) >= THIRD_SHARE

    indirect: set[tuple[str, str]] = set()
    for a, b in strength:
        if a == b:  # two a's and a third type w: the a's relate through w if they rest on it,
            # or, unless w rests on one a (then it is that a's alone), if w is tighter to them
            # (one w between them) or two w's are tighter to each other (each a by its own w)
            if any(
                explains(a, a, w)
                and (
                    (a, w) in resting
                    or (
                        (w, a) not in resting
                        and max(strength[key(a, w)], strength.get((w, w), -math.inf))
                        > strength[(a, a)]
                    )
                )
                for w in neighbours[a]
            ):
                indirect.add((a, a))
            continue
        for w in neighbours[a] & neighbours[b]:
            if w < b or b < a:  # each triangle once, as a < b < w
                continue
            edges = [(a, b), key(a, w), key(b, w)]
            riders = [
                key(third, upper)
                for upper, lower, third in (
                    (a, b, w),
                    (b, a, w),
                    (a, w, b),
                    (w, a, b),
                    (b, w, a),
                    (w, b, a),
                )
                if (upper, lower) in resting
                and not supported(third, upper)
                and explains(third, upper, lower)
            ]
            if riders:  # what rests on another relates to the third through it
                indirect.update(riders)
                continue
            thirds = dict(zip(edges, (w, b, a), strict=False))
            edges = [edge for edge in edges if explains(*edge, thirds[edge])]
            if not edges:
                continue
            verdicts = [through(*edge, thirds[edge]) for edge in edges] if through else [None]
            if (
                None in verdicts
            ):  # no test of indirectness: the farthest apart goes, then the weakest
                weakest = min(
                    edges,
                    key=lambda edge: (
                        tuple(-value for value in apart(*edge)) if apart else (),
                        strength[edge],
                    ),
                )
                if not supported(*weakest):
                    indirect.add(weakest)
            else:  # of the pairs found indirect, the least direct; of those about as direct, the farthest apart
                found = [
                    edge
                    for edge, through_third in zip(edges, verdicts, strict=False)
                    if through_third and not supported(*edge)
                ]
                if found and direct and len(found) > 1:
                    directness = {edge: direct(*edge, thirds[edge]) for edge in found}
                    least = min(directness.values())
                    found = [
                        edge for edge in found if directness[edge] <= least + DIRECTNESS_MARGIN
                    ]
                if found:
                    indirect.add(
                        max(
                            found,
                            key=lambda edge: (
                                (*apart(*edge), -strength[edge]) if apart else -strength[edge]
                            ),
                        )
                    )
    return [replace(p, related=False, pruned=True) if (p.a, p.b) in indirect else p for p in pairs]
