"""Triangle meshes for a scene: one per object, a ribbon per path, the ground, a room.

Objects are built in their local frame by the procedural builder their ``shape`` names
(``scenewright.render.builders``), or loaded from the user's mesh file, and always
fitted exactly to the catalog size, so what is drawn is the box the layout placed. A
shape with no builder (``validate`` warns about it) is drawn as a plain box of the
object's size and colour, still exactly the volume the layout reasoned about. A mesh
file is read by ``scenewright.core.shapes.load_mesh_file``, as ``validate`` reads it:
one that has become unreadable since raises its ``MeshFileError``, an input error.
``object_transform`` gives the local-to-world pose. Everything is in metres, +Y up.
A size beyond ``scenewright.core.limits.MAX_SIZE`` (or not a finite number) is refused
with an ``InputError`` before anything is built; within it, a builder's detail does not
grow with the size.

A room (``scene.room``, ``scenewright.core.room``) is drawn as its floor (the room's
polygon, ``floor_mesh``), its walls (``wall_mesh``: a slab ``WALL_THICKNESS`` thick
behind each inner face, built as boxes around its doors and windows, mitred at the
corners so they close whatever the angle) and its doors and windows (``opening_mesh``,
in the opening's own frame, posed by ``opening_transform``). ``room_walls`` gives the
walls a viewer sees from inside (``scenewright.render.camera.walls_in_view``).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import trimesh

from scenewright.core.errors import InputError
from scenewright.core.frames import transform_matrix
from scenewright.core.limits import MAX_SIZE
from scenewright.core.room import WALL_THICKNESS, Opening, Room, Wall
from scenewright.core.scene import Scene, SceneObject, ScenePath
from scenewright.core.shapes import DEFAULT_SHAPE, load_mesh_file

from .builders import BUILDERS
from .camera import walls_in_view
from .mesh_parts import IRON, WOOD, block, coloured, combine, shade, slab

#: Roads sit this far above the ground so they do not z-fight with it.
PATH_LIFT = 0.02
#: Junction discs sit above the path ribbons that start at them.
JUNCTION_LIFT = 0.03
#: A room's walls are plaster that sets the furniture off; their tops (the cut the
#: cut-away view shows, and the outline the top view shows) are darker.
WALL_COLOUR = (0.86, 0.83, 0.76)
WALL_TOP_COLOUR = (0.45, 0.42, 0.38)
#: A room's floor: a slab this thick (metres) under the room's polygon, top at y = 0,
#: in a pale oak that most furniture colours stand out from.
FLOOR_THICKNESS = 0.05
FLOOR_COLOUR = (0.74, 0.63, 0.48)
#: Door and window parts: painted frames, a wooden door leaf, pale-blue glass.
FRAME_COLOUR = (0.95, 0.94, 0.91)
DOOR_COLOUR = WOOD
GLASS_COLOUR = (0.7, 0.85, 0.95)
#: A mitred wall end reaches at most this many thicknesses past its corner, so a very
#: sharp corner does not grow a long spike.
MITRE_LIMIT = 4.0


def object_mesh(obj: SceneObject) -> trimesh.Trimesh:
    """The object's mesh in its local frame, fitted to ``obj.size`` (base centre at 0)."""
    return shaped_mesh(obj.shape, obj.mesh, tuple(obj.size), tuple(obj.colour))


def shaped_mesh(
    shape: str | None, mesh_file: str | None, size: tuple, colour: tuple
) -> trimesh.Trimesh:
    """A mesh from a builder name or a user mesh file, fitted to ``size``: everything
    an object's look depends on, so callers can cache by these arguments. A copy of
    the one built per process: the preview and the GLB of a scene build its looks once."""
    return _built_mesh(shape, mesh_file, size, colour).copy()


