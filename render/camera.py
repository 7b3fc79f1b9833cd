"""Automatic cameras that frame a scene, and the pixel projection they imply.

Pure numpy, no OpenGL: the renderer hands ``Camera.pose`` and the lens to pyrender,
and tests (or dataset tools) use ``Camera.project`` to find where a world point lands
in the image. Two views:

- ``perspective``: a 3/4 view from the south-east, looking down at ``ELEVATION``,
  placed so every framed point lies inside the view frustum (tight fit, then a margin).
  In a room it looks from outside the wall of the room's first door instead (turned
  ``AZIMUTH`` to the right, as the south-east view is turned from the south), so that
  wall is cut away and the far walls, with their windows, face the camera; a room with
  windows but no door is seen from opposite its first window.
  A house (``scene.house``) is seen from the south-east as a scene is, but from
  ``HOUSE_ELEVATION``, steeply, over walls cut low (``render.house_view``): a
  cut-away of the whole floor.
- ``top``: an orthographic view straight down with north (-Z) at the top of the image
  and east (+X) to the right.

``aimed_camera`` is a perspective camera given its direction and distance: it looks
at the centre of a target (an entity, or the whole scene) from any azimuth and
elevation, at a multiple of the distance that just frames the target (``render.views``
draws these from ranges).

``walls_in_view`` is the cut-away rule both views share: a room's walls are drawn
only where their inner face turns towards the viewer (from straight above: all of them,
of which only the tops show), so no wall stands between the camera and the room.

The points framed must be finite and within ``scenewright.core.limits`` (a scene.json
is checked for that when read); a scene built otherwise with a coordinate beyond them
is refused with an ``InputError`` rather than given a camera that cannot see it.

Camera frame as in OpenGL / pyrender: the camera looks along its local -Z, local +Y is
up in the image, local +X is right. Pixel coordinates: u to the right, v down, the
top-left pixel covers [0, 1) x [0, 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.house import House, room_of
from scenewright.core.limits import MAX_COORDINATE, MAX_SIZE
from scenewright.core.room import WALL_THICKNESS, Room, Wall
from scenewright.core.scene import Scene, object_corners

from .house_view import HOUSE_ELEVATION, wall_heights

VIEWS = ("perspective", "top")

#: Vertical field of view of the perspective view (radians).
YFOV = math.radians(45.0)
#: Perspective view direction: the camera sits this far round from south towards east...
AZIMUTH = math.radians(35.0)
#: ...and looks down at this angle above the horizon.
ELEVATION = math.radians(35.0)
#: Fraction of the image the framed points may fill (the rest is breathing room).
FILL = 0.9
#: The perspective camera stays at least this far (metres) in front of every point.
MIN_DISTANCE = 1.0


@dataclass(frozen=True)
class Camera:
    """A camera pose (camera-to-world, 4x4) and lens.

    ``yfov`` is set for perspective cameras, ``xmag``/``ymag`` (half the visible width
    and height in metres) for orthographic ones.
    """

    view: str
    pose: np.ndarray
    width: int
    height: int
    znear: float
    zfar: float
    yfov: float | None = None
    xmag: float | None = None
    ymag: float | None = None

    @property
    def orthographic(self) -> bool:
        return self.yfov is None

    def focal(self) -> float:
        """Perspective focal length in pixels (square pixels)."""
        return (self.height / 2.0) / math.tan(self.yfov / 2.0)

    def intrinsics(self) -> np.ndarray:
        """3x3 matrix K taking camera coordinates (x, y, -z) to pixels (u, v, 1).

        For a perspective camera K is the pinhole matrix (divide by depth); for an
        orthographic one it is affine (metres to pixels, no division).
        """
        cx, cy = self.width / 2.0, self.height / 2.0
        if self.orthographic:
            sx, sy = cx / self.xmag, cy / self.ymag
            return np.array([[sx, 0.0, cx], [0.0, -sy, cy], [0.0, 0.0, 1.0]])
        f = self.focal()
        return np.array([[f, 0.0, cx], [0.0, -f, cy], [0.0, 0.0, 1.0]])

    def extrinsics(self) -> np.ndarray:
        """4x4 world-to-camera matrix (the inverse of ``pose``)."""
        return np.linalg.inv(self.pose)

    def project(self, points) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates (N, 2) and depth along the view axis (N,) of world points."""
        world = np.atleast_2d(np.asarray(points, dtype=float))
        local = (self.extrinsics() @ np.column_stack([world, np.ones(len(world))]).T).T[:, :3]
        depth = -local[:, 2]
        if self.orthographic:
            homogeneous = np.column_stack([local[:, 0], local[:, 1], np.ones(len(local))])
        else:
            homogeneous = (
                np.column_stack([local[:, 0], local[:, 1], np.ones(len(local))]) / depth[:, None]
            )
            homogeneous[:, 2] = 1.0
        pixels = (self.intrinsics() @ homogeneous.T).T[:, :2]
        return pixels, depth

    def opencv(self) -> dict[str, Any]:
        """The camera in the computer-vision convention, as a dataset row records it.

        Axes x right, y down, z forward (OpenCV; the OpenGL frame of ``pose`` with y and
        z flipped). ``world_to_camera`` (4x4, row-major) takes world points to those
        axes; ``fx``, ``fy``, ``cx``, ``cy`` are pixels, the pixel grid as in the module
        docstring. Perspective: ``(u, v) = (fx x / z + cx, fy y / z + cy)``; orthographic
        (``projection`` says which): ``(fx x + cx, fy y + cy)``, fx and fy in pixels per metre.
        """
        k = self.intrinsics()
        flip = np.diag([1.0, -1.0, -1.0, 1.0])  # OpenGL camera axes -> OpenCV's
        world_to_camera = flip @ self.extrinsics()
        return {
            "projection": "orthographic" if self.orthographic else "perspective",
            "width": self.width,
            "height": self.height,
            "fx": round(float(k[0, 0]), 6),
            "fy": round(float(-k[1, 1]), 6),
            "cx": round(float(k[0, 2]), 6),
            "cy": round(float(k[1, 2]), 6),
            "world_to_camera": [[round(float(v), 9) + 0.0 for v in row] for row in world_to_camera],
        }

    def to_dict(self) -> dict[str, Any]:
        """The camera parameters for scene.json's ``render.camera``."""
        data: dict[str, Any] = {"view": self.view, "width": self.width, "height": self.height}
        if self.orthographic:
            data.update(xmag=float(self.xmag), ymag=float(self.ymag))
        else:
            data["yfov"] = float(self.yfov)
        data.update(znear=float(self.znear), zfar=float(self.zfar), pose=self.pose.tolist())
        return data

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Camera:
        """The camera back from ``to_dict`` (e.g. from a scene.json ``render`` entry)."""
        return cls(
            view=data["view"],
            pose=np.asarray(data["pose"], dtype=float),
            width=int(data["width"]),
            height=int(data["height"]),
            znear=float(data["znear"]),
            zfar=float(data["zfar"]),
            yfov=data.get("yfov"),
            xmag=data.get("xmag"),
            ymag=data.get("ymag"),
        )


