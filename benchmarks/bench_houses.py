"""House benchmark: how often each shipped house plan makes a good house, and what it costs.

    .venv/bin/python benchmarks/bench_houses.py                          # every set, seeds 1000..1199
    .venv/bin/python benchmarks/bench_houses.py --seeds 1000:1030        # seeds 1000..1029
    .venv/bin/python benchmarks/bench_houses.py --sets apartment,dungeon  # these sets only
    .venv/bin/python benchmarks/bench_houses.py --sets benchmarks/house_plans/courtyard.rules
    .venv/bin/python benchmarks/bench_houses.py --parse-every 5 --jobs 2

The sets are the shipped plans (``scenewright.house.shipped_plans``) and the plans of
people who wrote theirs from the docs (``benchmarks/house_plans/*.rules``). For each set
and seed it makes the house (``house_scene_from``: the floor plan, then every room laid
out, one process) and prints, per set:

- ok: houses made whose every room's layout is ok (a plan that finds no floor plan is
  not ok, and counted under "no plan");
- reachable: of all rooms, the share reachable from the front door through the doors;
- blocked doors: doors a person cannot walk through (no free way 0.6 m wide from it into
  its room, or the room's doors not joined by one, as ``furnish.door_paths`` finds) or
  with furniture in their swing (the layout's own problem), counted once per room side;
- outside: objects with a corner of their footprint outside their room's inner outline
  (1 cm of slack);
- CPU seconds (``time.process_time``) of plan + layout per house: median and 90th
  percentile, and the median by number of rooms;
- sentences: of the descriptions of every ``--parse-every``-th seed, the share that
  link-grammar (``link-parser en``) parses completely, when ``link-parser`` is installed.

The last lines give the two targets' figures: the median CPU seconds of a 6-room
apartment and of a 20-room office floor. Prints figures only; nothing is asserted.
With ``--jobs N`` the seeds run in N processes; CPU seconds are each house's own.
"""

from __future__ import annotations

import argparse
import re
import shutil
import statistics
import subprocess
import sys
import time
from collections import Counter, defaultdict
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.frames import footprint_corners_many
from scenewright.house import house_scene_from, shipped_plans
from scenewright.house.assemble import room_scene
from scenewright.house.describe import describe_house
from scenewright.house.furnish import door_paths

HERE = Path(__file__).parent
OWN_PLANS = HERE / "house_plans"
#: How far (m) a footprint corner may lie beyond its room's inner outline.
SLACK = 0.01


def default_sets() -> list[str]:
    return [*shipped_plans(), *(str(p) for p in sorted(OWN_PLANS.glob("*.rules")))]


def measure(job: tuple[str, int, bool]) -> dict:
    """One house: ok, rooms, reachable rooms, blocked doors, objects outside, CPU seconds."""
    plan, seed, describe = job
    start = time.process_time()
    try:
        scene = house_scene_from(plan, seed)
    except InputError as error:
        return {"seed": seed, "planned": False, "why": str(error).split("; give")[0], "ok": False}
    seconds = time.process_time() - start
    house = scene.house
    assert house is not None
    blocked: set[tuple[str, str]] = set()
    outside = 0
    problems: Counter[str] = Counter()
    for house_room in house.rooms:
        room = room_scene(scene, house_room.id)
        why = door_paths(room)
        if why is not None:
            door = why.split(":")[0] if why.startswith("door") else "doors"
            blocked.add((house_room.id, door))
        for problem in room.layout.problems:
            found = re.search(r"in the swing of (\w+)", problem)
            if found:
                blocked.add((house_room.id, found.group(1)))
            problems[f"{house_room.type}: {_kind(problem)}"] += 1
        outside += _outside(room)
    sentences: list[str] = []
    if describe:
        text = describe_house(scene).text
        sentences = [s for p in text.split("\n\n") for s in re.split(r"(?<=\.) (?=[A-Z])", p)]
    return {
        "seed": seed,
        "planned": True,
        "ok": bool(scene.layout.ok),
        "rooms": len(house.rooms),
        "reachable": len(house.reachable()),
        "blocked": len(blocked),
        "outside": outside,
        "seconds": seconds,
        "problems": problems,
        "sentences": sentences,
    }


def _kind(problem: str) -> str:
    """A layout problem without its object ids ("bed_1 overlaps rug_1" -> "overlaps")."""
    words = [w for w in problem.split() if not re.fullmatch(r"\w+_\d+|-?[\d.]+|\(.*|.*\)", w)]
    return " ".join(words[:4])


def _outside(room) -> int:
    objects = [o for o in room.placed_objects() if o.parent is None]
    if not objects:
        return 0
    centres = np.array([[o.position[0], o.position[2]] for o in objects])
    yaws = np.array([o.yaw for o in objects])
    sizes = np.array([[o.size[0], o.size[2]] for o in objects])
    corners = footprint_corners_many(centres, yaws, sizes)
    polygon = room.room.corners
    return sum(1 for quad in corners if not all(_within(polygon, x, z) for x, z in quad))


def _within(polygon, x: float, z: float) -> bool:
    inside = False
    n = len(polygon)
    for k in range(n):
        (xa, za), (xb, zb) = polygon[k], polygon[(k + 1) % n]
        if (za > z) != (zb > z) and x < xa + (z - za) * (xb - xa) / (zb - za):
            inside = not inside
        dx, dz = xb - xa, zb - za
        t = max(0.0, min(1.0, ((x - xa) * dx + (z - za) * dz) / max(dx * dx + dz * dz, 1e-12)))
        if (x - xa - t * dx) ** 2 + (z - za - t * dz) ** 2 <= SLACK * SLACK:
            return True
    return inside


