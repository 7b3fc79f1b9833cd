"""COCO annotation cost: CPU milliseconds to annotate one rendered image.

A dataset worker computes, per image, every entity's box, pixel area and run-length
encoded mask from the segmentation (``coco.view_annotations``). This renders a
few scenes of each rule set at the given size and times that step alone (CPU time,
``time.process_time``, the mean of several repeats), beside the render of the same frame.

    .venv/bin/python benchmarks/bench_coco.py                          # village and classroom, 512x512
    .venv/bin/python benchmarks/bench_coco.py --rules desk --size 256 --scenes 5
"""

from __future__ import annotations

import argparse
import time

from scenewright.api import generate, render_scene
from scenewright.dataset.coco import view_annotations
from scenewright.render.offscreen import Renderer


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--rules", nargs="+", default=["village", "classroom"])
    parser.add_argument("--size", type=int, default=512, help="image side in pixels (512)")
    parser.add_argument("--scenes", type=int, default=3, help="scenes per rule set (3)")
    parser.add_argument("--repeats", type=int, default=5, help="timed repeats per image (5)")
    args = parser.parse_args()

    with Renderer(args.size, args.size) as renderer:
        for rules in args.rules:
            annotate, render, annotations = [], [], 0
            for seed in range(args.scenes):
                scene = generate(rules, seed=seed)
                started = time.process_time()
                scene, result = render_scene(scene, size=(args.size, args.size), renderer=renderer)
                render.append(time.process_time() - started)
                started = time.process_time()
                for _ in range(args.repeats):
                    annotations_of_image = view_annotations(result, scene)
                annotate.append((time.process_time() - started) / args.repeats)
                annotations += len(annotations_of_image)
            print(
                f"{rules}: {args.scenes} images at {args.size}x{args.size}, {annotations} annotations; "
                f"annotating {1000 * sum(annotate) / len(annotate):.1f} ms CPU per image, "
                f"rendering {1000 * sum(render) / len(render):.1f} ms CPU per image"
            )


if __name__ == "__main__":
    main()
