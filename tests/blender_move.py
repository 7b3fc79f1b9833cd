"""Run inside Blender (``blender -b --factory-startup --python tests/blender_move.py --
IN.glb OUT.glb NODE DX``): import a GLB, move one object DX metres along x as a user
drags it, and export the scene as GLB again with Blender's own exporter."""

import sys

import numpy

if not hasattr(numpy, "bool"):  # Debian Blender 3.4's glTF importer (see blender_render.py)
    numpy.bool = bool

import bpy  # noqa: E402

source, target, name, step = sys.argv[sys.argv.index("--") + 1 :]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=source)
bpy.data.objects[name].location.x += float(step)
bpy.ops.export_scene.gltf(filepath=target, export_format="GLB", export_extras=True)
