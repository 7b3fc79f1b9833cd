"""The reachability grid of a room: which floor a person can walk on from a door.

Reachability is decided on an occupancy grid of about ACCESS_CELL metres (``AccessGrid``):
free floor is the room's floor minus every tall ground box, both grown by CORRIDOR_HALF
(so a way is at least 2 * CORRIDOR_HALF = 0.6 m wide); the reachable floor is the part
of the free floor connected (4-neighbours) to a door's opening (to the first door's, on
the ``rooted`` grid the layout uses). A box is reachable when a reachable cell lies
within CORRIDOR_HALF + one cell of its access sides (in front of a named side; anywhere
round it for ("any",)). ``floor_verdict`` judges the free floor as SceneEval does: the
share in its largest part, and the doors off that part.

The grid holds no energy: the room's ``access`` term (``room_terms``), the plan checks
and ``scene_metrics`` ask it which cells a shape covers and how the free floor connects.
"""

from __future__ import annotations

import copy
import math
import weakref
from typing import NamedTuple

import numpy as np

from scenewright.core.geometry import Rect, points_in_polygon, points_segments_distance
from scenewright.core.room import Room

#: ``scipy.ndimage.label``'s structure: cells connect through their sides only (its
#: ``generate_binary_structure(2, 1)``, written out so that importing the layout does
#: not import scipy.ndimage, which outdoor scenes never use).
FOUR_NEIGHBOURS = np.array([[False, True, False], [True, True, True], [False, True, False]])

#: Half the narrowest way a person walks (metres): corridors are at least 0.6 m wide.
CORRIDOR_HALF = 0.3
#: Side of a cell of the reachability grid (metres), grown for big rooms so the grid
#: has at most MAX_ACCESS_CELLS cells.
ACCESS_CELL = 0.1
MAX_ACCESS_CELLS = 20_000
#: Grids of more cells than this find the reachable floor from scratch by labelling
#: rather than by growing it from the doors (``AccessGrid.reachable``).
FLOOD_CELLS = 3500

#: A footprint whose yaw's sine or cosine is below this is square to the world axes
#: (quarter turns leave 6e-17, not 0) and is rasterised from templates.
SQUARE_AXIS = 1e-9
#: Rasters of footprints square to the axes put their centre on a 1/QUANTUM of a cell
#: (2.5 cm): a shape then covers the same cells, relative to its cell, wherever it
#: stands, and a template made once serves every pose (``AccessGrid._placed``).
QUANTUM = 4


def _square_extents(rect: Rect) -> tuple[float, float] | None:
    """Half extents along world x and z of a footprint square to the axes, else None."""
    if abs(rect.s) < SQUARE_AXIS:
        return rect.hw, rect.hd
    if abs(rect.c) < SQUARE_AXIS:
        return rect.hd, rect.hw
    return None


def bounds(rect: Rect, grow: float = 0.0) -> tuple[float, float, float, float]:
    """Axis-aligned bounds (x0, z0, x1, z1) of a footprint grown by ``grow``."""
    cx, cz, hw, hd, c, s = rect
    reach_x = hw * abs(c) + hd * abs(s) + grow
    reach_z = hw * abs(s) + hd * abs(c) + grow
    return cx - reach_x, cz - reach_z, cx + reach_x, cz + reach_z


class Raster(NamedTuple):
    """Cells of the reachability grid a shape covers, as a plane (see ``AccessGrid``),
    and the window (cell range [i0, i1) x [k0, k1) of the floor) holding those of them
    that are on the floor (it may cover padding cells too, which are never free)."""

    window: tuple[int, int, int, int]
    bits: int


