"""Dataset throughput: scenes per minute with 1 and 2 workers, and where the time goes.

Village scenes, 256x256 previews, full descriptions plus one short caption, the real
pipeline in worker processes. A small warm-up run first starts the fork server (which
imports the pipeline once for all runs of this process), so every measured run pays
the same start-up: its own workers, each parsing the rules and creating its OpenGL
context.

Per run it prints the wall-clock rate (start-up included) and, per scene, the CPU
seconds of each stage in the workers (from stats.json: ``layout`` is the expansion and
every layout tried, ``encode`` the PNG and scene.json) and of this process (receiving
the scenes, writing their files and records, the statistics at the end). On a machine
shared with other work the wall clock moves with the load, the CPU times much less:
``cpu-bound rate`` is what the workers' CPU time allows, 60 * workers / (CPU seconds
per scene), when each worker has a core to itself.

    .venv/bin/python benchmarks/bench_dataset.py            # 200 scenes per run
    .venv/bin/python benchmarks/bench_dataset.py -n 1000 --workers 2
    .venv/bin/python benchmarks/bench_dataset.py -n 20 --workers 1 --ground-truth --seed 1000

``--ground-truth`` turns on the 3D ground truth a dataset can carry: ``--depth`` (16-bit
PNG and float32 .npy), ``--normals`` (one more render pass) and ``--boxes-3d``
(the objects_3d column); each can be asked for alone. ``--seed`` is the dataset's base
seed (0; the figures for unseen scenes use 1000 and up).

A run pays about two seconds whatever its count: its workers start (each creates its
OpenGL context and, in its first scene, builds the catalog's meshes and compiles the
shaders), and at the end the statistics are gathered and stats.png is drawn. A
40-scene run at 2 workers is about 5 s, so that start and end are two fifths of it;
a dataset of thousands pays them once, hence the default of 200 scenes (and 1000 for
the figure the docs quote).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from scenewright.dataset.run import run_dataset
from scenewright.dataset.spec import dataset_spec

STAGES = ("layout", "describe", "render", "encode")


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("-n", "--count", type=int, default=200, help="scenes per run (200)")
    parser.add_argument(
        "--workers", type=int, nargs="+", default=[1, 2], help="worker counts to compare (1 2)"
    )
    parser.add_argument("--rules", default="village")
    parser.add_argument("--seed", type=int, default=0, help="the dataset's base seed (0)")
    parser.add_argument("--depth", action="store_true", help="depth PNG and float32 .npy")
    parser.add_argument("--normals", action="store_true", help="the surface normals image")
    parser.add_argument("--boxes-3d", action="store_true", help="the objects_3d column")
    parser.add_argument(
        "--ground-truth", action="store_true", help="all three: --depth --normals --boxes-3d"
    )
    args = parser.parse_args()

    truth = {
        "depth": args.depth or args.ground_truth,
        "normals": args.normals or args.ground_truth,
        "boxes_3d": args.boxes_3d or args.ground_truth,
    }
    spec = dataset_spec(args.rules, args.count, size=(256, 256), base_seed=args.seed, **truth)
    rates: dict[int, float] = {}
    with tempfile.TemporaryDirectory() as directory:
        warm_up = dataset_spec(args.rules, 2, size=(256, 256))
        run_dataset(warm_up, Path(directory) / "warm-up", workers=1, progress=False)
    print(
        f"{args.count} {args.rules} scenes at 256x256 from seed {args.seed}, full descriptions"
        + "".join(f", {name}" for name, on in truth.items() if on)
        + f"; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs"
    )
    for workers in args.workers:
        with tempfile.TemporaryDirectory() as directory:
            main_cpu = time.process_time()
            report = run_dataset(spec, Path(directory) / "data", workers=workers, progress=False)
            main_cpu = time.process_time() - main_cpu
        rates[workers] = report.scenes_per_minute
        cpu = report.stats["cpu_seconds_per_stage"]
        per_stage = {stage: cpu[stage]["mean"] for stage in STAGES if stage in cpu}
        worker_cpu = sum(per_stage.values())
        stages = ", ".join(f"{stage} {seconds:.3f}" for stage, seconds in per_stage.items())
        print(
            f"workers={workers}: {report.seconds:6.1f} s, {report.scenes_per_minute:6.1f} scenes/min (wall), "
            f"{report.failed} failed; CPU s/scene: {stages} = {worker_cpu:.3f} in a worker, "
            f"{main_cpu / args.count:.3f} here; cpu-bound rate {60.0 * workers / worker_cpu:.0f} scenes/min"
        )
    if len(rates) > 1:
        lowest, highest = min(rates), max(rates)
        print(
            f"scaling {lowest} -> {highest} workers (wall): x{rates[highest] / rates[lowest]:.2f}"
        )


if __name__ == "__main__":
    main()