@lru_cache(maxsize=1024)
def _built_mesh(
    shape: str | None, mesh_file: str | None, size: tuple, colour: tuple
) -> trimesh.Trimesh:
    if not all(math.isfinite(side) and 0 <= side <= MAX_SIZE for side in size):
        raise InputError(
            f"object size {list(size)} is not within 0..{MAX_SIZE:g} m on each side "
            "(the limits: docs/limits.md)"
        )
    if mesh_file:
        mesh = _load_user_mesh(mesh_file).copy()
        mesh = coloured(mesh, colour) if not _has_colours(mesh) else mesh
    else:
        build = BUILDERS.get(
            shape or DEFAULT_SHAPE, BUILDERS[DEFAULT_SHAPE]
        )  # unknown shape: its box
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
    """A flat ribbon of the path's width along its control points, just above the ground:
    a quad (two triangles) a segment, and a disc at each joint so turns have no gaps (and
    at the start when no junction covers it). Built as arrays in one go: a dataset draws
    every road of every scene anew."""
    points = np.asarray(path.points, dtype=float).reshape(-1, 2)
    half = path.width / 2.0
    starts, ends = points[:-1], points[1:]
    direction = ends - starts
    length = np.hypot(direction[:, 0], direction[:, 1])
    keep = length >= 1e-9
    starts, ends, direction, length = starts[keep], ends[keep], direction[keep], length[keep]
    normal = np.column_stack([-direction[:, 1], direction[:, 0]]) / length[:, None] * half
    # (segments, 4, 2): a + n, a - n, b - n, b + n, counter-clockwise seen from above (+Y).
    quads = np.stack(
        [starts + normal, starts - normal, ends - normal, ends + normal], axis=1
    ).reshape(-1, 2)
    quad_faces = (
        np.arange(len(starts))[:, None, None] * 4 + np.array([[0, 2, 1], [0, 3, 2]])
    ).reshape(-1, 3)
    centres = points[1:-1]
    if path.start is None and len(points):
        centres = np.vstack([centres, points[:1]])
    disc_vertices, disc_faces = _flat_discs(centres, half)
    vertices = _lifted(np.vstack([quads, disc_vertices]), PATH_LIFT)
    faces = np.vstack([quad_faces, disc_faces + len(quads)])
    return coloured(_flat_mesh(vertices, faces), path.colour)


def junction_mesh(obj: SceneObject) -> trimesh.Trimesh:
    """A junction's flat disc (its footprint's inscribed circle) in its local frame.

    It sits a little above path ribbons so the crossing it marks is drawn on top.
    """
    radius = max(min(obj.size[0], obj.size[2]) / 2.0, 0.1)
    vertices, faces = _flat_discs(np.zeros((1, 2)), radius)
    return coloured(_flat_mesh(_lifted(vertices, JUNCTION_LIFT), faces), obj.colour)


def ground_mesh(scene: Scene, margin: float = 1.5) -> trimesh.Trimesh:
    """The ground under the scene: outdoors a slab under the extent, ``margin`` times
    as large so its edges show; in a room its floor (``floor_mesh``)."""
    if scene.room is not None:
        return floor_mesh(scene.room)
    w, d = scene.extent
    colour = (0.35, 0.55, 0.25) if scene.ground == "grass" else (0.62, 0.55, 0.45)
    return block((w * margin, 0.02, d * margin), (0.0, -0.01, 0.0), colour)  # top face at y = 0


# -- rooms ----------------------------------------------------------------------------


def floor_mesh(room: Room) -> trimesh.Trimesh:
    """A slab ``FLOOR_THICKNESS`` thick whose top (y = 0) is exactly the room's polygon,
    any simple polygon (an L-shaped room's floor is L-shaped)."""
    return polygon_floor(room.corners)


