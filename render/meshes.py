"""Triangle meshes for a scene: one per object, a ribbon per path, the ground.

Objects are built in their local frame by the procedural builder their ``shape`` names
(``scenewright.render.builders``), or loaded from the user's mesh file, and always
fitted exactly to the catalog size, so what is drawn is the box the layout placed. A
shape with no builder (``validate`` warns about it) is drawn as a plain box of the
object's size and colour, still exactly the volume the layout reasoned about. A mesh
file is read by ``scenewright.core.shapes.load_mesh_file``, as ``validate`` reads it:
one that has become unreadable since raises its ``MeshFileError``, an input error.
``object_transform`` gives the local-to-world pose. Rooms (``scene.walls``) get the
walls a camera sees from inside (``room_walls``). Everything is in metres, +Y up.
A size beyond ``scenewright.core.limits.MAX_SIZE`` (or not a finite number) is refused
with an ``InputError`` before anything is built; within it, a builder's detail does not
grow with the size.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import trimesh

from scenewright.core.errors import InputError
from scenewright.core.frames import transform_matrix
from scenewright.core.limits import MAX_SIZE
from scenewright.core.scene import Scene, SceneObject, ScenePath
from scenewright.core.shapes import DEFAULT_SHAPE, load_mesh_file

from .builders import BUILDERS, block, coloured

#: Roads sit this far above the ground so they do not z-fight with it.
PATH_LIFT = 0.02
#: Junction discs sit above the path ribbons that start at them.
JUNCTION_LIFT = 0.03
#: A room's walls: height and thickness (metres) and a plaster colour that sets the
#: furniture off. They stand just outside the extent, so the floor the layout used is clear.
WALL_HEIGHT = 2.4
WALL_THICKNESS = 0.1
WALL_COLOUR = (0.86, 0.83, 0.76)


def object_mesh(obj: SceneObject) -> trimesh.Trimesh:
    """The object's mesh in its local frame, fitted to ``obj.size`` (base centre at 0)."""
    return shaped_mesh(obj.shape, obj.mesh, tuple(obj.size), tuple(obj.colour))


def shaped_mesh(shape: str | None, mesh_file: str | None, size: tuple, colour: tuple) -> trimesh.Trimesh:
    """A mesh from a builder name or a user mesh file, fitted to ``size``: everything
    an object's look depends on, so callers can cache by these arguments."""
    if not all(math.isfinite(side) and 0 <= side <= MAX_SIZE for side in size):
        raise InputError(f"object size {list(size)} is not within 0..{MAX_SIZE:g} m on each side "
                         "(the limits: docs/limits.md)")
    if mesh_file:
        mesh = _load_user_mesh(mesh_file).copy()
        mesh = coloured(mesh, colour) if not _has_colours(mesh) else mesh
    else:
        build = BUILDERS.get(shape or DEFAULT_SHAPE, BUILDERS[DEFAULT_SHAPE])  # unknown shape: its box
        mesh = build(size, colour)
    return fit_to_size(mesh, size)


def object_transform(obj: SceneObject) -> np.ndarray:
    """4x4 local-to-world matrix: yaw about +Y, then the base centre."""
    return transform_matrix(*obj.position, obj.yaw)


def fit_to_size(mesh: trimesh.Trimesh, size) -> trimesh.Trimesh:
    """Scale and move ``mesh`` so its bounds are exactly ``size`` with base centre at 0."""
    lo, hi = mesh.bounds
    extents = np.maximum(hi - lo, 1e-9)
    target = np.maximum(np.asarray(size, dtype=float), 1e-3)
    fitted = mesh.copy()
    fitted.apply_translation(-np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2]))
    fitted.apply_transform(np.diag(np.append(target / extents, 1.0)))
    return fitted


def path_mesh(path: ScenePath) -> trimesh.Trimesh:
    """A flat ribbon of the path's width along its control points, just above the ground."""
    points = np.asarray(path.points, dtype=float)
    half = path.width / 2.0
    pieces = []
    for a, b in zip(points[:-1], points[1:]):
        direction = b - a
        length = float(np.hypot(*direction))
        if length < 1e-9:
            continue
        normal = np.array([-direction[1], direction[0]]) / length * half
        quad = np.array([a + normal, a - normal, b - normal, b + normal])
        pieces.append(_flat_polygon(quad))
    for point in points[1:-1]:  # round the joints so turns have no gaps
        pieces.append(_flat_disc(point, half))
    if path.start is None and len(points):
        pieces.append(_flat_disc(points[0], half))
    mesh = trimesh.util.concatenate(pieces)
    return coloured(mesh, path.colour)


