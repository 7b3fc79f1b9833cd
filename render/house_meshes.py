"""Triangle meshes of a house (``core.house``): its walls, its floors, its doors and
windows, as ``render.house_view`` says where they are and how high a view draws them.

A wall is a slab on its centre line, its thickness either side, built of boxes around
its doors (floor to the door's top) and windows (sill to top) as a room's walls are
(``render.meshes.wall_mesh``), the same plaster with darker tops. Each room's floor is
a slab under its outline (the walls' centre lines), so the floors meet under the walls
and a doorway has floor under it. A door or window is the room's (``opening_mesh``); an
``open`` doorway (no leaf) is its frame only; either is cut down to a cut wall's height.

``scene_ground`` and ``scene_walls`` are what a picture draws behind the entities for
any scene: outdoors the ground, in a room its floor and walls, in a house its floors and
walls.
"""

from __future__ import annotations

import numpy as np
import trimesh

from scenewright.core.house import House, HouseOpening
from scenewright.core.room import WALL_THICKNESS, Opening, Wall
from scenewright.core.scene import Scene

from .house_view import wall_heights, wall_openings, wall_reach
from .mesh_parts import combine
from .meshes import (
    FRAME_COLOUR,
    WALL_COLOUR,
    WALL_TOP_COLOUR,
    _frame,
    _wall_pieces,
    ground_mesh,
    opening_mesh,
    polygon_floor,
    room_walls,
)


def scene_ground(scene: Scene, margin: float) -> trimesh.Trimesh:
    """What a picture draws under a scene: a house's floors, else ``ground_mesh``."""
    if scene.house is not None:
        return house_floors(scene.house)
    return ground_mesh(scene, margin=margin)


def scene_walls(scene: Scene, towards_viewer) -> trimesh.Trimesh | None:
    """The walls a viewer in direction ``towards_viewer`` sees, in world coordinates:
    a room's (``room_walls``) or a house's (``house_walls``); None outdoors."""
    if scene.house is not None:
        return house_walls(scene.house, towards_viewer)
    return room_walls(scene, towards_viewer)


def house_walls(house: House, towards_viewer) -> trimesh.Trimesh | None:
    """Every wall of ``house`` at the height a viewer in direction ``towards_viewer``
    draws it (``house_view.wall_heights``), in world coordinates."""
    heights = wall_heights(house, towards_viewer)
    holes = wall_openings(house)
    walls = [
        house_wall_mesh(house, index, heights[index], holes[index])
        for index in range(len(house.walls))
    ]
    return trimesh.util.concatenate(walls) if walls else None


def house_wall_mesh(
    house: House, index: int, height: float, openings: list[tuple[HouseOpening, float]]
) -> trimesh.Trimesh:
    """Wall ``index`` of ``house`` in world coordinates, ``height`` tall, with a hole for
    each of ``openings`` (each with its centre's distance along the wall)."""
    wall = house.walls[index]
    t = wall.thickness
    (sx, sz), (ex, ez) = wall.start, wall.end
    length = max(wall.length, 1e-12)
    dx, dz = (ex - sx) / length, (ez - sz) / length
    nx, nz = -dz, dx
    # A room wall whose inner face is the centre line moved half a thickness along +n:
    # its slab (v from -t to 0) is then the house wall's, centred on the line.
    face = Wall(
        "", (sx + nx * t / 2, sz + nz * t / 2), (ex + nx * t / 2, ez + nz * t / 2), height, (nx, nz)
    )
    before, after = wall_reach(house, index)
    pieces: list[tuple[float, float, float, float]] = []
    edge = -before
    for opening, u in openings:
        u0, u1 = u - opening.width / 2.0, u + opening.width / 2.0
        top = opening.sill + opening.height
        pieces.append((edge, u0, 0.0, height))
        pieces.append((u0, u1, 0.0, min(opening.sill, height)))
        pieces.append((u0, u1, top, height))
        edge = u1
    pieces.append((edge, wall.length + after, 0.0, height))
    rows = np.array(
        [
            (u0, u1, u0, u1, y0, y1)
            for u0, u1, y0, y1 in pieces
            if u1 - u0 > 1e-9 and y1 - y0 > 1e-9
        ],
        dtype=float,
    ).reshape(-1, 6)
    mesh = _wall_pieces(face, rows, t)
    colours = np.tile(np.append(WALL_COLOUR, 1.0) * 255, (len(mesh.faces), 1))
    colours[mesh.face_normals[:, 1] > 0.99] = np.append(WALL_TOP_COLOUR, 1.0) * 255
    mesh.visual.face_colors = colours.round().astype(np.uint8)
    return mesh


def house_floors(house: House) -> trimesh.Trimesh:
    """Every room's floor (``room_floor``) as one mesh, in world coordinates."""
    return trimesh.util.concatenate([room_floor(house, room.id) for room in house.rooms])


def room_floor(house: House, room_id: str) -> trimesh.Trimesh:
    """A room's floor: a slab whose top (y = 0) is its outline, in world coordinates."""
    return polygon_floor(house.room(room_id).outline)


def house_opening_mesh(opening: HouseOpening, height: float | None = None) -> trimesh.Trimesh:
    """A door or window of the house in its frame (``house_view.opening_pose``): the
    room's door or window, an open doorway's frame alone, cut down to ``height``."""
    if opening.open:
        w, f = opening.width, min(0.06, 0.15 * opening.width, 0.15 * opening.height)
        mesh = combine(
            _frame(w, opening.sill, opening.sill + opening.height, f, WALL_THICKNESS, FRAME_COLOUR)
        )
    else:
        mesh = opening_mesh(
            Opening("", opening.kind, "", 0.0, opening.width, opening.height, opening.sill)
        )
    if height is not None and height < opening.sill + opening.height:
        mesh = cut_below(mesh, height)
    return mesh


def cut_below(mesh: trimesh.Trimesh, height: float) -> trimesh.Trimesh:
    """``mesh`` (boxes, each a connected part, as ``mesh_parts.slab`` makes them) cut
    at ``height``: a part wholly above it goes, a part across it is lowered to it (its
    top face becomes the cut)."""
    faces = np.asarray(mesh.faces)
    labels = trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(faces))
    vertices = np.asarray(mesh.vertices, dtype=float).copy()
    lowest = np.full(int(labels.max()) + 1 if len(labels) else 0, np.inf)
    np.minimum.at(lowest, labels, vertices[faces][:, :, 1].min(axis=1))
    keep = lowest[labels] < height - 1e-9
    vertices[:, 1] = np.minimum(vertices[:, 1], height)
    colours = np.asarray(mesh.visual.face_colors)[keep]
    cut = trimesh.Trimesh(vertices, faces[keep], process=False)
    area = cut.area_faces > 1e-12
    result = trimesh.Trimesh(vertices, faces[keep][area], process=False)
    result.visual.face_colors = colours[area]
    return result