def polygon_floor(points) -> trimesh.Trimesh:
    """A floor slab ``FLOOR_THICKNESS`` thick whose top (y = 0) is the simple polygon
    ``points`` (x, z)."""
    corners = np.asarray(points, dtype=float)  # (n, 2): x, z
    triangles = _triangulate(corners)
    # trimesh extrudes a 2D triangulation along +Z; map its (X, Y, Z) to world (X, Z - t, Y).
    slab_mesh = trimesh.creation.extrude_triangulation(corners, triangles, FLOOR_THICKNESS)
    swap = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, -FLOOR_THICKNESS], [0, 1.0, 0, 0], [0, 0, 0, 1.0]])
    slab_mesh.apply_transform(swap)
    if slab_mesh.volume < 0:  # the swap mirrors: turn the faces back outwards
        slab_mesh.invert()
    return coloured(slab_mesh, FLOOR_COLOUR)


def room_walls(scene: Scene, towards_viewer) -> trimesh.Trimesh | None:
    """The walls of the room (``scene.room``) that a viewer looking from direction
    ``towards_viewer`` (a world vector from the scene to the viewer) sees from inside
    (``walls_in_view``: in a perspective view the walls whose inner face turns towards
    it, the far ones, which hide no furniture; from straight above, all of them), in
    world coordinates, openings cut. None outdoors."""
    if scene.room is None:
        return None
    walls = [wall_mesh(scene.room, wall) for wall in walls_in_view(scene.room, towards_viewer)]
    return trimesh.util.concatenate(walls) if walls else None


def wall_mesh(room: Room, wall: Wall) -> trimesh.Trimesh:
    """One wall in world coordinates: a slab ``WALL_THICKNESS`` thick behind its inner
    face, ``wall.height`` tall, with a hole for each of its doors (floor to the door's
    top) and windows (sill to top).

    It is built of boxes around the openings (the full-height pieces between and beside
    them, and the pieces below each sill and above each top), not by cutting solids. The
    two end pieces are mitred: their outer face runs to where the neighbouring wall's
    outer face meets it, so walls meet in a closed corner at any angle, convex or (an
    L-shaped room's inside corner) reflex, without overlapping.
    """
    t = WALL_THICKNESS
    before, after = room.neighbours(wall.id)
    length, height = wall.length, wall.height
    start_out = -_mitre(wall, before, at_end=False)  # where the outer face starts and ends
    end_out = max(length + _mitre(wall, after, at_end=True), start_out)
    openings = sorted(room.openings_on(wall.id), key=lambda o: o.offset)
    # Rows (u0, u1 on the inner face; u0, u1 on the outer face; y0, y1). On the outer
    # face every piece stops where the mitred ends do; the full-height pieces at the
    # wall's ends reach them, so each corner is closed once.
    pieces: list[tuple[float, float, float, float, float, float]] = []

    def piece(u0: float, u1: float, y0: float, y1: float) -> None:
        out0 = start_out if u0 <= 0.0 and y0 <= 0.0 and y1 >= height else max(u0, start_out)
        out1 = end_out if u1 >= length and y0 <= 0.0 and y1 >= height else min(u1, end_out)
        pieces.append((u0, u1, out0, max(out0, out1), y0, y1))

    edge = 0.0
    for opening in openings:
        u0, u1 = opening.span
        piece(edge, u0, 0.0, height)  # beside it
        piece(u0, u1, 0.0, opening.sill)  # below the sill (none for a door)
        piece(u0, u1, opening.top, height)  # above its top
        edge = u1
    piece(edge, length, 0.0, height)
    rows = np.array(
        [p for p in pieces if p[5] - p[4] > 1e-9 and max(p[1] - p[0], p[3] - p[2]) > 1e-9],
        dtype=float,
    ).reshape(-1, 6)
    mesh = _wall_pieces(wall, rows, t)
    colours = np.tile(np.append(WALL_COLOUR, 1.0) * 255, (len(mesh.faces), 1))
    colours[mesh.face_normals[:, 1] > 0.99] = np.append(WALL_TOP_COLOUR, 1.0) * 255  # the tops
    mesh.visual.face_colors = colours.round().astype(np.uint8)
    return mesh


