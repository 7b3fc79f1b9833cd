"""Round trip of composing: a shipped rule set's scene, its full description, the scene
composed from that text, and what of the description holds there.

For each room rule set and seed: generate the scene, describe it (full style), compose
that text (with the rule set's catalog, seed the same), then

- unused: whether composing left any word or phrase unused;
- held: each relation the input description states (its facts), matched to a relation
  of the composed scene between things of the same type and style (or the same wall,
  or the same corner) that holds when the composed layout is measured again from its
  poses (``measure_layout``), not as the compose report says;
- CPU seconds per text for reading and planning (no layout).

The sets are every shipped room rule set (groups included: the classroom's rows of
desks) and the village (roads meeting at intersections, things next to them, groups);
``--sets town`` or ``city`` measure the larger outdoor ones (a town's scene holds about
300 things, a city's 1,100 to 2,200), which take minutes for twenty seeds. Usage:

    python benchmarks/bench_compose.py                    # seeds 1000-1099
    python benchmarks/bench_compose.py --seeds 1000:1020 --sets bedroom,kitchen
    python benchmarks/bench_compose.py --seeds 1000:1010 --sets town
    python benchmarks/bench_compose.py --seeds 1000:1020 --sets city
"""

from __future__ import annotations

import argparse
import math
import time
from collections import Counter

from scenewright.api import build_scene, compose, describe
from scenewright.composer.compose import plan
from scenewright.composer.outdoor import catalog_for
from scenewright.core.relations import RELATIONS
from scenewright.describer.rooms import DOOR_NEAR_CORNER
from scenewright.generator import load_rules
from scenewright.generator.layout.measure import measure_layout
from scenewright.generator.layout.pinning import scene_layout

ROOM_SETS = (
    "bathroom",
    "bedroom",
    "desk",
    "kitchen",
    "living_room",
    "study",
    "classroom",
    "library",
    "hall",
    "corridor",
    "office",
    "meeting_room",
    "treasury",
    "barracks",
    "guard_room",
)
#: Outdoor rule sets measured by default (``--sets town`` adds the town's).
OUTDOOR_SETS = ("village",)
_WALL_LABELS = ("AgainstWall", "InCorner", "UnderWindow", "BesideWindow")


def _corner(scene, obj) -> str:
    """The corner a thing stands in: "by the door" when a door is close (as the
    describer says it), else by its quarter of the room."""
    x, z = obj.position[0], obj.position[2]
    xs = [w.start[0] for w in scene.room.walls]
    zs = [w.start[1] for w in scene.room.walls]
    corner = (max(xs) if x > 0 else min(xs), max(zs) if z > 0 else min(zs))
    for opening in scene.room.openings:
        if opening.kind == "door":
            cx, cz = opening.center
            edge = math.hypot(cx - corner[0], cz - corner[1]) - opening.width / 2
            if edge <= DOOR_NEAR_CORNER:
                return "by the door"
    return ("north" if z < 0 else "south") + "-" + ("west" if x < 0 else "east")


def _said_as(label: str, chosen: str | None) -> str:
    """The label whose words the text uses for ``label``: a label that chooses its
    direction is said in the words of the direction chosen, which are those of one fixed
    label ("is just to the left of": BesideLeft, "is north of": NextToNorth); a seat is
    said in its own words ("The chairs are at the table.")."""
    spec = RELATIONS[label]
    if not (spec.chooses and chosen) or spec.seat:
        return label
    words = spec.wordings_for(chosen)
    return next(
        other.name
        for other in RELATIONS
        if other.described and not other.chooses and other.wordings == words
    )


def _signatures(scene, relations) -> Counter:
    """Each relation as (A's type and style, label, B's type and style, or B's wall, or
    A's corner): what a description can say of it."""
    objects = {o.id: o for o in scene.objects}
    objects.update({p.id: p for p in scene.paths})  # "next to the first road"
    out: Counter = Counter()

    def kind(o) -> tuple[str, str | None]:
        # a composed rule set names a type's second look TYPE_2 (docs/compose.md)
        stem, _, number = o.type.rpartition("_")
        return (stem if number.isdigit() and stem else o.type, getattr(o, "style", None))

    for source, label, target, chosen in relations:
        if label.startswith("Implicit") or source not in objects:
            continue
        label = _said_as(label, chosen)
        a = objects[source]
        what_a = kind(a)
        if label in ("AgainstWall",):
            b = target if target.startswith("wall_") else (chosen or "")
            out[(what_a, label, b)] += 1
        elif label == "InCorner":
            out[(what_a, label, _corner(scene, a))] += 1
        elif label in ("UnderWindow", "BesideWindow"):
            out[(what_a, label, "window")] += 1
        elif target in objects:
            b = objects[target]
            out[(what_a, label, kind(b))] += 1
    return out


def _held(scene) -> Counter:
    poses, points = scene_layout(scene)
    measured = measure_layout(scene.graph(), poses, points)
    return _signatures(
        scene,
        [(r.source, r.label, r.target, r.chosen) for r in measured.relations if r.satisfied],
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="1000:1100", help="FIRST:END (end excluded)")
    parser.add_argument("--sets", default=",".join(ROOM_SETS + OUTDOOR_SETS))
    args = parser.parse_args()
    first, end = (int(v) for v in args.seeds.split(":"))
    totals: Counter = Counter()
    cpu: list[float] = []
    for name in args.sets.split(","):
        rules = load_rules(name)
        entries, prefer, ground = catalog_for("", rules)
        per: Counter = Counter()
        for seed in range(first, end):
            source = build_scene(rules, seed)
            text = describe(source, style="full").text
            stated = _signatures(
                source,
                [
                    (
                        f[0],
                        f[1],
                        f[2],
                        next(
                            (
                                r.chosen
                                for r in source.relations
                                if (r.source, r.label, r.target) == tuple(f)
                            ),
                            None,
                        ),
                    )
                    for f in describe(source, style="full").facts
                ],
            )
            started = time.process_time()
            plan(text, entries, prefer, ground)
            cpu.append(time.process_time() - started)
            composed, report = compose(text, seed, catalog=rules)
            held = _held(composed)
            matched = sum(min(n, held[k]) for k, n in stated.items())
            per["scenes"] += 1
            per["clean"] += not report.unused
            per["stated"] += sum(stated.values())
            per["held"] += matched
            if report.unused or matched < sum(stated.values()):
                missing = stated - held
                print(
                    f"  {name} {seed}: unused {report.messages()[:3]} not held {list(missing)[:3]}"
                )
        totals.update(per)
        print(
            f"{name:12s} scenes {per['scenes']:3d}  no unused span {per['clean'] / per['scenes']:6.1%}"
            f"  relations held {per['held']}/{per['stated']} = {per['held'] / max(per['stated'], 1):6.1%}"
        )
    print(
        f"all          scenes {totals['scenes']:3d}  no unused span {totals['clean'] / totals['scenes']:6.1%}"
        f"  relations held {totals['held']}/{totals['stated']} = {totals['held'] / max(totals['stated'], 1):6.1%}"
    )
    cpu.sort()
    print(
        f"CPU per text for reading and planning: mean {sum(cpu) / len(cpu):.3f} s, "
        f"max {cpu[-1]:.3f} s"
    )


if __name__ == "__main__":
    main()
