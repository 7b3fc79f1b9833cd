"""Put images side by side in a grid, each scaled to one tile size, for the docs:

    python3 scripts/side_by_side.py OUT.png --columns 3 A.png B.png C.png D.png E.png F.png

Images fill the grid row by row; every tile is ``--tile`` (default 400x300) pixels."""

import argparse
import sys
from pathlib import Path

from PIL import Image


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("images", type=Path, nargs="+")
    parser.add_argument("--columns", type=int, default=2)
    parser.add_argument("--tile", default="400x300", help="WIDTHxHEIGHT of each tile")
    args = parser.parse_args(argv)
    missing = [str(image) for image in args.images if not image.is_file()]
    if missing or args.columns < 1:
        print(
            f"side_by_side: no such file: {missing[0]}"
            if missing
            else "side_by_side: --columns must be >= 1",
            file=sys.stderr,
        )
        return 2
    width, height = (int(v) for v in args.tile.split("x"))
    rows = -(-len(args.images) // args.columns)
    sheet = Image.new("RGB", (width * args.columns, height * rows), "white")
    for k, path in enumerate(args.images):
        tile = Image.open(path).convert("RGB").resize((width, height), Image.Resampling.LANCZOS)
        sheet.paste(tile, ((k % args.columns) * width, (k // args.columns) * height))
    sheet.save(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
