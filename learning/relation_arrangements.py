"""Pairs the room fixes, which no test of within- against across-scene poses can see: a
*fixed arrangement* (b stands beside a at one pose in scene after scene, and so does
the b of another scene) and a *surrounding arrangement* (several b's about each a, as
chairs about a dining table, at the same places from scene to scene).
Design notes: docs/notes/design.md, "Relation finding".
"""

from __future__ import annotations

import numpy as np

from scenewright.core.geometry import wrap_angles

from .relation_poses import TypePoses, counterparts, footprint_gaps, nearest_indices, relative_poses
from .relation_thresholds import (
    FIXED_OFFSET,
    FIXED_SHARE,
    FIXED_TURN,
    MAX_SCENES,
    NEXT_TO_DISTANCE,
    PAIR_SCENES,
)


def nearest_next_to(
    first: TypePoses,
    second: TypePoses,
    a_scenes: np.ndarray,
    b_scenes: np.ndarray,
    chosen: np.ndarray,
    same: bool,
    rng: np.random.Generator,
) -> tuple[np.ndarray, np.ndarray]:
    """For the a's ``first.poses[a_scenes, chosen]``: the pose of the nearest b of the
    scene ``b_scenes[k]`` in a's frame (n, 4), and whether it stands next to it (n,)
    (when ``same``, the a's ``counterparts`` are no candidates)."""
    centres = first.poses[a_scenes, chosen]
    left_out = counterparts(second, b_scenes, chosen, rng) if same else None
    index = nearest_indices(centres, second, b_scenes, left_out)
    pose = relative_poses(centres, second.poses[b_scenes, index][:, None])[:, 0]
    next_to = (
        footprint_gaps(pose, first.footprints[a_scenes, chosen], second.footprints[b_scenes, index])
        <= NEXT_TO_DISTANCE
    )
    return pose, next_to


def at_pose(pose: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Whether relative poses (..., 4) stand within ``FIXED_OFFSET`` and ``FIXED_TURN`` of
    ``reference`` poses (broadcast against them)."""
    turn = np.arctan2(pose[..., 3], pose[..., 2]) - np.arctan2(reference[..., 3], reference[..., 2])
    close = (
        np.hypot(pose[..., 0] - reference[..., 0], pose[..., 1] - reference[..., 1]) <= FIXED_OFFSET
    )
    return close & (np.abs(wrap_angles(turn)) <= FIXED_TURN)


def share_at_one_pose(
    first: TypePoses,
    second: TypePoses,
    a_scenes: np.ndarray,
    b_scenes: np.ndarray,
    chosen: np.ndarray,
    same: bool,
    rng: np.random.Generator,
) -> float:
    """The share of the a's ``first.poses[a_scenes, chosen]`` whose nearest b of the scene
    ``b_scenes[k]`` stands next to it and within ``FIXED_OFFSET`` and ``FIXED_TURN`` of the
    median of those poses in a's frame (``nearest_next_to``)."""
    pose, next_to = nearest_next_to(first, second, a_scenes, b_scenes, chosen, same, rng)
    return float(np.mean(at_pose(pose, np.median(pose, axis=0)) & next_to))


def fixed_arrangement(
    first: TypePoses, second: TypePoses, same: bool, together: np.ndarray, rng: np.random.Generator
) -> bool:
    """Whether the pair is a fixed arrangement (design notes) in the scenes
    ``together`` (at most ``MAX_SCENES`` of them, in a random cycle): the b nearest a
    random a stands next to it at one pose in at least ``FIXED_SHARE`` of them, and so
    does the nearest b of the next scene of the cycle (the room fixes both)."""
    scenes = rng.permutation(together)[:MAX_SCENES]
    chosen = np.floor(rng.random(len(scenes)) * first.counts[scenes]).astype(int)
    if share_at_one_pose(first, second, scenes, scenes, chosen, same, rng) < FIXED_SHARE:
        return False
    return (
        share_at_one_pose(first, second, scenes, np.roll(scenes, -1), chosen, same, rng)
        >= FIXED_SHARE
    )


def surrounds(first: TypePoses, second: TypePoses, same: bool, together: np.ndarray) -> bool:
    """Whether an a has two or more b's (besides itself) in at least ``FIXED_SHARE`` of
    the scenes ``together``: chairs around a table, where the b nearest an a is any
    of them."""
    others = second.counts[together] - (1 if same else 0)
    return bool(np.mean(others >= 2) >= FIXED_SHARE)


def share_at_some_pose(
    first: TypePoses,
    second: TypePoses,
    scenes: np.ndarray,
    chosen: np.ndarray,
    same: bool,
    rng: np.random.Generator,
) -> float:
    """The share of the a's ``first.poses[scenes, chosen]`` whose nearest b stands next
    to it and within ``FIXED_OFFSET`` and ``FIXED_TURN`` of where some b stands about the
    a of the next scene (``np.roll(scenes, -1)``, its a ``np.roll(chosen, -1)``), both in
    their a's frame; for one type, an a's counterpart is not its b."""
    pose, next_to = nearest_next_to(first, second, scenes, scenes, chosen, same, rng)
    following, its_a = np.roll(scenes, -1), np.roll(chosen, -1)
    around = relative_poses(first.poses[following, its_a], second.poses[following])  # (n, K, 4)
    valid = np.arange(second.poses.shape[1])[None, :] < second.counts[following][:, None]
    if same:  # the next scene's a is no b about itself
        valid[np.arange(len(scenes)), its_a] = False
    matched = np.any(valid & at_pose(pose[:, None, :], around), axis=1)
    return float(np.mean(matched & next_to))


def surrounding_arrangement(
    first: TypePoses, second: TypePoses, same: bool, together: np.ndarray, rng: np.random.Generator
) -> bool:
    """Whether a's b's stand about it at the same places from scene to scene, with too
    few scenes for the test (design notes, "Chairs around a table"): fewer than
    ``PAIR_SCENES`` scenes, an a surrounded by two or more b's in most (``surrounds``),
    and in at least ``FIXED_SHARE`` of the scenes, in a random cycle, the b nearest a
    random a next to it where some b stands about the next scene's a."""
    if len(together) >= PAIR_SCENES or not surrounds(first, second, same, together):
        return False
    scenes = rng.permutation(together)
    chosen = np.floor(rng.random(len(scenes)) * first.counts[scenes]).astype(int)
    return share_at_some_pose(first, second, scenes, chosen, same, rng) >= FIXED_SHARE
