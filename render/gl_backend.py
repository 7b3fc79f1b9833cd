"""The OpenGL side of the offscreen renderer. ``load_pyrender`` chooses the backend
before pyrender is imported: the user's ``PYOPENGL_PLATFORM`` if set, else EGL when
libEGL is installed, else OSMesa; when none can start, ``GenerationError`` says what to
install. ``pyrender_classes`` gives pyrender's Renderer and Scene with less work per
pass, drawing the same pixels (one bilinear shadow lookup instead of nine:
``shader_source``), and ``keep_display_on_delete`` stops a closed renderer from taking
the process's one EGL display with it.
"""

from __future__ import annotations

import ctypes.util
import importlib
import os
import sys
import threading
import types
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from scenewright.core.errors import GenerationError

#: pyrender's fragment shader softens each shadow lookup over a 3x3 grid of bilinear
#: lookups: 36 shadow-map reads on every pixel of every colour pass, which a software
#: OpenGL pays in full (design notes, docs/notes/design.md, "Offscreen rendering"). One
#: bilinear lookup, 4 reads, draws the same shadows with edges about one texel soft
#: instead of three.
PYRENDER_SHADOW_FILTER = """    float result = 0.0;
    for(int x=-1; x<=1; x++){
        for(int y=-1; y<=1; y++){
            vec2 off = vec2(x,y)/size;
            result += texture2DShadowLerp(depths, size, uv+off, compare);
        }
    }
    return result/9.0;"""
SHADOW_FILTER = "    return texture2DShadowLerp(depths, size, uv, compare);"

INSTALL_HINT = (
    "install EGL (apt-get install libegl1 libegl-mesa0) and set PYOPENGL_PLATFORM=egl, "
    "or OSMesa (apt-get install libosmesa6) and set PYOPENGL_PLATFORM=osmesa"
)


def keep_display_on_delete(renderer) -> None:
    """Make deleting ``renderer`` (a pyrender OffscreenRenderer) leave the EGL display up.

    pyrender's EGL platform terminates the EGL display when a renderer is deleted. The
    display is one and the same for every renderer of the process, so closing one
    renderer broke every other one still alive (their next eglMakeCurrent failed with
    EGL_BAD_DISPLAY): a dataset worker's kept renderer after a test, or another thread's,
    had drawn and closed its own. Only the renderer's own context is released here.
    """
    platform = getattr(renderer, "_platform", None)
    if platform is None or type(platform).__name__ != "EGLPlatform":
        return

    def delete_context() -> None:
        from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglDestroyContext, eglMakeCurrent

        if platform._egl_display is not None and platform._egl_context is not None:
            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
            eglDestroyContext(platform._egl_display, platform._egl_context)
        platform._egl_context = None
        platform._egl_display = None

    platform.delete_context = delete_context


def release(renderer) -> None:
    """Free ``renderer``'s (a pyrender OffscreenRenderer) OpenGL resources and context.

    pyrender's own ``delete`` does the same and then runs a full garbage collection of
    the process, a tenth of a cold command's render time with a scene's objects alive;
    nothing of the renderer's is left for it to find (its OpenGL objects are freed here).
    """
    renderer._platform.make_current()
    renderer._renderer.delete()
    renderer._platform.delete_context()
    renderer._renderer = None
    renderer._platform = None


def load_pyrender():
    """Import pyrender with an offscreen platform chosen, or say what to install."""
    if "PYOPENGL_PLATFORM" not in os.environ:
        if ctypes.util.find_library("EGL"):
            os.environ["PYOPENGL_PLATFORM"] = "egl"
        elif ctypes.util.find_library("OSMesa"):
            os.environ["PYOPENGL_PLATFORM"] = "osmesa"
        else:
            raise GenerationError(f"no offscreen OpenGL library found; {INSTALL_HINT}")
    try:
        return _import_without_viewer()
    except Exception as error:  # PyOpenGL raises various errors for a broken platform
        raise backend_error(error) from None


