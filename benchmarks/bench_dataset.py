"""Dataset throughput: scenes per minute with 1 and 2 workers, and the scaling ratio.

Village scenes, 256x256 previews, full descriptions plus one short caption, the real
pipeline in worker processes. A small warm-up run first starts the fork server (which
imports the pipeline once for all runs of this process), so every measured run pays
the same start-up: its own workers, each parsing the rules and creating its OpenGL
context.

    .venv/bin/python benchmarks/bench_dataset.py            # 40 scenes per run
    .venv/bin/python benchmarks/bench_dataset.py -n 100 --workers 1 2
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from scenewright.dataset import dataset_spec, run_dataset


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("-n", "--count", type=int, default=40, help="scenes per run (40)")
    parser.add_argument(
        "--workers", type=int, nargs="+", default=[1, 2], help="worker counts to compare (1 2)"
    )
    parser.add_argument("--rules", default="village")
    args = parser.parse_args()

    spec = dataset_spec(args.rules, args.count, size=(256, 256))
    rates: dict[int, float] = {}
    with tempfile.TemporaryDirectory() as directory:
        warm_up = dataset_spec(args.rules, 2, size=(256, 256))
        run_dataset(warm_up, Path(directory) / "warm-up", workers=1, progress=False)
    print(f"{args.count} {args.rules} scenes at 256x256, full descriptions")
    for workers in args.workers:
        with tempfile.TemporaryDirectory() as directory:
            report = run_dataset(spec, Path(directory) / "data", workers=workers, progress=False)
        rates[workers] = report.scenes_per_minute
        stages = report.stats["seconds_per_stage"]
        per_stage = ", ".join(
            f"{stage} {stages[stage]['median']:.3f}" for stage in ("layout", "describe", "render")
        )
        print(
            f"workers={workers}: {report.seconds:6.1f} s, {report.scenes_per_minute:6.1f} scenes/min, "
            f"{report.failed} failed layouts; median s/scene: {per_stage}"
        )
    if len(rates) > 1:
        lowest, highest = min(rates), max(rates)
        print(f"scaling {lowest} -> {highest} workers: x{rates[highest] / rates[lowest]:.2f}")


if __name__ == "__main__":
    main()
