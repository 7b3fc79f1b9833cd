"""Room layout benchmark: how often rooms come out usable, and what the room terms cost.

    .venv/bin/python benchmarks/bench_rooms.py                     # every shipped room rule set, seeds 0..49
    .venv/bin/python benchmarks/bench_rooms.py bedroom study       # these rule sets (names or paths)
    .venv/bin/python benchmarks/bench_rooms.py --seeds 20          # seeds 0..19
    .venv/bin/python benchmarks/bench_rooms.py --without-room-terms   # what they buy

``--without-room-terms`` lays every scene out with the room's own energy terms switched
off (walls, square, clearance, door swing, windows, access) and then measures the result with
them (``measure_layout``), so the figures show what a layout ignorant of them gets wrong.

Per rule set (default: every shipped rule set whose scene is a room) it prints:

- ok: layouts with no problem at all;
- held by a wall: of the objects with a wall relation (AgainstWall, InCorner,
  UnderWindow, BesideWindow and their Implicit forms), the share whose wall relations
  all hold;
- in a door's swing, crossing a wall: objects the layout reports so, in all scenes;
- before a window: scenes with a tall ground object in a window's view (the room's
  ``windows`` term above 0: its top more than 0.3 m above the sill, within 0.5 m of the
  window), which the layout avoids where it can but does not count as a problem;
- reachable: of the ground objects someone must reach (``access`` not empty), the share
  reachable from a door (all of them when the room has no door);
- layout CPU seconds, median and 90th percentile (this process only, so other work on
  the machine does not count);
- reachability: CPU microseconds per proposal spent on the access term
  (``RoomTerms._access_changes``, timed around each call), averaged over all proposals
  and over those that moved an obstacle and had it evaluated (the sampler skips it for
  a step the rest of the energy already rejects: ``sampler.metropolis``), and the share
  of the latter that had to grow the reachable floor from the doors instead of from
  the old one.

Prints figures only; nothing is asserted. One process, one core.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections import Counter

from scenewright.generator import expand, load_rules
from scenewright.generator.layout import energy as energy_module
from scenewright.generator.layout import layout_scene, measure_layout, room_terms
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.rules import shipped_rule_sets


class AccessClock:
    """Times ``RoomTerms._access_changes`` and counts proposals while installed."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self.calls = 0  # proposals that touched reachability (moved an obstacle or a box to reach)
        self.proposals = 0  # every proposal in a room
        self.moved = 0  # proposals that moved an obstacle
        self.grown_from_doors = 0

    def __enter__(self) -> AccessClock:
        self._access = room_terms.RoomTerms._access_changes
        self._propose = energy_module.Energy.propose
        clock, access, propose = self, self._access, self._propose

        def timed_access(terms, boxes):
            labelled, evaluated = terms.labelled, terms.evaluated
            started = time.process_time()
            result = access(terms, boxes)
            clock.seconds += time.process_time() - started
            clock.calls += 1
            clock.moved += terms.evaluated - evaluated
            clock.grown_from_doors += terms.labelled - labelled
            return result

        def counted_propose(energy, boxes, paths, **keywords):
            if energy.room is not None:
                clock.proposals += 1
            return propose(energy, boxes, paths, **keywords)

        room_terms.RoomTerms._access_changes = timed_access
        energy_module.Energy.propose = counted_propose
        return self

    def __exit__(self, *exc) -> None:
        room_terms.RoomTerms._access_changes = self._access
        energy_module.Energy.propose = self._propose


def room_rule_sets() -> list[str]:
    """The shipped rule sets whose scene is a room (those that load; others are skipped)."""
    found = []
    for name in shipped_rule_sets():
        try:
            if load_rules(name).params.room is not None:
                found.append(name)
        except Exception as error:  # a rule set being rewritten may not load
            print(f"{name}: skipped ({type(error).__name__}: {str(error).splitlines()[0]})")
    return found


class NoRoomTerms:
    """While installed, energies are built without the room's own terms."""

    def __enter__(self) -> NoRoomTerms:
        self._terms = energy_module.RoomTerms
        energy_module.RoomTerms = lambda *args, **keywords: None
        return self

    def __exit__(self, *exc) -> None:
        energy_module.RoomTerms = self._terms


