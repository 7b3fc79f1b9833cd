"""Offscreen rendering speed: renderer start-up, then seconds per 640x480 frame.

A frame is everything ``Renderer.render`` returns: colour (with the sun's shadows),
depth, instance segmentation, 2D boxes and visible fractions. The scene is a village
from the shipped rules (``scenewright`` pipeline, one seed per frame, layout time not
counted); while the generator cannot produce one, a synthetic scene of village size
(35 objects, three roads) stands in and the output says so.

    .venv/bin/python benchmarks/bench_render.py [--frames 20] [--no-shadows]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

from scenewright.render.offscreen import Renderer
from scenewright.scene import Scene, SceneObject, ScenePath

#: Village-like types: (type, shape, size w x h x d, colour).
KINDS = [
    ("house", "house", (6.0, 5.0, 5.0), (0.85, 0.8, 0.7)),
    ("shed", "shed", (3.0, 2.8, 2.5), (0.54, 0.42, 0.28)),
    ("tower", "tower", (4.0, 10.0, 4.0), (0.66, 0.64, 0.6)),
    ("oak_tree", "oak_tree", (6.0, 9.0, 6.0), (0.29, 0.48, 0.21)),
    ("bush", "bush", (1.6, 1.2, 1.6), (0.25, 0.45, 0.21)),
    ("street_lamp", "lamp_post", (0.4, 3.5, 0.4), (0.29, 0.23, 0.16)),
    ("barrel", "barrel", (0.6, 0.9, 0.6), (0.54, 0.35, 0.19)),
    ("table", "table", (1.6, 0.8, 0.9), (0.55, 0.35, 0.17)),
    ("wagon_of_grain", "grain_wagon", (1.6, 1.7, 3.0), (0.55, 0.37, 0.24)),
]


def synthetic_village(seed: int, objects: int = 35) -> Scene:
    """Three roads from a central junction and ``objects`` non-overlapping objects
    beside them, placed by rejection sampling with a seeded generator."""
    rng = np.random.default_rng(seed)
    extent = 60.0
    paths = []
    for k, angle in enumerate(rng.uniform(0, 2 * np.pi) + np.array([0.0, 2.1, 4.2])):
        bend = angle + rng.uniform(-0.4, 0.4)
        points = [[0.0, 0.0], [12 * np.cos(angle), 12 * np.sin(angle)], [26 * np.cos(bend), 26 * np.sin(bend)]]
        paths.append(ScenePath(f"road_{k + 1}", "road", "road", None, None, points, 3.0, "intersection_1"))
    placed = [SceneObject("intersection_1", "intersection", "junction", "intersection", None, None, None,
                          [0.0, 0.0, 0.0], 0.0, [4.0, 0.05, 4.0], colour=[0.61, 0.5, 0.38])]  # fmt: skip
    road_points = np.vstack([_densify(p.points) for p in paths])
    footprints: list[tuple[float, float, float]] = []
    counts: dict[str, int] = {}
    while len(placed) < objects + 1:
        type_name, shape, size, colour = KINDS[rng.integers(len(KINDS))]
        x, z = rng.uniform(-extent / 2 + 4, extent / 2 - 4, size=2)
        radius = float(np.hypot(size[0], size[2])) / 2
        if np.min(np.hypot(*(road_points - [x, z]).T)) < radius + 1.6:
            continue  # on a road
        if any(np.hypot(x - fx, z - fz) < radius + fr + 0.3 for fx, fz, fr in footprints):
            continue  # on another object
        footprints.append((x, z, radius))
        counts[type_name] = counts.get(type_name, 0) + 1
        placed.append(SceneObject(f"{type_name}_{counts[type_name]}", type_name, "object", type_name.replace("_", " "),
                                  None, None, None, [float(x), 0.0, float(z)], float(rng.uniform(0, 2 * np.pi)),
                                  list(size), shape=shape, colour=list(colour)))  # fmt: skip
    return Scene("synthetic village", seed, [extent, extent], placed, paths, [])


def _densify(points, step: float = 0.5) -> np.ndarray:
    points = np.asarray(points, dtype=float)
    pieces = [np.linspace(a, b, max(int(np.hypot(*(b - a)) / step), 2)) for a, b in zip(points[:-1], points[1:])]
    return np.vstack(pieces)


def village_scenes(frames: int) -> tuple[list[Scene], str]:
    """The scenes to render and where they came from."""
    try:
        from scenewright.api import build_scene

        return [build_scene("village", seed) for seed in range(frames)], "village rules"
    except ImportError as missing:  # the generator is not complete in this checkout
        note = f"synthetic village-sized scenes (village pipeline unavailable: {missing})"
        return [synthetic_village(seed) for seed in range(frames)], note


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--no-shadows", dest="shadows", action="store_false")
    options = parser.parse_args()

    scenes, source = village_scenes(options.frames)
    start = time.perf_counter()
    renderer = Renderer(options.width, options.height, shadows=options.shadows)
    startup = time.perf_counter() - start
    with renderer:
        renderer.render(scenes[0])  # the first frame compiles shaders: not a steady-state frame
        seconds, cpu_seconds = [], []
        for scene in scenes:
            start, cpu_start = time.perf_counter(), time.process_time()
            result = renderer.render(scene)
            seconds.append(time.perf_counter() - start)
            cpu_seconds.append(time.process_time() - cpu_start)
    drawn = len(result.ids)
    print(f"scenes: {source}; {drawn} drawn entities in the last one")
    print(f"renderer start-up: {startup:.3f} s")
    print(
        f"frame {options.width}x{options.height} colour+depth+segmentation+visibility"
        f"{' with shadows' if options.shadows else ''}: median {statistics.median(seconds):.3f} s,"
        f" p90 {np.percentile(seconds, 90):.3f} s over {len(seconds)} frames"
    )
    # Wall time depends on what else runs; CPU time (all threads, Mesa's included) does not.
    print(
        f"CPU time per frame: median {statistics.median(cpu_seconds):.3f} s;"
        f" load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs"
    )


if __name__ == "__main__":
    main()
