"""The honest verdict on a layout: which relations hold, what overlaps, what is outside.

Thresholds for ``satisfied`` (the describer states only relations that hold, so these
are geometric truths, not energy levels):

- NextTo*: distanceBetween(A, B) <= 2 m (``next_to_distance``); with a direction
  (North/East/South/West, Left/Right/Front/Behind, and the direction a Choose* label
  resolved to) also the direction from B to A within 45 degrees of it, so the word used
  for it is the right one.
- OnTopOf* / IsPartOf*: A's base within 1 cm of B's top and A's centre over B's top;
  *Middle: centres within 10 cm in plan; *Edge / *FrontEdge: A's side within 5 cm of
  (one of / the front) edge of B's top.
- Facing*: within 30 degrees of the wanted direction (90 degrees for Orthogonal).

The layout is ``ok`` when every relation is satisfied, no two boxes and no box and path
run into each other by more than 1 cm (``OVERLAP_TOLERANCE``, the penetration depth in
metres whatever the sizes: a lamp post 5 cm into a basin is as wrong as a chair 5 cm
into a desk; a floor covering under furniture is no overlap), every box and path
control point lies inside the scene extent (1 mm tolerance), every path is within its
maximum length with turns of at most gamma, and paths leave a junction at least gamma
apart. In a room the walls replace the extent for boxes, and a layout is not ok either
when a box crosses a wall, stands in a door's swing or in the space another box keeps
free, when such a space runs into a wall, or when a box that needs reaching cannot be
reached from a door (``room_terms.RoomTerms.problems``: 1 cm of slack on each distance),
or when a box's centre lies beyond a layout mask that confines it (``mask_term``).
"""

from __future__ import annotations

import math

from scenewright.core.geometry import polyline_length, polyline_turns
from scenewright.core.relations import Relation

from .branches import branch_angle
from .energy import Energy
from .families import complaint, satisfied
from .relation_terms import EPSILON

#: How far (metres) two boxes, or a box and a path, may run into each other.
OVERLAP_TOLERANCE = 0.01
EXTENT_TOLERANCE = 0.001


def assess(energy: Energy) -> tuple[list[Relation], list[str]]:
    """A verdict for every edge of the graph, in graph order, and the list of problems
    (empty when the layout is ok). Structural edges (a path's start at its junction) hold
    by construction. Relations are measured through ``Energy.measure``, which keeps the
    measures of those nothing has moved since."""
    problem, params = energy.problem, energy.params
    results: list[Relation] = []
    problems: list[str] = []
    for source, target, label, index in problem.edges:
        if index is None:
            results.append(Relation(source, target, label, 0.0, True))
            continue
        term = problem.relations[index]
        if not term.placeable:
            results.append(Relation(source, target, label, 0.0, False))
            problems.append(
                f"{source} {label} {target}: a group with nothing in it cannot be placed"
            )
            continue
        measure = energy.measure(index)
        holds = satisfied(term, measure, params)
        results.append(Relation(source, target, label, -measure.energy, holds, measure.chosen))
        if not holds:
            problems.append(complaint(term, measure, params))
    problems.extend(_overlaps(energy))
    problems.extend(_outside(energy))
    problems.extend(_path_shapes(energy))
    if energy.room is not None:
        problems.extend(energy.room.problems())
    problems.extend(
        f"{problem.ids[box]} stands outside its part of the room" for box in energy.strays()
    )
    return results, problems


def unsatisfied_terms(energy: Energy, relations: list[Relation]) -> list[int]:
    """The relation terms (indices into ``problem.relations``) of the verdicts in
    ``relations`` (``assess``'s, in graph order, structural edges included) that do not hold."""
    edges = energy.problem.edges
    return [
        index
        for (_, _, _, index), relation in zip(edges, relations, strict=False)
        if index is not None and not relation.satisfied
    ]


def _overlaps(energy: Energy) -> list[str]:
    problem, found = energy.problem, []
    xs, zs, size = energy.state.x, energy.state.z, problem.size
    for box in range(problem.n_boxes):
        x, z = xs[box], zs[box]
        for other in sorted(other for other in energy.grid.near_box(box) if other > box):
            # Footprints within bounding circles (diameter ``size``) that miss each other
            # cannot overlap (corners on the circles touch at most, by rounding): skipped.
            dx, dz, apart = xs[other] - x, zs[other] - z, (size[box] + size[other]) / 2.0
            if dx * dx + dz * dz > apart * apart:
                continue
            depth = energy.pair_penetration(box, other)
            if depth > OVERLAP_TOLERANCE:
                found.append(
                    f"{problem.ids[box]} overlaps {problem.ids[other]} by {100 * depth:.0f} cm"
                )
        if energy.collides_with_paths[box]:
            for path in energy.paths_near(box):
                depth = energy.path_penetration(box, path)
                if depth > OVERLAP_TOLERANCE:
                    found.append(
                        f"{problem.ids[box]} overlaps {problem.path_ids[path]} by {100 * depth:.0f} cm"
                    )
    return found


def _outside(energy: Energy) -> list[str]:
    problem, found = energy.problem, []
    if energy.room is None:  # in a room the walls say it ("crosses the wall")
        for box in range(problem.n_boxes):
            excess = energy.box_excess(box)
            if excess > EXTENT_TOLERANCE:
                found.append(f"{problem.ids[box]} is outside the scene by {excess:.2f} m")
    for path in range(problem.n_paths):
        excess = energy.path_excess(path)
        if excess > EXTENT_TOLERANCE:
            found.append(f"{problem.path_ids[path]} leaves the scene by {excess:.2f} m")
    return found


def _path_shapes(energy: Energy) -> list[str]:
    problem, state, params = energy.problem, energy.state, energy.params
    found = []
    for path in range(problem.n_paths):
        points = state.points[path]
        length = polyline_length(points)
        if length > problem.path_max_length[path] + EPSILON:
            found.append(
                f"{problem.path_ids[path]} is {length:.1f} m long (at most {problem.path_max_length[path]:.0f} m)"
            )
        turns = polyline_turns(points)
        if turns and max(turns) > params.gamma + EPSILON:
            found.append(
                f"{problem.path_ids[path]} turns by {math.degrees(max(turns)):.0f}° (at most {math.degrees(params.gamma):.0f}°)"
            )
    for path in range(problem.n_paths):
        parent = problem.path_parent[path]
        if parent >= 0:
            angle = branch_angle(state.points[parent], state.points[path])
            if angle < params.gamma - EPSILON:
                found.append(
                    f"{problem.path_ids[path]} leaves {problem.path_ids[parent]} at only "
                    f"{math.degrees(angle):.0f}° (at least {math.degrees(params.gamma):.0f}°)"
                )
    for junction in problem.paths_of_junction:
        angles = energy.junction_angles(junction)
        if angles and min(angles) < params.gamma - EPSILON:
            found.append(
                f"paths leave {problem.ids[junction]} only {math.degrees(min(angles)):.0f}° apart (at least {math.degrees(params.gamma):.0f}°)"
            )
    return found
