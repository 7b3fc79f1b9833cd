"""Seeded camera views: ranges to draw a camera from, and the search for a view that
shows its target.

``CameraRanges`` holds an azimuth, elevation and distance range and an optional
target; ``aimed_view`` draws a camera from them with a numpy Generator (the scene's
``camera`` stream of the view, ``core.seeds``), renders it, and draws again while the
target shows less than ``min_visible`` of itself, ``tries`` times at most, keeping the
view that showed the most of it. The render's ``camera`` entry then carries ``aim``:
the values drawn, the target, how much of it showed and the tries it took.

- ``azimuth``: degrees round from south (+Z) towards east (+X), as ``camera.AZIMUTH``;
  any range up to a full turn (``0:360``). Default: the automatic view's (35 degrees
  outdoors; in a room the one ``camera.room_azimuth`` picks).
- ``elevation``: degrees above the horizon, 0 to 89. Default: 35 (``camera.ELEVATION``).
- ``distance``: a factor of the distance that just frames the target (1: the target
  fills 90 % of the image's height or width; 2: twice as far), 0.1 to 10. Default 1.
- ``target``: an entity id (``table_1``, a group ``market_stand_1``, a path) or a type
  (``table``: its first instance in the scene), or in a house a room's id or type
  (``bedroom_2``, ``kitchen``: its floor and objects); the camera looks at the centre
  of its box. None: the whole scene (its objects, paths and, in a room, the floor and the walls
  in view). A scene without it is framed whole (``require_target`` makes that an error).

How much of the target shows: the mean visible fraction (``RenderResult.visible``:
occlusion by other entities, out of frame) over its solid objects; for the whole scene,
over every object; for a path or junction, or a group of those only, over them.

In a room any azimuth works: the walls drawn are always those whose inner face turns
towards the camera (``camera.walls_in_view``), so the walls between the camera and the
room are cut away from whichever side it looks, as in the automatic view.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene

from .camera import ELEVATION, Camera, aimed_camera, entity_family, house_room, room_azimuth
from .ground_truth import camera_matrices

if TYPE_CHECKING:
    from .offscreen import Renderer, RenderResult

#: Bounds of each range (inclusive): elevation in degrees, distance as a factor.
ELEVATION_BOUNDS = (0.0, 89.0)
DISTANCE_BOUNDS = (0.1, 10.0)
#: An azimuth range spans at most a full turn.
FULL_TURN = 360.0
#: Views showing less of their target than this are drawn again...
MIN_TARGET_VISIBLE = 0.5
#: ...at most this many times in all per view.
VIEW_TRIES = 8
#: A range of each kind, for error messages.
EXAMPLES = {"azimuth": "0:360", "elevation": "20:60", "distance": "0.8:1.2"}
#: The keys ``generate --camera`` takes (``parse_camera``).
CAMERA_KEYS = ("azimuth", "elevation", "distance", "target")

_NUMBER = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)"


@dataclass(frozen=True)
class CameraRanges:
    """Where a view's camera is drawn from (see the module docstring); each range is
    (low, high) with low <= high, a fixed value being (v, v); None: the default value.

    Invalid values raise ``InputError`` with one line saying which and why.
    """

    azimuth: tuple[float, float] | None = None
    elevation: tuple[float, float] | None = None
    distance: tuple[float, float] | None = None
    target: str | None = None
    min_visible: float = MIN_TARGET_VISIBLE
    tries: int = VIEW_TRIES

    def __post_init__(self) -> None:
        for name, bounds in (
            ("azimuth", None),
            ("elevation", ELEVATION_BOUNDS),
            ("distance", DISTANCE_BOUNDS),
        ):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, checked_range(name, value, bounds))
        if self.target is not None and (
            not isinstance(self.target, str) or not self.target.strip()
        ):
            raise InputError(f"the camera target must be an entity id or type, not {self.target!r}")
        if isinstance(self.min_visible, bool) or not 0.0 <= self.min_visible <= 1.0:
            raise InputError(
                f"the target's visible fraction must be between 0 and 1, not {self.min_visible!r}"
            )
        if (
            isinstance(self.tries, bool)
            or not isinstance(self.tries, int)
            or not 1 <= self.tries <= 100
        ):
            raise InputError(
                f"the tries per view must be a whole number from 1 to 100, not {self.tries!r}"
            )

    def varies(self) -> bool:
        """Whether some range is wider than a point (so two draws may differ)."""
        return any(
            r is not None and r[0] < r[1] for r in (self.azimuth, self.elevation, self.distance)
        )

    def draw(self, rng: np.random.Generator, default_azimuth: float) -> tuple[float, float, float]:
        """Azimuth and elevation (degrees) and distance (factor), each uniform in its
        range. Three numbers are drawn whatever the ranges, so a view's stream is used
        alike by every setting."""
        u = rng.random(3)
        defaults = ((default_azimuth, default_azimuth), (math.degrees(ELEVATION),) * 2, (1.0, 1.0))
        ranges = (self.azimuth, self.elevation, self.distance)
        low_high = [given or default for given, default in zip(ranges, defaults, strict=True)]
        azimuth, elevation, distance = (
            float(lo + k * (hi - lo)) for k, (lo, hi) in zip(u, low_high, strict=True)
        )
        return azimuth, elevation, distance


def checked_range(name: str, value, bounds: tuple[float, float] | None) -> tuple[float, float]:
    """``value`` (low, high) as floats when finite, ordered and within ``bounds`` (an
    azimuth: spanning at most ``FULL_TURN``); else ``InputError``."""
    try:
        low, high = (float(v) for v in value)
    except (TypeError, ValueError):
        raise InputError(
            f"the {name} range must be two numbers (low, high), not {value!r}"
        ) from None
    if not (math.isfinite(low) and math.isfinite(high)):
        raise InputError(f"the {name} range must be finite numbers, not {low:g}:{high:g}")
    if low > high:
        raise InputError(f"the {name} range {low:g}:{high:g} runs backwards; write LOW:HIGH")
    if bounds is None:
        if high - low > FULL_TURN:
            raise InputError(
                f"the azimuth range {low:g}:{high:g} spans more than a full turn (360 degrees)"
            )
    elif low < bounds[0] or high > bounds[1]:
        given = f"{low:g}" if low == high else f"range {low:g}:{high:g}"
        raise InputError(f"the {name} {given} must lie within {bounds[0]:g}:{bounds[1]:g}")
    return low, high


def parse_range(text: str, name: str) -> tuple[float, float]:
    """``A`` (a fixed value) or ``LOW:HIGH``, plain decimal numbers, checked as
    ``checked_range`` does for ``name``; else ``InputError``."""
    match = re.fullmatch(rf"\s*({_NUMBER})\s*(?::\s*({_NUMBER})\s*)?", text)
    if match is None:
        example = EXAMPLES.get(name, "20:60")
        raise InputError(
            f"the {name} must be a number or a range LOW:HIGH such as {example}, not {ascii(text)[:40]}"
        )
    low = float(match[1])
    high = float(match[2]) if match[2] is not None else low
    bounds = {"elevation": ELEVATION_BOUNDS, "distance": DISTANCE_BOUNDS}.get(name)
    return checked_range(name, (low, high), bounds)


def parse_camera(text: str) -> CameraRanges:
    """``generate --camera``'s value: comma-separated ``KEY=VALUE`` with the keys of
    ``CAMERA_KEYS`` (each at most once), e.g. ``azimuth=30,elevation=45,distance=1.2``;
    a number may be a range ``LOW:HIGH``, drawn from the scene's camera stream."""
    settings: dict = {}
    for part in text.split(","):
        key, equals, value = (piece.strip() for piece in part.partition("="))
        if not equals or not key or not value:
            raise InputError(
                f"--camera takes KEY=VALUE pairs separated by commas, not {ascii(part)[:40]}"
            )
        if key not in CAMERA_KEYS:
            raise InputError(
                f"unknown --camera key {ascii(key)[:40]}; choose from {', '.join(CAMERA_KEYS)}"
            )
        if key in settings:
            raise InputError(f"--camera gives {key} twice")
        settings[key] = value if key == "target" else parse_range(value, key)
    return CameraRanges(**settings)


