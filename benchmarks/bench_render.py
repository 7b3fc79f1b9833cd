"""Offscreen rendering speed: renderer start-up, then seconds per 640x480 frame.

A frame is everything ``Renderer.render`` returns: colour (with the sun's shadows),
depth, instance segmentation, 2D boxes and visible fractions. The scenes are villages
from the shipped rules (30-40 objects, three roads), one seed per frame; generating
them is not timed.

    .venv/bin/python benchmarks/bench_render.py [--frames 20] [--no-shadows]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

from scenewright.api import build_scene
from scenewright.core.scene import Scene
from scenewright.render.offscreen import Renderer


def village_scenes(count: int) -> list[Scene]:
    """Village scenes from the shipped rules, seeds 0 .. count-1 (layout not timed)."""
    return [build_scene("village", seed) for seed in range(count)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--no-shadows", dest="shadows", action="store_false")
    options = parser.parse_args()

    scenes = village_scenes(options.frames)
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
    print(f"scenes: {len(scenes)} villages; {drawn} drawn entities in the last one")
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