def _import_without_viewer():
    """Import pyrender without its interactive viewer.

    pyrender's package imports ``pyrender.viewer`` (pyglet's window system and imageio)
    whether or not a window is ever opened: about 0.12 s of every command that renders,
    a tenth of a cold ``generate``'s start-up. The offscreen renderer never opens one,
    so pyrender is imported with a stand-in for that module; its ``Viewer`` imports the
    real viewer when called, and the stand-in is gone from ``sys.modules`` afterwards,
    so ``from pyrender.viewer import Viewer`` still gets the real one.
    """
    # One thread at a time (a dask worker's threads each start a renderer): another
    # thread must neither see the stand-in come and go nor take a pyrender still being
    # imported; import_module waits for a module another thread is importing.
    with _IMPORTING:
        if "pyrender" in sys.modules:
            return importlib.import_module("pyrender")

        def viewer(*args, **kwargs):
            from pyrender.viewer import Viewer

            return Viewer(*args, **kwargs)

        stand_in = types.ModuleType("pyrender.viewer")
        stand_in.Viewer = viewer  # type: ignore[attr-defined]
        sys.modules["pyrender.viewer"] = stand_in
        try:
            return importlib.import_module("pyrender")
        finally:
            del sys.modules["pyrender.viewer"]


_IMPORTING = threading.Lock()


@dataclass(frozen=True)
class PyrenderClasses:
    """The pyrender classes a ``Renderer`` draws with."""

    renderer: type
    scene: type