def scene_points(scene: Scene, towards_viewer=None) -> np.ndarray:
    """World points (N, 3) the camera must keep in frame: object boxes and path edges;
    in a room also its floor's corners and the tops of the walls a viewer looking from
    ``towards_viewer`` sees (``walls_in_view``; None: from straight above, all walls),
    their thickness included."""
    # A group's box is the union of its members, framed through them.
    chunks = [_box_points(obj) for obj in scene.objects if obj.kind != "group"]
    chunks.extend(_ribbon_points(path) for path in scene.paths)
    towards = [0.0, 1.0, 0.0] if towards_viewer is None else towards_viewer
    if scene.room is not None:
        chunks.append(_room_points(scene.room, towards))
    if scene.house is not None:
        chunks.append(_house_points(scene.house, towards))
    if not chunks:  # nothing placed: frame the scene's extent
        w, d = scene.extent
        chunks.append(
            np.array(
                [[-w / 2, 0, -d / 2], [w / 2, 0, -d / 2], [w / 2, 0, d / 2], [-w / 2, 0, d / 2]]
            )
        )
    return np.vstack(chunks)


def entity_points(scene: Scene, entity_id: str) -> np.ndarray:
    """World points (N, 3) of one entity's extent: an object's or junction's box, a
    path's ribbon, a group's members (at any depth), a house's room (its floor and its
    objects). ``KeyError`` for an unknown id."""
    if house_room(scene, entity_id):
        outline = scene.house.room(entity_id).outline  # type: ignore[union-attr]
        floor = np.array([[x, 0.0, z] for x, z in outline], dtype=float)
        inside = entity_family(scene, entity_id)
        boxes = [_box_points(o) for o in scene.objects if o.kind != "group" and o.id in inside]
        return np.vstack([floor, *boxes])
    scene.entity(entity_id)  # raises KeyError for an id the scene lacks
    inside = entity_family(scene, entity_id)
    chunks = [_box_points(o) for o in scene.objects if o.kind != "group" and o.id in inside]
    chunks.extend(_ribbon_points(p) for p in scene.paths if p.id in inside)
    if not chunks:  # an empty group: its own box
        chunks.append(_box_points(scene.object(entity_id)))
    return np.vstack(chunks)