class AccessGrid:
    """The reachability grid of one room: its cells, the static free floor, the door
    seeds, and the rasters of shapes on it.

    A set of cells is a *plane*: one Python int, bit i * stride + k for the cell in row i,
    column k. Unions, intersections and one step of growth (shifts by 1 and by the
    stride) are then a few int operations on a few hundred bytes, where numpy's cost per
    call would dominate at this size. The grid is padded by ``pad`` cells all round (as
    far as a raster reaches past a box, and one more): row i, column k is the cell whose
    centre is (x0 + (k - pad + 0.5) * cell, z0 + (i - pad + 0.5) * cell), the floor's
    cells are rows [pad, pad + rows) and columns [pad, pad + cols). Padding cells are
    never free, so shifts never carry a cell from one row's end to the next row, and
    the rasters of furniture against a wall fit on the grid whole. numpy arrays of the
    grid are (rows + 2 * pad, stride).
    """

    def __init__(self, room: Room):
        self.x0, self.z0, x1, z1 = room.bounds
        width, depth = x1 - self.x0, z1 - self.z0
        self.cell = max(ACCESS_CELL, math.sqrt(width * depth / MAX_ACCESS_CELLS))
        self.cols = max(1, math.ceil(width / self.cell))
        self.rows = max(1, math.ceil(depth / self.cell))
        self.pad = math.ceil((CORRIDOR_HALF + self.cell) / self.cell) + 1
        self.stride = 8 * (
            (self.cols + 2 * self.pad + 7) // 8
        )  # whole bytes per row: packbits gives planes directly
        self.shape = (self.rows + 2 * self.pad, self.stride)
        self.plane_bytes = self.shape[0] * self.stride // 8
        # Cell centres, per column (x) and per row (z).
        self.xc = self.x0 + (np.arange(self.stride) - self.pad + 0.5) * self.cell
        self.zc = self.z0 + (np.arange(self.shape[0]) - self.pad + 0.5) * self.cell
        gx, gz = np.meshgrid(self.xc, self.zc)
        inside = np.zeros(self.shape, dtype=bool)  # the floor's cells, padding left out
        floor = (slice(self.pad, self.pad + self.rows), slice(self.pad, self.pad + self.cols))
        inside[floor] = points_in_polygon(room.corners, gx[floor], gz[floor])
        solid, doors = _wall_segments(room)
        # Floor a person's centre can be on, boxes aside: inside, 0.3 m from solid wall
        # (a doorway is no wall: the way in runs through it).
        static = inside & (points_segments_distance(gx, gz, solid) >= CORRIDOR_HALF)
        #: The static free floor, and the cells that count as "at a door": free floor
        #: within CORRIDOR_HALF + one cell of an opening.
        self.static = self.plane(static)
        reach = CORRIDOR_HALF + self.cell
        self._set_seeds(static & (points_segments_distance(gx, gz, doors) <= reach))
        #: Per door of the room (``room.doors`` order), its own door cells: a plane, and
        #: the window (cell range) holding them (empty for a door with none).
        self.door_seeds: list[int] = []
        self.door_windows: list[tuple[int, int, int, int]] = []
        for door in room.doors:
            wall = room.wall_of(door)
            segment = (wall.to_world(door.span[0], 0.0), wall.to_world(door.span[1], 0.0))
            mask = static & (points_segments_distance(gx, gz, [segment]) <= reach)
            self.door_seeds.append(self.plane(mask))
            rows, cols = np.nonzero(mask)
            self.door_windows.append(
                (int(rows.min()), int(rows.max()) + 1, int(cols.min()), int(cols.max()) + 1)
                if rows.size
                else (0, 0, 0, 0)
            )
        self.has_doors = bool(doors)
        self._templates: dict[tuple, tuple] = {}  # (shape, f, g) -> ``_template``
        self._rooted: AccessGrid | None = None

    def _set_seeds(self, seeds: np.ndarray) -> None:
        """Make the True cells of ``seeds`` the door cells the reachable floor grows from."""
        self.seeds = self.plane(seeds)
        self.seed_cells = np.flatnonzero(seeds)
        rows, cols = np.nonzero(seeds)
        self.seed_box = (
            (int(rows.min()), int(rows.max()), int(cols.min()), int(cols.max()))
            if rows.size
            else None
        )

    def rooted(self) -> AccessGrid:
        """This grid with the first door's cells alone as the way in (the first door that
        has door cells; itself in a room of one door or none): the floor reachable from
        them is then one piece, and every other door must be reached from it like a box,
        so that two doors each leading into a part of the room of its own do not pass for
        a room one can cross. The copy shares the rasters' templates with this grid."""
        if self._rooted is None:
            if len(self.door_seeds) <= 1 or not self.seeds:
                self._rooted = self
            else:
                rooted = copy.copy(self)
                rooted._set_seeds(self.array(self.door_seeds[self.root]))
                rooted._rooted = rooted
                self._rooted = rooted
        return self._rooted

    @property
    def root(self) -> int:
        """The door the reachable floor of ``rooted`` grows from: the first with door
        cells (0 when none has)."""
        return next((d for d, seeds in enumerate(self.door_seeds) if seeds), 0)

    # -- planes and arrays -------------------------------------------------------------------

    def plane(self, mask: np.ndarray) -> int:
        """The plane of a bool array (rows + 2 * pad, stride)."""
        return int.from_bytes(np.packbits(mask, axis=1, bitorder="little").tobytes(), "little")

    def array(self, plane: int) -> np.ndarray:
        """The bool array (rows + 2 * pad, stride) of a plane."""
        packed = np.frombuffer(plane.to_bytes(self.plane_bytes, "little"), dtype=np.uint8)
        return np.unpackbits(packed, bitorder="little").reshape(self.shape).view(bool)

    def window_plane(self, window: tuple[int, int, int, int]) -> int:
        """The plane of every cell of a window."""
        i0, i1, k0, k1 = window
        stride = self.stride
        row = ((1 << (k1 - k0)) - 1) << k0
        repeat = ((1 << (stride * (i1 - i0))) - 1) // (
            (1 << stride) - 1
        )  # bit j * stride for each row j
        return (row * repeat) << (i0 * stride)

    def widen(self, window: tuple[int, int, int, int], grow: int) -> tuple[int, int, int, int]:
        """A window grown by ``grow`` cells each way, kept on the floor's grid."""
        i0, i1, k0, k1 = window
        pad = self.pad
        return (
            max(i0 - grow, pad),
            min(i1 + grow, pad + self.rows),
            max(k0 - grow, pad),
            min(k1 + grow, pad + self.cols),
        )

    def keeps_a_door(self, reach: int, window: tuple[int, int, int, int]) -> bool:
        """Whether the window holds no door cell, or a reachable door cell lies on the
        ring just outside it (``_reach_after``'s second condition)."""
        if not self.holds_seed(window):
            return True
        i0, i1, k0, k1 = window
        ring = self.window_plane((i0 - 1, i1 + 1, k0 - 1, k1 + 1)) & ~self.window_plane(window)
        return bool(ring & reach & self.seeds)

    def holds_seed(self, window: tuple[int, int, int, int]) -> bool:
        """Whether a window holds a door cell."""
        seed = self.seed_box
        i0, i1, k0, k1 = window
        if seed is None or i1 <= seed[0] or seed[1] < i0 or k1 <= seed[2] or seed[3] < k0:
            return False
        return bool(self.seeds & self.window_plane(window))

    # -- rasters ------------------------------------------------------------------------------

    def window(self, rect: Rect, grow: float) -> tuple[int, int, int, int]:
        """Padded cell range [i0, i1) x [k0, k1) of the cells whose centres lie in the
        footprint's bounding box grown by ``grow`` (clipped to the floor; may be empty)."""
        x0, z0, x1, z1 = bounds(rect, grow)
        cell, pad = self.cell, self.pad
        # Column k's centre sits at x0 + (k - pad + 0.5) * cell.
        k0 = min(max(pad, math.ceil((x0 - self.x0) / cell + pad - 0.5)), pad + self.cols)
        k1 = min(pad + self.cols, math.floor((x1 - self.x0) / cell + pad - 0.5) + 1)
        i0 = min(max(pad, math.ceil((z0 - self.z0) / cell + pad - 0.5)), pad + self.rows)
        i1 = min(pad + self.rows, math.floor((z1 - self.z0) / cell + pad - 0.5) + 1)
        return i0, max(i0, i1), k0, max(k0, k1)

    def _mask_plane(self, mask: np.ndarray, window: tuple[int, int, int, int]) -> int:
        """The plane of a bool mask over a window."""
        i0, i1, k0, k1 = window
        full = np.zeros((i1 - i0, self.stride), dtype=bool)
        full[:, k0:k1] = mask
        return int.from_bytes(np.packbits(full, axis=1, bitorder="little").tobytes(), "little") << (
            i0 * self.stride
        )

    def _local(
        self, rect: Rect, window: tuple[int, int, int, int]
    ) -> tuple[np.ndarray, np.ndarray]:
        """Window cell centres in the footprint's frame: (along its left, along its
        forward), each (i1 - i0, k1 - k0)."""
        i0, i1, k0, k1 = window
        cx, cz, _, _, c, s = rect
        dx = self.xc[k0:k1][None, :] - cx
        dz = self.zc[i0:i1][:, None] - cz
        return dx * c - dz * s, dx * s + dz * c

    def obstacle(self, rect: Rect) -> Raster:
        """The cells a box takes from the free floor: centres closer than CORRIDOR_HALF
        to its footprint (for a footprint square to the axes, at its centre rounded to a
        1/QUANTUM of a cell: see ``_placed``)."""
        square = _square_extents(rect)
        if square is not None:
            hx, hz = square
            return self._placed(
                ("obstacle", hx, hz),
                rect,
                lambda f, g: self._rounded(f, g, hx, hz, CORRIDOR_HALF, True),
            )
        window = self.window(rect, CORRIDOR_HALF)
        if window[0] == window[1] or window[2] == window[3]:
            return Raster(window, 0)
        lx, lz = self._local(rect, window)
        ex = np.maximum(np.abs(lx) - rect.hw, 0.0)
        ez = np.maximum(np.abs(lz) - rect.hd, 0.0)
        return Raster(
            window, self._mask_plane(ex * ex + ez * ez < CORRIDOR_HALF * CORRIDOR_HALF, window)
        )

    def access(self, rect: Rect, sides: tuple[str, ...]) -> Raster:
        """The cells a person may stand on to use a box: for ("any",) the centres within
        CORRIDOR_HALF + one cell of its footprint; for named sides, those in front of a
        side (in the band as long as the side) within that distance of it. A desk whose
        front faces a wall 20 cm off is not used from its front, however open its ends."""
        reach = CORRIDOR_HALF + self.cell
        square = _square_extents(rect)
        if square is not None:
            if "any" in sides:
                hx, hz = square
                return self._placed(
                    ("any", hx, hz), rect, lambda f, g: self._rounded(f, g, hx, hz, reach, False)
                )
            bands = self._side_bands(rect, sides, reach)
            return self._placed(("bands", *bands), rect, lambda f, g: self._bands(f, g, bands))
        window = self.window(rect, reach)
        if window[0] == window[1] or window[2] == window[3]:
            return Raster(window, 0)
        lx, lz = self._local(rect, window)
        hw, hd, limit = rect.hw, rect.hd, reach * reach
        if "any" in sides:
            ex = np.maximum(np.abs(lx) - hw, 0.0)
            ez = np.maximum(np.abs(lz) - hd, 0.0)
            mask = ex * ex + ez * ez <= limit
        else:
            mask = np.zeros(lx.shape, dtype=bool)
            for side in sides:
                if side in ("front", "back"):
                    mask |= (np.abs(lx) <= hw) & (
                        np.abs(lz - (hd if side == "front" else -hd)) <= reach
                    )
                elif side in ("left", "right"):
                    mask |= (np.abs(lz) <= hd) & (
                        np.abs(lx - (hw if side == "left" else -hw)) <= reach
                    )
        return Raster(window, self._mask_plane(mask, window))

    # Footprints square to the axes (nearly all, in a room) are rasterised from templates.
    # The centre is rounded to a 1/QUANTUM of a cell, so it sits a whole number of cells
    # (a, b) plus a fraction (f, g) / QUANTUM from the grid's corner; the cells are found
    # by their offsets (m, n) from cell (a, b), whose centres lie (m + 0.5 - f / QUANTUM,
    # n + 0.5 - g / QUANTUM) cells from the shape's centre: exact binary fractions, the
    # same wherever the shape is. A template (the rows of offsets a shape covers, for one
    # fraction) is made once per shape and fraction, shared by boxes of the same size, and
    # placed by one shift of its plane.

    def _placed(self, key: tuple, rect: Rect, make) -> Raster:
        """The raster of a template shape (``key``; ``make(f, g)`` its rows) at a
        footprint's centre: the template's plane shifted into place, or its rows put in
        one by one where it would reach past the grid."""
        u = round((rect.cx - self.x0) / self.cell * QUANTUM)
        v = round((rect.cz - self.z0) / self.cell * QUANTUM)
        a, f = divmod(u, QUANTUM)
        b, g = divmod(v, QUANTUM)
        template = self._templates.get((key, f, g))
        if template is None:
            template = self._templates[(key, f, g)] = self._template(make(f, g))
        n0, n1, m0, m1, plane, spans = template
        pad, rows, cols = self.pad, self.rows, self.cols
        a, b = a + pad, b + pad  # padded cell (i, k) is offset (i - b, k - a)
        i0, i1, k0, k1 = b + n0, b + n1, a + m0, a + m1
        window = (
            min(max(i0, pad), pad + rows),
            min(max(i1, pad), pad + rows),
            min(max(k0, pad), pad + cols),
            min(max(k1, pad), pad + cols),
        )
        if plane is not None and i0 >= 0 and i1 <= self.shape[0] and k0 >= 0 and k1 <= self.stride:
            return Raster(window, plane << (i0 * self.stride + k0))
        bits = 0
        for n, low, high in spans:  # the rows on the grid, clipped to it
            i = b + n
            low, high = max(a + low, 0), min(a + high, self.stride - 1)
            if 0 <= i < self.shape[0] and low <= high:
                bits |= ((1 << (high - low + 1)) - 1) << (i * self.stride + low)
        return Raster(window, bits)

    def _template(self, spans: list[tuple[int, int, int]]) -> tuple:
        """(n0, n1, m0, m1, plane, spans) of the spans (n, m_low, m_high) a shape covers:
        offsets [n0, n1) x [m0, m1), and the plane with bit (n - n0) * stride + m - m0
        (None when wider than a row of the grid)."""
        if not spans:
            return 0, 0, 0, 0, 0, spans
        n0, n1 = min(n for n, _, _ in spans), max(n for n, _, _ in spans) + 1
        m0, m1 = min(low for _, low, _ in spans), max(high for _, _, high in spans) + 1
        if m1 - m0 > self.stride:
            return n0, n1, m0, m1, None, spans
        plane = 0
        for n, low, high in spans:
            plane |= ((1 << (high - low + 1)) - 1) << ((n - n0) * self.stride + low - m0)
        return n0, n1, m0, m1, plane, spans

    def _rounded(
        self, f: int, g: int, hx: float, hz: float, r: float, strict: bool
    ) -> list[tuple[int, int, int]]:
        """Spans (n, m_low, m_high) of the cells within r (closer than r if ``strict``)
        of a rectangle of half extents hx, hz (metres) centred at fraction (f, g) of cell
        (0, 0), whose centre is half a cell past its corner."""
        cell = self.cell
        hx, hz, r = hx / cell, hz / cell, r / cell
        fx, fz = (
            f / QUANTUM - 0.5,
            g / QUANTUM - 0.5,
        )  # offset m's centre is m - fx from the shape's
        spans = []
        for n in range(math.floor(fz - hz - r), math.ceil(fz + hz + r) + 1):
            ez = max(abs(n - fz) - hz, 0.0)
            rest = r * r - ez * ez
            if rest < 0.0 or (strict and rest == 0.0):
                continue
            half = hx + math.sqrt(rest)
            low, high = (
                (math.floor(fx - half) + 1, math.ceil(fx + half) - 1)
                if strict
                else (math.ceil(fx - half), math.floor(fx + half))
            )
            if low <= high:
                spans.append((n, low, high))
        return spans

    def _bands(self, f: int, g: int, bands: tuple) -> list[tuple[int, int, int]]:
        """Spans (n, m_low, m_high) of the cells in bands (ox, oz, hx, hz): rectangles at
        offset (ox, oz) from a centre at fraction (f, g), half extents hx, hz (metres)."""
        cell = self.cell
        fx, fz = f / QUANTUM - 0.5, g / QUANTUM - 0.5
        rows: dict[int, list[tuple[int, int]]] = {}
        for ox, oz, hx, hz in bands:
            ox, oz, hx, hz = ox / cell, oz / cell, hx / cell, hz / cell
            low, high = math.ceil(fx + ox - hx), math.floor(fx + ox + hx)
            if low > high:
                continue
            for n in range(math.ceil(fz + oz - hz), math.floor(fz + oz + hz) + 1):
                rows.setdefault(n, []).append((low, high))
        spans = []
        for n, runs in sorted(rows.items()):  # runs of one row that meet or touch are joined
            runs.sort()
            low, high = runs[0]
            for start, end in runs[1:]:
                if start <= high + 1:
                    high = max(high, end)
                else:
                    spans.append((n, low, high))
                    low, high = start, end
            spans.append((n, low, high))
        return spans

    @staticmethod
    def _side_bands(
        rect: Rect, sides: tuple[str, ...], reach: float
    ) -> tuple[tuple[float, float, float, float], ...]:
        """The bands (ox, oz, hx, hz) in front of the named sides of a footprint square to
        the axes (offsets from its centre), each as long as its side and ``reach`` either
        way of it. Quarter turns leave sines and cosines a rounding error off 0 and 1:
        they are taken exact, so each turn has one set of bands."""
        _, _, hw, hd, c, s = rect
        c, s = float(round(c)), float(round(s))
        forward_x = c == 0.0  # forward along world x: front and back run along z
        bands = []
        for side in sides:
            if side in ("front", "back"):
                sign = 1.0 if side == "front" else -1.0
                bands.append(
                    (sign * s * hd, sign * c * hd, reach, hw)
                    if forward_x
                    else (sign * s * hd, sign * c * hd, hw, reach)
                )
            elif side in ("left", "right"):
                sign = 1.0 if side == "left" else -1.0
                bands.append(
                    (sign * c * hw, -sign * s * hw, hd, reach)
                    if forward_x
                    else (sign * c * hw, -sign * s * hw, reach, hd)
                )
        return tuple(bands)

    # -- reachability ---------------------------------------------------------------------

    def label(self, free: int) -> int:
        """The reachable floor from scratch: the free cells connected (4-neighbours) to a
        door's seed cells (``scipy.ndimage.label``)."""
        from scipy import ndimage

        labels = np.empty(
            self.shape, dtype=np.int32
        )  # (not kept: a grid is shared between layouts)
        ndimage.label(self.array(free), FOUR_NEIGHBOURS, output=labels)
        found = set(labels.ravel()[self.seed_cells].tolist()) - {0}
        if not found:
            return 0
        reach = labels == found.pop() if len(found) == 1 else np.isin(labels, sorted(found))
        return self.plane(reach)

    def reachable(self, free: int) -> int:
        """The reachable floor from the doors alone: grown from the door cells on a small
        grid, labelled on a big one (growing costs a round per cell of the longest way,
        labelling a fixed ~50 us plus the grid's size; they cross at ~3500 cells)."""
        if self.shape[0] * self.stride > FLOOD_CELLS:
            return self.label(free)
        return self.flood(self.seeds & free, free)

    def flood(self, start: int, free: int) -> int:
        """The free cells connected (4-neighbours) to ``start`` (a plane within ``free``):
        grows it one cell a round until it stops. Rounds: the farthest new cell's
        distance in cells from ``start``, a few when ``start`` is most of the answer."""
        stride = self.stride
        reach = start
        while True:
            grown = (reach | reach << 1 | reach >> 1 | reach << stride | reach >> stride) & free
            if grown == reach:
                return reach
            reach = grown

    def ring_single(self, reach: int, window: tuple[int, int, int, int]) -> bool:
        """Whether the cells of ``reach`` on the ring just outside ``window`` form at most
        one contiguous arc going round it: then taking the window out of ``reach`` cuts
        no way, since a way entering and leaving the window can go round along the arc."""
        i0, i1, k0, k1 = window
        stride = self.stride
        r0, c0, c1 = i0 - 1, k0 - 1, k1  # the ring: rows r0 and i1, columns c0 and c1
        height = i1 - i0
        size = (height + 2) * stride
        # The ring's rows as a string of 0s and 1s, bit j of the block at index j.
        cells = format((reach >> (r0 * stride)) & ((1 << size) - 1), f"0{size}b")[::-1]
        bottom = (height + 1) * stride
        ring = (
            cells[c0 : c1 + 1]  # top row, left to right
            + cells[stride + c1 : bottom : stride]  # right column, top to bottom
            + cells[bottom + c0 : bottom + c1 + 1][::-1]  # bottom row, right to left
            + cells[stride + c0 : bottom : stride][::-1]  # left column, bottom to top
        )
        return (ring[-1] + ring).count("01") <= 1  # arcs start where a 0 is followed by a 1

    def distance(
        self, target: int, window: tuple[int, int, int, int], guess: int | None = None
    ) -> int:
        """Cells between a window and the nearest cell of ``target`` (a non-empty plane),
        counted on both axes at once (Chebyshev): the fewest cells the window must grow
        by to take one in. ``guess``: the answer last time, tried first (two tests when
        it still holds)."""
        rows, cols = self.shape
        i0, i1, k0, k1 = window

        def holds(grow: int) -> bool:
            wider = (
                max(i0 - grow, 0),
                min(i1 + grow, rows),
                max(k0 - grow, 0),
                min(k1 + grow, cols),
            )
            return bool(target & self.window_plane(wider))

        if guess is not None and holds(guess) and (guess == 0 or not holds(guess - 1)):
            return guess
        low, high = -1, max(rows, cols)  # holds(high); not holds(low) (nothing within -1)
        while high - low > 1:
            middle = (low + high) // 2
            if holds(middle):
                high = middle
            else:
                low = middle
        return high