def unparsed(sentences: list[str]) -> list[str] | None:
    """The sentences link-grammar finds no complete linkage for; None without link-parser."""
    if shutil.which("link-parser") is None:
        return None
    unique = list(dict.fromkeys(sentences))
    if not unique:
        return []
    run = subprocess.run(
        ["link-parser", "en", "-batch"],
        input="!echo=1\n" + "\n".join(unique) + "\n",
        capture_output=True,
        text=True,
        timeout=120 + 0.5 * len(unique),
    )
    failed, last = [], None
    for line in run.stdout.splitlines():
        if line.startswith("+++++ error"):
            failed.append(last)
        elif line in unique:
            last = line
    return [f for f in failed if f is not None]


def percentile(values: list[float], share: float) -> float:
    return float(np.percentile(values, share)) if values else float("nan")


def report(name: str, results: list[dict]) -> dict[int, list[float]]:
    n = len(results)
    planned = [r for r in results if r["planned"]]
    ok = sum(r["ok"] for r in results)
    rooms = sum(r["rooms"] for r in planned)
    reachable = sum(r["reachable"] for r in planned)
    seconds = [r["seconds"] for r in planned]
    by_rooms: dict[int, list[float]] = defaultdict(list)
    for r in planned:
        by_rooms[r["rooms"]].append(r["seconds"])
    print(f"{name}: {n} seeds")
    print(
        f"  ok {100 * ok / n:.1f} % ({ok}/{n}); no plan {n - len(planned)}; rooms "
        f"{min((r['rooms'] for r in planned), default=0)}..{max((r['rooms'] for r in planned), default=0)}"
    )
    print(
        f"  reachable {100 * reachable / max(rooms, 1):.1f} % of {rooms} rooms; blocked doors "
        f"{sum(r['blocked'] for r in planned)}; objects outside their room "
        f"{sum(r['outside'] for r in planned)}"
    )
    print(
        f"  cpu s plan+layout: median {statistics.median(seconds) if seconds else float('nan'):.2f}"
        f"  p90 {percentile(seconds, 90):.2f}  max {max(seconds, default=float('nan')):.2f}"
    )
    print(
        "  median cpu s by rooms: "
        + ", ".join(
            f"{k}: {statistics.median(v):.2f} ({len(v)})" for k, v in sorted(by_rooms.items())
        )
    )
    problems: Counter[str] = Counter()
    for r in planned:
        problems.update(r["problems"])
    if problems:
        print("  problems: " + "; ".join(f"{k} x{v}" for k, v in problems.most_common(6)))
    good = [r["seed"] for r in results if r["ok"]]
    if good:
        print(f"  ok: seeds {', '.join(map(str, good[:8]))}{' ...' if len(good) > 8 else ''}")
    failed = [r["seed"] for r in results if not r["ok"]]
    if failed:
        print(
            f"  not ok: seeds {', '.join(map(str, failed[:20]))}{' ...' if len(failed) > 20 else ''}"
        )
    whys = Counter(r["why"] for r in results if not r["planned"])
    for why, count in whys.most_common(3):
        print(f"  no plan x{count}: {why}")
    sentences = [s for r in planned for s in r["sentences"]]
    if sentences:
        failed_sentences = unparsed(sentences)
        if failed_sentences is None:
            print("  sentences: link-parser not installed")
        else:
            unique = len(set(sentences))
            print(
                f"  sentences parsed {100 * (unique - len(failed_sentences)) / unique:.1f} % "
                f"of {unique} distinct ({len(sentences)} in all)"
            )
            for sentence in failed_sentences[:5]:
                print(f"    unparsed: {sentence}")
    sys.stdout.flush()
    return by_rooms


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", default="1000:1200", help="A:B, seeds A..B-1 (1000:1200)")
    parser.add_argument("--sets", default="", help="comma-separated plan names or paths (all)")
    parser.add_argument(
        "--parse-every", type=int, default=10, help="describe every Nth seed (10; 0: none)"
    )
    parser.add_argument("--jobs", type=int, default=1, help="processes (1)")
    args = parser.parse_args(argv)
    first, last = (int(v) for v in args.seeds.split(":"))
    sets = [s for s in args.sets.split(",") if s] or default_sets()
    medians: dict[str, dict[int, list[float]]] = {}
    started = time.time()
    for plan in sets:
        jobs = [
            (plan, seed, args.parse_every > 0 and (seed - first) % args.parse_every == 0)
            for seed in range(first, last)
        ]
        if args.jobs > 1:
            with ProcessPoolExecutor(max_workers=args.jobs) as pool:
                results = list(pool.map(measure, jobs))
        else:
            results = [measure(job) for job in jobs]
        medians[plan] = report(Path(plan).name.removesuffix(".rules"), results)
    for plan, rooms, words in (
        ("apartment", 6, "6-room apartment"),
        ("office_floor", 20, "20-room office floor"),
    ):
        times = medians.get(plan, {}).get(rooms)
        if times:
            print(
                f"median cpu s of a {words}: {statistics.median(times):.2f} ({len(times)} houses)"
            )
    print(f"wall time {time.time() - started:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
