"""Which pairs of object types are spatially related in a set of example scenes.

A type pair (a, b) is *related* when where a b stands relative to an a is not what it
would be if the two were placed independently of each other. ``find_relations(scenes,
test=..., seed=..., alpha=..., prune=...)`` runs one test of ``TESTS`` on every pair of
object types that occur together in some scene, same-type pairs included, and returns a
``RelationsResult``: per pair whether it is related, the test's statistic and p-value,
its strength, and how many poses and scenes it rests on. A pair's random draws come
from its own stream (``pair_stream``), so its verdict depends on nothing but its own
data and the seed.

The tests (``relation_tests``):

- ``permutation`` (the default): the pose of the nearest b in a's frame within one
  scene against the same across two scenes that share the room's frame, by the energy
  distance and a permutation test. Related when p <= ``alpha`` (0.01) and the
  within-scene poses are clearly tighter (``MIN_LOCAL_TIGHTNESS``). A pair held by 20
  scenes or more is tested on random pairs of scenes, by 10 to 19 on two halves, by 5
  to 9 on pairings of whole scenes, and a pair of 3 to 9 scenes this misses once more
  on its poses with either side of a alike (``relation_tests.paired_outcome``); fewer
  than 3: not tested. A pair the room fixes in
  place (``relation_arrangements``) and an object resting on another are related too.
- ``angle``: the test of complete spatial randomness by angles that Zhang et al.
  (IEEE TVCG 2021) use.
- ``cooccurrence``: related when more than half of the scenes hold both types.

Where the scenes have groups (a home, a market stand, a park), the tests run on *roles*,
a type with the kind of group holding it, and a type pair takes the verdict of its most
related pair of roles (``by_type``). Indirect relations (a lamp on a nightstand relates
to the bed only through the nightstand) are pruned for the permutation and angle tests
(``relation_pruning``). The thresholds are in ``relation_thresholds``; why each step is
as it is, with the measurements behind the thresholds, is in the design notes
(docs/notes/design.md, "Relation finding"), whose headings the code's comments cite.
"""

from __future__ import annotations

import functools
import math
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import replace

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene
from scenewright.core.seeds import check_seed

from .relation_poses import Role, holding_both, object_roles, pair_stream, path_poses, type_poses
from .relation_pruning import (
    indirect_through,
    informative_directness,
    prune_indirect,
    resting_pairs,
    third_share,
    typical_gap,
)
from .relation_results import PairRelation, RelationsResult
from .relation_tests import TESTS
from .relation_thresholds import ALPHA


def find_relations(
    scenes: Sequence[Scene],
    *,
    test: str = "permutation",
    seed: int = 0,
    alpha: float = ALPHA,
    prune: bool = True,
) -> RelationsResult:
    """Which object type pairs of ``scenes`` are spatially related, by ``test`` (a name
    of ``TESTS``); ``prune`` removes indirect relations where the test allows it.
    ``InputError`` for fewer than two scenes, an unknown test, or scenes without two
    objects together."""
    if test not in TESTS:
        raise InputError(f"unknown relation test {test!r}; choose one of {', '.join(TESTS)}")
    seed = check_seed(seed)
    if len(scenes) < 2:
        raise InputError(f"finding relations needs at least 2 example scenes, got {len(scenes)}")
    chosen = TESTS[test]
    roles = [object_roles(scene) for scene in scenes]
    role_names = [
        {object_id: role.name for object_id, role in scene_roles.items()} for scene_roles in roles
    ]
    role_of = {role.name: role for scene_roles in roles for role in scene_roles.values()}
    poses = type_poses(scenes, role_names)
    resting = (
        resting_pairs(scenes, poses, role_names)
        if chosen.spares_resting or (prune and chosen.prunes)
        else set()
    )
    # Paths are third types of triangles only: tested with the objects, never reported.
    paths = path_poses(scenes) if prune and chosen.tests_indirect else {}
    poses.update({name: points for name, points in paths.items() if name not in poses})
    names = sorted(poses)
    results = []
    for i, a in enumerate(names):
        for b in names[i:]:
            same = a == b
            if (a in paths and b in paths) or len(holding_both(poses[a], poses[b], same)) == 0:
                continue
            outcome = chosen.outcome(poses[a], poses[b], same, pair_stream(seed, a, b), alpha)
            # One object standing on the other is a relation the boxes show, whatever the
            # test makes of it: the floor on the strength and the level are for
            # dependences the poses alone suggest, which this is not.
            spared = chosen.spares_resting and ((a, b) in resting or (b, a) in resting)
            resting_related = spared and outcome.statistic is not None
            related = outcome.related or resting_related
            results.append(
                PairRelation(
                    a,
                    b,
                    bool(related),
                    outcome.statistic,
                    outcome.p_value,
                    outcome.poses,
                    outcome.scenes,
                    outcome.strength,
                    tested=outcome.statistic is not None,
                    fixed=outcome.fixed and not resting_related,
                )
            )
    if not results:
        raise InputError(
            f"no two objects stand in one scene in any of the {len(scenes)} example scenes"
        )
    if prune and chosen.prunes:
        kinds = {name: role.group for name, role in role_of.items()}
        through = (
            (lambda a, c, b: indirect_through(poses, a, c, b, seed, alpha, kinds))
            if chosen.tests_indirect
            else None
        )
        apart = (
            functools.cache(lambda a, c: typical_gap(poses[a], poses[c], a == c))
            if chosen.tests_indirect
            else None
        )
        direct = (
            # Sides mixed (a plant left of the desk in some rooms, right in others) hide
            # how direct a pair is; either side alike shows it.
            (
                lambda a, c, b: max(
                    informative_directness(poses, a, c, b, seed, kinds),
                    informative_directness(poses, a, c, b, seed, kinds, mirrored=True),
                )
            )
            if chosen.tests_indirect
            else None
        )
        results = prune_indirect(
            results, resting, through, apart, functools.partial(third_share, poses), direct
        )
    results = [pair for pair in results if pair.a not in paths and pair.b not in paths]
    return RelationsResult(test, len(scenes), seed, alpha, tuple(by_type(results, role_of)))


def by_type(pairs: Sequence[PairRelation], role_of: dict[str, Role]) -> list[PairRelation]:
    """The verdicts on pairs of roles (named by ``Role.name``) as verdicts on pairs of
    types, in (a, b) order: each type pair takes the verdict of its most related pair of
    roles (related, else pruned, else tested; then the strongest, then the one held by
    the most scenes), with the groups of those roles."""
    grouped: dict[tuple[str, str], list[tuple[PairRelation, tuple[str, str]]]] = defaultdict(list)
    for pair in pairs:
        first, second = sorted((role_of[pair.a], role_of[pair.b]))
        grouped[(first.type, second.type)].append((pair, (first.group, second.group)))

    def rank(option: tuple[PairRelation, tuple[str, str]]) -> tuple:
        pair = option[0]
        return (
            pair.related,
            pair.pruned,
            pair.tested,
            -math.inf if pair.strength is None else pair.strength,
            pair.scenes,
        )

    return [
        replace(pair, a=a, b=b, groups=groups)
        for (a, b), options in sorted(grouped.items())
        for pair, groups in [max(options, key=rank)]
    ]