class FloorVerdict(NamedTuple):
    """How whole a room's free floor is (``floor_verdict``)."""

    navigability: float  # share of the free cells in the largest part (1 with none free)
    cut_doors: list[int]  # doors (``room.doors`` indices) with no door cell on that part
    cut_cells: int  # free cells off that part
    free_cells: int
    main: int  # the plane of that part


def floor_verdict(grid: AccessGrid, free: int) -> FloorVerdict:
    """The free floor ``free`` (a plane of ``grid``) in SceneEval's terms: the share of it
    in its largest 4-connected part (the first in row order among equal ones), and the
    doors whose door cells (``AccessGrid.door_seeds``) all lie off that part, a door
    into a pocket cut off from the rest. ``scene_metrics`` scores a scene by it, and the
    layout's verdict (``room_terms``) reports by it, so the two cannot disagree."""
    from scipy import ndimage

    labels = np.zeros(grid.shape, dtype=np.int32)
    if not ndimage.label(grid.array(free), FOUR_NEIGHBOURS, output=labels):
        return FloorVerdict(1.0, list(range(len(grid.door_seeds))), 0, 0, 0)
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    largest = int(np.argmax(sizes))
    total, kept = int(sizes.sum()), int(sizes[largest])
    main = grid.plane(labels == largest)
    cut = [door for door, seeds in enumerate(grid.door_seeds) if not seeds & main]
    return FloorVerdict(kept / total, cut, total - kept, total, main)


#: One grid per room, shared by every chain and layout of it (its templates with it).
_GRIDS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def access_grid(room: Room) -> AccessGrid:
    """The room's reachability grid, made once per room (rooms equal in value share it).
    Threads may share it: it is read-only once made but for its template cache, whose
    entries come out the same whoever makes them."""
    grid = _GRIDS.get(room)
    if grid is None:
        grid = _GRIDS[room] = AccessGrid(room)
    return grid


def _wall_segments(room: Room) -> tuple[list, list]:
    """The room's walls as segments ((x0, z0), (x1, z1)): the solid stretches (doorways
    cut out) and the doorways."""
    solid, doors = [], []
    for wall in room.walls:
        cuts = sorted(d.span for d in room.doors if d.wall == wall.id)
        u = 0.0
        for low, high in cuts:
            if low > u:
                solid.append((wall.to_world(u, 0.0), wall.to_world(low, 0.0)))
            doors.append((wall.to_world(low, 0.0), wall.to_world(high, 0.0)))
            u = max(u, high)
        if u < wall.length:
            solid.append((wall.to_world(u, 0.0), wall.to_world(wall.length, 0.0)))
    return solid, doors
