"""Render a scenewright GLB in Godot 3 (Debian's ``godot3``), from the file's camera, as a
game project that imports the file shows it:

    python3 scripts/godot_render.py out/scene.glb out/godot.png 640 480

It makes a throwaway Godot project in a temporary folder, copies the GLB in, lets the
editor import it (``godot3 --editor --quit``: Godot imports a .glb as a scene), then runs
a small GDScript that instances the imported scene, makes the file's camera current,
renders one frame and saves the viewport as a PNG. Godot needs a display and OpenGL: it
runs under ``xvfb-run`` (Mesa's software OpenGL on a machine without a GPU), with the
GLES3 renderer.

The colours, normals, camera and sun are the file's: Godot's importer turns the
KHR_lights_punctual sun into a DirectionalLight. Its energy is divided by pi: Godot
3.2's importer copies the glTF intensity (lux) into the light's energy, and a Godot
energy of 1 already lights a face turned to the light with its full colour. The sun
casts shadows. As in ``scripts/blender_render.py`` and ``scripts/threejs_render.py`` the
script adds only what surrounds the scene: an environment of the preview's background
colour (sky outdoors, light grey round a room) whose ambient light lights the faces
turned away from the sun. It prints what Godot made of the file as one JSON line after
``PROBE`` (each node's path and class, how many directional lights), which
``tests/test_godot_import.py`` reads. Exit status 2 with one line
on stderr when the file, ``godot3`` or ``xvfb-run`` is missing or Godot fails."""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import NoReturn

PROJECT = """; Engine configuration file.
config_version=4

[application]
config/name="scenewright import"

[display]
window/size/width=__WIDTH__
window/size/height=__HEIGHT__
window/vsync/use_vsync=false

[rendering]
quality/driver/driver_name="GLES3"
quality/driver/fallback_to_gles2=true
environment/default_clear_color=Color( __BACK__, 1 )
"""

# Runs as the main loop (godot3 -s render.gd): instance the import, take its camera, add
# the sky, wait for frames to be drawn, then save the root viewport's texture.
RENDER = """extends SceneTree

var frames = 0
var probe = {}

func walk(node, path):
	probe[path] = node.get_class()
	for child in node.get_children():
		walk(child, path + "/" + child.name)

func first_of(node, kind):
	if node.is_class(kind):
		return node
	for child in node.get_children():
		var found = first_of(child, kind)
		if found != null:
			return found
	return null

func _init():
	var packed = load("res://scene.glb")
	if packed == null:
		printerr("FAILED Godot did not import the file")
		quit(3)
		return
	var scene = packed.instance()
	root.add_child(scene)
	walk(scene, scene.name)
	var camera = first_of(scene, "Camera")
	if camera == null:
		printerr("FAILED the file has no camera")
		quit(3)
		return
	camera.current = true
	var lights = 0
	for path in probe:
		if probe[path] == "DirectionalLight":
			lights += 1
			var sun = scene.get_node(path.substr(scene.name.length() + 1))
			# Godot 3.2's importer copies the glTF intensity (lux) into the light's
			# energy, but a Godot energy of 1 already lights a face turned to it with
			# its full colour: lux over pi is the radiance glTF viewers give it.
			sun.light_energy = sun.light_energy / PI
			sun.shadow_enabled = true
			sun.directional_shadow_max_distance = 2.0 * camera.global_transform.origin.length() + 10.0
	# What surrounds the scene: the preview's background behind it, and its colour as
	# ambient light so that the faces turned away from the sun are not black (sky blue
	# outdoors; light grey round a room, which a blue sky would tint).
	var environment = Environment.new()
	environment.background_mode = Environment.BG_COLOR
	environment.background_color = Color(__BACK__)
	environment.ambient_light_color = Color(__BACK__)
	environment.ambient_light_energy = 0.5
	var world = WorldEnvironment.new()
	world.environment = environment
	root.add_child(world)
	print("PROBE" + to_json({"nodes": probe, "lights": lights}))

func _idle(_delta):
	frames += 1
	# a few frames: the first ones may still be compiling shaders
	if frames < 5:
		return false
	var image = root.get_texture().get_data()
	image.flip_y()
	var failed = image.save_png("__OUT__")
	if failed != OK:
		printerr("FAILED could not write the image")
		quit(3)
		return true
	quit(0)
	return true
"""


def fail(message: str) -> NoReturn:
    print(f"godot_render: {message}", file=sys.stderr)
    sys.exit(2)


