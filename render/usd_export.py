"""Export a laid-out scene as a USD stage (``.usda`` text or ``.usdc`` binary), for
simulators and studio pipelines (Isaac Sim, Omniverse, Houdini, Blender), written
atomically.

The stage holds what the GLB holds (``render.export.scene_nodes``: the same node tree,
names, poses, what rests on what, the ground, the camera and the sun), in USD's terms:

- ``/World`` (the default prim), stage metadata ``metersPerUnit = 1`` and
  ``upAxis = "Y"``; every entity an ``Xform`` at its node's place in the tree, with its
  ``xformOp:transform`` (relative to its parent) and the GLB node's extras as
  ``customData`` (id, type, kind, noun, on, group, cutaway, a house's rooms as a
  string array, ...); a house's rooms are ``Xform`` s holding their walls, doors and
  windows, floor and objects, as in the GLB;
- its mesh as ``Mesh`` children ``Geom0``, ``Geom1``, ... (one per colour), flat shaded:
  ``normals`` per face corner (``faceVarying``), ``subdivisionScheme = "none"``;
- materials under ``/World/Looks``, one ``UsdPreviewSurface`` per colour (diffuse
  colour, roughness 0.9, not metallic), bound to the meshes;
- the camera (``UsdGeom.Camera``: focal length and apertures giving the preview's field
  of view, clipping range) and the sun (``UsdLux.DistantLight``, shining along its -Z).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene

from .export import scene_nodes
from .gltf_file import ROUGHNESS, Node

#: File name endings written as USD (``.usd`` is binary, as USD itself writes it).
USD_SUFFIXES = (".usda", ".usdc", ".usd")
#: The camera's focal length (USD: tenths of a scene unit, i.e. millimetres here); the
#: apertures are set from it so the field of view is the preview's.
FOCAL_LENGTH = 50.0
#: The sun's intensity: a DistantLight's illuminance in nits-like units, about the
#: preview's brightness in renderers that take USD's light units (Omniverse, Blender).
SUN_INTENSITY = 3.0


def export_usd(
    scene: Scene,
    path: str | os.PathLike,
    *,
    ground: bool = True,
    camera: bool = True,
    light: bool = True,
    cutaway: bool = False,
) -> Path:
    """Write ``scene`` to ``path`` (``.usda``, ``.usdc`` or ``.usd``) as a USD stage and
    return the path; options as ``export.glb_bytes``."""
    target = Path(path)
    if target.suffix.lower() not in USD_SUFFIXES:
        raise InputError(f"{target}: a USD file name ends in {', '.join(USD_SUFFIXES)}")
    roots = scene_nodes(scene, ground=ground, camera=camera, light=light, cutaway=cutaway)
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(
        prefix=f".{target.stem}.", suffix=target.suffix, dir=target.parent
    )
    os.close(handle)
    try:
        write_stage(roots, temporary)
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return target


def write_stage(roots: list[Node], path: str) -> None:
    """Write the node trees ``roots`` as a new USD stage at ``path``."""
    from pxr import Sdf, Usd, UsdGeom

    Path(path).unlink(missing_ok=True)  # CreateNew refuses an existing file
    stage = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    world = UsdGeom.Xform.Define(stage, Sdf.Path("/World"))
    stage.SetDefaultPrim(world.GetPrim())
    writer = _StageWriter(stage)
    for root in roots:
        writer.node(root, Sdf.Path("/World"))
    stage.GetRootLayer().Save()


class _StageWriter:
    def __init__(self, stage) -> None:
        self.stage = stage
        self.materials: dict[tuple[int, ...], Any] = {}

    def node(self, node: Node, parent) -> None:
        from pxr import Gf, UsdGeom, Vt

        path = parent.AppendChild(_identifier(node.name))
        if node.camera is not None:
            prim = UsdGeom.Camera.Define(self.stage, path)
            _set_camera(prim, node.camera)
        elif node.light is not None:
            from pxr import UsdLux

            prim = UsdLux.DistantLight.Define(self.stage, path)
            prim.CreateIntensityAttr(SUN_INTENSITY)
            prim.CreateColorAttr(Gf.Vec3f(*node.light.get("color", (1.0, 1.0, 1.0))))
        else:
            prim = UsdGeom.Xform.Define(self.stage, path)
        matrix = Gf.Matrix4d(np.asarray(node.matrix, dtype=float).T.tolist())  # USD: row vectors
        prim.AddTransformOp().Set(matrix)
        usd_prim = prim.GetPrim()
        usd_prim.SetCustomDataByKey("name", node.name)
        for key, value in node.extras.items():
            if isinstance(value, list):  # a house's wall or door: its rooms' ids
                value = Vt.StringArray([str(item) for item in value])
            usd_prim.SetCustomDataByKey(key, value)
        if node.mesh is not None and len(node.mesh.faces):
            self.meshes(node, path)
        for child in node.children:
            self.node(child, path)

    def meshes(self, node: Node, path) -> None:
        from pxr import UsdGeom, UsdShade, Vt

        mesh = node.mesh
        assert mesh is not None
        faces = np.asarray(mesh.faces)
        corners = np.asarray(mesh.vertices, dtype=float)[faces]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normals, axis=1)
        keep = length > 1e-12
        colours = np.asarray(mesh.visual.face_colors, dtype=np.uint8)[keep]
        corners, normals = corners[keep], normals[keep] / length[keep, None]
        looks, which = np.unique(colours, axis=0, return_inverse=True)
        for k, look in enumerate(looks):
            chosen = np.asarray(which).ravel() == k
            points = corners[chosen].reshape(-1, 3).astype(np.float32)
            geom = UsdGeom.Mesh.Define(self.stage, path.AppendChild(f"Geom{k}"))
            geom.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(points))
            geom.CreateFaceVertexCountsAttr(Vt.IntArray([3] * int(chosen.sum())))
            geom.CreateFaceVertexIndicesAttr(Vt.IntArray(list(range(len(points)))))
            geom.CreateNormalsAttr(
                Vt.Vec3fArray.FromNumpy(np.repeat(normals[chosen], 3, axis=0).astype(np.float32))
            )
            geom.SetNormalsInterpolation(UsdGeom.Tokens.faceVarying)
            geom.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
            geom.CreateExtentAttr(
                Vt.Vec3fArray.FromNumpy(np.array([points.min(axis=0), points.max(axis=0)]))
            )
            binding = UsdShade.MaterialBindingAPI.Apply(geom.GetPrim())
            binding.Bind(self.material(look))

    def material(self, rgba: np.ndarray):
        from pxr import Gf, Sdf, UsdShade

        key = tuple(int(v) for v in rgba)
        if key not in self.materials:
            name = "colour_{:02x}{:02x}{:02x}{:02x}".format(*key)
            path = Sdf.Path("/World/Looks").AppendChild(name)
            if not self.stage.GetPrimAtPath("/World/Looks"):
                self.stage.DefinePrim("/World/Looks", "Scope")
            material = UsdShade.Material.Define(self.stage, path)
            shader = UsdShade.Shader.Define(self.stage, path.AppendChild("PreviewSurface"))
            shader.CreateIdAttr("UsdPreviewSurface")
            r, g, b, a = (v / 255.0 for v in key)
            shader.CreateInput("diffuseColor", Sdf.ValueTypeNames.Color3f).Set(Gf.Vec3f(r, g, b))
            shader.CreateInput("roughness", Sdf.ValueTypeNames.Float).Set(ROUGHNESS)
            shader.CreateInput("metallic", Sdf.ValueTypeNames.Float).Set(0.0)
            if a < 1.0:
                shader.CreateInput("opacity", Sdf.ValueTypeNames.Float).Set(a)
            surface = shader.CreateOutput("surface", Sdf.ValueTypeNames.Token)
            material.CreateSurfaceOutput().ConnectToSource(surface)
            self.materials[key] = material
        return self.materials[key]


def _set_camera(prim, lens: dict[str, Any]) -> None:
    from pxr import Gf, UsdGeom

    if lens["type"] == "perspective":
        view = lens["perspective"]
        vertical = 2.0 * FOCAL_LENGTH * math.tan(view["yfov"] / 2.0)
        prim.CreateProjectionAttr(UsdGeom.Tokens.perspective)
        prim.CreateFocalLengthAttr(FOCAL_LENGTH)
        prim.CreateVerticalApertureAttr(vertical)
        prim.CreateHorizontalApertureAttr(vertical * view["aspectRatio"])
    else:
        view = lens["orthographic"]
        prim.CreateProjectionAttr(UsdGeom.Tokens.orthographic)
        # Orthographic apertures are in tenths of a scene unit: the view's full width.
        prim.CreateHorizontalApertureAttr(20.0 * view["xmag"])
        prim.CreateVerticalApertureAttr(20.0 * view["ymag"])
    prim.CreateClippingRangeAttr(Gf.Vec2f(view["znear"], view["zfar"]))


def _identifier(name: str) -> str:
    """``name`` as a USD prim name (letters, digits and underscores, not starting with a
    digit); the node's own name is kept in its ``customData``."""
    from pxr import Tf

    return Tf.MakeValidIdentifier(name)
