"""Time and peak memory of the hostile inputs of the hardening of example files, plans
and count options: each runs as the command a user would type, in a fresh process.

    .venv/bin/python benchmarks/bench_hostile_inputs.py
    .venv/bin/python benchmarks/bench_hostile_inputs.py --nodes 10000 --stack 1500

Prints, per input, the exit code, the wall time, the peak resident memory of the
command and the first 100 characters of what it said. The GLBs are made here: one box
mesh used by N nodes on a grid (the largest allowed, and twice that), and the 840-byte
kind with an accessor of 50 million elements and no data. Prints figures only.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from test_hostile_examples import box_document, glb_bytes  # noqa: E402

from scenewright.examples.glb_check import MAX_GLB_NODES  # noqa: E402


def grid_glb(path: Path, count: int) -> Path:
    document, binary = box_document([f"chair.{k:05d}" for k in range(count)])
    side = math.ceil(math.sqrt(count))
    for k, node in enumerate(document["nodes"]):
        node["translation"] = [1.5 * (k % side), 0.0, 1.5 * (k // side)]
    path.write_bytes(glb_bytes(document, binary))
    return path


def hollow_glb(path: Path) -> Path:
    document, binary = box_document()
    document["accessors"].append({"componentType": 5126, "count": 50_000_000, "type": "VEC3"})
    document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2
    path.write_bytes(glb_bytes(document, binary))
    return path


def stack(path: Path, count: int) -> Path:
    objects = [{"id": "o0", "type": "crate", "size": [1, 0.1, 1], "position": [0, 0]}]
    objects += [
        {
            "id": f"o{k}",
            "type": "crate",
            "size": [1, 0.1, 1],
            "position": [0, 0],
            "parent": f"o{k - 1}",
        }
        for k in range(1, count)
    ]
    path.write_text(json.dumps({"extent": [20, 20], "objects": objects}))
    return path


def run(label: str, *argv: str) -> None:
    command = [
        sys.executable,
        "-c",
        "import resource, sys\n"
        "from scenewright.cli import main\n"
        "code = main(sys.argv[1:])\n"
        "sys.stderr.write(f'\\nPEAK {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}\\n')\n"
        "sys.exit(code)\n",
        *argv,
    ]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, timeout=600)
    seconds = time.perf_counter() - start
    lines = (done.stdout + done.stderr).strip().splitlines()
    peak = next((int(line.split()[1]) for line in lines if line.startswith("PEAK ")), 0)
    said = next((line for line in lines if line and not line.startswith("PEAK ")), "")
    said = said.split(": ", 1)[-1] if said.startswith("/") else said
    print(
        f"{label:<34} exit {done.returncode}  {seconds:6.2f} s  {peak / 1024:7.0f} MiB  {said[:100]}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=MAX_GLB_NODES)
    parser.add_argument("--stack", type=int, default=1500)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        tmp = Path(folder)
        run("GLB accessor of 5e7, no data", "validate", str(hollow_glb(tmp / "hollow.glb")))
        run(f"GLB of {args.nodes} nodes", "validate", str(grid_glb(tmp / "n.glb", args.nodes)))
        big = grid_glb(tmp / "n2.glb", 2 * args.nodes)
        run(f"GLB of {2 * args.nodes} nodes", "validate", str(big))
        run(f"stack of {args.stack} objects", "validate", str(stack(tmp / "s.json", args.stack)))
        (tmp / "deep.json").write_text("[" * 100_000 + "]" * 100_000)
        run("JSON nested 100,000 deep", "validate", str(tmp / "deep.json"))
        corners = " ".join(
            f"{10 * math.cos(k * math.tau / 1000):.4f},{10 * math.sin(k * math.tau / 1000):.4f}"
            for k in range(1000)
        )
        run(
            "complete, room of 1000 corners",
            "complete",
            "--room",
            corners,
            "--with",
            "bed",
            "-o",
            str(tmp / "c"),
        )
        run(
            "complete --room 1000x1000",
            "complete",
            "--room",
            "1000x1000",
            "--with",
            "bed",
            "-o",
            str(tmp / "c"),
        )
        run("vary -n 1000000000", "vary", "a", "b", "-n", "1000000000", "-o", str(tmp / "v"))
        run(
            "dataset --captions 100000",
            "dataset",
            "desk",
            "-n",
            "1",
            "--captions",
            "100000",
            "-o",
            str(tmp / "d"),
        )


if __name__ == "__main__":
    main()