def document(glb: Path) -> dict:
    """The GLB's JSON chunk."""
    data = glb.read_bytes()
    if data[:4] != b"glTF" or len(data) < 20:
        raise ValueError(f"not a GLB file: {glb}")
    length = int.from_bytes(data[12:16], "little")
    try:
        return json.loads(data[20 : 20 + length])
    except ValueError:
        raise ValueError(f"not a GLB file: {glb} (its JSON chunk does not read)") from None


def background(glb: Path) -> str:
    """The preview's background as a GDScript colour: light grey round a room (whose file
    has a floor node), sky outdoors; the preview writes sRGB, as Godot's Color takes it."""
    names = {node.get("name") for node in document(glb).get("nodes", [])}
    return "0.9, 0.9, 0.9" if "floor" in names else "0.62, 0.77, 0.92"


def render(glb: Path, out: Path, width: int, height: int, timeout: float = 300.0) -> dict:
    """Render ``glb`` to the PNG ``out``; returns the probe (node paths and classes, number
    of directional lights). Raises RuntimeError with a one-line reason."""
    back = background(glb)
    with tempfile.TemporaryDirectory(prefix="scenewright-godot-") as folder:
        project = Path(folder)
        shutil.copyfile(glb, project / "scene.glb")
        (project / "project.godot").write_text(
            PROJECT.replace("__WIDTH__", str(width))
            .replace("__HEIGHT__", str(height))
            .replace("__BACK__", back)
        )
        image = project / "render.png"
        (project / "render.gd").write_text(
            RENDER.replace("__BACK__", back).replace("__OUT__", str(image))
        )
        # Godot writes its settings and caches under HOME; keep them in the throwaway folder.
        # Mesa's compiled shaders stay where Mesa keeps them for this user (a folder it
        # creates when it can, and goes without otherwise): kept in the throwaway folder,
        # they were compiled anew by every run, about 1 s of 8.
        cache = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        mesa = os.environ.get("MESA_SHADER_CACHE_DIR") or str(Path(cache) / "mesa_shader_cache")
        home = str(project / "home")
        env = dict(os.environ, HOME=home, XDG_CONFIG_HOME=home, XDG_DATA_HOME=home)
        env["MESA_SHADER_CACHE_DIR"] = mesa
        env["XDG_CACHE_HOME"] = home
        xvfb = ["xvfb-run", "-a", "-s", f"-screen 0 {max(width, 640)}x{max(height, 480)}x24"]
        imported = subprocess.run(
            [*xvfb, "godot3", "--path", str(project), "--editor", "--quit"],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=env,
        )
        if not (project / ".import").is_dir() or not any((project / ".import").iterdir()):
            raise RuntimeError(
                "Godot did not import the file: " + _last_line(imported.stderr + imported.stdout)
            )
        done = subprocess.run(
            [
                *xvfb,
                "godot3",
                "--path",
                str(project),
                "--resolution",
                f"{width}x{height}",
                "-s",
                "res://render.gd",
            ],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=env,
        )
        probe = None
        for line in done.stdout.splitlines():
            if line.startswith("PROBE"):
                probe = json.loads(line[len("PROBE") :])
        if done.returncode != 0 or probe is None or not image.is_file():
            raise RuntimeError("Godot failed: " + _last_line(done.stderr + done.stdout))
        out.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(image, out)
    print("PROBE" + json.dumps(probe))
    return probe


def _last_line(text: str) -> str:
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    failed = [line for line in lines if "FAILED" in line or "ERROR" in line]
    return (failed or lines or ["no output"])[-1][:300]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("glb", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("width", type=int, nargs="?", default=640)
    parser.add_argument("height", type=int, nargs="?", default=480)
    args = parser.parse_args()
    if not args.glb.is_file():
        fail(f"no such file: {args.glb}")
    if not (16 <= args.width <= 8192 and 16 <= args.height <= 8192):
        fail("width and height must be between 16 and 8192")
    for tool, package in (("godot3", "godot3"), ("xvfb-run", "xvfb")):
        if shutil.which(tool) is None:
            fail(f"{tool} is not installed (apt-get install {package})")
    try:
        render(args.glb, args.out, args.width, args.height)
    except (RuntimeError, ValueError, OSError, subprocess.TimeoutExpired) as error:
        fail(str(error).splitlines()[0] if str(error) else type(error).__name__)


if __name__ == "__main__":
    main()
