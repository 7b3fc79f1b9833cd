"""What a catalog entry may look like, checked alike by ``validate`` and the renderer.

An object's look is a ``shape`` (a procedural builder of ``scenewright.render.builders``)
or a ``mesh`` file. ``SHAPES`` is the registry of shape names: for each, a one-line
description and its footprint convention in the object frame of
``scenewright.core.frames`` (forward is local +Z, left local +X, up +Y): what its front
(+Z) shows, and from which side a person sits at, stands at or uses it. The static
checks warn about a name not in it (it would be drawn as a plain box) and the renderer
refuses to import if its builders and this registry differ.

``load_mesh_file`` is the one way a mesh file is read, at ``validate`` time and when
rendering: regular files only, at most ``MAX_MESH_BYTES`` (with the files a mesh refers
to, such as a .gltf's buffers), and it must parse into at least one triangle. Anything
else raises ``MeshFileError``, an ``InputError`` whose ``reason`` completes the
sentence "mesh file 'F' ...".
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import MeshFileError
from .files import UnusableFile, read_regular_file

if TYPE_CHECKING:
    import trimesh

#: The shape of an entry that names none: its box, exactly the volume the layout uses.
DEFAULT_SHAPE = "box"


@dataclass(frozen=True)
class Shape:
    """One procedural shape and its footprint convention (local +Z is its front)."""

    name: str
    description: str
    #: What the front (+Z) shows, or "none ..." for a shape that looks alike from the front and the back.
    front: str
    #: Where a person is when sitting at, standing at or using it.
    used_from: str


_ROUND = "none (round)"
_ANY_SIDE = "any side"

SHAPES: dict[str, Shape] = {
    shape.name: shape
    for shape in (
        Shape(
            "anvil",
            "a smith's anvil: foot, waist, face block and a horn",
            "none (the horn points left, +X)",
            "either long side (+Z or -Z)",
        ),
        Shape(
            "armchair",
            "an upholstered chair: a seat cushion between two arms, a back rest",
            "the open seat; back rest at -Z",
            "sits on it facing +Z",
        ),
        Shape(
            "banner",
            "a cloth with a pale stripe hanging from a crossbar on a pole",
            "the cloth's face",
            "seen from the front (+Z); its back (-Z) to a wall",
        ),
        Shape("barrel", "a bulging wooden barrel with two iron hoops", _ROUND, _ANY_SIDE),
        Shape(
            "bathtub",
            "a bathtub along X, water in it, a tap inside its -X end",
            "the long side one steps in over",
            "gets in from the front (+Z)",
        ),
        Shape(
            "bed",
            "frame, mattress, blanket and pillow, a headboard at one end",
            "the foot end; headboard and pillow at -Z",
            "lies head at the back (-Z), feet to +Z",
        ),
        Shape(
            "bench",
            "a plank seat on two trestle legs",
            "none (the same from the back)",
            "either long side (+Z or -Z)",
        ),
        Shape(
            "book",
            "a closed book lying flat, pages showing on three sides",
            "cover up; spine on its right (-X)",
            "read from the front (+Z)",
        ),
        Shape(
            "bookshelf",
            "an open shelf unit with a row of books on each shelf",
            "the open shelves; back board at -Z",
            "the front (+Z)",
        ),
        Shape("bottle", "a glass bottle: body, shoulder, neck and cork", _ROUND, _ANY_SIDE),
        Shape("box", "a plain box filling the whole size (the default shape)", "none", _ANY_SIDE),
        Shape("brazier", "an iron fire bowl of glowing coals on three legs", _ROUND, _ANY_SIDE),
        Shape(
            "bucket",
            "a tapered pail of water with a bail handle",
            "none (handle across, from -X to +X)",
            _ANY_SIDE,
        ),
        Shape(
            "bunk",
            "a low wooden bed frame with a straw mattress and a rolled blanket",
            "the foot end, with the blanket; the head at -Z",
            "lies head at the back (-Z), feet to +Z",
        ),
        Shape("bush", "three overlapping leafy lumps", _ROUND, _ANY_SIDE),
        Shape(
            "chair",
            "a seat on four legs with a back rest",
            "the open seat; back rest at -Z",
            "sits on it facing +Z",
        ),
        Shape(
            "chest",
            "a wooden chest with a darker lid, iron bands and a lock plate",
            "the lock plate; the lid opens towards it",
            "opened from the front (+Z)",
        ),
        Shape(
            "clothes_line",
            "two posts with a line between them and laundry hanging on it",
            "none (posts at the ends, -X and +X)",
            "either long side (+Z or -Z)",
        ),
        Shape(
            "coal_bucket",
            "a tapered pail full of coal with a bail handle",
            "none (handle across, from -X to +X)",
            _ANY_SIDE,
        ),
        Shape(
            "coffee_table",
            "a low table, a shelf under its top with magazines on it",
            "none (the same on every side)",
            _ANY_SIDE,
        ),
        Shape(
            "crate",
            "a closed wooden crate: boards with darker slats across each side",
            "none (the same on every side)",
            _ANY_SIDE,
        ),
        Shape(
            "crate_wagon",
            "a two-axle cart loaded with wooden crates",
            "the shaft",
            "drawn from the front (+Z)",
        ),
        Shape(
            "desk",
            "a writing desk: top, a drawer pedestal and two legs",
            "drawer fronts; pedestal on its right (-X)",
            "sits at the front (+Z), facing -Z",
        ),
        Shape(
            "desk_lamp",
            "an angled lamp: base at the back, arm up and forward, shade aiming down",
            "the shade, over what it lights; base at -Z",
            "lights what lies in front of it (+Z)",
        ),
        Shape(
            "desk_phone",
            "a telephone: body, keypad and a handset lying across",
            "the keypad; handset across the back (-Z)",
            "the front (+Z)",
        ),
        Shape(
            "dining_table",
            "a table on an apron and four legs, a runner and four plates",
            "none (the same on every side)",
            _ANY_SIDE,
        ),
        Shape(
            "dresser",
            "a chest of drawers: two small drawers over two wide ones",
            "the drawers and knobs",
            "the front (+Z)",
        ),
        Shape(
            "dumbbell_rack",
            "a two-tier rack of hex dumbbells on a steel frame",
            "the dumbbells' front heads; the upper tier at the back (-Z)",
            "stands at the front (+Z)",
        ),
        Shape(
            "exercise_bike",
            "an upright bike: flywheel, crank, saddle, handlebars and a console",
            "the saddle end; flywheel, handlebars and console at -Z",
            "rides it from the front (+Z), facing -Z",
        ),
        Shape(
            "exercise_mat",
            "a flat exercise mat with a stripe across each end",
            "none (flat)",
            _ANY_SIDE,
        ),
        Shape(
            "fancy_table",
            "a dark table with an apron, turned legs and a drawer",
            "the drawer in the apron",
            "sits at the front (+Z), at the drawer",
        ),
        Shape(
            "field",
            "a plot of tilled soil with rows of crop",
            "none (crop rows run along Z)",
            _ANY_SIDE,
        ),
        Shape(
            "floor_lamp", "a standing lamp: round foot, tall pole, a cloth shade", _ROUND, _ANY_SIDE
        ),
        Shape("flowerpot", "a terracotta pot with leaves and a few blossoms", _ROUND, _ANY_SIDE),
        Shape(
            "forge",
            "a stone hearth with a chimney",
            "the glowing mouth; chimney at the back (-Z)",
            "worked from the front (+Z)",
        ),
        Shape(
            "grain_pallet", "a wooden pallet with six upright sheaves of grain", "none", _ANY_SIDE
        ),
        Shape(
            "grain_wagon",
            "a two-axle cart heaped with grain",
            "the shaft",
            "drawn from the front (+Z)",
        ),
        Shape(
            "hammer",
            "a hammer lying flat, handle and iron head",
            "none (the head is at its left end, +X)",
            _ANY_SIDE,
        ),
        Shape(
            "house",
            "a one-storey house: walls, a gable roof, door and windows",
            "door and windows; roof ridge along X",
            "entered from the front (+Z)",
        ),
        Shape(
            "kitchen_counter",
            "a kitchen base cabinet: doors under drawers, a dark worktop",
            "drawers, doors and handles",
            "stands at the front (+Z)",
        ),
        Shape(
            "lamp_post",
            "a wooden pole on a foot with a lit lantern under a little roof",
            "none (square, lit on every side)",
            _ANY_SIDE,
        ),
        Shape(
            "laptop",
            "an open laptop: base with keyboard, screen upright",
            "keyboard; screen upright at -Z, facing +Z",
            "sits at the front (+Z), facing -Z",
        ),
        Shape(
            "nightstand",
            "a small cabinet with two drawers and knobs",
            "the drawers and knobs",
            "the front (+Z)",
        ),
        Shape("oak_tree", "a thick trunk under a broad crown of leaf clusters", _ROUND, _ANY_SIDE),
        Shape(
            "paper",
            "a sheet of paper with a few printed lines",
            "the foot of the page; heading line at -Z",
            "read from the front (+Z)",
        ),
        Shape("phone", "a mobile phone lying flat, screen up", "none (lies flat)", _ANY_SIDE),
        Shape(
            "piano",
            "an upright piano: tall case, keyboard, music desk and pedals",
            "the keyboard; the tall case at the back (-Z)",
            "sits at the front (+Z), facing -Z",
        ),
        Shape("pine_tree", "a trunk under three stacked cones", _ROUND, _ANY_SIDE),
        Shape(
            "pot",
            "a big iron cooking pot full of stew",
            "none (round; handles at -X and +X)",
            _ANY_SIDE,
        ),
        Shape("potted_plant", "a clay pot with a leafy crown", _ROUND, _ANY_SIDE),
        Shape(
            "refrigerator",
            "a tall fridge-freezer: two doors, a long handle on each",
            "the doors and handles",
            "opened from the front (+Z)",
        ),
        Shape(
            "rowing_machine",
            "a rower: flywheel housing, footrests, a rail with a seat on it",
            "the rail's end; flywheel and footrests at -Z",
            "sits on the seat facing -Z",
        ),
        Shape("rug", "a flat rug with a lighter border", "none (flat)", _ANY_SIDE),
        Shape(
            "sack",
            "a filled sack tied at the top",
            "none (round, flatter front to back)",
            _ANY_SIDE,
        ),
        Shape("sheaf", "a bundle of straw tied at the waist", _ROUND, _ANY_SIDE),
        Shape(
            "shed",
            "plank walls under a straw roof with a wide double door",
            "the double door",
            "entered from the front (+Z)",
        ),
        Shape(
            "shower",
            "a shower tray, a glass screen, a riser with a shower head",
            "the way in, open on its -X half; glass on +X; riser at -Z",
            "steps in from the front (+Z)",
        ),
        Shape(
            "sign",
            "two posts holding a painted board",
            "the painted board face; posts at -Z",
            "read from the front (+Z)",
        ),
        Shape(
            "sink_counter",
            "a kitchen counter with a sunk steel basin and a tap",
            "doors; the tap at the back (-Z), above the worktop",
            "stands at the front (+Z)",
        ),
        Shape(
            "sofa",
            "an upholstered sofa: two or three seats between two arms",
            "the open seats; back rest at -Z",
            "sits on it facing +Z",
        ),
        Shape("stool", "a round seat on three splayed legs", _ROUND, _ANY_SIDE),
        Shape(
            "stove",
            "a cooker: oven door and knobs under a black hob with four rings",
            "the oven door, its handle and the knobs",
            "cooks at the front (+Z)",
        ),
        Shape("table", "a plank top on four legs", "none (the same on every side)", _ANY_SIDE),
        Shape(
            "table_lamp", "a bedside lamp: round base, stem and a cloth shade", _ROUND, _ANY_SIDE
        ),
        Shape("tablet", "a tablet computer lying flat, screen up", "none (lies flat)", _ANY_SIDE),
        Shape(
            "teacher_desk",
            "a teacher's writing desk (drawn as the desk shape)",
            "drawer fronts; pedestal on its right (-X)",
            "sits at the front (+Z), facing -Z",
        ),
        Shape(
            "toilet",
            "a toilet: cistern, an oval bowl with an open seat, the lid up",
            "the bowl; cistern and lid at the back (-Z)",
            "sits on it facing +Z",
        ),
        Shape(
            "torch_stand",
            "an iron pole on four splayed feet holding a burning torch",
            _ROUND,
            _ANY_SIDE,
        ),
        Shape(
            "towel_rail",
            "a standing rail of three bars with towels over two of them",
            "none (posts at the ends, -X and +X)",
            "either long side (+Z or -Z)",
        ),
        Shape(
            "tower",
            "an octagonal stone tower with a pointed roof",
            "door and windows",
            "entered from the front (+Z)",
        ),
        Shape(
            "townhouse",
            "a two-storey house: walls, a gable roof, door and windows",
            "door and windows; roof ridge along X",
            "entered from the front (+Z)",
        ),
        Shape(
            "treadmill",
            "a treadmill: a belt deck, a motor hood, uprights and a console",
            "the belt's open end; motor hood and console at -Z",
            "walks on it facing -Z",
        ),
        Shape("tv", "a flat screen on a small foot", "the screen", "watched from the front (+Z)"),
        Shape(
            "tv_stand",
            "a low media cabinet: two doors, an open shelf with a box",
            "the doors and the open shelf",
            "the front (+Z)",
        ),
        Shape(
            "wagon",
            "an empty two-axle cart with side boards",
            "the shaft",
            "drawn from the front (+Z)",
        ),
        Shape(
            "wardrobe",
            "a tall cabinet with two doors",
            "the doors and handles",
            "opened from the front (+Z)",
        ),
        Shape(
            "washbasin",
            "a bathroom sink: an oval basin on a pedestal, a tap",
            "the basin's front; tap at the back (-Z)",
            "stands at the front (+Z)",
        ),
        Shape(
            "washing_machine",
            "a front-loading washing machine: round door, control panel",
            "the round door and the control panel",
            "loaded from the front (+Z)",
        ),
        Shape(
            "weapon_rack",
            "two posts and two rails holding a row of blades",
            "the blades",
            "taken from at the front (+Z); its back (-Z) to a wall",
        ),
        Shape(
            "weight_bench",
            "a padded bench on a steel frame with a foot at each end",
            "the seat pad's end; the back pad's head end at -Z",
            "sits on it facing +Z, or lies back",
        ),
        Shape("well", "a round stone well with dark water inside its rim", _ROUND, _ANY_SIDE),
        Shape(
            "whiteboard",
            "a whiteboard on two legs, marker writing on it, a pen tray",
            "the writing face and the pen tray",
            "written on from the front (+Z)",
        ),
        Shape(
            "windmill",
            "a tapering mill house under a cap, with four sails",
            "the sails and the door",
            "entered from the front (+Z)",
        ),
        Shape(
            "wine_box",
            "an open wooden crate with six bottle necks showing",
            "none (the same on every side)",
            _ANY_SIDE,
        ),
    )
}

# -- mesh files -----------------------------------------------------------------------

#: The file types a mesh may be, by suffix (any case).
MESH_SUFFIXES = (".glb", ".gltf", ".obj", ".ply", ".stl")
#: The most a mesh file may hold, the files it refers to included (256 MiB).
MAX_MESH_BYTES = 256 * 1024 * 1024


def load_mesh_file(path: str | os.PathLike[str]) -> trimesh.Trimesh:
    """The triangles of a .glb, .gltf, .obj, .ply or .stl file, all its parts in one mesh.

    Raises ``MeshFileError`` when the file is missing, not a regular file, empty, larger
    than ``MAX_MESH_BYTES``, not parsable as its suffix says, or has no triangles.
    """
    import trimesh  # imported on first use: checking rules without meshes stays quick

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in MESH_SUFFIXES:
        raise MeshFileError(
            path, f"is not a {', '.join(MESH_SUFFIXES[:-1])} or {MESH_SUFFIXES[-1]} file"
        )
    try:
        data = _read_mesh_bytes(path, MAX_MESH_BYTES)
    except UnusableFile as problem:
        raise MeshFileError(path, str(problem)) from None
    if not data:
        raise MeshFileError(path, "is empty")
    if suffix == ".glb" and (header_problem := _glb_header_problem(data)):
        raise MeshFileError(path, f"is not a valid .glb file ({header_problem})")
    referred = _ReferredFiles(path.parent, MAX_MESH_BYTES - len(data))
    try:
        mesh = trimesh.load_mesh(io.BytesIO(data), file_type=suffix.lstrip("."), resolver=referred)
    except UnusableFile as problem:  # a file it refers to, such as a .gltf's buffer
        raise MeshFileError(path, str(problem)) from None
    except ImportError as error:  # a parser's optional helper, tried on a malformed file
        raise MeshFileError(
            path,
            f"is not a valid {suffix} file (reading it needs the missing module '{error.name}')",
        ) from None
    except Exception as error:  # trimesh's parsers raise many kinds for a malformed file
        detail = " ".join(str(error).split())[:200] or type(error).__name__
        raise MeshFileError(path, f"is not a valid {suffix} file ({detail})") from None
    if len(mesh.faces) == 0:
        raise MeshFileError(path, "has no triangles")
    return mesh


def _glb_header_problem(data: bytes) -> str | None:
    """What is wrong with a binary glTF's 12-byte header (its magic word and length), if anything.

    trimesh's own message for a cut-short file is an index error, so these are told first.
    """
    if len(data) < 12 or data[:4] != b"glTF":
        return "it does not start with a binary glTF header"
    declared = int.from_bytes(data[8:12], "little")
    if declared > len(data):
        return f"its header gives {declared} bytes but the file has only {len(data)}: cut short"
    return None


def _read_mesh_bytes(path: Path, limit: int) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes (``read_regular_file``).

    Every failure is an ``UnusableFile`` whose text completes "mesh file 'F' ...": an
    ``OSError``, as trimesh's loaders expect of a file they cannot get (an .obj whose
    material file is unusable still loads, without its materials).
    """
    try:
        return read_regular_file(path, limit, "a mesh")
    except UnusableFile:
        raise
    except FileNotFoundError:
        raise UnusableFile("does not exist") from None
    except OSError as error:
        raise UnusableFile(f"cannot be read ({error.strerror or error})") from None


class _ReferredFiles:
    """The files a mesh file refers to (a .gltf's buffers, an .obj's materials and
    textures), for trimesh's loaders: found in the mesh file's folder or below it, read
    as the mesh file is, and together within the bytes the mesh file left over."""

    def __init__(self, folder: Path, budget: int):
        self.folder = folder.resolve()
        self.budget = budget

    def get(self, name: str) -> bytes:
        path = (self.folder / name.strip()).resolve()
        if not path.is_relative_to(self.folder):
            raise UnusableFile(f"refers to '{name}', outside its folder")
        try:
            data = _read_mesh_bytes(path, self.budget)
        except UnusableFile as problem:
            raise UnusableFile(f"refers to '{name}', which {problem}") from None
        self.budget -= len(data)
        return data

    __getitem__ = get
