"""The command that measures scenes: ``evaluate`` prints SceneEval's four plausibility
metrics (collision, out of bounds, navigability, opening clearance) per scene and over
all of them (``scenewright.generator.scene_metrics``)."""

from __future__ import annotations

import argparse
import json
from functools import partial

from .common import emit, read_scene
from .options import add_command

HELP = {
    "evaluate": """\
examples:
  scenewright evaluate out/scene.json
  scenewright evaluate runs/*/scene.json --json -o metrics.json
  scenewright evaluate completed/scene.json --tolerance 0.02

Per scene: the share of objects in a collision and out of bounds (beyond --tolerance
metres), the share of the free floor in its largest connected part (rooms), and the
doors and windows blocked (rooms); then the same over all scenes. A house is measured
room by room (one row per room, named "PATH ROOM"). Any scene.json:
generated, laid out again, completed, varied or converted from an example.""",
}


def add_commands(commands) -> None:
    """Add the command evaluate to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)
    evaluate = command(
        "evaluate",
        "measure scenes by SceneEval's metrics: collision, out of bounds, navigability, opening clearance",
        run_evaluate,
    )
    evaluate.add_argument("scenes", nargs="+", metavar="SCENE", help="scene.json files")
    evaluate.add_argument(
        "--json", action="store_true", help="print JSON (per scene and the summary)"
    )
    evaluate.add_argument(
        "--tolerance",
        type=_tolerance,
        default=None,
        metavar="M",
        help="depth in metres a collision or a wall crossing may have unseen (0.01)",
    )
    evaluate.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")


def _rooms_of(path: str, scene):
    """The scenes to measure in a scene.json: the scene, or each room of a house (named
    ``PATH ROOM``): a house is measured room by room, as SceneEval measures rooms."""
    if scene.house is None:
        return [(path, scene)]
    from scenewright.house.assemble import room_scene

    return [(f"{path} {room.id}", room_scene(scene, room.id)) for room in scene.house.rooms]


def _tolerance(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"{text} is not between 0 and 1 (metres)")
    return value


def run_evaluate(args: argparse.Namespace) -> int:
    from scenewright.generator.scene_metrics import TOLERANCE, evaluate_scene, summarise

    tolerance = TOLERANCE if args.tolerance is None else args.tolerance
    scenes = [(path, read_scene(path)) for path in args.scenes]  # all read before any output
    results = [
        evaluate_scene(room, name, tolerance)
        for path, scene in scenes
        for name, room in _rooms_of(path, scene)
    ]
    summary = summarise(results)
    if args.json:
        text = json.dumps(
            {
                "tolerance_m": tolerance,
                "scenes": [r.as_dict() for r in results],
                "summary": summary.as_dict(),
            },
            indent=2,
        )
        return emit(args, text + "\n")
    rows = [("scene", "objects", "collision", "out of bounds", "navigability", "doors", "windows")]
    for r in results:
        rows.append(
            (
                r.name,
                str(r.objects),
                f"{100 * r.collision_rate:.1f} %",
                f"{100 * r.out_of_bounds_rate:.1f} %",
                "-" if r.navigability is None else f"{100 * r.navigability:.1f} %",
                f"{len(r.blocked_doors)}/{r.doors} blocked",
                f"{len({w for w, _ in r.blocked_windows})}/{r.windows} blocked",
            )
        )
    rows.append(
        (
            f"all ({summary.scenes})",
            "",
            f"{100 * summary.collision_rate:.1f} %",
            f"{100 * summary.out_of_bounds_rate:.1f} %",
            "-" if summary.navigability is None else f"{100 * summary.navigability:.1f} %",
            f"{summary.blocked_doors}/{summary.doors} blocked",
            f"{summary.blocked_windows}/{summary.windows} blocked",
        )
    )
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = [
        "  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
        for row in rows
    ]
    details = []
    for r in results:
        details += [f"{r.name}: {a} runs {100 * d:.0f} cm into {b}" for a, b, d in r.collisions]
        details += [
            f"{r.name}: {i} is out of bounds by {100 * e:.0f} cm" for i, e in r.out_of_bounds
        ]
        details += [f"{r.name}: {door} is blocked" for door in r.blocked_doors]
        details += [f"{r.name}: {w} is blocked by {by}" for w, by in r.blocked_windows]
    text = "\n".join(lines + ([""] + details if details else [])) + "\n"
    return emit(args, text)
