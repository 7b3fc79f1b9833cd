"""Referring expressions for a rendered picture, each with a program that picks out its object.

For every object the picture shows well enough (``PictureView.seen``), the first of
these forms that picks out exactly that object among the seen ones:

1. "the tent": the only seen object of its noun;
2. "the sign to the left of the table" (or "to the right of"): the only one of its noun
   on that side of an anchor that is itself the only one of its noun, across the
   picture (box centres, at least ``SIDE_MARGIN`` pixels apart);
3. "the second chair from the left" (or "from the right"): its place among the seen
   objects of its noun, ordered across the picture, when its neighbours in that order
   are at least ``SIDE_MARGIN`` pixels away and the place is at most ``MAX_PLACE``
   (nobody counts to the twelfth chair);
4. "the nearest chair" / "the farthest chair": the one of its noun nearest to (or
   farthest from) the camera by at least ``DEPTH_MARGIN`` metres.

Each expression comes with a functional program in the style of CLEVR (Johnson et al.,
"CLEVR: A Diagnostic Dataset for Compositional Language and Elementary Visual
Reasoning", 2017): a list of steps, each ``{"function", "inputs", "side_inputs"}``
whose ``inputs`` are indices of earlier steps and ``side_inputs`` strings (all
strings, so a table of programs has one type per column). ``execute`` runs a program on the picture's
facts (``PictureFacts``); an expression is kept only when its program, executed, gives
exactly its object: uniqueness is checked by running the program, not assumed.

Functions: ``scene`` (every seen object), ``filter_noun`` (those of a noun), ``unique``
(the one object of a set; an error when there are none or several), ``relate`` (the
objects on a side, "left" or "right", of one object, by at least ``SIDE_MARGIN``),
``nth`` (side inputs [side, k]: the k-th from that side, 1-based; an error when a
neighbour is nearer than ``SIDE_MARGIN``), ``extreme`` ("nearest" or "farthest": the
one nearest or farthest from the camera; an error when the runner-up is within
``DEPTH_MARGIN``), ``intersect``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .english import ordinal_word
from .world import world_of

if TYPE_CHECKING:
    from scenewright.core.scene import Scene
    from scenewright.render.visibility import PictureView

#: Two objects are on different sides of each other in the picture, or in a clear order
#: across it, when their box centres are at least this many pixels apart.
SIDE_MARGIN = 4.0
#: The furthest place in an order across the picture an expression counts to.
MAX_PLACE = 5
#: "The nearest chair": nearer to the camera than every other chair by at least this (metres).
DEPTH_MARGIN = 0.5

Program = list[dict]


class ProgramError(ValueError):
    """A program that does not pick out one object (``unique`` of none or several, an
    order that is not clear)."""


@dataclass(frozen=True)
class Seen:
    """A seen object as programs read it: its noun, box centre across the picture (pixels)
    and depth from the camera (metres)."""

    id: str
    noun: str
    across: float
    depth: float


class PictureFacts:
    """The seen objects of one picture, what programs run on."""

    def __init__(self, objects: list[Seen]) -> None:
        self.objects = {o.id: o for o in objects}

    @classmethod
    def of(cls, scene: Scene, picture: PictureView) -> PictureFacts:
        """The objects (not groups, paths, junctions, doors or windows) the picture shows well enough."""
        world = world_of(scene)
        ids = [i for i, e in world.entities.items() if e.kind == "object" and picture.seen(i)]
        if not ids:
            return cls([])
        _, depths = picture.camera.project(np.stack([picture.centres[i] for i in ids]))
        objects = []
        for entity_id, depth in zip(ids, depths, strict=True):
            x0, _, x1, _ = picture.entities[entity_id].box
            objects.append(Seen(entity_id, world[entity_id].noun, (x0 + x1) / 2.0, float(depth)))
        return cls(objects)


def execute(program: Program, facts: PictureFacts):
    """The result of the program's last step: an object id, or a list of ids for a set.

    Raises ``ProgramError`` when a step cannot pick out what it must."""
    results: list = []
    for step in program:
        inputs = [results[i] for i in step["inputs"]]
        results.append(_STEPS[step["function"]](facts, step["side_inputs"], *inputs))
    return results[-1]


def _scene(facts: PictureFacts, _side: list[str]) -> list[str]:
    return sorted(facts.objects)


def _filter_noun(facts: PictureFacts, side: list[str], found: list[str]) -> list[str]:
    return [i for i in found if facts.objects[i].noun == side[0]]


def _unique(_facts: PictureFacts, _side: list[str], found: list[str]) -> str:
    if len(found) != 1:
        raise ProgramError(f"unique: {len(found)} objects, not one")
    return found[0]


def _relate(facts: PictureFacts, side: list[str], anchor: str) -> list[str]:
    at = facts.objects[anchor].across
    sign = -1.0 if side[0] == "left" else 1.0
    return sorted(i for i, o in facts.objects.items() if i != anchor and sign * (o.across - at) >= SIDE_MARGIN)


def _nth(facts: PictureFacts, side_inputs: list[str], found: list[str]) -> str:
    side, position = side_inputs[0], int(side_inputs[1])
    ordered = sorted(found, key=lambda i: facts.objects[i].across, reverse=side == "right")
    if not 1 <= position <= len(ordered):
        raise ProgramError(f"nth: no {position}th of {len(ordered)}")
    chosen = facts.objects[ordered[position - 1]].across
    neighbours = [ordered[k] for k in (position - 2, position) if 0 <= k < len(ordered)]
    if any(abs(facts.objects[i].across - chosen) < SIDE_MARGIN for i in neighbours):
        raise ProgramError("nth: the order across the picture is not clear")
    return ordered[position - 1]


def _extreme(facts: PictureFacts, side: list[str], found: list[str]) -> str:
    which = side[0]
    ordered = sorted(found, key=lambda i: facts.objects[i].depth, reverse=which == "farthest")
    if not ordered:
        raise ProgramError("extreme: no objects")
    if len(ordered) > 1 and abs(facts.objects[ordered[1]].depth - facts.objects[ordered[0]].depth) < DEPTH_MARGIN:
        raise ProgramError(f"extreme: the {which} is not clear")
    return ordered[0]


def _intersect(_facts: PictureFacts, _side: list[str], first: list[str], second: list[str]) -> list[str]:
    return sorted(set(first) & set(second))


_STEPS = {
    "scene": _scene, "filter_noun": _filter_noun, "unique": _unique, "relate": _relate,
    "nth": _nth, "extreme": _extreme, "intersect": _intersect,
}  # fmt: skip


def referring_expressions(facts: PictureFacts) -> list[dict]:
    """One ``{"text", "id", "program"}`` for each seen object some form picks out, in id
    order; each program, executed on ``facts``, gives its ``id``."""
    found = []
    for entity_id in sorted(facts.objects):
        for text, program in _candidates(facts, entity_id):
            try:
                picked = execute(program, facts)
            except ProgramError:
                continue
            if picked == entity_id:
                found.append({"text": text, "id": entity_id, "program": program})
                break
    return found


def _candidates(facts: PictureFacts, entity_id: str):
    """The forms of the module docstring for one object, in order, as (text, program)."""
    noun = facts.objects[entity_id].noun
    nouns = [o.noun for o in facts.objects.values()]
    yield f"the {noun}", [_step("scene"), _step("filter_noun", noun, 0), _step("unique", None, 1)]
    anchors = sorted(i for i, o in facts.objects.items() if i != entity_id and nouns.count(o.noun) == 1)
    for anchor in anchors:
        anchor_noun = facts.objects[anchor].noun
        for side in ("left", "right"):
            program = [
                _step("scene"), _step("filter_noun", anchor_noun, 0), _step("unique", None, 1),
                _step("relate", side, 2), _step("filter_noun", noun, 3), _step("unique", None, 4),
            ]  # fmt: skip
            yield f"the {noun} to the {side} of the {anchor_noun}", program
    same = sorted((o for o in facts.objects.values() if o.noun == noun), key=lambda o: o.across)
    position = [o.id for o in same].index(entity_id) + 1
    for side, place in (("left", position), ("right", len(same) + 1 - position)):
        if place > MAX_PLACE:
            continue
        program = [_step("scene"), _step("filter_noun", noun, 0), _step("nth", [side, str(place)], 1)]
        yield f"the {ordinal_word(place)} {noun} from the {side}", program
    for which in ("nearest", "farthest"):
        yield f"the {which} {noun}", [_step("scene"), _step("filter_noun", noun, 0), _step("extreme", which, 1)]


def _step(function: str, side=None, *inputs: int) -> dict:
    """A program step; ``side``: its side input (a string) or inputs (a list of strings)."""
    side_inputs = [] if side is None else [side] if isinstance(side, str) else list(side)
    return {"function": function, "inputs": list(inputs), "side_inputs": side_inputs}
