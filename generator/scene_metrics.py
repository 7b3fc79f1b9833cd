"""SceneEval's plausibility metrics for any laid-out scene.

Tam et al., "SceneEval: Evaluating Semantic Coherence in Text-Conditioned 3D Indoor
Scene Synthesis" (WACV 2026), score a scene's physical plausibility by four measures;
this module computes them on a ``Scene`` (generated, imported, completed or varied),
from their definitions, on the scene's boxes:

- **collision**: the objects that run into another object by more than ``tolerance``
  (the depth in metres: the separating translation of the two turned footprints, or
  the vertical overlap where that is smaller, so a lamp on a nightstand is no
  collision); their share of all objects. A floor covering (a ground object at most
  5 cm tall: a rug, a mat) lies under furniture and collides only with another one.
- **out of bounds**: the objects whose footprint crosses the room's walls (outdoors:
  leaves the scene's extent) by more than ``tolerance``; their share.
- **navigability**: of the floor a person can stand on with the furniture in place
  (the room's reachability grid: 0.1 m cells at least 0.3 m from walls and tall ground
  objects, a way 0.6 m wide), the share in its largest connected part. 1 when the
  floor is one piece; lower when furniture cuts a part of the room off.
- **opening clearance**: each door whose swing holds a tall object by more than
  ``tolerance`` or whose doorway reaches no free floor is blocked; each window with a
  ground object before it (in the strip as wide as the window and 0.5 m deep) whose
  top rises more than 0.3 m above the sill is blocked (a desk under it is fine, a
  bookshelf is not).

Navigability and opening clearance are room measures: outdoors they are None. Where
our reading differs from the paper's (it samples meshes; we measure the boxes the
layout placed, and its robot is ours, a person 0.6 m wide) is said in docs/cli.md (evaluate).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from scenewright.core.geometry import Rect, corners, make_rect, rect_penetration
from scenewright.core.scene import Scene, SceneObject

from .layout.problem import FLAT_HEIGHT
from .layout.reachability import access_grid, floor_verdict
from .layout.room_zones import WINDOW_VIEW_MARGIN, swing_rect, view_rect

#: Depth (metres) two boxes, or a box and a wall, may run into each other unseen.
TOLERANCE = 0.01

#: The metrics, in the order they are printed.
METRICS = ("collision", "out_of_bounds", "navigability", "opening_clearance")


@dataclass
class SceneMetrics:
    """SceneEval's four measures of one scene (see the module docstring)."""

    name: str
    objects: int
    colliding: list[str] = field(default_factory=list)  # ids in a collision
    collisions: list[tuple[str, str, float]] = field(default_factory=list)  # pairs, depth (m)
    out_of_bounds: list[tuple[str, float]] = field(default_factory=list)  # id, excess (m)
    navigability: float | None = None  # share of the free floor in its largest part
    doors: int = 0
    blocked_doors: list[str] = field(default_factory=list)
    windows: int = 0
    blocked_windows: list[tuple[str, str]] = field(default_factory=list)  # window, by

    @property
    def collision_rate(self) -> float:
        return len(self.colliding) / self.objects if self.objects else 0.0

    @property
    def out_of_bounds_rate(self) -> float:
        return len(self.out_of_bounds) / self.objects if self.objects else 0.0

    def as_dict(self) -> dict:
        return {
            "scene": self.name,
            "objects": self.objects,
            "collision": {
                "rate": round(self.collision_rate, 6),
                "objects": self.colliding,
                "pairs": [
                    {"a": a, "b": b, "depth_m": round(depth, 4)} for a, b, depth in self.collisions
                ],
            },
            "out_of_bounds": {
                "rate": round(self.out_of_bounds_rate, 6),
                "objects": [{"id": i, "excess_m": round(e, 4)} for i, e in self.out_of_bounds],
            },
            "navigability": None if self.navigability is None else round(self.navigability, 6),
            "opening_clearance": {
                "doors": self.doors,
                "blocked_doors": self.blocked_doors,
                "windows": self.windows,
                "blocked_windows": [{"window": w, "by": by} for w, by in self.blocked_windows],
            },
        }


def _footprint(obj: SceneObject) -> Rect:
    return make_rect(obj.position[0], obj.position[2], obj.size[0], obj.size[2], obj.yaw)


def _covering(obj: SceneObject) -> bool:
    return obj.position[1] <= TOLERANCE and obj.size[1] <= FLAT_HEIGHT


def _tall_ground(obj: SceneObject) -> bool:
    return obj.position[1] <= TOLERANCE and obj.size[1] > FLAT_HEIGHT