@lru_cache(maxsize=1)
def pyrender_classes(gl) -> PyrenderClasses:
    """pyrender's Renderer and Scene with less work per pass, drawing the same pixels.

    pyrender draws every pass into its 4x multisampled framebuffer, then resolves its
    colour and depth, reads the depth as floats and linearises it. A segmentation pass
    is drawn with multisampling off (each pixel takes its centre's triangle), so its
    samples are all alike: it is drawn here into a plain framebuffer of the same size
    instead, and only its colour is read (its depth, which nobody uses, is returned as
    None). Colour passes are pyrender's own but for the shadow's softening
    (``shader_source``).

    pyrender also recomputes, in every pass, every node's world pose (for each
    primitive drawn, and again for the camera's position), the nodes' order by distance
    from the camera, and which meshes and textures the GPU holds; a frame draws one
    scene in up to a dozen passes without changing it, so these are kept until the
    scene changes (a node added, removed or moved through the scene).
    """
    from OpenGL import GL
    from pyrender.shader_program import ShaderProgram, ShaderProgramCache

    class FrameScene(gl.Scene):
        """A pyrender scene that keeps node poses and the renderer's per-scene
        results until it changes."""

        def __init__(self, *args, **kwargs):
            self._poses: dict = {}
            self.frame_cache: dict = {}  # the renderer's results for this scene as it is
            self.version = 0  # counts the changes
            self._added: dict = {}  # node -> when it was added (draw order, below)
            self._additions = 0
            super().__init__(*args, **kwargs)

        def _changed(self) -> None:
            self._poses.clear()
            self.frame_cache.clear()
            self.version += 1

        def add_node(self, node, parent_node=None):
            self._changed()
            if node not in self._added:
                self._added[node] = self._additions
                self._additions += 1
            return super().add_node(node, parent_node=parent_node)

        def remove_node(self, node):
            self._changed()
            return super().remove_node(node)

        def _remove_node(self, node):  # pyrender's: the node, then each child the same way
            self._added.pop(node, None)
            return super()._remove_node(node)

        def added_order(self, node) -> int:
            return self._added.get(node, self._additions)

        def set_pose(self, node, pose):
            self._changed()
            return super().set_pose(node, pose)

        def clear(self):
            self._changed()
            self._added.clear()
            return super().clear()

        def get_pose(self, node):
            pose = self._poses.get(node)
            if pose is None:
                pose = super().get_pose(node)
                pose.setflags(
                    write=False
                )  # shared by every caller; pyrender copies before changing one
                self._poses[node] = pose
            return pose

    class Program(ShaderProgram):
        """pyrender's shader program, with our shadow filter (``shader_source``) and its
        uniforms' locations asked of OpenGL once per compiled program instead of at
        every ``set_uniform`` (a frame sets some 2000). ``set_uniform`` is pyrender's
        otherwise, down to ignoring a name the program lacks or a value of no known type."""

        _locations: dict | None = None

        def _load(self, shader_filename):
            return shader_source(os.path.basename(shader_filename), super()._load(shader_filename))

        def _add_to_context(self):
            self._locations = {}  # a new program: its locations are its own
            return super()._add_to_context()

        def set_uniform(self, name, value, unsigned=False):
            loc = self._locations.get(name)
            if loc is None:
                loc = self._locations[name] = GL.glGetUniformLocation(self._program_id, name)
            if loc == -1:
                return
            if isinstance(value, np.ndarray):
                if value.ndim == 1:
                    if np.issubdtype(value.dtype, np.unsignedinteger) or unsigned:
                        kind, value = "u", value.astype(np.uint32)
                    elif np.issubdtype(value.dtype, np.integer):
                        kind, value = "i", value.astype(np.int32)
                    else:
                        kind, value = "f", value.astype(np.float32)
                    self._FUNC_MAP[(value.shape[0], kind)](loc, 1, value)
                else:
                    self._FUNC_MAP[value.shape](loc, 1, GL.GL_TRUE, value)
            elif isinstance(value, float):
                GL.glUniform1f(loc, value)
            elif isinstance(value, int):  # bool included, as 0 or 1
                (GL.glUniform1ui if unsigned else GL.glUniform1i)(loc, int(value))

    class Programs(ShaderProgramCache):
        def get_program(self, *args, **kwargs):
            program = super().get_program(*args, **kwargs)
            if type(program) is ShaderProgram:  # just made, not compiled yet
                program.__class__ = Program
            return program

    class PassRenderer(gl.Renderer):
        _seg_fb = None
        _seg_buffers = None
        _context_of = None  # (scene, its version, shadow flags) of the last context update

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self._program_cache = Programs()
            self._max_lights: dict = {}

        def _compute_max_n_lights(self, flags):
            # pyrender asks it for every primitive drawn; it depends on the flags and the
            # context's count of texture units only.
            if flags not in self._max_lights:
                self._max_lights[flags] = super()._compute_max_n_lights(flags)
            return self._max_lights[flags]

        def _get_light_cam_matrices(self, scene, light_node, flags):
            # Asked for every primitive drawn with shadows; it depends on the scene's
            # bounds and the light's pose, which a FrameScene keeps until it changes.
            if not isinstance(scene, FrameScene):
                return super()._get_light_cam_matrices(scene, light_node, flags)
            key = ("light matrices", light_node)
            if key not in scene.frame_cache:
                matrices = super()._get_light_cam_matrices(scene, light_node, flags)
                for matrix in matrices:
                    matrix.setflags(write=False)
                scene.frame_cache[key] = matrices
            return scene.frame_cache[key]

        def _sorted_mesh_nodes(self, scene):
            # pyrender's order: solid meshes, then see-through ones, each farthest first.
            # It starts from a set of nodes, ordered by their addresses in memory, so two
            # meshes as far from the camera (a window's pane and frame) were drawn in
            # either order from run to run and a pixel where both blend came out either
            # way. Here they start in the order they were added.
            if not isinstance(scene, FrameScene):
                return super()._sorted_mesh_nodes(scene)
            if "sorted" not in scene.frame_cache:
                camera = scene.get_pose(scene.main_camera_node)[:3, 3]
                nodes = sorted(scene.mesh_nodes, key=scene.added_order)

                def farthest_first(node) -> float:
                    return -float(np.linalg.norm(scene.get_pose(node)[:3, 3] - camera))

                solid = sorted((n for n in nodes if not n.mesh.is_transparent), key=farthest_first)
                clear = sorted((n for n in nodes if n.mesh.is_transparent), key=farthest_first)
                scene.frame_cache["sorted"] = solid + clear
            return scene.frame_cache["sorted"]

        def _update_context(self, scene, flags):
            # What pyrender updates depends on the scene and the shadow flags only.
            shadows = flags & (
                gl.RenderFlags.SHADOWS_DIRECTIONAL
                | gl.RenderFlags.SHADOWS_SPOT
                | gl.RenderFlags.SHADOWS_POINT
            )
            last = self._context_of
            if (
                isinstance(scene, FrameScene)
                and last
                and last[0] is scene
                and last[1:] == (scene.version, shadows)
            ):
                return
            super()._update_context(scene, flags)
            self._context_of = (
                (scene, scene.version, shadows) if isinstance(scene, FrameScene) else None
            )

        def _configure_shadow_mapping_viewport(self, light, flags):
            # pyrender sets the viewport to its default map size (2048) whatever the
            # light's texture is: a smaller map then held only a corner of the view.
            super()._configure_shadow_mapping_viewport(light, flags)
            GL.glViewport(0, 0, light.shadow_texture.width, light.shadow_texture.height)

        def _configure_forward_pass_viewport(self, flags):
            if not (flags & gl.RenderFlags.SEG and flags & gl.RenderFlags.OFFSCREEN):
                return super()._configure_forward_pass_viewport(flags)
            if self._seg_fb is None:
                colour, depth = GL.glGenRenderbuffers(2)
                GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, colour)
                GL.glRenderbufferStorage(
                    GL.GL_RENDERBUFFER, GL.GL_RGBA, self.viewport_width, self.viewport_height
                )
                GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, depth)
                GL.glRenderbufferStorage(
                    GL.GL_RENDERBUFFER,
                    GL.GL_DEPTH_COMPONENT24,
                    self.viewport_width,
                    self.viewport_height,
                )
                self._seg_fb = GL.glGenFramebuffers(1)
                GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, self._seg_fb)
                GL.glFramebufferRenderbuffer(
                    GL.GL_DRAW_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0, GL.GL_RENDERBUFFER, colour
                )
                GL.glFramebufferRenderbuffer(
                    GL.GL_DRAW_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT, GL.GL_RENDERBUFFER, depth
                )
                self._seg_buffers = (colour, depth)
            GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, self._seg_fb)
            GL.glViewport(0, 0, self.viewport_width, self.viewport_height)
            GL.glEnable(GL.GL_DEPTH_TEST)
            GL.glDepthMask(GL.GL_TRUE)
            GL.glDepthFunc(GL.GL_LESS)
            GL.glDepthRange(0.0, 1.0)

        def _read_main_framebuffer(self, scene, flags):
            if not flags & gl.RenderFlags.SEG:
                return super()._read_main_framebuffer(scene, flags)
            width, height = self.viewport_width, self.viewport_height
            GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, self._seg_fb)
            pixels = GL.glReadPixels(0, 0, width, height, GL.GL_RGB, GL.GL_UNSIGNED_BYTE)
            colour = np.frombuffer(pixels, dtype=np.uint8).reshape((height, width, 3))
            return np.flip(colour, axis=0), None

        def delete(self):
            super().delete()
            self._context_of = None
            if self._seg_fb is not None:
                GL.glDeleteFramebuffers(1, [self._seg_fb])
                GL.glDeleteRenderbuffers(2, list(self._seg_buffers))
                self._seg_fb = self._seg_buffers = None

    return PyrenderClasses(renderer=PassRenderer, scene=FrameScene)


def shader_source(name: str, text: str) -> str:
    """The source of pyrender's shader file ``name`` (``text``, its defines applied) as
    the renderer compiles it: ``mesh.frag`` with one bilinear shadow lookup
    (``SHADOW_FILTER``), the others as they are."""
    if name != "mesh.frag":
        return text
    if PYRENDER_SHADOW_FILTER not in text:
        raise GenerationError(
            "pyrender's mesh.frag is not the one this renderer was written for (pyrender 0.1.45)"
        )
    return text.replace(PYRENDER_SHADOW_FILTER, SHADOW_FILTER)


def backend_error(error: Exception) -> GenerationError:
    platform = os.environ.get("PYOPENGL_PLATFORM", "")
    reason = " ".join(str(error).split()) or type(error).__name__
    return GenerationError(
        f"offscreen OpenGL backend PYOPENGL_PLATFORM={platform!r} could not start ({reason}); {INSTALL_HINT}"
    )