def wall_footprint(room: Room, wall: Wall) -> np.ndarray:
    """(4, 2) corners (x, z) of the wall's plan, as ``wall_mesh`` builds it (openings
    aside): inner face start and end, then outer face end and start (mitred)."""
    start_out = -_mitre(wall, room.neighbours(wall.id)[0], at_end=False)
    end_out = wall.length + _mitre(wall, room.neighbours(wall.id)[1], at_end=True)
    end_out = max(end_out, start_out)  # a short wall between two reflex corners
    t = WALL_THICKNESS
    return np.array(
        [
            wall.to_world(0.0, 0.0),
            wall.to_world(wall.length, 0.0),
            wall.to_world(end_out, -t),
            wall.to_world(start_out, -t),
        ]
    )


def wall_transform(wall: Wall) -> np.ndarray:
    """4x4 local-to-world matrix of a wall's own frame: origin at the middle of its inner
    face on the floor, local +Z its inner normal (into the room), +Y up."""
    x, z = wall.to_world(wall.length / 2.0, 0.0)
    return transform_matrix(x, 0.0, z, wall.facing_yaw)


def opening_transform(room: Room, opening: Opening) -> np.ndarray:
    """4x4 local-to-world matrix of an opening's frame: origin at its centre on the
    wall's inner face, on the floor; local +Z into the room, +X along the wall."""
    wall = room.part(opening.wall)
    return transform_matrix(opening.center[0], 0.0, opening.center[1], wall.facing_yaw)


def opening_mesh(opening: Opening) -> trimesh.Trimesh:
    """A door or window in its opening's frame (``opening_transform``): it fills the
    hole ``opening.width`` wide from ``opening.sill`` to ``opening.top``, within the
    wall's thickness (local z from ``-WALL_THICKNESS`` to 0), so it never reaches into
    the room (a door's swing zone stays as free as the layout left it)."""
    build = door_mesh if opening.kind == "door" else window_mesh
    return build(opening.width, opening.height, opening.sill)


def door_mesh(width: float, height: float, sill: float = 0.0) -> trimesh.Trimesh:
    """A closed door in its frame: painted jambs and head lining the hole, a wooden leaf
    set 1.5 cm back from the wall's face with two raised panels, and a handle."""
    t = WALL_THICKNESS
    w, top = width, sill + height
    f = min(0.06, 0.15 * w, 0.15 * height)  # frame width
    inner_w, leaf_top = w - 2 * f, top - f
    panel_w = 0.7 * inner_w
    panel_h = (leaf_top - sill) * 0.36
    panels = [
        slab(
            (-panel_w / 2, y, -0.016), (panel_w / 2, y + panel_h, -0.009), shade(DOOR_COLOUR, 1.18)
        )
        for y in (sill + 0.08 * (leaf_top - sill), sill + 0.54 * (leaf_top - sill))
    ]
    handle_x = w / 2 - f - min(0.08, 0.15 * inner_w)
    handle_y = sill + min(1.0, 0.48 * height)
    return combine(
        _frame(w, sill, top, f, t, FRAME_COLOUR),
        slab((-w / 2 + f, sill + 0.005, -0.055), (w / 2 - f, leaf_top, -0.015), DOOR_COLOUR),
        panels,
        slab(
            (handle_x - 0.07, handle_y - 0.012, -0.015),
            (handle_x + 0.01, handle_y + 0.012, 0.0),
            IRON,
        ),
    )