def penetration(first: SceneObject, second: SceneObject) -> float:
    """How far (metres) two objects run into each other (see ``collision`` above)."""
    if _covering(first) != _covering(second):
        return 0.0
    planar = rect_penetration(_footprint(first), _footprint(second))
    if planar <= 0.0:
        return 0.0
    vertical = min(first.position[1] + first.size[1], second.position[1] + second.size[1]) - max(
        first.position[1], second.position[1]
    )
    return max(0.0, min(planar, vertical))


def evaluate_scene(scene: Scene, name: str = "", tolerance: float = TOLERANCE) -> SceneMetrics:
    """The four measures of one scene."""
    objects = [o for o in scene.objects if o.kind == "object"]
    result = SceneMetrics(name or scene.name, len(objects))
    colliding: set[str] = set()
    for i, first in enumerate(objects):
        for second in objects[i + 1 :]:
            depth = penetration(first, second)
            if depth > tolerance:
                result.collisions.append((first.id, second.id, depth))
                colliding.update((first.id, second.id))
    result.colliding = [o.id for o in objects if o.id in colliding]
    room = scene.room
    for obj in objects:
        rect = _footprint(obj)
        if room is not None:
            excess = room.footprint_excess(corners(rect))
        else:
            half_x, half_z = scene.extent[0] / 2.0, scene.extent[1] / 2.0
            excess = max(max(abs(x) - half_x, abs(z) - half_z, 0.0) for x, z in corners(rect))
        if excess > tolerance:
            result.out_of_bounds.append((obj.id, excess))
    if room is not None:
        _room_measures(scene, objects, result, tolerance)
    return result


def _room_measures(
    scene: Scene, objects: list[SceneObject], result: SceneMetrics, tolerance: float
) -> None:
    room = scene.room
    assert room is not None
    grid = access_grid(room)
    tall = [o for o in objects if _tall_ground(o)]
    used = 0
    for obj in tall:
        used |= grid.obstacle(_footprint(obj)).bits
    # The free floor's largest part, and the doors whose doorway (a person's centre within
    # reach of the opening) reaches none of it: a door into a pocket furniture walls off.
    verdict = floor_verdict(grid, grid.static & ~used)
    result.navigability = verdict.navigability
    result.doors, result.windows = len(room.doors), len(room.windows)
    for k, door in enumerate(room.doors):
        swing = swing_rect(room, door)
        if k in verdict.cut_doors or any(
            rect_penetration(swing, _footprint(o)) > tolerance for o in tall
        ):
            result.blocked_doors.append(door.id)
    for window in room.windows:
        view = view_rect(room, window)
        for obj in tall:
            top = obj.position[1] + obj.size[1]
            if top > window.sill + WINDOW_VIEW_MARGIN and (
                rect_penetration(view, _footprint(obj)) > tolerance
            ):
                result.blocked_windows.append((window.id, obj.id))
                break


@dataclass
class Summary:
    """The measures over several scenes."""

    scenes: int
    collision_rate: float  # mean over scenes of the share of objects in a collision
    scenes_with_collision: int
    out_of_bounds_rate: float
    scenes_out_of_bounds: int
    navigability: float | None  # mean over the room scenes
    doors: int
    blocked_doors: int
    windows: int
    blocked_windows: int

    def as_dict(self) -> dict:
        return {
            "scenes": self.scenes,
            "collision_rate": round(self.collision_rate, 6),
            "scenes_with_collision": self.scenes_with_collision,
            "out_of_bounds_rate": round(self.out_of_bounds_rate, 6),
            "scenes_out_of_bounds": self.scenes_out_of_bounds,
            "navigability": None if self.navigability is None else round(self.navigability, 6),
            "doors": self.doors,
            "blocked_doors": self.blocked_doors,
            "windows": self.windows,
            "blocked_windows": self.blocked_windows,
        }


def summarise(results: list[SceneMetrics]) -> Summary:
    """The measures aggregated as SceneEval reports them: rates averaged over scenes."""
    n = len(results) or 1
    navigable = [r.navigability for r in results if r.navigability is not None]
    return Summary(
        scenes=len(results),
        collision_rate=sum(r.collision_rate for r in results) / n,
        scenes_with_collision=sum(bool(r.colliding) for r in results),
        out_of_bounds_rate=sum(r.out_of_bounds_rate for r in results) / n,
        scenes_out_of_bounds=sum(bool(r.out_of_bounds) for r in results),
        navigability=sum(navigable) / len(navigable) if navigable else None,
        doors=sum(r.doors for r in results),
        blocked_doors=sum(len(r.blocked_doors) for r in results),
        windows=sum(r.windows for r in results),
        blocked_windows=sum(len({w for w, _ in r.blocked_windows}) for r in results),
    )
