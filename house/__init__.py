"""Houses: several rooms joined by doors, from a plan in the rules language or a given floor plan.

``house_scene_from`` is the stage's entry: a plan file (``plan NAME { ... }``, read by
``plan_language``) is drawn into room outlines (``floor_plan``), or a given plan
(``given_plan``) supplies them; ``walls`` builds the house (walls, doors, windows, each
room's own room); ``furnish`` lays each room out with its room type's rule set; and
``assemble`` joins them into one scene. ``describe`` writes its text.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from scenewright.core.seeds import check_seed, retry_seed, stream

from .plan_language import is_plan_file, read_plan, shipped_plans

if TYPE_CHECKING:
    from scenewright.core.house import House
    from scenewright.core.scene import Scene

__all__ = ["house_of", "house_scene_from", "is_plan_file", "read_plan", "shipped_plans"]


#: Floor plans a generated house draws before its best is kept. A room that none of its
#: rule set's tries furnishes (a 3 m bedroom whose doors leave no wall long enough for
#: the bed) is seldom a problem of its rule set but of the cut the plan drew, so the
#: whole plan is drawn again (from the seed's ``retry`` children, as a dataset retries a
#: layout); a given plan has only its one floor plan.
PLAN_TRIES = 3
PLAN_RETRY = 200


def house_of(source: str | os.PathLike[str], seed: int) -> House:
    """The floor plan (no furniture) that ``seed`` draws from a plan file, or a given plan as it is."""
    from .floor_plan import generate_outlines
    from .given_plan import is_given_plan, read_given_plan
    from .walls import build_house

    if is_given_plan(source):
        outlines = read_given_plan(source)
    else:
        outlines = generate_outlines(read_plan(source), seed)
    return build_house(outlines, stream(seed, "plan", 1))


def house_scene_from(
    source: str | os.PathLike[str], seed: int, *, workers: int = 1, label: str | None = None
) -> Scene:
    """A furnished house scene (no text yet) from a plan file or a given plan: the first of
    ``PLAN_TRIES`` floor plans whose every room is furnished ok, or else the one with the
    most rooms ok."""
    from pathlib import Path

    from .assemble import house_scene
    from .furnish import furnish
    from .given_plan import is_given_plan

    seed = check_seed(seed)
    name = Path(os.fspath(source)).name.removesuffix(".rules").removesuffix(".json")
    best: Scene | None = None
    best_ok = -1
    for attempt in range(1 if is_given_plan(source) else PLAN_TRIES):
        drawn = retry_seed(seed, PLAN_RETRY + attempt) if attempt else seed
        house = house_of(source, drawn)
        rooms = furnish(house, drawn, workers=workers)
        scene = house_scene(house, rooms, rules=label or os.fspath(source), seed=seed, name=name)
        rooms_ok = sum(room.layout.ok for room in rooms)
        if rooms_ok == len(rooms):
            return scene
        if rooms_ok > best_ok:
            best, best_ok = scene, rooms_ok
    assert best is not None
    return best
