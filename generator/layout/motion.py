"""Rigid motions of boxes and the cheap random draws that placement and moves share.

A proposal moves boxes rigidly (``rigid``): whatever rests on a moved box moves with it
(``carried_by``). ``reach`` and ``end_reach`` say how far a footprint reaches in a
direction, so a placement can leave a given gap. ``uniform`` and ``draw_index`` draw
the numbers numpy's ``Generator.uniform`` and ``integers`` would, at less cost per call.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .relation_terms import centre
from .state import State
from .terms import Endpoint

if TYPE_CHECKING:  # the problem's compiler reads the families, which move boxes by these
    from .problem import Problem

HALF_PI = math.pi / 2.0


def wrap(angle: float) -> float:
    """The angle in [-pi, pi)."""
    return angle - 2.0 * math.pi * math.floor((angle + math.pi) / (2.0 * math.pi))


def rigid(
    state: State,
    boxes: list[int],
    pivot: tuple[float, float],
    turn: float,
    shift: tuple[float, float],
) -> dict:
    """New poses of ``boxes`` turned by ``turn`` about ``pivot`` then shifted."""
    if turn == 0.0:  # exact translation, so the energy can see that nothing turned
        return {
            box: (state.x[box] + shift[0], state.z[box] + shift[1], state.yaw[box]) for box in boxes
        }
    c, s = math.cos(turn), math.sin(turn)
    px, pz = pivot
    moved = {}
    for box in boxes:
        rx, rz = state.x[box] - px, state.z[box] - pz
        moved[box] = (
            px + rx * c + rz * s + shift[0],
            pz - rx * s + rz * c + shift[1],
            wrap(state.yaw[box] + turn),
        )
    return moved


def carried_by(problem: Problem, boxes) -> list[int]:
    """The boxes plus everything stacked on them, each once, in a fixed order."""
    found: list[int] = []
    for box in boxes:
        for item in problem.carried(box):
            if item not in found:
                found.append(item)
    return found


def reach(problem: Problem, state: State, box: int, wx: float, wz: float) -> float:
    """How far a box's footprint reaches from its centre along the unit direction (wx, wz)."""
    c, s = state.c[box], state.s[box]
    return problem.half_width[box] * abs(c * wx - s * wz) + problem.half_depth[box] * abs(
        s * wx + c * wz
    )


def end_reach(problem: Problem, state: State, end: Endpoint, wx: float, wz: float) -> float:
    """How far an object or group reaches from its centre along (wx, wz)."""
    if end.kind == "object":
        return reach(problem, state, end.index, wx, wz)
    cx, cz = centre(end, state)
    return max(
        (state.x[b] - cx) * wx + (state.z[b] - cz) * wz + reach(problem, state, b, wx, wz)
        for b in end.members
    )


def uniform(rng: np.random.Generator, low: float, high: float) -> float:
    """The number ``rng.uniform(low, high)`` draws, without its cost per call: numpy's
    ``Generator.uniform`` is low + (high - low) times one standard uniform draw, the one
    ``rng.random()`` makes (``tests/test_layout_shortcuts.py`` holds them equal). A range it
    refuses (high below low, or not finite) is left to it, so that it raises as ever."""
    span = high - low
    if 0.0 <= span < math.inf and math.copysign(1.0, span) > 0.0:
        return low + span * rng.random()
    return rng.uniform(low, high)


def draw_index(rng: np.random.Generator, count: int) -> int:
    """A uniform index below ``count``, the one ``int(rng.integers(count))`` draws: for a
    count of 1 numpy returns 0 without drawing, so no call is made (it costs microseconds,
    and many picks are from one thing: a group's one anchor, a road's one junction)."""
    return 0 if count == 1 else int(rng.integers(count))


def log_uniform(rng: np.random.Generator, low: float, high: float) -> float:
    """A number drawn evenly on a log scale between ``low`` and ``high``."""
    return math.exp(uniform(rng, math.log(low), math.log(high)))
