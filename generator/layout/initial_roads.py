"""The roads and junctions of the constructive initial placement, laid before any box.

Roads leave their junction at evenly spread headings (several junctions spread over
the scene, each farthest from the others), free roads cross the scene near its middle
(several: each through the candidate point farthest from the roads laid so far), each
new road as long as its maximum allows, wiggling a little at each control point.

Around pinned or started boxes and paths (``pinning.Pins``), given roads keep their
points; each junction's other roads (and the junction, unless it is given), and each
other free road, are the best of ``path_candidates`` random ones by the energy (which
already holds the given boxes) plus ``held``: how far the pinned things that must be
next to a road are from it. So new roads avoid pinned things and pass by those that
must be next to them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from scenewright.core.geometry import point_segment_distance

from .branches import along, stations
from .energy import Energy
from .motion import uniform, wrap
from .pinning import Pins

#: Paths stay this far (metres) inside the extent when first laid out.
PATH_MARGIN = 1.0
#: New paths take this share of their maximum length (room permitting): long roads give
#: the items placed along them room, and the length term stays near 0 below the maximum.
PATH_LENGTH_SHARE = 0.95
#: Where free paths cross the scene: within this share of the extent from its centre.
LONE_PATH_SPREAD = 0.2
FREE_PATH_SPREAD = 0.4
#: Spread (radians) of the heading change at each control point of a new path.
PATH_WIGGLE = 0.15
#: Spread (radians) of an organic branch's heading about square to its road.
BRANCH_TURN = 0.15
#: Around pinned or started things, candidate junctions lie within this share of the
#: extent from its centre (without them: 0.15).
JUNCTION_SPREAD = 0.25
#: Several junctions lie within this share of the extent from its centre, each the
#: farthest from the others of this many candidate points.
JUNCTIONS_SPREAD = 0.3
SPREAD_CANDIDATES = 8


def lay_paths(
    energy: Energy,
    rng: np.random.Generator,
    pins: Pins,
    held=None,
    fit: Mapping[int, float] | None = None,
) -> None:
    """Lay out every junction and path. ``fit`` (a large outdoor scene: per path, the
    metres of frontage the items beside it need): the road networks are fitted to the
    scene, to each other and to that need (``_fit_networks``)."""
    if pins.preset:
        _lay_paths_around(energy, rng, pins, held)
        return
    if fit is not None and any(energy.problem.is_junction):
        _fit_networks(energy, rng, fit)
        return
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    junctions = [b for b in range(problem.n_boxes) if problem.is_junction[b]]
    if len(junctions) > 1:
        _spread_junctions(energy, rng, junctions)
    else:
        for junction in junctions:
            state.set_pose(
                junction,
                uniform(rng, -0.15, 0.15) * 2 * half_x,
                uniform(rng, -0.15, 0.15) * 2 * half_z,
                0.0,
            )
    energy.activate(junctions)
    for junction in junctions:
        paths = problem.paths_of_junction.get(junction, [])
        base = uniform(rng, 0.0, 2.0 * math.pi)
        if problem.grid[junction]:  # a grid: square to the scene, at right angles
            base = 0.5 * math.pi * int(rng.integers(4))
        for k, path in enumerate(paths):
            if problem.grid[junction]:
                heading = _grid_heading(base, k)
            else:
                heading = base + 2.0 * math.pi * k / len(paths) + rng.normal(0.0, 0.1)
            start = (state.x[junction], state.z[junction])
            _set_path(energy, rng, path, start, heading, _room(start, heading, half_x, half_z))
    free = _free_roads(problem)
    # A lone road crosses near the middle; several spread out, each through the candidate
    # point farthest from the roads laid so far.
    spread = FREE_PATH_SPREAD if len(free) > 1 else LONE_PATH_SPREAD
    for path in free:
        heading = uniform(rng, 0.0, 2.0 * math.pi)
        laid = [
            p
            for other in range(problem.n_paths)
            if other not in free or other < path
            for p in state.points[other]
        ]
        candidates = [
            (uniform(rng, -spread, spread) * 2 * half_x, uniform(rng, -spread, spread) * 2 * half_z)
            for _ in range(8)
        ]
        middle = max(
            candidates,
            key=lambda c: min((math.hypot(c[0] - p[0], c[1] - p[1]) for p in laid), default=0.0),
        )
        back = _room(middle, heading + math.pi, half_x, half_z)
        ahead = _room(middle, heading, half_x, half_z)
        length = min(PATH_LENGTH_SHARE * problem.path_max_length[path], back + ahead)
        behind = min(back, length / 2.0)
        start = (middle[0] - math.cos(heading) * behind, middle[1] - math.sin(heading) * behind)
        _set_path(energy, rng, path, start, heading, length)
    for path in problem.path_order:  # branches, each after the road it branches from
        if problem.path_parent[path] >= 0:
            _set_branch(energy, rng, path)


def _spread_junctions(energy: Energy, rng: np.random.Generator, junctions: list[int]) -> None:
    """Several junctions (road networks) spread over the scene: each at the candidate
    point (of ``SPREAD_CANDIDATES`` within ``JUNCTIONS_SPREAD`` of the extent from its
    centre) farthest from the junctions placed before it, so the networks' roads give
    the items beside them room instead of crossing each other in the middle."""
    state, (width, depth) = energy.state, energy.problem.extent
    placed: list[tuple[float, float]] = []
    for junction in junctions:
        candidates = [
            (
                uniform(rng, -JUNCTIONS_SPREAD, JUNCTIONS_SPREAD) * width,
                uniform(rng, -JUNCTIONS_SPREAD, JUNCTIONS_SPREAD) * depth,
            )
            for _ in range(SPREAD_CANDIDATES)
        ]
        x, z = max(
            candidates,
            key=lambda c: min((math.hypot(c[0] - p[0], c[1] - p[1]) for p in placed), default=0.0),
        )
        placed.append((x, z))
        state.set_pose(junction, x, z, 0.0)


def _free_headings(
    energy: Energy, pins: Pins, junction: int, paths: list[int], base: float
) -> list[float]:
    """Headings for the roads of a junction, by position in ``paths``: evenly spread from
    ``base``; when some roads are given, spread from the first given one's heading, each
    given road taking the free slot nearest its own heading and the others the rest in
    order."""
    count = len(paths)
    grid = energy.problem.grid[junction]
    given = {path: pins.preset_points(path) for path in paths}
    given = {path: points for path, points in given.items() if points is not None}
    if grid:
        base = 0.5 * math.pi * round(base / (0.5 * math.pi))
    if not given:
        if grid:
            return [_grid_heading(base, k) for k in range(count)]
        return [base + 2.0 * math.pi * k / count for k in range(count)]
    state = energy.state
    start = (state.x[junction], state.z[junction])

    def heading(points) -> float:
        return math.atan2(points[1][1] - start[1], points[1][0] - start[0])

    base = heading(next(iter(given.values())))
    if grid:
        slots = [_grid_heading(base, k) for k in range(count)]
    else:
        slots = [base + 2.0 * math.pi * k / count for k in range(count)]
    for points in given.values():
        own = heading(points)
        nearest = min(range(len(slots)), key=lambda k: abs(wrap(slots[k] - own)))
        slots.pop(nearest)
    free_slots = iter(slots)
    return [0.0 if path in given else next(free_slots) for path in paths]


def _grid_heading(base: float, k: int) -> float:
    """The heading of a grid junction's k-th road: the four right angles from ``base``
    first, then (a fifth road and more) the diagonals between them."""
    if k < 4:
        return base + 0.5 * math.pi * k
    return base + 0.25 * math.pi + 0.5 * math.pi * (k - 4)


def _room(start: tuple[float, float], heading: float, half_x: float, half_z: float) -> float:
    """How far one can go from ``start`` along ``heading`` and stay PATH_MARGIN inside."""
    dx, dz = math.cos(heading), math.sin(heading)
    limits = []
    for position, direction, half in ((start[0], dx, half_x), (start[1], dz, half_z)):
        if abs(direction) > 1e-9:
            bound = (half - PATH_MARGIN) if direction > 0 else -(half - PATH_MARGIN)
            limits.append((bound - position) / direction)
    return max(min(limits), 0.0)


def _free_roads(problem) -> list[int]:
    """The paths that start neither at a junction nor on another path."""
    return [
        path
        for path in range(problem.n_paths)
        if problem.path_start[path] < 0 and problem.path_parent[path] < 0
    ]


def _branch_start(problem, points: list, path: int) -> tuple[tuple[float, float], float, bool]:
    """Where branch ``path`` leaves its road (laid as ``points``), its heading (square
    to the road, to its station's side: ``branches.stations``) and whether it is alone
    at its station (so it may take the other side instead)."""
    siblings = problem.branches_of[problem.path_parent[path]]
    grid = problem.path_grid[path]
    k = siblings.index(path)
    s, side = stations(_length(points), len(siblings), grid)[k]
    x, z, along_heading = along(points, s)
    alone = not grid or (k % 2 == 0 and k == len(siblings) - 1)
    return (x, z), along_heading + side * 0.5 * math.pi, alone


def _set_branch(energy: Energy, rng: np.random.Generator, path: int) -> None:
    """Lay a branch from its station on its road as laid now (an organic one turned a
    little from square, to whichever side leaves it more room when it is alone there)."""
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    start, heading, alone = _branch_start(problem, state.points[problem.path_parent[path]], path)
    if not problem.path_grid[path]:
        heading += float(np.clip(rng.normal(0.0, BRANCH_TURN), -0.35, 0.35))
    if alone and _room(start, heading + math.pi, half_x, half_z) > _room(
        start, heading, half_x, half_z
    ):
        heading += math.pi
    _set_path(energy, rng, path, start, heading, _room(start, heading, half_x, half_z))


def _lay_paths_around(energy: Energy, rng: np.random.Generator, pins: Pins, held=None) -> None:
    """Paths when some boxes or paths are given (pinned or started): given paths at their
    points; each junction's other roads (and the junction, unless it is given) as the best
    of ``path_candidates`` fans, and each other free road as the best of as many
    crossings, by the energy (which already holds the given boxes) plus ``held`` (how far
    the pinned things that must be next to a road are from it): so new roads avoid
    pinned things and pass by those that must be next to them."""
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    count = energy.params.path_candidates
    for junction in [b for b in range(problem.n_boxes) if problem.is_junction[b]]:
        paths = problem.paths_of_junction.get(junction, [])
        given: dict[int, list[list[float]]] = {}
        for path in paths:
            preset = pins.preset_points(path)
            if preset is not None:
                given[path] = preset
        placed = energy.active[junction]
        if not placed and given:  # where a given road starts
            first = next(iter(given.values()))[0]
            state.set_pose(junction, first[0], first[1], 0.0)
            placed = True
        if not energy.active[junction]:
            energy.activate([junction])
        for path, points in given.items():
            points = [list(p) for p in points]
            if not pins.path[path]:  # a started road begins at its junction
                points[0] = [state.x[junction], state.z[junction]]
            energy.propose({}, {path: points})
            energy.accept()
        if len(given) == len(paths) and placed:
            continue

        def fan(junction=junction, paths=paths, placed=placed) -> tuple[dict, dict]:
            if placed:
                x, z, boxes = state.x[junction], state.z[junction], {}
            else:
                x = uniform(rng, -JUNCTION_SPREAD, JUNCTION_SPREAD) * 2 * half_x
                z = uniform(rng, -JUNCTION_SPREAD, JUNCTION_SPREAD) * 2 * half_z
                boxes = {junction: (x, z, 0.0)}
            slots = _free_headings(energy, pins, junction, paths, uniform(rng, 0.0, 2.0 * math.pi))
            laid = {}
            for k, path in enumerate(paths):
                if pins.preset_points(path) is None:
                    heading = slots[k]
                    if not problem.grid[junction]:
                        heading += rng.normal(0.0, 0.1)
                    room = _room((x, z), heading, half_x, half_z)
                    laid[path] = _path_points(problem, rng, path, (x, z), heading, room)
            return boxes, laid

        _take_best(energy, fan, count, held)
    free = _free_roads(problem)
    for path in free:
        preset = pins.preset_points(path)
        if preset is not None:
            energy.propose({}, {path: [list(p) for p in preset]})
            energy.accept()
    spread = FREE_PATH_SPREAD if len(free) > 1 else LONE_PATH_SPREAD
    for path in free:
        if pins.preset_points(path) is not None:
            continue

        def crossing(path=path) -> tuple[dict, dict]:
            heading = uniform(rng, 0.0, 2.0 * math.pi)
            middle = (
                uniform(rng, -spread, spread) * 2 * half_x,
                uniform(rng, -spread, spread) * 2 * half_z,
            )
            back = _room(middle, heading + math.pi, half_x, half_z)
            ahead = _room(middle, heading, half_x, half_z)
            length = min(PATH_LENGTH_SHARE * problem.path_max_length[path], back + ahead)
            behind = min(back, length / 2.0)
            start = (middle[0] - math.cos(heading) * behind, middle[1] - math.sin(heading) * behind)
            return {}, {path: _path_points(problem, rng, path, start, heading, length)}

        _take_best(energy, crossing, count, held)
    for path in problem.path_order:  # branches: given ones as they are, the others laid
        if problem.path_parent[path] < 0:
            continue
        preset = pins.preset_points(path)
        if preset is not None:
            energy.propose({}, {path: [list(p) for p in preset]})
            energy.accept()
        else:
            _set_branch(energy, rng, path)


def _take_best(energy: Energy, draw, count: int, extra=None) -> None:
    """Try ``count`` proposals from ``draw()`` and keep the one of lowest energy (plus
    ``extra()``, if given), even when it is worse than the state now (a placeholder)."""
    best, best_delta = None, math.inf
    for _ in range(count):
        proposal = draw()
        delta = energy.propose(*proposal)
        kept = energy.kept(delta)
        if extra is not None:
            delta += extra()
        energy.reject()
        if delta < best_delta:
            best, best_delta, best_kept = proposal, delta, kept
    if best is not None:
        energy.repropose(best, best_kept)
        energy.accept()


def _set_path(
    energy: Energy, rng: np.random.Generator, path: int, start, heading: float, room: float
) -> None:
    energy.propose({}, {path: _path_points(energy.problem, rng, path, start, heading, room)})
    energy.accept()


def _path_points(
    problem, rng: np.random.Generator, path: int, start, heading: float, room: float
) -> list[list[float]]:
    """Control points of a new path from ``start`` along ``heading`` (wiggling a little,
    unless it is a grid's)."""
    half_x, half_z = problem.extent[0] / 2.0 - PATH_MARGIN, problem.extent[1] / 2.0 - PATH_MARGIN
    segments = problem.path_segments[path]
    step = min(PATH_LENGTH_SHARE * problem.path_max_length[path], room) / segments
    points = [[float(start[0]), float(start[1])]]
    for _ in range(segments):
        if not problem.path_grid[path]:  # a grid's roads run straight
            heading += float(np.clip(rng.normal(0.0, PATH_WIGGLE), -0.4, 0.4))
        x = points[-1][0] + math.cos(heading) * step
        z = points[-1][1] + math.sin(heading) * step
        points.append([min(max(x, -half_x), half_x), min(max(z, -half_z), half_z)])
    return points


#: Fitted road networks (``_fit_networks``): whole plans tried, candidate networks drawn
#: per junction in each; the
#: distance (metres) a junction keeps from the roads of other networks (room for the lots
#: of both), the distance at which a road ends when it meets another network's road, and
#: the shortest a road is cut to (a share of its maximum).
NETWORK_CANDIDATES = 24
NETWORK_TRIES = 4
NETWORK_SPREAD = 0.35
JUNCTION_CLEARANCE = 30.0
ROAD_CLEARANCE = 6.0
SHORTEST_ROAD = 0.3
#: A plan's grids are turned by at most this much (radians) from the scene's axes.
GRID_TILT = math.radians(10.0)
#: Metres of each side of a road lost for lots at each of its ends (where it meets its
#: junction's other roads, or another network's road).
CORNER_LOSS = 6.0
#: Arc-length step (metres) at which a new road is tested against the roads laid.
CLEARANCE_STEP = 1.0
#: A road cut short of another network's road runs on to meet it (``_meet``) when that
#: road is at most this far (metres) straight ahead and crossed at this angle or more.
MEET_REACH = 2.0 * ROAD_CLEARANCE
MEET_ANGLE = math.radians(45.0)


def _fit_networks(energy: Energy, rng: np.random.Generator, need: Mapping[int, float]) -> None:
    """Road networks that fit the scene and each other: the best of ``NETWORK_TRIES``
    plans (``_network_plan``) by the frontage met, then the road laid."""
    problem, state = energy.problem, energy.state
    best = None
    for _ in range(NETWORK_TRIES):
        plan = _network_plan(problem, rng, need)
        if best is None or plan[0] > best[0]:
            best = plan
    assert best is not None
    _, junctions, roads = best
    for junction, (x, z) in junctions.items():
        state.set_pose(junction, x, z, 0.0)
    energy.activate(list(junctions))
    for path in problem.path_order:  # a road before its branches
        energy.propose({}, {path: roads[path]})
        energy.accept()


def _network_plan(problem, rng: np.random.Generator, need: Mapping[int, float]) -> tuple:
    """One plan of the road networks, one junction after another: (its score, junction
    spots, path points).

    Each junction is the best of ``NETWORK_CANDIDATES`` drawn networks: a spot within
    ``NETWORK_SPREAD`` of the extent from its centre, at least ``JUNCTION_CLEARANCE``
    from the roads laid so far, and its roads at evenly spread headings from a drawn
    base, each as long as its maximum allows (``PATH_LENGTH_SHARE``) but ending where it
    would leave the scene or meet another network's road (``ROAD_CLEARANCE`` short of
    it); the best gives the most of the frontage its roads' items need (``need``: each
    road's two sides, less ``CORNER_LOSS`` at each end, count up to its need), then the
    most road. Free roads then cross the scene, cut the same way. The plan's score is
    the frontage met over all roads, then their length."""
    width, depth = problem.extent
    half_x, half_z = width / 2.0, depth / 2.0
    laid = _Segments()
    spots: dict[int, tuple[float, float]] = {}
    laid_roads: dict[int, list] = {}
    total = 0.0
    junctions = [b for b in range(problem.n_boxes) if problem.is_junction[b]]
    # The grids of a plan share one orientation (within GRID_TILT of the scene's axes),
    # so that their roads run parallel or square to each other.
    grid_base = (
        uniform(rng, -GRID_TILT, GRID_TILT) if any(problem.grid[j] for j in junctions) else 0.0
    )
    for junction in junctions:
        paths = problem.paths_of_junction.get(junction, [])
        grid = problem.grid[junction]
        best = None
        for _ in range(NETWORK_CANDIDATES):
            x = uniform(rng, -NETWORK_SPREAD, NETWORK_SPREAD) * width
            z = uniform(rng, -NETWORK_SPREAD, NETWORK_SPREAD) * depth
            if grid:  # which of the four square headings the first road takes
                base = grid_base + 0.5 * math.pi * int(rng.integers(4))
            else:
                base = uniform(rng, 0.0, 2.0 * math.pi)
            clearance = laid.distance((x, z), JUNCTION_CLEARANCE)
            roads = {}
            for k, path in enumerate(paths):
                if grid:  # straight, at right angles
                    heading = _grid_heading(base, k)
                    turns = [0.0] * problem.path_segments[path]
                else:
                    heading = base + 2.0 * math.pi * k / max(len(paths), 1)
                    # The first segment leaves at its slot's heading, so the roads of a
                    # junction stay as far apart as they are spread.
                    turns = [0.0] + [
                        float(np.clip(rng.normal(0.0, PATH_WIGGLE), -0.4, 0.4))
                        for _ in range(problem.path_segments[path] - 1)
                    ]
                roads[path] = _fitted_road(problem, path, (x, z), heading, turns, laid)
            roads.update(_fitted_branches(problem, rng, roads, laid))
            score = _frontage_score(roads, need)
            if clearance < JUNCTION_CLEARANCE:
                score -= 1e4 - clearance
            if best is None or score > best[0]:
                best = (score, x, z, roads)
        assert best is not None
        score, x, z, roads = best
        total += score
        spots[junction] = (x, z)
        for path, points in roads.items():
            laid.add(points, path)
            laid_roads[path] = points
    for path in _free_roads(problem):
        chosen: list | None = None
        for _ in range(SPREAD_CANDIDATES):
            heading = uniform(rng, 0.0, 2.0 * math.pi)
            middle = (
                uniform(rng, -FREE_PATH_SPREAD, FREE_PATH_SPREAD) * width,
                uniform(rng, -FREE_PATH_SPREAD, FREE_PATH_SPREAD) * depth,
            )
            back = _room(middle, heading + math.pi, half_x, half_z)
            behind = min(back, PATH_LENGTH_SHARE * problem.path_max_length[path] / 2.0)
            start = (middle[0] - math.cos(heading) * behind, middle[1] - math.sin(heading) * behind)
            turns = [0.0] + [
                float(np.clip(rng.normal(0.0, PATH_WIGGLE), -0.4, 0.4))
                for _ in range(problem.path_segments[path] - 1)
            ]
            points = _fitted_road(problem, path, start, heading, turns, laid)
            if chosen is None or _length(points) > _length(chosen):
                chosen = points
        assert chosen is not None
        total += _frontage_score({path: chosen}, need)
        laid.add(chosen, path)
        laid_roads[path] = chosen
    free = {path: laid_roads[path] for path in _free_roads(problem)}
    branches = _fitted_branches(problem, rng, free, laid)  # of the free roads
    total += _frontage_score(branches, need)
    for path, points in branches.items():
        laid.add(points, path)
        laid_roads[path] = points
    return total, spots, laid_roads


#: ``lengthen``: a road short of frontage may grow to this share of its ``max_length``
#: (the length term is about 0.1 there), bending at its control points after the first
#: by one of ``BENDS`` (radians, under gamma) at one point, or at each of them alike.
LONGEST_SHARE = 0.99
BENDS = (0.0, -0.4, 0.4, -0.8, 0.8)
#: ... drawn as long as these shares of that length (then cut where there is no room).
GROW_SHARES = (1.0, 0.85, 0.7)


def lengthen(energy: Energy, paths: list[int]) -> dict[int, list]:
    """Roads of ``paths`` that are short of frontage made longer where there is room:
    each (that has no branches) the longest of its candidates, if it beats it by a
    metre: the road as laid, grown to ``LONGEST_SHARE`` of its maximum, with its first
    segment's heading kept (so it leaves its junction or road as before) and its free
    end bent into free space (``BENDS``; a grid's roads run on straight), each drawn at
    ``GROW_SHARES`` of that length, cut like a fitted road where it would leave the
    scene or come near another road. Returns the
    points each changed road had before."""
    problem, state = energy.problem, energy.state
    changed: dict[int, list] = {}
    for path in paths:
        if path in problem.branches_of:
            continue
        points = state.points[path]
        length = _length(points)
        full = LONGEST_SHARE * problem.path_max_length[path]
        if full < length + 1.0:
            continue
        laid, beside = _Segments(), _Segments()
        start_at = problem.path_start[path]
        parent = problem.path_parent[path]
        for other in range(problem.n_paths):
            if other == path:
                continue
            same_start = (
                (start_at >= 0 and problem.path_start[other] == start_at)
                or (parent >= 0 and problem.path_parent[other] == parent)
                or other == parent
            )
            (beside if same_start else laid).add(state.points[other], other)
        # the roads leaving where it does (and the road it branches from) are tested once
        # it is as far out as it was
        beside_from = min(_length(points[:2]), ROAD_CLEARANCE + problem.path_width[path])
        heading = math.atan2(points[1][1] - points[0][1], points[1][0] - points[0][0])
        segments = problem.path_segments[path]
        shapes: list[list[float]] = [[0.0] * segments]
        if not problem.path_grid[path]:
            own = [0.0] + [
                _signed_turn(points[k - 1], points[k], points[k + 1]) for k in range(1, segments)
            ]
            shapes = [own]
            for bend in BENDS[1:]:
                shapes.append([0.0] + [bend] * (segments - 1))
                for k in range(1, segments):
                    shapes.append([0.0] + [bend if j == k else 0.0 for j in range(1, segments)])
        best, best_length = None, length + 1.0
        for turns in shapes:
            for share in GROW_SHARES:  # shorter pieces bend sooner, before an edge
                road = _fitted_road(
                    problem,
                    path,
                    points[0],
                    heading,
                    turns,
                    laid,
                    max(share * full, length),
                    beside,
                    beside_from,
                )
                if _length(road) > best_length:
                    best, best_length = road, _length(road)
        if best is not None:
            changed[path] = [list(p) for p in points]
            energy.propose({}, {path: best})
            energy.accept()
    return changed


def _signed_turn(a, b, c) -> float:
    """The turn (radians, left positive) at b between a-b and b-c."""
    first = math.atan2(b[1] - a[1], b[0] - a[0])
    return wrap(math.atan2(c[1] - b[1], c[0] - b[0]) - first)


def _fitted_branches(
    problem, rng: np.random.Generator, roads: Mapping[int, list], laid: _Segments
) -> dict[int, list]:
    """The branches of ``roads`` (and theirs), each from its station on its road
    (``branches.stations``), square to it (an organic one turned a little, and to the
    side that leaves it longer when it is alone at its station), cut like any fitted
    road where it would leave the scene or come near a road of ``laid``, of ``roads`` or
    a branch laid before it (its own road excepted)."""
    if not problem.branches_of or not any(path in problem.branches_of for path in roads):
        return {}
    own = _Segments()
    for path, points in roads.items():
        own.add(points, path)
    made: dict[int, list] = {}
    for path in problem.path_order:
        parent = problem.path_parent[path]
        if parent < 0 or (parent not in roads and parent not in made):
            continue
        points = roads[parent] if parent in roads else made[parent]
        start, heading, alone = _branch_start(problem, points, path)
        grid = problem.path_grid[path]
        if grid:
            turns = [0.0] * problem.path_segments[path]
        else:
            heading += float(np.clip(rng.normal(0.0, BRANCH_TURN), -0.35, 0.35))
            turns = [0.0] + [
                float(np.clip(rng.normal(0.0, PATH_WIGGLE), -0.4, 0.4))
                for _ in range(problem.path_segments[path] - 1)
            ]
        near = _Near((laid, own), parent)
        branch = _fitted_road(problem, path, start, heading, turns, near)
        if alone:
            other = _fitted_road(problem, path, start, heading + math.pi, turns, near)
            if _length(other) > _length(branch):
                branch = other
        made[path] = branch
        own.add(branch, path)
    return made


def _frontage_score(roads: Mapping[int, list], need: Mapping[int, float]) -> float:
    """How much of their items' need the roads' sides meet (weighted), plus their length."""
    met = sum(
        min(2.0 * max(_length(points) - 2.0 * CORNER_LOSS, 0.0), need.get(path, 0.0))
        for path, points in roads.items()
    )
    return 10.0 * met + sum(_length(points) for points in roads.values())


def _fitted_road(
    problem,
    path: int,
    start,
    heading: float,
    turns: list[float],
    laid,
    full: float | None = None,
    beside=None,
    beside_from: float = 0.0,
) -> list:
    """A road from ``start`` along ``heading`` turning by ``turns`` at its control points,
    ``full`` long (default: as long as its maximum allows, ``PATH_LENGTH_SHARE``) but
    cut where it would leave the scene or come within ``ROAD_CLEARANCE`` of a road in
    ``laid`` (or, from ``beside_from`` metres along it on, in ``beside``: the roads
    that start where it does); never shorter than ``SHORTEST_ROAD`` of its maximum."""
    half_x, half_z = problem.extent[0] / 2.0 - PATH_MARGIN, problem.extent[1] / 2.0 - PATH_MARGIN
    if full is None:
        full = PATH_LENGTH_SHARE * problem.path_max_length[path]
    segments = len(turns)

    def points_for(length: float) -> list[list[float]]:
        step, angle = length / segments, heading
        points = [[float(start[0]), float(start[1])]]
        for turn in turns:
            angle += turn
            points.append(
                [points[-1][0] + math.cos(angle) * step, points[-1][1] + math.sin(angle) * step]
            )
        return points

    points = points_for(full)
    # How far along it stays inside and clear of the other roads.
    free, walked, met = full, 0.0, False
    for (ax, az), (bx, bz) in zip(points, points[1:], strict=False):
        segment = math.hypot(bx - ax, bz - az)
        steps = max(1, int(segment / CLEARANCE_STEP))
        stop = None
        for k in range(1, steps + 1):
            t = k / steps
            px, pz = ax + t * (bx - ax), az + t * (bz - az)
            if (
                abs(px) > half_x
                or abs(pz) > half_z
                or laid.closer_than((px, pz), ROAD_CLEARANCE)
                or (
                    beside is not None
                    and walked + t * segment >= beside_from
                    and beside.closer_than((px, pz), ROAD_CLEARANCE)
                )
            ):
                stop = walked + (k - 1) / steps * segment
                met = (
                    abs(px) <= half_x
                    and abs(pz) <= half_z
                    and laid.closer_than((px, pz), ROAD_CLEARANCE)
                )
                break
        if stop is not None:
            free = stop
            break
        walked += segment
    shortest = SHORTEST_ROAD * (PATH_LENGTH_SHARE * problem.path_max_length[path])
    length = max(free, shortest)
    points = points_for(min(length, full))
    points = [[min(max(x, -half_x), half_x), min(max(z, -half_z), half_z)] for x, z in points]
    if met and free >= shortest:  # it stopped short of another road: it meets that road
        _meet(points, laid, LONGEST_SHARE * problem.path_max_length[path] - _length(points))
    return points


def _meet(points: list, laid, spare: float) -> None:
    """Run a road cut short of another road on to it (a T junction): its last point
    moved on along its last segment to where that meets a road of ``laid``, if it does
    within ``MEET_REACH`` and ``spare`` metres, at ``MEET_ANGLE`` or more."""
    (ax, az), (bx, bz) = points[-2], points[-1]
    length = math.hypot(bx - ax, bz - az)
    if length <= 0.0:
        return
    ux, uz = (bx - ax) / length, (bz - az) / length
    hit = laid.ray((bx, bz), (ux, uz), min(MEET_REACH, spare))
    if hit is None:
        return
    distance, (vx, vz) = hit
    if abs(ux * vx + uz * vz) > math.cos(MEET_ANGLE):
        return
    points[-1] = [bx + ux * distance, bz + uz * distance]


class _Segments:
    """The segments of the roads laid so far, in a grid of cells, for distance tests."""

    CELL = 25.0

    def __init__(self) -> None:
        self.cells: dict[tuple[int, int], list[tuple[float, float, float, float, int]]] = {}

    def add(self, points, owner: int = -1) -> None:
        """Add a road's segments (``owner``: its path, for ``distance``'s ``ignore``)."""
        for (ax, az), (bx, bz) in zip(points, points[1:], strict=False):
            segment = (ax, az, bx, bz, owner)
            for i in range(
                math.floor(min(ax, bx) / self.CELL), math.floor(max(ax, bx) / self.CELL) + 1
            ):
                for j in range(
                    math.floor(min(az, bz) / self.CELL), math.floor(max(az, bz) / self.CELL) + 1
                ):
                    self.cells.setdefault((i, j), []).append(segment)

    def distance(self, point, within: float, ignore: int = -2) -> float:
        """The distance from ``point`` to the nearest segment (not of path ``ignore``),
        exact when under ``within`` (else some value of at least ``within``)."""
        px, pz = point
        reach = math.ceil(within / self.CELL)
        ci, cj = math.floor(px / self.CELL), math.floor(pz / self.CELL)
        best = math.inf
        for i in range(ci - reach, ci + reach + 1):
            for j in range(cj - reach, cj + reach + 1):
                for ax, az, bx, bz, owner in self.cells.get((i, j), ()):
                    if owner != ignore:
                        best = min(best, point_segment_distance(px, pz, ax, az, bx, bz))
        return best

    def closer_than(self, point, radius: float, ignore: int = -2) -> bool:
        """Whether some segment (not of path ``ignore``) is nearer ``point`` than
        ``radius``: ``distance(point, radius, ignore) < radius``, without measuring the
        segments whose box is clearly farther (most of them, on a clear stretch)."""
        px, pz = point
        reach = math.ceil(radius / self.CELL)
        ci, cj = math.floor(px / self.CELL), math.floor(pz / self.CELL)
        # The margin keeps a segment a rounding error away from ``radius`` measured.
        low_x, high_x = px - radius - 1e-9, px + radius + 1e-9
        low_z, high_z = pz - radius - 1e-9, pz + radius + 1e-9
        for i in range(ci - reach, ci + reach + 1):
            for j in range(cj - reach, cj + reach + 1):
                for ax, az, bx, bz, owner in self.cells.get((i, j), ()):
                    if (
                        owner == ignore
                        or (ax < low_x and bx < low_x)
                        or (ax > high_x and bx > high_x)
                        or (az < low_z and bz < low_z)
                        or (az > high_z and bz > high_z)
                    ):
                        continue
                    if point_segment_distance(px, pz, ax, az, bx, bz) < radius:
                        return True
        return False

    def ray(self, origin, direction, reach: float, ignore: int = -2):
        """(distance, unit direction of the segment) of the first segment (not of path
        ``ignore``) crossed going ``reach`` metres from ``origin`` along ``direction``;
        None if there is none."""
        ox, oz = origin
        dx, dz = direction
        ex, ez = ox + dx * reach, oz + dz * reach
        best = None
        for i in range(
            math.floor(min(ox, ex) / self.CELL), math.floor(max(ox, ex) / self.CELL) + 1
        ):
            for j in range(
                math.floor(min(oz, ez) / self.CELL), math.floor(max(oz, ez) / self.CELL) + 1
            ):
                for ax, az, bx, bz, owner in self.cells.get((i, j), ()):
                    if owner == ignore:
                        continue
                    sx, sz = bx - ax, bz - az
                    cross = dx * sz - dz * sx
                    if abs(cross) < 1e-12:
                        continue
                    t = ((ax - ox) * sz - (az - oz) * sx) / cross  # along the ray
                    u = ((ax - ox) * dz - (az - oz) * dx) / cross  # along the segment
                    if 0.0 <= t <= reach and 0.0 <= u <= 1.0 and (best is None or t < best[0]):
                        length = math.hypot(sx, sz)
                        best = (t, (sx / length, sz / length))
        return best


class _Near:
    """The nearest of several ``_Segments``, leaving out one road (a branch's own)."""

    def __init__(self, sets: tuple[_Segments, ...], ignore: int) -> None:
        self.sets, self.ignore = sets, ignore

    def distance(self, point, within: float) -> float:
        return min(found.distance(point, within, self.ignore) for found in self.sets)

    def closer_than(self, point, radius: float) -> bool:
        return any(found.closer_than(point, radius, self.ignore) for found in self.sets)

    def ray(self, origin, direction, reach: float):
        hits = [found.ray(origin, direction, reach, self.ignore) for found in self.sets]
        return min((hit for hit in hits if hit is not None), default=None)


def _length(points) -> float:
    return sum(
        math.hypot(bx - ax, bz - az) for (ax, az), (bx, bz) in zip(points, points[1:], strict=False)
    )
