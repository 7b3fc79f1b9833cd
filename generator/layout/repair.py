"""Restarts that keep what was fine: a failed chain's layout, its troubled items placed anew.

A chain that ends not ok has usually settled all but one or two items: a smithy that
cannot get beside its tower, a bucket off the well's rim. A fresh chain would redo the
whole scene and may fail elsewhere. ``repair_pins(problem, run, pins)`` instead gives
the next chain a warm start (``pinning``): every box at its pose in ``run`` except the
*troubled items*, which the constructive placement puts anew around the rest, and every
path at its points (they may still move).

The troubled items are the top-level items (a group, or a free object with what rests
on it) holding a box of an unsatisfied relation's either end, or a box that overlaps
something or sticks out of the extent (``Energy.troubled_boxes``). Taking both ends of a
relation frees the spot the relation wants: a tower the smithy must be beside is placed
anew together with the smithy.
"""

from __future__ import annotations

from dataclasses import replace

from scenewright.core.poses import Pose

from .pinning import Pins
from .problem import Problem
from .sampler import Run


def item_boxes(problem: Problem) -> list[tuple[int, ...]]:
    """For every box, the boxes of the top-level item it belongs to (itself and what
    rests on it for a free object; all members for a box in a top-level group; a
    junction alone)."""
    items: list[tuple[int, ...]] = [(box,) for box in range(problem.n_boxes)]
    for group in problem.top_groups:
        for box in problem.group_members[group]:
            items[box] = problem.group_members[group]
    in_group = {box for group in problem.top_groups for box in problem.group_members[group]}
    for box in range(problem.n_boxes):
        if box not in in_group and not problem.is_junction[box]:
            beneath = problem.beneath(box)
            root = beneath[-1] if beneath else box
            items[box] = items[root] if root in in_group else tuple(problem.carried(root))
    return items


def troubled_items(problem: Problem, run: Run) -> set[int]:
    """The boxes of every troubled item of a finished chain (module docstring)."""
    troubled = set(run.energy.troubled_boxes())
    for (_, _, _, index), relation in zip(problem.edges, run.relations, strict=False):
        if index is not None and not relation.satisfied:
            term = problem.relations[index]
            troubled.update(term.a.members + term.b.members)
    items = item_boxes(problem)
    return {box for start in troubled for box in items[start]}


def repair_pins(problem: Problem, run: Run, pins: Pins) -> Pins:
    """``pins`` with a warm start from ``run``: every box but the troubled items' at its
    pose there (pinned ones stay pinned), every free path at its points."""
    state = run.energy.state
    again = troubled_items(problem, run)
    start_poses = {
        box: Pose(state.x[box], state.y[box], state.z[box], state.yaw[box])
        for box in range(problem.n_boxes)
        if box not in again and not pins.box[box]
    }
    start_points = {
        path: [list(point) for point in state.points[path]]
        for path in range(problem.n_paths)
        if not pins.path[path]
    }
    return replace(pins, start_poses=start_poses, start_points=start_points)
