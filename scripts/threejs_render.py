"""Render a scenewright GLB with three.js in headless Chromium, from the file's camera,
as a web page that loads the file with three.js's GLTFLoader shows it:

    python3 scripts/threejs_render.py out/scene.glb out/threejs.png 640 480 [--three DIR] [--chromium PATH]

``--three`` is the folder of the npm package ``three`` (default: ``$SCENEWRIGHT_THREE``,
else ``.tools-three/node_modules/three`` or ``.tools/node_modules/three`` of this
checkout; ``npm install --prefix .tools-three three`` fills the first). ``--chromium``
defaults to ``chromium`` on the PATH. The page is served by a server on 127.0.0.1 (ES
modules do not load from file:// pages) and sends the canvas back to it as a PNG;
nothing else is reached.

The colours, normals, camera and sun are the file's. A glTF directional light lights
only the faces turned towards it, so the sides turned away would be black: the page adds
a hemisphere light standing for the sky, as Blender's world does in
``scripts/blender_render.py`` (sky colour above, darker below), and turns the sun's
shadows on over the scene's objects. Exit status 2 with one line on stderr when the
file, three.js or Chromium is missing or the page fails."""

import argparse
import base64
import http.server
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

# What the page does: load the GLB, use its camera and lights, add the sky's light, render
# once and post the canvas to /result (errors to /error).
PAGE = """<!DOCTYPE html>
<html><head><meta charset="utf-8"><style>body{margin:0}</style>
<script type="importmap">
{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}
</script></head><body>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const W = __WIDTH__, H = __HEIGHT__;
const report = (where, body) => fetch(where, {method: 'POST', body});
window.addEventListener('error', e => report('/error', String(e.message)));
window.addEventListener('unhandledrejection', e => report('/error', String(e.reason)));
try {
  const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(1);
  renderer.setSize(W, H);
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFSoftShadowMap;
  document.body.appendChild(renderer.domElement);
  const gltf = await new GLTFLoader().loadAsync('/scene.glb');
  // gltf.scene is a Group: the background belongs to a Scene round it.
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  // The preview's background, taken as sRGB as the preview writes it: sky outdoors
  // (render.offscreen.SKY), light grey round a room (INDOOR_BACKGROUND), whose file has a floor.
  const indoor = gltf.scene.getObjectByName('floor') !== undefined;
  const back = indoor ? [0.9, 0.9, 0.9] : [0.62, 0.77, 0.92];
  scene.background = new THREE.Color().setRGB(...back, THREE.SRGBColorSpace);
  // Blender's world of the sky colour at strength 0.5 is a radiance of 0.5 x sky from every
  // direction; three.js divides an ambient irradiance by pi, hence 0.5 * pi.
  scene.add(new THREE.HemisphereLight(new THREE.Color(0.62, 0.77, 0.92), new THREE.Color(0.25, 0.25, 0.25), 0.5 * Math.PI));
  scene.updateMatrixWorld(true);
  let camera = gltf.cameras[0];
  if (!camera) throw new Error('the file has no camera');
  camera.aspect = W / H;
  camera.updateProjectionMatrix();
  // Shadows: every mesh casts and receives; the sun's shadow camera covers the bodies,
  // not the ground (three times the scene), so its map stays fine.
  const bodies = new THREE.Box3();
  scene.traverse(o => {
    if (!o.isMesh) return;
    o.castShadow = true; o.receiveShadow = true;
    let top = o; while (top.parent && top.parent !== gltf.scene) top = top.parent;
    if (top.name !== 'ground' && top.name !== 'floor') bodies.expandByObject(o);
  });
  scene.traverse(o => {
    if (!o.isDirectionalLight || bodies.isEmpty()) return;
    o.castShadow = true;
    const shadowCamera = o.shadow.camera;
    const from = new THREE.Vector3().setFromMatrixPosition(o.matrixWorld);
    const to = new THREE.Vector3().setFromMatrixPosition(o.target.matrixWorld);
    shadowCamera.position.copy(from);
    shadowCamera.lookAt(to);
    shadowCamera.updateMatrixWorld(true);
    const inverse = shadowCamera.matrixWorldInverse;
    const box = new THREE.Box3();
    for (let i = 0; i < 8; i++) {
      box.expandByPoint(new THREE.Vector3(
        i & 1 ? bodies.max.x : bodies.min.x, i & 2 ? bodies.max.y : bodies.min.y,
        i & 4 ? bodies.max.z : bodies.min.z).applyMatrix4(inverse));
    }
    const margin = 0.05 * Math.max(box.max.x - box.min.x, box.max.y - box.min.y);
    shadowCamera.left = box.min.x - margin; shadowCamera.right = box.max.x + margin;
    shadowCamera.bottom = box.min.y - margin; shadowCamera.top = box.max.y + margin;
    // A glTF sun is only a direction: its node may stand among the bodies, so the
    // orthographic shadow camera's near plane may lie behind it.
    shadowCamera.near = -box.max.z - margin; shadowCamera.far = -box.min.z + margin;
    shadowCamera.updateProjectionMatrix();
    o.shadow.mapSize.set(4096, 4096);
    o.shadow.bias = -0.0005;
    o.shadow.normalBias = 0.02;
  });
  renderer.render(scene, camera);
  await report('/result', renderer.domElement.toDataURL('image/png'));
} catch (e) {
  await report('/error', String(e && e.stack || e));
}
</script></body></html>
"""