def window_mesh(width: float, height: float, sill: float) -> trimesh.Trimesh:
    """A window in its frame: painted jambs, head and sill lining the hole, a pale-blue
    pane in the middle of the wall's thickness, and glazing bars across it."""
    t = WALL_THICKNESS
    w, top = width, sill + height
    f = min(0.06, 0.12 * w, 0.12 * height)
    bar = 0.6 * f
    middle_y = sill + 0.62 * height
    return combine(
        _frame(w, sill, top, f, t, FRAME_COLOUR),
        slab(
            (-w / 2 + f, sill + f, -t / 2 - 0.006),
            (w / 2 - f, top - f, -t / 2 + 0.006),
            GLASS_COLOUR,
        ),
        slab((-bar / 2, sill + f, -t / 2 - 0.02), (bar / 2, top - f, -t / 2 + 0.02), FRAME_COLOUR),
        slab(
            (-w / 2 + f, middle_y - bar / 2, -t / 2 - 0.02),
            (w / 2 - f, middle_y + bar / 2, -t / 2 + 0.02),
            FRAME_COLOUR,
        ),
    )


def _frame(
    width: float, bottom: float, top: float, f: float, t: float, colour
) -> list[trimesh.Trimesh]:
    """Jambs, head and (for a window, ``bottom`` above the floor) sill lining a hole
    ``width`` wide from ``bottom`` to ``top``, ``f`` wide, through the wall's thickness ``t``."""
    w = width
    parts = [
        slab((-w / 2, bottom, -t), (-w / 2 + f, top, 0.0), colour),
        slab((w / 2 - f, bottom, -t), (w / 2, top, 0.0), colour),
        slab((-w / 2 + f, top - f, -t), (w / 2 - f, top, 0.0), colour),
    ]
    if bottom > 0.0:
        parts.append(
            slab((-w / 2 + f, bottom, -t), (w / 2 - f, bottom + f, 0.0), shade(colour, 0.92))
        )
    return parts


def _mitre(wall: Wall, neighbour: Wall, *, at_end: bool) -> float:
    """How far past its corner with ``neighbour`` (metres along the wall, outwards) the
    wall's outer face runs to meet the neighbour's outer face: +t at a square convex
    corner, -t at a square reflex one, 0 where the walls run straight on.

    The outer face is the line v = -t of the wall's frame; the neighbour's outer face is
    where (p - corner) . n' = -t. Along the first, that is at s * (d . n') - t (n . n') = -t
    with s the distance from the corner in the wall's direction d (away from it at the end).
    """
    t = WALL_THICKNESS
    d = np.array(wall.direction) * (
        1.0 if at_end else -1.0
    )  # pointing away from the wall, past the corner
    n, other = np.array(wall.normal), np.array(neighbour.normal)
    along = float(d @ other)
    if abs(along) < 1e-9:  # the walls run straight on: the outer faces meet end to end
        return 0.0
    reach = t * (float(n @ other) - 1.0) / along
    return float(np.clip(reach, -MITRE_LIMIT * t, MITRE_LIMIT * t))


def _wall_pieces(wall: Wall, rows: np.ndarray, t: float) -> trimesh.Trimesh:
    """The wall's pieces as one mesh. ``rows`` (P, 6): each piece's u range on the inner
    face and on the outer face (v = -t), and its y range; a piece is a box, or a box with
    slanted ends where it is mitred. Zero-area faces (a piece that is a triangle in plan,
    where an opening meets a mitred corner) are left out."""
    box = trimesh.creation.box(extents=(2.0, 2.0, 2.0))
    signs = box.vertices > 0  # (8, 3): which end of each axis a corner is at
    # A corner's u: the inner range for the +z (room) side, the outer range for -z.
    u = np.where(
        signs[None, :, 2],
        np.where(signs[None, :, 0], rows[:, None, 1], rows[:, None, 0]),
        np.where(signs[None, :, 0], rows[:, None, 3], rows[:, None, 2]),
    )  # (P, 8)
    v = np.where(signs[:, 2], 0.0, -t)[None, :]
    y = np.where(signs[None, :, 1], rows[:, None, 5], rows[:, None, 4])
    (sx, sz), (dx, dz), (nx, nz) = wall.start, wall.direction, wall.normal
    vertices = np.stack([sx + u * dx + v * nx, y, sz + u * dz + v * nz], axis=-1).reshape(-1, 3)
    faces = (box.faces[None, :, :] + 8 * np.arange(len(rows))[:, None, None]).reshape(-1, 3)
    if dx * nz - dz * nx < 0:  # the frame (along, up, normal) is left-handed: wind the other way
        faces = faces[:, ::-1]
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    return trimesh.Trimesh(vertices, faces[mesh.area_faces > 1e-12], process=False)


