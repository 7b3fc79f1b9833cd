"""Dataset resume cost: seconds to rerun a finished dataset of 500 and of 2000 scenes.

A rerun of a finished dataset makes nothing: it reads the records folder once, rebuilds
metadata.jsonl and the statistics from the records, and redraws stats.png, so its time
should grow in step with the number of scenes, not with its square (as it did when the
records folder was read again for every scene). The datasets are
real desk scenes at 8x8 pixels, the smallest --size, so that making them is quick; the
first is made with 500 scenes and then grown to 2000 (-n may grow), each rerun timed.

    .venv/bin/python benchmarks/bench_dataset_resume.py             # 500 and 2000 scenes
    .venv/bin/python benchmarks/bench_dataset_resume.py --counts 100 1000 --workers 1
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from scenewright.dataset.run import run_dataset
from scenewright.dataset.spec import dataset_spec


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "--counts",
        type=int,
        nargs="+",
        default=[500, 2000],
        help="dataset sizes, ascending (500 2000)",
    )
    parser.add_argument(
        "--workers", type=int, help="worker processes while making (default: one per CPU)"
    )
    parser.add_argument("--rules", default="desk")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as directory:
        root = Path(directory) / "data"
        for count in sorted(args.counts):
            spec = dataset_spec(args.rules, count, size=(8, 8))
            made = run_dataset(spec, root, workers=args.workers, progress=False)
            started = time.perf_counter()
            rerun = run_dataset(spec, root, workers=args.workers, progress=False)
            seconds = time.perf_counter() - started
            assert rerun.made == 0 and rerun.skipped == count
            print(
                f"rerun of a finished {count}-scene {args.rules} dataset: {seconds:6.2f} s "
                f"(making its last {made.made} scenes took {made.seconds:.1f} s)"
            )


if __name__ == "__main__":
    main()
