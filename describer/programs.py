"""Functional programs over the objects of one rendered picture, and the executor that runs them.

A program is a list of steps in the style of CLEVR (Johnson et al., "CLEVR: A
Diagnostic Dataset for Compositional Language and Elementary Visual Reasoning", 2017,
as its public release writes them): each step is ``{"function", "inputs",
"value_inputs"}``, ``inputs`` the indices of earlier steps whose results it takes,
``value_inputs`` strings (all strings, so a table of programs has one type per
column). ``execute`` runs a program on the picture's facts (``PictureFacts``: the
objects the picture shows well enough, ``PictureView.seen``); referring expressions
(``refexp``) and questions (``questions``) are both checked by running their programs
here, never by trusting how they were made.

Functions, by what they give (``FUNCTIONS``):

- a set of objects (ids, sorted): ``scene`` (every seen object), ``filter_noun``
  ([noun]: those of that noun), ``relate`` ([side]: the objects on that side of one
  object: "left" / "right" across the picture, box centres at least ``SIDE_MARGIN``
  pixels apart; "front" / "behind" nearer to / farther from the camera by at least
  ``DEPTH_MARGIN`` metres), ``intersect``;
- one object: ``unique`` (the one object of a set; an error for none or several),
  ``nth`` ([side, k]: the k-th from that side, 1-based; an error when a neighbour is
  nearer than ``SIDE_MARGIN``), ``extreme`` (["nearest"] or ["farthest"]: from the
  camera; an error when the runner-up is within ``DEPTH_MARGIN``);
- a number: ``count``; a yes or no: ``exist``, ``greater_than``, ``less_than``,
  ``equal_integer`` (of two counts);
- a word: ``query_noun`` (an object's noun), ``query_colour`` (its colour word,
  ``colours.colour_word``; an error when its colour has no clear name).

``answer_text`` writes a result as a question's answer: "yes" / "no", a count in
digits, a word.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .colours import colour_word
from .errors import ProgramError
from .world import world_of

if TYPE_CHECKING:
    from scenewright.core.scene import Scene
    from scenewright.render.visibility import PictureView

#: Two objects are on different sides of each other in the picture, or in a clear order
#: across it, when their box centres are at least this many pixels apart.
SIDE_MARGIN = 4.0
#: In front of / behind, nearest / farthest: nearer to the camera by at least this (metres).
DEPTH_MARGIN = 0.5

Program = list[dict]


@dataclass(frozen=True)
class Seen:
    """An object as programs read it: its noun, box centre across the picture (pixels),
    depth from the camera (metres) and colour word (None: no clear name)."""

    id: str
    noun: str
    across: float
    depth: float
    colour: str | None = None


class PictureFacts:
    """The objects of one picture, what programs run on: ``objects``, those it shows well
    enough (what programs see), and ``glimpsed``, those it shows some of but not enough
    (programs never see them; a question about them would be unclear to a person)."""

    def __init__(self, objects: Sequence[Seen], glimpsed: Sequence[Seen] = ()) -> None:
        self.objects = {o.id: o for o in objects}
        self.glimpsed = {o.id: o for o in glimpsed}

    @classmethod
    def of(cls, scene: Scene, picture: PictureView) -> PictureFacts:
        """The objects (not groups, paths, junctions, doors or windows) the picture shows
        well enough, and those it shows only some pixels of."""
        world = world_of(scene)
        drawn = [
            i
            for i, e in world.entities.items()
            if e.kind == "object" and i in picture.entities and picture.entities[i].box is not None
        ]
        if not drawn:
            return cls([])
        _, depths = picture.camera.project(np.stack([picture.centres[i] for i in drawn]))
        seen: list[Seen] = []
        glimpsed: list[Seen] = []
        for entity_id, depth in zip(drawn, depths, strict=True):
            box = picture.entities[entity_id].box
            assert box is not None  # drawn: only entities with a box
            x0, _, x1, _ = box
            colour = colour_word(scene.object(entity_id).colour)
            fact = Seen(entity_id, world[entity_id].noun, (x0 + x1) / 2.0, float(depth), colour)
            (seen if picture.seen(entity_id) else glimpsed).append(fact)
        return cls(seen, glimpsed)


def execute(program: Program, facts: PictureFacts):
    """The result of the program's last step: an object id, a sorted list of ids for a
    set, an int, a bool or a word.

    Raises ``ProgramError`` when a step cannot give what it must."""
    results: list = []
    for step in program:
        inputs = [results[i] for i in step["inputs"]]
        results.append(FUNCTIONS[step["function"]](facts, step["value_inputs"], *inputs))
    return results[-1]


def answer_text(result) -> str:
    """A program's result as a question's answer: "yes" / "no", digits, or the word."""
    if isinstance(result, bool):
        return "yes" if result else "no"
    if isinstance(result, int):
        return str(result)
    if isinstance(result, str):
        return result
    raise ProgramError(f"a program giving {type(result).__name__} does not answer a question")


def step(function: str, values=None, *inputs: int) -> dict:
    """A program step; ``values``: its one value input (a string) or several (a list)."""
    value_inputs = [] if values is None else [values] if isinstance(values, str) else list(values)
    return {"function": function, "inputs": list(inputs), "value_inputs": value_inputs}


def _scene(facts: PictureFacts, _values: list[str]) -> list[str]:
    return sorted(facts.objects)


def _filter_noun(facts: PictureFacts, values: list[str], found: list[str]) -> list[str]:
    return [i for i in found if facts.objects[i].noun == values[0]]


def _unique(_facts: PictureFacts, _values: list[str], found: list[str]) -> str:
    if len(found) != 1:
        raise ProgramError(f"unique: {len(found)} objects, not one")
    return found[0]


#: For each side ``relate`` knows: which measure it compares and the sign of "on that side".
RELATE_SIDES = {
    "left": ("across", -1.0),
    "right": ("across", 1.0),
    "front": ("depth", -1.0),
    "behind": ("depth", 1.0),
}
#: The margin of each measure.
MARGINS = {"across": SIDE_MARGIN, "depth": DEPTH_MARGIN}


def _relate(facts: PictureFacts, values: list[str], anchor: str) -> list[str]:
    measure, sign = RELATE_SIDES[values[0]]
    at = getattr(facts.objects[anchor], measure)
    return sorted(
        i
        for i, o in facts.objects.items()
        if i != anchor and sign * (getattr(o, measure) - at) >= MARGINS[measure]
    )


def _nth(facts: PictureFacts, values: list[str], found: list[str]) -> str:
    side, position = values[0], int(values[1])
    ordered = sorted(found, key=lambda i: facts.objects[i].across, reverse=side == "right")
    if not 1 <= position <= len(ordered):
        raise ProgramError(f"nth: no {position}th of {len(ordered)}")
    chosen = facts.objects[ordered[position - 1]].across
    neighbours = [ordered[k] for k in (position - 2, position) if 0 <= k < len(ordered)]
    if any(abs(facts.objects[i].across - chosen) < SIDE_MARGIN for i in neighbours):
        raise ProgramError("nth: the order across the picture is not clear")
    return ordered[position - 1]


def _extreme(facts: PictureFacts, values: list[str], found: list[str]) -> str:
    which = values[0]
    ordered = sorted(found, key=lambda i: facts.objects[i].depth, reverse=which == "farthest")
    if not ordered:
        raise ProgramError("extreme: no objects")
    if (
        len(ordered) > 1
        and abs(facts.objects[ordered[1]].depth - facts.objects[ordered[0]].depth) < DEPTH_MARGIN
    ):
        raise ProgramError(f"extreme: the {which} is not clear")
    return ordered[0]


def _intersect(
    _facts: PictureFacts, _values: list[str], first: list[str], second: list[str]
) -> list[str]:
    return sorted(set(first) & set(second))


def _count(_facts: PictureFacts, _values: list[str], found: list[str]) -> int:
    return len(found)


def _exist(_facts: PictureFacts, _values: list[str], found: list[str]) -> bool:
    return bool(found)


def _greater_than(_facts: PictureFacts, _values: list[str], first: int, second: int) -> bool:
    return first > second


def _less_than(_facts: PictureFacts, _values: list[str], first: int, second: int) -> bool:
    return first < second


def _equal_integer(_facts: PictureFacts, _values: list[str], first: int, second: int) -> bool:
    return first == second


def _query_noun(facts: PictureFacts, _values: list[str], found: str) -> str:
    return facts.objects[found].noun


def _query_colour(facts: PictureFacts, _values: list[str], found: str) -> str:
    colour = facts.objects[found].colour
    if colour is None:
        raise ProgramError(f"query_colour: {found}'s colour has no clear name")
    return colour


#: Every function a program may call, by name (each takes the facts, the step's value
#: inputs and the results of its inputs).
FUNCTIONS: dict[str, Callable[..., Any]] = {
    "scene": _scene,
    "filter_noun": _filter_noun,
    "unique": _unique,
    "relate": _relate,
    "nth": _nth,
    "extreme": _extreme,
    "intersect": _intersect,
    "count": _count,
    "exist": _exist,
    "greater_than": _greater_than,
    "less_than": _less_than,
    "equal_integer": _equal_integer,
    "query_noun": _query_noun,
    "query_colour": _query_colour,
}