def bench(name: str, seeds: int, without: bool = False) -> None:
    rules = load_rules(name)
    cpu, counts = [], []
    ok = walled = held = used = reached = swing = crossing = windowed = 0
    kinds: Counter[str] = Counter()
    with AccessClock() as clock:
        for seed in range(seeds):
            graph = expand(rules, seed)
            problem = compile_problem(graph)
            counts.append(sum(1 for node in graph.nodes() if node.kind == "object"))
            started = time.process_time()
            if without:
                with NoRoomTerms():
                    result = layout_scene(graph, seed)
                result = measure_layout(graph, result.poses, result.paths)
            else:
                result = layout_scene(graph, seed)
            cpu.append(time.process_time() - started)
            ok += result.ok
            windowed += result.parts.get("windows", 0.0) > 0.0
            unreachable = {p.split(" ", 1)[0] for p in result.problems if "cannot be reached" in p}
            swing += sum("stands in the swing of" in p for p in result.problems)
            crossing += sum(p.endswith("crosses the wall") for p in result.problems)
            for problem_text in result.problems:
                kinds[_kind(problem_text)] += 1
            verdicts: dict[str, list[bool]] = {}
            for term, relation in zip(_terms_by_edge(problem), result.relations, strict=False):
                if term is not None and term.spec.family == "wall":
                    verdicts.setdefault(relation.source, []).append(relation.satisfied)
            walled += len(verdicts)
            held += sum(all(v) for v in verdicts.values())
            doors = bool(graph.params.room.doors)
            for box, box_id in enumerate(problem.ids):
                if (
                    problem.support[box] == -1
                    and not problem.is_junction[box]
                    and problem.access[box]
                ):
                    used += 1
                    reached += box_id not in unreachable if doors else 1
    cpu.sort()
    print(
        f"{name}: {seeds} seeds, {min(counts)}..{max(counts)} objects per scene"
        + (", laid out WITHOUT the room terms" if without else "")
    )
    print(f"  ok {100 * ok / seeds:.1f} %")
    print(f"  held by a wall {_share(held, walled)} of {walled} objects with a wall relation")
    print(f"  in a door's swing {swing}   crossing a wall {crossing}   (objects, all scenes)")
    print(f"  before a window: {windowed} of {seeds} scenes (a tall object in a window's view)")
    print(f"  reachable {_share(reached, used)} of {used} objects someone must reach")
    print(
        f"  layout cpu seconds: median {statistics.median(cpu):.3f}  p90 {cpu[int(0.9 * (seeds - 1))]:.3f}"
    )
    if clock.proposals and not without:
        per_moved = 1e6 * clock.seconds / clock.moved if clock.moved else 0.0
        print(
            f"  reachability: {1e6 * clock.seconds / clock.proposals:.1f} us per proposal "
            f"({clock.proposals} proposals), {per_moved:.1f} us per evaluated proposal moving an obstacle "
            f"({clock.moved}; grown from the doors in {_share(clock.grown_from_doors, clock.moved)})"
        )
    if kinds:
        print("  problems by kind:", dict(kinds.most_common()))


def _terms_by_edge(problem) -> list:
    """The relation term of every edge of the graph, in graph order (None: structural)."""
    return [problem.relations[index] if index is not None else None for *_, index in problem.edges]


def _share(part: int, whole: int) -> str:
    return f"{100 * part / whole:.1f} %" if whole else "-"


def _kind(problem: str) -> str:
    for words in (
        "swing",
        "kept free",
        "cannot be reached",
        "crosses the wall",
        "overlaps",
        "is not",
        "runs into",
    ):
        if words in problem:
            return words
    return "other"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rules", nargs="*", help="rule sets (default: every shipped room rule set)")
    parser.add_argument(
        "--seeds", type=int, default=50, help="seeds 0..N-1 per rule set (default 50)"
    )
    parser.add_argument(
        "--without-room-terms",
        action="store_true",
        help="lay out without them, then measure with them",
    )
    args = parser.parse_args()
    for name in args.rules or room_rule_sets():
        bench(name, args.seeds, args.without_room_terms)


if __name__ == "__main__":
    main()