def junction_mesh(obj: SceneObject) -> trimesh.Trimesh:
    """A junction's flat disc (its footprint's inscribed circle) in its local frame.

    It sits a little above path ribbons so the crossing it marks is drawn on top.
    """
    radius = max(min(obj.size[0], obj.size[2]) / 2.0, 0.1)
    return coloured(_flat_disc(np.zeros(2), radius, lift=JUNCTION_LIFT), obj.colour)


def ground_mesh(scene: Scene, margin: float = 1.5) -> trimesh.Trimesh:
    """The ground plane under the scene extent (a little larger, so edges show)."""
    w, d = scene.extent
    colour = (0.35, 0.55, 0.25) if scene.ground == "grass" else (0.62, 0.55, 0.45)
    return block((w * margin, 0.02, d * margin), (0.0, -0.01, 0.0), colour)  # top face at y = 0


def room_walls(scene: Scene, towards_viewer) -> trimesh.Trimesh | None:
    """The walls of a room (``scene.walls``) that a viewer looking from direction
    ``towards_viewer`` (a world vector from the scene to the viewer) sees from inside:
    those whose inner face turns towards the viewer, that is the far sides, which stand
    behind the furniture and hide none of it. None when no wall qualifies (not a room,
    or a viewer straight above, who would see only their tops).

    Each wall runs the full length of its side plus the thickness at both ends, so two
    walls meet in a closed corner (their overlap is the same colour, so it cannot flicker).
    """
    if not scene.walls:
        return None
    towards = np.asarray(towards_viewer, dtype=float)
    w, d, t = scene.extent[0], scene.extent[1], WALL_THICKNESS
    walls = []
    # Per side: the wall's inward normal (x, z) and its box's centre and extents.
    for inward, centre, extents in (
        ((0.0, 1.0), (0.0, -(d + t) / 2), (w + 2 * t, WALL_HEIGHT, t)),  # north
        ((0.0, -1.0), (0.0, (d + t) / 2), (w + 2 * t, WALL_HEIGHT, t)),  # south
        ((1.0, 0.0), (-(w + t) / 2, 0.0), (t, WALL_HEIGHT, d + 2 * t)),  # west
        ((-1.0, 0.0), ((w + t) / 2, 0.0), (t, WALL_HEIGHT, d + 2 * t)),  # east
    ):
        if inward[0] * towards[0] + inward[1] * towards[2] > 1e-9:
            walls.append(block(extents, (centre[0], WALL_HEIGHT / 2, centre[1]), WALL_COLOUR))
    return trimesh.util.concatenate(walls) if walls else None


@lru_cache(maxsize=64)
def _load_user_mesh(path: str) -> trimesh.Trimesh:
    """A mesh file's triangles, read once per process (``MeshFileError`` if unusable)."""
    return load_mesh_file(path)


def _has_colours(mesh: trimesh.Trimesh) -> bool:
    return mesh.visual.kind in ("face", "vertex", "texture")


def _flat_polygon(quad: np.ndarray) -> trimesh.Trimesh:
    vertices = np.column_stack([quad[:, 0], np.full(len(quad), PATH_LIFT), quad[:, 1]])
    # Counter-clockwise seen from above (+Y) so normals point up.
    faces = np.array([[0, 2, 1], [0, 3, 2]])
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    if mesh.face_normals[:, 1].mean() < 0:
        mesh.invert()
    return mesh


def _flat_disc(centre: np.ndarray, radius: float, sections: int = 16, lift: float = PATH_LIFT) -> trimesh.Trimesh:
    angles = np.linspace(0, 2 * np.pi, sections, endpoint=False)
    ring = np.column_stack([centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)])
    vertices = np.vstack([[centre[0], lift, centre[1]], np.column_stack([ring[:, 0], np.full(sections, lift), ring[:, 1]])])
    faces = np.array([[0, 1 + (i + 1) % sections, 1 + i] for i in range(sections)])
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    if mesh.face_normals[:, 1].mean() < 0:
        mesh.invert()
    return mesh