def resolve_target(scene: Scene, name: str | None) -> str | None:
    """The id of the entity ``name`` stands for: itself when an object, group, junction
    or path (or a house's room) has that id, else the first entity of that type, else
    in a house the first room of that type (``bedroom``); None for the whole scene (no
    name, or nothing in the scene by that name)."""
    if name is None:
        return None
    entities = [*scene.objects, *scene.paths]
    if any(e.id == name for e in entities) or house_room(scene, name):
        return name
    found = next((e.id for e in entities if e.type == name), None)
    if found is None and scene.house is not None:
        found = next((room.id for room in scene.house.rooms if room.type == name), None)
    return found


def target_members(scene: Scene, target: str | None) -> list[str]:
    """The drawn entities whose visible fractions say how much of ``target`` shows (see
    the module docstring)."""
    inside = None if target is None else entity_family(scene, target)
    chosen = [e for e in [*scene.objects, *scene.paths] if inside is None or e.id in inside]
    solid = [e.id for e in chosen if getattr(e, "kind", "path") == "object"]
    return solid or [e.id for e in chosen if getattr(e, "kind", "path") != "group"]


def target_visible(result: RenderResult, members: list[str]) -> float:
    """The mean visible fraction of ``members`` in ``result`` (1.0 when there are none:
    nothing can hide an empty scene)."""
    fractions = [result.visible.get(member, 0.0) for member in members]
    return float(np.mean(fractions)) if fractions else 1.0


