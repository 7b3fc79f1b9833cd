"""A user's example scenes, read into one in-memory form: the core ``Scene``.

Learning from examples and varying them start from scenes a user already has. Three
formats are read (``formats``), each into a ``Scene`` of plain objects (kind
``object``) with their poses and sizes, and a support relation (``OnTopOf``) for every
object that stands on another:

- ``scene.json`` written by scenewright (``scene_json``): read as it is, derivation and
  relations included;
- the hand-written example format (``handwritten``, JSON Schema
  ``examples/schema/example.schema.json``): an extent or a room, and objects with
  ``id``, ``type``, ``size``, ``position``, ``yaw`` (degrees), optional ``style`` and
  ``parent`` (the object it stands on); types are free names;
- GLB files with one named node per object, as Blender exports them (``glb``): type
  and style from the node name (``desk.oak.001``), size from the mesh bounds, yaw from
  the node's rotation.

Where a file does not say what an object stands on, the support is measured from the
geometry (``stacking``). ``load_example(path)`` reads one file, ``load_examples``
several (names made unique); a bad file raises ``ExampleError``, an ``InputError``
whose one line names the file and where in it the problem is.
"""

from .example import scene_supports
from .formats import FORMATS, Example, ExampleError, load_example, load_examples
from .stacking import infer_supports

__all__ = [
    "FORMATS",
    "Example",
    "ExampleError",
    "infer_supports",
    "load_example",
    "load_examples",
    "scene_supports",
]