def entity_family(scene: Scene, entity_id: str) -> set[str]:
    """The ids of ``entity_id`` and of the objects, groups, junctions and paths within it
    at any depth (a group's members, their members, ...); of a house's room, its objects."""
    if house_room(scene, entity_id):
        return {o.id for o in scene.objects if room_of(o.id) == entity_id}
    owners = {**{o.id: o.parent for o in scene.objects}, **{p.id: p.parent for p in scene.paths}}
    family = set()
    for item_id in owners:
        owner: str | None = item_id
        while owner is not None and owner != entity_id:
            owner = owners.get(owner)
        if owner == entity_id:
            family.add(item_id)
    return family


def house_room(scene: Scene, name: str) -> bool:
    """Whether ``name`` is the id of a room of the scene's house."""
    return scene.house is not None and any(room.id == name for room in scene.house.rooms)


def _box_points(obj) -> np.ndarray:
    """The 8 corners (8, 3) of an object's box (turned by its yaw)."""
    corners = object_corners([obj])[0]
    bottom, top = obj.position[1], obj.position[1] + obj.size[1]
    return np.vstack(
        [np.column_stack([corners[:, 0], np.full(4, y), corners[:, 1]]) for y in (bottom, top)]
    )


def _ribbon_points(path) -> np.ndarray:
    """Points (4N, 3) round a path's ribbon: its outline lies within half a width of its
    N control points."""
    points = np.asarray(path.points, dtype=float)
    half = path.width / 2.0
    corners = ((-half, -half), (half, -half), (half, half), (-half, half))
    return np.vstack(
        [
            np.column_stack([points[:, 0] + dx, np.zeros(len(points)), points[:, 1] + dz])
            for dx, dz in corners
        ]
    )


def walls_in_view(room: Room, towards_viewer) -> list[Wall]:
    """The walls of ``room`` drawn for a viewer in direction ``towards_viewer`` (a world
    vector from the room to the viewer): those whose inner face turns towards it, the
    far walls, which stand behind the furniture and hide none of it. A viewer straight
    above sees every wall (only their tops, which hide no furniture)."""
    towards = np.asarray(towards_viewer, dtype=float)
    if math.hypot(towards[0], towards[2]) <= 1e-6 * float(
        np.linalg.norm(towards)
    ):  # straight above
        return list(room.walls)
    return [
        wall
        for wall in room.walls
        if wall.normal[0] * towards[0] + wall.normal[1] * towards[2] > 1e-9
    ]


def room_azimuth(room: Room | None) -> float:
    """The perspective view's azimuth (radians round from south towards east, as
    ``AZIMUTH``) for a room: from outside the wall of its first door, turned ``AZIMUTH``
    to the right (or to the left, when that shows more of the windows), so that wall is
    cut away; without a door, from opposite its first window, so the window's wall is
    seen; otherwise (or outdoors) ``AZIMUTH``."""
    if room is None:
        return AZIMUTH
    if room.doors:
        nx, nz = room.part(room.doors[0].wall).normal
        outwards = math.atan2(-nx, -nz)  # through the door's wall
        turns = [outwards + AZIMUTH, outwards - AZIMUTH]
        return max(turns, key=lambda azimuth: _windows_seen(room, azimuth))  # the first wins a tie
    if room.windows:
        nx, nz = room.part(room.windows[0].wall).normal
        return math.atan2(nx, nz) + AZIMUTH  # across the room from the window
    return AZIMUTH


def _windows_seen(room: Room, azimuth: float) -> int:
    """How many windows are in walls a camera at ``azimuth`` sees from inside (the walls
    whose inner face turns towards it; the others are cut away)."""
    towards = view_direction(azimuth)
    return sum(
        1
        for window in room.windows
        if room.part(window.wall).normal[0] * towards[0]
        + room.part(window.wall).normal[1] * towards[2]
        > 1e-9
    )