def default_three() -> Path | None:
    """The three.js package this checkout has, if any."""
    candidates = [os.environ.get("SCENEWRIGHT_THREE", "")]
    candidates += [
        str(REPO / ".tools-three/node_modules/three"),
        str(REPO / ".tools/node_modules/three"),
    ]
    for candidate in candidates:
        if candidate and (Path(candidate) / "build/three.module.js").is_file():
            return Path(candidate)
    return None


def render(
    glb: Path,
    out: Path,
    width: int,
    height: int,
    three: Path,
    chromium: str,
    timeout: float = 120.0,
) -> None:
    """Render ``glb`` to the PNG ``out``; raises RuntimeError with a one-line reason."""
    page = PAGE.replace("__WIDTH__", str(width)).replace("__HEIGHT__", str(height)).encode()
    outcome: dict[str, bytes] = {}
    done = threading.Event()

    class Handler(http.server.BaseHTTPRequestHandler):
        def log_message(self, *args: object) -> None:  # quiet: the result is the PNG
            pass

        def do_GET(self) -> None:
            path = self.path.split("?")[0]
            body, kind = None, "application/octet-stream"
            if path == "/index.html":
                body, kind = page, "text/html"
            elif path == "/scene.glb":
                body = glb.read_bytes()
            elif path.startswith("/three/") and ".." not in path:
                file = three / path[len("/three/") :]
                if file.is_file():
                    body, kind = file.read_bytes(), "text/javascript"
            if body is None:
                self.send_error(404)
                return
            self.send_response(200)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def do_POST(self) -> None:
            data = self.rfile.read(int(self.headers.get("Content-Length", 0)))
            outcome[self.path] = data
            self.send_response(204)
            self.end_headers()
            if self.path in ("/result", "/error"):
                done.set()

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    profile = tempfile.mkdtemp(prefix="threejs-render-")
    url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
    command = [
        chromium,
        "--headless=new",
        "--no-sandbox",  # Chromium refuses to start as root with its sandbox
        "--use-angle=swiftshader",  # WebGL on the CPU: no GPU or display needed
        "--enable-unsafe-swiftshader",
        "--no-first-run",
        "--disable-extensions",
        "--disable-background-networking",
        f"--user-data-dir={profile}",
        f"--window-size={width},{height}",
        url,
    ]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        if not done.wait(timeout):
            raise RuntimeError(f"three.js page gave no image within {timeout:.0f} s")
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
        server.shutdown()
        shutil.rmtree(profile, ignore_errors=True)
    if "/error" in outcome:
        raise RuntimeError(
            "three.js page failed: " + outcome["/error"].decode(errors="replace").splitlines()[0]
        )
    data_url = outcome["/result"].decode()
    png = base64.b64decode(data_url.split(",", 1)[1])
    out.parent.mkdir(parents=True, exist_ok=True)
    partial = out.with_name(out.name + ".part")
    partial.write_bytes(png)
    partial.replace(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("glb", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("width", type=int, nargs="?", default=640)
    parser.add_argument("height", type=int, nargs="?", default=480)
    parser.add_argument("--three", type=Path, default=None, help="folder of the npm package three")
    parser.add_argument("--chromium", default="chromium", help="Chromium executable")
    args = parser.parse_args(argv)
    three = args.three or default_three()
    problem = None
    if not args.glb.is_file():
        problem = f"no such file: {args.glb}"
    elif three is None or not (three / "build/three.module.js").is_file():
        problem = "three.js not found: npm install --prefix .tools-three three, or pass --three"
    elif shutil.which(args.chromium) is None:
        problem = f"{args.chromium} not found: apt-get install chromium, or pass --chromium"
    elif not (0 < args.width <= 4096 and 0 < args.height <= 4096):
        problem = "width and height must be 1..4096"
    if problem is None:
        try:
            render(args.glb, args.out, args.width, args.height, three, args.chromium)  # type: ignore[arg-type]
        except RuntimeError as error:
            problem = str(error)
    if problem is not None:
        print(f"threejs_render: {problem}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