def _triangulate(points: np.ndarray) -> np.ndarray:
    """Triangles (n - 2, 3) of indices into ``points`` (n, 2) covering the simple polygon
    they outline, by ear clipping (a room has a handful of corners)."""
    count = len(points)
    order = list(range(count))
    x, z = points[:, 0], points[:, 1]
    if np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z) < 0:
        order.reverse()  # counter-clockwise in (x, z), so a convex corner turns left

    def turn(a, b, c) -> float:
        return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    triangles = []
    while len(order) > 3:
        for k in range(len(order)):
            i, j, m = order[k - 1], order[k], order[(k + 1) % len(order)]
            a, b, c = points[i], points[j], points[m]
            if turn(a, b, c) <= 1e-12:
                continue  # a reflex or straight corner is no ear
            others = [points[o] for o in order if o not in (i, j, m)]
            if any(
                turn(a, b, p) >= 0 and turn(b, c, p) >= 0 and turn(c, a, p) >= 0 for p in others
            ):
                continue  # another corner lies in it
            triangles.append((i, j, m))
            del order[k]
            break
        else:  # only straight corners left (collinear walls): any one closes the fan
            triangles.append((order[-1], order[0], order[1]))
            del order[0]
    triangles.append(tuple(order))
    return np.array(triangles, dtype=np.int64)


@lru_cache(maxsize=64)
def _load_user_mesh(path: str) -> trimesh.Trimesh:
    """A mesh file's triangles, read once per process (``MeshFileError`` if unusable)."""
    return load_mesh_file(path)


def _has_colours(mesh: trimesh.Trimesh) -> bool:
    return mesh.visual.kind in ("face", "vertex", "texture")


def _flat_discs(
    centres: np.ndarray, radius: float, sections: int = 16
) -> tuple[np.ndarray, np.ndarray]:
    """(x, z) vertices (n * (1 + sections), 2) and triangles (n * sections, 3) of a disc
    of ``radius`` around each of ``centres`` (n, 2): its centre, then its rim counter-
    clockwise seen from above, each triangle (centre, next, this) facing up."""
    angles = np.linspace(0, 2 * np.pi, sections, endpoint=False)
    rim_x = centres[:, :1] + radius * np.cos(angles)  # (n, sections)
    rim_z = centres[:, 1:] + radius * np.sin(angles)
    vertices = np.concatenate(
        [centres[:, None, :], np.stack([rim_x, rim_z], axis=2)], axis=1
    ).reshape(-1, 2)
    around = np.arange(sections)
    one = np.column_stack([np.zeros(sections, dtype=int), 1 + (around + 1) % sections, 1 + around])
    faces = (np.arange(len(centres))[:, None, None] * (1 + sections) + one).reshape(-1, 3)
    return vertices, faces


def _lifted(points: np.ndarray, lift: float) -> np.ndarray:
    """(n, 2) ground points (x, z) as (n, 3) vertices ``lift`` above the ground."""
    return np.column_stack([points[:, 0], np.full(len(points), lift), points[:, 1]])


def _flat_mesh(vertices: np.ndarray, faces: np.ndarray) -> trimesh.Trimesh:
    """A mesh of horizontal triangles wound to face up: its normals are +Y exactly, given
    rather than computed."""
    normals = np.zeros((len(faces), 3))
    normals[:, 1] = 1.0
    return trimesh.Trimesh(vertices, faces, face_normals=normals, process=False)
