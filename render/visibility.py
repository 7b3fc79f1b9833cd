"""What one rendered view shows: which entities are visible enough to name, where they
are in the picture, and how two of them stand to each other in it.

``PictureView.from_render(result, scene, thresholds)`` reads a ``RenderResult``:

- **visible fraction**: the renderer's own, exact: an entity's pixels in the
  segmentation over its pixels when drawn without the other entities (the walls stay),
  from extra segmentation passes (``offscreen.Renderer``; 1.0 unoccluded, 0.0 hidden or
  out of frame). It is measured on the rendered image rather than estimated from the
  projected box, which overcounts any shape that does not fill its box (a tree, a
  road's ribbon) and knows nothing of what stands in front.
- **box**: the entity's pixel box [x0, y0, x1, y1] (x1, y1 exclusive) in the
  segmentation, ``RenderResult.boxes``; None when none of it is seen.
- **seen**: visible enough to name in a caption of this picture: a visible fraction of
  at least ``Thresholds.min_visible`` (default 0.25) and a box whose longer side is at
  least ``Thresholds.min_size`` pixels (default: 16, or a sixteenth of the image's
  shorter side when that is less, so a 64 x 64 thumbnail asks for 4). Both are settable.

Two relations of the picture (``describer.view`` uses them to word captions true of it):

- ``between(a, b)``: something else stands between two entities in the picture: of the
  points on the segment joining their box centres that fall on neither, at least
  ``BETWEEN_FRACTION`` show a third solid entity (not a path or junction, which lie on
  the ground, nor one of ``ignore``). "The chair is in front of the desk" with a board
  between them in the picture is not said of that picture.
- ``picture_side(a, b)``: where entity A is from entity B as the picture shows it:
  "left" / "right" when they are further apart across the picture than in depth,
  "front" / "behind" (nearer to / further from the camera) otherwise, measured on the
  ground plane in the camera's axes from their centres; the answer must agree with the
  projection (A's centre left of B's in the image for "left", nearer in depth for
  "front"), else None. A view straight down has no depth on the ground, so it only
  says "left" or "right".
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene

from .camera import Camera, walls_in_view

if TYPE_CHECKING:
    from .offscreen import RenderResult

#: "Something stands between A and B in the picture": at least this fraction of the
#: points between them (on neither) shows a third solid entity.
BETWEEN_FRACTION = 0.3
#: Points sampled on the segment between two box centres.
BETWEEN_SAMPLES = 64
#: The default box size threshold, in pixels (for images of 256 pixels a side and more).
DEFAULT_SIZE = 16


@dataclass(frozen=True)
class Thresholds:
    """How much of an entity a picture must show for a caption of it to name the entity.

    ``min_visible``: the least visible fraction (0..1); ``min_size``: the least length,
    in pixels, of the longer side of its box; None: ``DEFAULT_SIZE``, or a sixteenth of
    the image's shorter side when that is less (``size_in``).
    """

    min_visible: float = 0.25
    min_size: int | None = None

    def __post_init__(self) -> None:
        if isinstance(self.min_visible, bool) or not 0.0 <= self.min_visible <= 1.0:
            raise InputError(
                f"the visible fraction threshold must be between 0 and 1, got {self.min_visible!r}"
            )
        size = self.min_size
        if size is not None and (isinstance(size, bool) or not isinstance(size, int) or size < 0):
            raise InputError(
                f"the box size threshold must be a whole number of pixels >= 0, got {size!r}"
            )

    def size_in(self, width: int, height: int) -> int:
        """The box size threshold for an image of ``width`` x ``height`` pixels."""
        if self.min_size is not None:
            return self.min_size
        return min(DEFAULT_SIZE, min(width, height) // 16)


@dataclass(frozen=True)
class EntityInPicture:
    """One drawn entity in one picture: its visible fraction, pixel box and pixel count."""

    visible: float
    box: tuple[int, int, int, int] | None
    pixels: int

    def size(self) -> int:
        """The longer side of its box in pixels (0 when unseen)."""
        if self.box is None:
            return 0
        x0, y0, x1, y1 = self.box
        return max(x1 - x0, y1 - y0)


@dataclass
class PictureView:
    """One rendered view of a scene, as the captions of that picture need it.

    ``segmentation``: (H, W) entity index + 1 per pixel (0 background); ``ids``: entity
    id of each index; ``entities``: every drawn entity; ``centres``: world centres (3,)
    of objects, junctions and paths; ``flat``: paths and junctions (the ground layer);
    ``walls``: the ids of a room's walls the view draws (``camera.walls_in_view``).
    """

    camera: Camera
    segmentation: np.ndarray
    ids: list[str]
    entities: dict[str, EntityInPicture]
    centres: dict[str, np.ndarray]
    flat: frozenset[str]
    thresholds: Thresholds = field(default_factory=Thresholds)
    walls: frozenset[str] = frozenset()

    @classmethod
    def from_render(
        cls, result: RenderResult, scene: Scene, thresholds: Thresholds | None = None
    ) -> PictureView:
        pixels = np.bincount(result.segmentation.ravel(), minlength=len(result.ids) + 1)
        entities = {
            entity_id: EntityInPicture(
                float(result.visible[entity_id]),
                tuple(result.boxes[entity_id]) if entity_id in result.boxes else None,
                int(pixels[k + 1]),
            )
            for k, entity_id in enumerate(result.ids)
        }
        camera = Camera.from_dict(result.camera)
        walls = walls_in_view(scene.room, camera.pose[:3, 2]) if scene.room is not None else []
        return cls(
            camera=camera,
            segmentation=result.segmentation,
            ids=list(result.ids),
            entities=entities,
            centres=world_centres(scene),
            flat=frozenset(p.id for p in scene.paths)
            | {o.id for o in scene.objects if o.kind == "junction"},
            thresholds=thresholds or Thresholds(),
            walls=frozenset(wall.id for wall in walls),
        )

    def seen(self, entity_id: str) -> bool:
        """Whether the picture shows enough of the entity to name it (``thresholds``)."""
        entity = self.entities.get(entity_id)
        return (
            entity is not None
            and entity.visible >= self.thresholds.min_visible
            and entity.size() >= self.thresholds.size_in(self.camera.width, self.camera.height)
        )

    def box(self, entity_id: str) -> list[int] | None:
        """The entity's pixel box [x0, y0, x1, y1], or None when none of it is seen."""
        entity = self.entities.get(entity_id)
        return list(entity.box) if entity is not None and entity.box is not None else None

    def segment(self, entity_id: str) -> int | None:
        """The entity's label in the segmentation image (its index in ``ids`` + 1), or
        None when the picture does not draw it."""
        return self.ids.index(entity_id) + 1 if entity_id in self.entities else None

    def union_box(self, entity_ids) -> tuple[float, float, float, float] | None:
        """The box round the seen boxes of ``entity_ids`` (a group's members), or None."""
        boxes = [
            self.entities[i].box for i in entity_ids if i in self.entities and self.entities[i].box
        ]
        if not boxes:
            return None
        array = np.array(boxes, dtype=float)
        return (*array[:, :2].min(axis=0), *array[:, 2:].max(axis=0))

    def between(self, a_ids, b_ids, ignore=()) -> bool:
        """Whether a third solid entity stands between A and B in the picture (A and B
        may each be several entities: a group's members). See the module docstring."""
        a_box, b_box = self.union_box(a_ids), self.union_box(b_ids)
        if a_box is None or b_box is None:
            return False
        start = np.array([(a_box[0] + a_box[2]) / 2, (a_box[1] + a_box[3]) / 2])
        end = np.array([(b_box[0] + b_box[2]) / 2, (b_box[1] + b_box[3]) / 2])
        steps = (np.arange(BETWEEN_SAMPLES) + 0.5) / BETWEEN_SAMPLES
        points = start + steps[:, None] * (end - start)
        height, width = self.segmentation.shape
        columns = np.clip(points[:, 0].astype(int), 0, width - 1)
        rows = np.clip(points[:, 1].astype(int), 0, height - 1)
        labels = self.segmentation[rows, columns]
        index = {entity_id: k + 1 for k, entity_id in enumerate(self.ids)}
        ends = [index[i] for i in (*a_ids, *b_ids) if i in index]
        passable = [index[i] for i in (*self.flat, *ignore) if i in index]
        gap = ~np.isin(labels, ends)
        if not gap.any():
            return False  # they touch in the picture
        solid = gap & (labels != 0) & ~np.isin(labels, passable)
        return bool(solid.sum() >= BETWEEN_FRACTION * gap.sum())

    def picture_side(self, a_id: str, b_id: str) -> str | None:
        """Where A is from B as the picture shows it: "left", "right", "front", "behind"
        or None (see the module docstring)."""
        if a_id not in self.centres or b_id not in self.centres:
            return None
        a, b = self.centres[a_id], self.centres[b_id]
        (pixel_a, pixel_b), (depth_a, depth_b) = self.camera.project(np.stack([a, b]))
        right, back = self.camera.pose[:3, 0], self.camera.pose[:3, 2]
        flat_back = np.array([back[0], 0.0, back[2]])
        offset = a - b
        across = float(offset @ right)
        towards = (
            float(offset @ flat_back / np.linalg.norm(flat_back))
            if np.linalg.norm(flat_back) > 1e-6
            else 0.0
        )
        if abs(across) >= abs(towards):
            side = "right" if across > 0 else "left"
            agrees = (pixel_a[0] > pixel_b[0]) == (side == "right") and pixel_a[0] != pixel_b[0]
        else:
            side = "front" if towards > 0 else "behind"
            agrees = (depth_a < depth_b) == (side == "front") and depth_a != depth_b
        return side if agrees else None


def world_centres(scene: Scene) -> dict[str, np.ndarray]:
    """The centre (3,) of every object's box (a group's is the box round its members)
    and junction, and of every path's control points, in world coordinates."""
    centres = {
        o.id: np.array([o.position[0], o.position[1] + o.size[1] / 2.0, o.position[2]], dtype=float)
        for o in scene.objects
    }
    for path in scene.paths:
        points = np.asarray(path.points, dtype=float)
        centres[path.id] = np.array([points[:, 0].mean(), 0.0, points[:, 1].mean()])
    return centres