def view_direction(azimuth: float = AZIMUTH, elevation: float = ELEVATION) -> np.ndarray:
    """Unit vector (3,) from the scene towards a perspective camera: south (+Z) turned
    towards east (+X) by ``azimuth``, raised by ``elevation``."""
    return np.array(
        [
            math.cos(elevation) * math.sin(azimuth),
            math.sin(elevation),
            math.cos(elevation) * math.cos(azimuth),
        ]
    )


def frame_scene(
    scene: Scene, view: str = "perspective", width: int = 640, height: int = 480
) -> Camera:
    """The automatic camera for ``view`` that frames all of ``scene``'s objects and paths
    (and in a room, its floor and the walls the view shows).

    An unknown ``view`` is the user's mistake (a CLI option): ``InputError``, as is a
    point that is not finite or lies beyond the coordinate limit (with the object's size).
    """
    if view not in VIEWS:
        raise InputError(f"unknown view {view!r}; choose one of: {', '.join(VIEWS)}")
    azimuth = room_azimuth(scene.room)
    elevation = ELEVATION if scene.house is None else HOUSE_ELEVATION
    towards = (
        view_direction(azimuth, elevation) if view == "perspective" else np.array([0.0, 1.0, 0.0])
    )
    points = _checked(scene_points(scene, towards))
    if view == "perspective":
        return perspective_camera(points, width, height, azimuth=azimuth, elevation=elevation)
    return top_down_camera(points, width, height)


def _checked(points: np.ndarray) -> np.ndarray:
    """``points`` when finite and within the coordinate limits, else ``InputError``."""
    reach = MAX_COORDINATE + MAX_SIZE
    if not np.isfinite(points).all() or np.abs(points).max() > reach:
        raise InputError(
            f"the scene reaches beyond {reach:g} m from the origin or has coordinates that are "
            "not finite numbers (the limits: docs/limits.md)"
        )
    return points


def aimed_camera(
    scene: Scene,
    width: int,
    height: int,
    *,
    azimuth: float,
    elevation: float,
    distance: float = 1.0,
    target: str | None = None,
    yfov: float = YFOV,
    fill: float = FILL,
) -> Camera:
    """A perspective camera that looks at the centre of ``target`` from ``azimuth`` and
    ``elevation`` (radians, as ``view_direction``), ``distance`` times as far from it as
    the nearest camera on that line that keeps all of the target inside ``fill`` of
    the image (and ``MIN_DISTANCE`` in front of it).

    ``target``: an entity id (``entity_points``; ``KeyError`` if the scene lacks it) or
    None, the whole scene (``scene_points``, a room's walls in view included). The
    centre is the middle of the box round the target's points, and lands in the middle
    of the image. The clipping planes cover the whole scene, whatever the target.
    """
    back = view_direction(azimuth, elevation)
    everything = _checked(scene_points(scene, back))
    framed = everything if target is None else _checked(entity_points(scene, target))
    centre = (framed.min(axis=0) + framed.max(axis=0)) / 2.0
    rotation = _view_rotation(back)
    local = (framed - centre) @ rotation  # camera axes, the centre at the origin
    tan_y = math.tan(yfov / 2.0) * fill
    tan_x = math.tan(yfov / 2.0) * (width / height) * fill
    # A point (x, y, z) is inside the frame when |x| <= tan_x (d - z), |y| <= tan_y (d - z).
    fit = max(
        float(np.max(local[:, 2] + np.abs(local[:, 0]) / tan_x)),
        float(np.max(local[:, 2] + np.abs(local[:, 1]) / tan_y)),
        float(local[:, 2].max()) + MIN_DISTANCE,
    )
    origin = centre + back * fit * distance
    pose = np.eye(4)
    pose[:3, :3] = rotation
    pose[:3, 3] = origin
    znear, zfar = _clip_range((origin - everything) @ back)
    return Camera("perspective", pose, width, height, znear, zfar, yfov=yfov)


def _view_rotation(back: np.ndarray) -> np.ndarray:
    """Camera axes (3, 3) as columns (right, up, back) in world coordinates for a camera
    whose local +Z is ``back`` (it looks along -``back``), level: right is horizontal."""
    right = np.cross([0.0, 1.0, 0.0], back)
    right /= np.linalg.norm(right)
    return np.column_stack([right, np.cross(back, right), back])


