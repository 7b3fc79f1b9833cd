"""Render a scenewright GLB in Blender with Cycles, from the file's camera, as a user's
import shows it:

    blender -b --factory-startup --python scripts/blender_render.py -- out/scene.glb out/blender.png 640 480

It adds nothing to the file's look (materials, sun and camera are the file's own) but a
sky-coloured world and a plain sRGB view transform, as the preview uses. It prints
what Blender made of the file as one JSON line after ``PROBE`` (each object's type,
parent, world location and materials), which ``tests/test_blender_import.py`` reads."""

import json
import sys

import numpy

# Debian's Blender 3.4 glTF importer still uses ``numpy.bool``, which numpy 1.24 removed;
# the alias is all it needs.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402  (Blender's own module, after the alias)

glb, out, width, height = sys.argv[sys.argv.index("--") + 1 :]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
scene = bpy.context.scene
cameras = [o for o in scene.objects if o.type == "CAMERA"]
if cameras:
    scene.camera = cameras[0]
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 32
scene.cycles.use_denoising = False  # Debian's build has no OpenImageDenoise
scene.cycles.seed = 0
scene.render.resolution_x, scene.render.resolution_y = int(width), int(height)
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"  # plain sRGB, as the preview writes
scene.render.filepath = out
world = bpy.data.worlds.new("sky")
scene.world = world
world.use_nodes = True
background = world.node_tree.nodes["Background"]
background.inputs[0].default_value = (0.62, 0.77, 0.92, 1.0)  # the preview's sky
background.inputs[1].default_value = 0.5
bpy.ops.render.render(write_still=True)
info = {
    o.name: {
        "type": o.type,
        "parent": o.parent.name if o.parent else None,
        "location": list(o.matrix_world.translation),
        "materials": [s.material.name for s in o.material_slots if s.material],
    }
    for o in scene.objects
}
print("PROBE" + json.dumps(info))