def aimed_view(
    renderer: Renderer,
    scene: Scene,
    ranges: CameraRanges,
    rng: np.random.Generator,
    *,
    require_target: bool = False,
    normals: bool = False,
) -> RenderResult:
    """The render of the first view drawn from ``ranges`` with ``rng`` that shows at
    least ``ranges.min_visible`` of its target, or after ``ranges.tries`` draws the one
    that showed the most (the first of equals); one draw when no range varies. Its
    ``camera`` entry gets ``aim`` (``aim_record``). With ``require_target`` a target the
    scene lacks is an ``InputError``. ``normals``: as ``Renderer.render``."""
    target = resolve_target(scene, ranges.target)
    if require_target and ranges.target is not None and target is None:
        known = ", ".join(sorted({*(o.id for o in scene.objects), *(p.id for p in scene.paths)}))
        raise InputError(
            f"the scene has no entity or type {ranges.target!r} to aim the camera at; ids: {known}"
        )
    members = target_members(scene, target)
    default_azimuth = math.degrees(room_azimuth(scene.room))
    best: tuple[float, RenderResult, tuple[float, float, float]] | None = None
    tries = ranges.tries if ranges.varies() else 1
    for attempt in range(1, tries + 1):  # noqa: B007 (the attempt kept is reported below)
        azimuth, elevation, distance = drawn = ranges.draw(rng, default_azimuth)
        camera = aimed_camera(
            scene,
            renderer.width,
            renderer.height,
            azimuth=math.radians(azimuth),
            elevation=math.radians(elevation),
            distance=distance,
            target=target,
        )
        result = renderer.render(scene, camera=camera, normals=normals)
        visible = target_visible(result, members)
        if best is None or visible > best[0]:
            best = (visible, result, drawn)
        if visible >= ranges.min_visible:
            break
    visible, result, drawn = best
    result.camera["aim"] = aim_record(drawn, target, visible, attempt)
    return result


def aim_record(
    drawn: tuple[float, float, float], target: str | None, visible: float, tries: int
) -> dict:
    """What a render records of how its camera was drawn (scene.json ``render.camera.aim``,
    a dataset row's ``camera``)."""
    azimuth, elevation, distance = drawn
    return {
        "azimuth": round(azimuth, 6),
        "elevation": round(elevation, 6),
        "distance": round(distance, 6),
        "target": target,
        "target_visible": round(visible, 4),
        "tries": tries,
    }


def camera_column(camera: dict) -> dict:
    """A dataset row's ``camera`` value of a render's camera entry: the intrinsics and
    extrinsics (``Camera.opencv``), K and the extrinsics in the OpenCV and OpenGL
    conventions (``ground_truth.camera_matrices``) and, for a drawn camera, its ``aim``
    values."""
    lens = Camera.from_dict(camera)
    column = lens.opencv()
    column.update(camera_matrices(lens))
    column.update(camera.get("aim", {}))
    return column