def perspective_camera(
    points: np.ndarray,
    width: int,
    height: int,
    *,
    yfov: float = YFOV,
    azimuth: float = AZIMUTH,
    elevation: float = ELEVATION,
    fill: float = FILL,
) -> Camera:
    """A perspective camera looking along a fixed direction, as close as it can get
    while every point stays inside ``fill`` of the image in both directions."""
    back = view_direction(azimuth, elevation)  # from the scene towards the camera
    rotation = _view_rotation(back)  # camera axes in world coordinates

    local = points @ rotation  # points in the camera's axes (camera at origin for now)
    tan_y = math.tan(yfov / 2.0) * fill
    tan_x = math.tan(yfov / 2.0) * (width / height) * fill
    # For each image axis, the camera offset c along it and distance back along +z
    # must satisfy |p_axis - c| <= tan * (z_cam - p_z) for all points; the tightest
    # z_cam is found where the two bounding planes of the frustum meet.
    cx, zx = _fit_axis(local[:, 0], local[:, 2], tan_x)
    cy, zy = _fit_axis(local[:, 1], local[:, 2], tan_y)
    # Stepping back only loosens the fit; a minimum keeps a single tiny object viewable.
    distance = max(zx, zy, float(local[:, 2].max()) + MIN_DISTANCE)
    origin = rotation @ np.array([cx, cy, distance])

    pose = np.eye(4)
    pose[:3, :3] = rotation
    pose[:3, 3] = origin
    depths = (origin - points) @ back
    znear, zfar = _clip_range(depths)
    return Camera("perspective", pose, width, height, znear, zfar, yfov=yfov)


def top_down_camera(points: np.ndarray, width: int, height: int, *, fill: float = FILL) -> Camera:
    """An orthographic camera looking straight down, north (-Z) up, east (+X) right."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre = (lo + hi) / 2.0
    aspect = width / height
    half_x = max((hi[0] - lo[0]) / 2.0, 0.5)
    half_z = max((hi[2] - lo[2]) / 2.0, 0.5)
    xmag = max(half_x, half_z * aspect) / fill
    ymag = xmag / aspect

    height_above = hi[1] + max(xmag, 1.0)
    pose = np.eye(4)
    # Camera +X = east (+X), camera +Y (image up) = north (-Z), camera +Z = up (+Y).
    pose[:3, :3] = np.column_stack([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    pose[:3, 3] = [centre[0], height_above, centre[2]]
    depths = height_above - points[:, 1]
    znear, zfar = _clip_range(np.append(depths, height_above))  # the ground must be in range
    return Camera("top", pose, width, height, znear, zfar, xmag=xmag, ymag=ymag)


def _room_points(room: Room, towards_viewer) -> np.ndarray:
    """(M, 3) points a room adds to the framing: its floor's corners, and a square of
    the wall's thickness round the top of each end of every wall in view."""
    t = WALL_THICKNESS
    floor = np.array([[x, 0.0, z] for x, z in room.corners])
    tops = [
        [x + dx, wall.height, z + dz]
        for wall in walls_in_view(room, towards_viewer)
        for x, z in (wall.start, wall.end)
        for dx in (-t, t)
        for dz in (-t, t)
    ]
    return np.vstack([floor, np.array(tops, dtype=float).reshape(-1, 3)])


def _house_points(house: House, towards_viewer) -> np.ndarray:
    """(M, 3) points a house adds to the framing: its footprint's corners, and a square
    of a wall's thickness round the top of each end of every wall, at the height the
    view draws it (``house_view.wall_heights``)."""
    floor = np.array([[x, 0.0, z] for x, z in house.footprint], dtype=float).reshape(-1, 3)
    tops = [
        [x + dx, height, z + dz]
        for wall, height in zip(house.walls, wall_heights(house, towards_viewer), strict=True)
        for x, z in (wall.start, wall.end)
        for dx in (-wall.thickness, wall.thickness)
        for dz in (-wall.thickness, wall.thickness)
    ]
    return np.vstack([floor, np.array(tops, dtype=float).reshape(-1, 3)])


def _fit_axis(along: np.ndarray, depth: np.ndarray, tan: float) -> tuple[float, float]:
    """Offset and distance of the camera on one image axis (see ``perspective_camera``)."""
    a = float(np.max(depth + along / tan))
    b = float(np.max(depth - along / tan))
    return tan * (a - b) / 2.0, (a + b) / 2.0


def _clip_range(depths: np.ndarray) -> tuple[float, float]:
    """Near and far planes around the framed depths, with room for the ground beyond."""
    nearest, farthest = float(np.min(depths)), float(np.max(depths))
    znear = max(0.05, nearest * 0.5)
    zfar = farthest * 3.0 + 10.0  # the ground plane reaches past the framed points
    return znear, zfar
