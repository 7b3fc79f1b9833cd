"""What a room should hold: its type(s) (the paper's Equation 2, Section 5.2) and its
categories (Algorithm 1, object exploration, Section 5.3).

**Types.** ``choose_types`` searches every set of the model's types (exactly: there are
few) among the sets in which some type has each requested category (``P(o | s) > 0``).
The paper also requires the set's plans to hold as many as asked (``sum N(o, s) >=
n_o``, ``N`` the most of ``o`` in one plan of ``s``); here that bound is soft (below).
The paper then takes the set whose mean room areas add up closest to the room's area,
``|theta_r - sum theta_s| / theta_r``, and approximates that search greedily; with a
handful of types the exact answer is cheap. Our reading of "close": home rooms' mean
areas lie near one another while each type's rooms spread widely, so the nearest mean
alone made small living rooms with a sofa studies (design notes, docs/notes/design.md,
"Room completion"). Each set is scored as a likelihood instead:

    log N(theta_r; sum mu_s, sum sigma_s^2)  +  sum_o log max_s P(o | s)
      -  b log(1 + n_S)  -  (|S| - 1) log(1 + n)

the room's area under the set's area distribution (each type's plans' mean and standard
deviation, ``area_spreads``; areas of several types add), how often the set's types have
what was asked, a cost for the ``b`` requested categories of which the set's ``n_S``
plans never held as many as asked (``sum N(o, s) < n_o``), and a cost for each type
beyond the first. Both costs are the rule of succession: after ``n_S`` plans none of
which held more, one that does is ``1 / (1 + n_S)`` as likely; the plans show ``n``
rooms of one type and none of several, so a room of several types is ``1 / (1 + n)``
as likely. The paper's hard bound read every request for more than the plans showed
(two beds where the bedrooms seen hold one, four treadmills where the gyms seen hold up
to three) as a room of several types, or as no room at all. (The command still refuses a
count beyond what the plans of all types hold together, ``check_counts``: it lays out
no more of a thing than the designers drew.) A type joins a set of several only when
it has a requested category or the plans have seen it with one (``_joins``): the plans
of some type have both a category of its own (one it has more often than any other
type) and a requested category. A room splits only when no single type's rooms come
near its area. Each requested category belongs to the type of the set that has it most
often.

**Categories.** Start from every category of the type's relation graph (and the ones the user asked
for), then repeatedly remove the non-requested category with the weakest mean edge
weight to its remaining neighbours, ``E(W_s, o) = (1/J) sum_j W_s(o, o_j)``, and any
non-requested category left without a neighbour; keep the set whose cost

    C(O) = (1/K) sum_k |R(O, theta_r) - r_s^k|  -  omega * sum_{pairs in O} W_s(o_i, o_j)

is lowest. ``R(O, theta_r) = sum theta_c / theta_r`` is the occupancy the set would give
the room, ``r_s^k`` the occupancy of the k-th of the ``K = 10`` plans of the type most
like the room, ``omega = 0.02``.

Two readings where the paper is open:

- *Which plans are "most like the room".* Its room feature includes the occupancy, which
  is what the algorithm is choosing; comparing with it would pick plans as full as the
  set being tried and make the cost agree with itself. So the K plans are the nearest
  by the feature's room-only parts: the door-window angle, the aspect ratio and the
  relative size (Euclidean, uniform weights, as the paper compares features).
- *How much floor a category takes.* ``theta_c`` is the category's mean floor area; a
  requested category counts as many times as asked, as the paper says. An added one
  counts as many times as the reference plans that have it hold on average, rounded
  (four chairs at the small tables of small dining rooms, six in larger ones; the whole
  type's plans when no reference has it), where the paper counts one: ``r_s^k`` counts
  every chair of a plan, so counting one would not compare like with like.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from scenewright.completion import CATEGORY_METHODS
from scenewright.completion.plan_model import PlanEntry, PlanModel
from scenewright.core.errors import InputError

#: The paper's constants: how many similar plans the cost compares with, and the weight of relations.
K = 10
OMEGA = 0.02
#: The least spread of a type's room areas, as a share of its mean area.
MIN_AREA_SPREAD = 0.2
#: The parts of the room feature ``f_r`` that describe the room alone: angle, aspect, relative size.
ROOM_PARTS = (0, 2, 3)


@dataclass(frozen=True)
class TypeChoice:
    """Equation 2's answer: the types (largest mean area first), which type each
    requested category belongs to, and the relative area error of the set."""

    types: tuple[str, ...]
    owners: dict[str, str]
    area_error: float


def choose_types(model: PlanModel, requested: dict[str, int], room_area: float) -> TypeChoice:
    """The set of room types for a room of ``room_area`` square metres holding
    ``requested`` (category -> count); ``InputError`` when no plan has one of them."""
    types = sorted(model.types)
    for name in sorted(requested):
        if not any(_p(model, t, name) > 0.0 for t in types):
            raise InputError(f"no plan of any type has a {name!r} (the plans know {_known(model)})")
    spreads = area_spreads(model)
    extra_type = math.log(1 + sum(entry.plans for entry in model.types.values()))
    joins = {t for t in types if _joins(model, t, requested)}
    candidates = []  # the set of the types that have a requested category has each of them
    for mask in range(1, 2 ** len(types)):
        chosen = [t for k, t in enumerate(types) if mask >> k & 1]
        if len(chosen) > 1 and not joins.issuperset(chosen):
            continue
        holds = [max(_p(model, t, name) for t in chosen) for name in requested]
        if all(p > 0.0 for p in holds):
            mean = sum(model.types[t].mean_area for t in chosen)
            variance = sum(spreads[t] ** 2 for t in chosen)
            log_area = -0.5 * (room_area - mean) ** 2 / variance - 0.5 * math.log(
                2 * math.pi * variance
            )
            log_holds = sum(math.log(p) for p in holds)
            unseen = math.log(1 + sum(model.types[t].plans for t in chosen))
            beyond = sum(
                1 for name, count in requested.items() if _most(model, chosen, name) < count
            )
            score = log_area + log_holds - unseen * beyond - extra_type * (len(chosen) - 1)
            candidates.append(
                (-round(score, 9), len(chosen), chosen, abs(room_area - mean) / room_area)
            )
    _, _, chosen, error = min(candidates)
    ordered = tuple(sorted(chosen, key=lambda t: (-model.types[t].mean_area, t)))
    owners = {
        name: max(ordered, key=lambda t: (_p(model, t, name), -ordered.index(t)))
        for name in sorted(requested)
    }
    return TypeChoice(ordered, owners, error)


def area_spreads(model: PlanModel) -> dict[str, float]:
    """Each type's spread of room areas in square metres: the standard deviation of its
    plans' areas, at least ``MIN_AREA_SPREAD`` of its mean (a type drawn from one or two
    plans says little about how its rooms vary)."""
    areas: dict[str, list[float]] = {t: [] for t in model.types}
    for plan in model.plans:
        areas.setdefault(plan.type, []).append(plan.area)
    return {
        t: max(
            float(np.std(areas[t])) if len(areas[t]) > 1 else 0.0,
            MIN_AREA_SPREAD * entry.mean_area,
        )
        for t, entry in model.types.items()
    }


def own_categories(model: PlanModel) -> dict[str, set[str]]:
    """Per type, the categories it has more often than every other type (the largest
    P(category | type); ties to the first type by name): a bed is a bedroom's, a sofa
    and a television a living room's, a treadmill a gym's."""
    owned: dict[str, set[str]] = {t: set() for t in model.types}
    for name in sorted(model.categories):
        best = max(sorted(model.types), key=lambda t: _p(model, t, name))
        if _p(model, best, name) > 0.0:
            owned[best].add(name)
    return owned


def _joins(model: PlanModel, room_type: str, requested) -> bool:
    """Whether ``room_type`` may be one of several types of a room asked for ``requested``:
    it has a requested category, or the plans of some type have both one of its own
    categories (``own_categories``) and a requested one (bedrooms have desks, so a study
    may join a bedroom; no type has both a treadmill and a bed)."""
    if any(_p(model, room_type, name) > 0.0 for name in requested):
        return True
    own = own_categories(model)[room_type]
    return any(
        any(_p(model, other, name) > 0.0 for name in own)
        and any(_p(model, other, name) > 0.0 for name in requested)
        for other in model.types
    )


def _p(model: PlanModel, room_type: str, name: str) -> float:
    return model.types[room_type].probability(name)


def _most(model: PlanModel, chosen, name: str) -> int:
    """``sum N(o, s)`` over the ``chosen`` types: the most of ``name`` their plans hold, one plan of each."""
    return sum(model.types[t].most(name) for t in chosen)


def check_counts(model: PlanModel, requested: dict[str, int]) -> None:
    """``InputError`` for a count beyond what the plans of every type hold together (one
    plan of each): Equation 2 only charges a set for holding fewer than asked, but a
    room is not laid out with more of a thing than any designer drew."""
    for name, count in sorted(requested.items()):
        most = _most(model, sorted(model.types), name)
        if most < count:
            raise InputError(f"the plans hold at most {most} of {name!r} together, not {count}")


def _known(model: PlanModel) -> str:
    names = sorted(model.categories)
    return ", ".join(names[:12]) + (", ..." if len(names) > 12 else "")


@dataclass(frozen=True)
class Exploration:
    """Algorithm 1's answer: the categories (requested first, then added by how strongly
    they are related), how many of each, the best cost, the reference plans, and every
    step (the category removed, those removed with it as isolated, the cost after)."""

    categories: tuple[str, ...]
    counts: dict[str, int]
    cost: float
    references: tuple[str, ...]
    steps: tuple[dict, ...] = field(default=())


def nearest_plans(model: PlanModel, room_type: str, room_parts, k: int = K) -> list[PlanEntry]:
    """The ``k`` plans of ``room_type`` whose room-only feature parts are nearest to
    ``room_parts`` (angle / pi, aspect, relative size); ties by plan id."""
    plans = [plan for plan in model.plans if plan.type == room_type]
    target = np.asarray(room_parts, dtype=float)
    distance = {
        plan.id: float(np.linalg.norm(np.asarray(plan.feature)[list(ROOM_PARTS)] - target))
        for plan in plans
    }
    return sorted(plans, key=lambda plan: (distance[plan.id], plan.id))[:k]


def explore_categories(
    model: PlanModel,
    room_type: str,
    requested: dict[str, int],
    room_area: float,
    room_parts,
    *,
    k: int = K,
    omega: float = OMEGA,
) -> Exploration:
    """Algorithm 1 for a room of ``room_area`` square metres whose room-only feature
    parts are ``room_parts``, with ``requested`` categories and counts."""
    if room_type not in model.types:
        raise InputError(f"the plans have no type {room_type!r}")
    entry = model.types[room_type]
    unknown = sorted(name for name in requested if name not in model.categories)
    if unknown:
        raise InputError(f"no plan has a {unknown[0]!r}")
    weights = {tuple(pair.pair): pair.weight for pair in entry.pairs if pair.weight > 0.0}
    references = nearest_plans(model, room_type, room_parts, k)
    occupancies = np.array([plan.feature[1] for plan in references])
    typical = {
        **_typical_counts(model.plans, room_type),
        **_typical_counts(references, room_type),
    }
    names = sorted({name for pair in weights for name in pair} | set(requested))
    counts = {name: requested.get(name, typical.get(name, 1)) for name in names}

    def weight(first: str, second: str) -> float:
        return weights.get((min(first, second), max(first, second)), 0.0)

    # Sums run over sorted names: a set's order changes with the interpreter's hash seed,
    # and a float sum's last bit with its order, which could flip a tie between two costs.
    def cost(chosen: set[str]) -> float:
        names = sorted(chosen)
        ratio = sum(model.categories[name].floor_area * counts[name] for name in names) / room_area
        related = sum(weight(a, b) for i, a in enumerate(names) for b in names[i + 1 :])
        return float(np.mean(np.abs(ratio - occupancies))) - omega * related

    def mean_weight(name: str, chosen: set[str]) -> float:
        neighbours = [
            weight(name, other)
            for other in sorted(chosen)
            if other != name and weight(name, other) > 0.0
        ]
        return sum(neighbours) / len(neighbours) if neighbours else 0.0

    chosen = set(counts)
    best, best_cost = set(chosen), cost(chosen)
    steps = []
    while len(chosen) > len(requested):
        removable = sorted(name for name in chosen if name not in requested)
        weakest = min(removable, key=lambda name: (mean_weight(name, chosen), name))
        chosen.discard(weakest)
        isolated = sorted(
            name for name in chosen if name not in requested and mean_weight(name, chosen) == 0.0
        )
        chosen.difference_update(isolated)
        now = cost(chosen)
        steps.append({"removed": weakest, "isolated": isolated, "cost": now})
        if now < best_cost:
            best, best_cost = set(chosen), now
    added = sorted(
        best - set(requested), key=lambda name: (-sum(weight(name, r) for r in requested), name)
    )
    ordered = tuple(sorted(requested)) + tuple(added)
    return Exploration(
        ordered,
        {name: counts[name] for name in ordered},
        best_cost,
        tuple(plan.id for plan in references),
        tuple(steps),
    )


def _typical_counts(plans: list[PlanEntry], room_type: str) -> dict[str, int]:
    """Per category, the mean number of it in those of ``plans`` of the type that have
    one, rounded (at least 1)."""
    totals: dict[str, list[int]] = {}
    for plan in plans:
        if plan.type == room_type:
            for name, count in plan.counts.items():
                totals.setdefault(name, []).append(count)
    return {name: max(1, int(round(float(np.mean(values))))) for name, values in totals.items()}


def usual_categories(
    model: PlanModel,
    room_type: str,
    requested: dict[str, int],
    room_area: float,
    room_parts,
    *,
    k: int = K,
) -> Exploration:
    """The co-occurrence step, ``complete``'s default (``--categories co-occurrence``):
    as many categories beyond the request as the ``k`` plans of the type most like the
    room (``nearest_plans``, Algorithm 1's reference plans) hold on average, rounded;
    those most often seen with the requested ones (the sum of ``P(o, o_req | s)``; ties:
    the more common ``P(o | s)``, then the name), each as many times as Algorithm 1
    would count it. The leave-one-out measured Algorithm 1 no better than this
    (docs/completion.md, "How well it predicts"). ``room_area`` is unused: the room
    enters through ``room_parts`` (its relative size among them)."""
    if room_type not in model.types:
        raise InputError(f"the plans have no type {room_type!r}")
    unknown = sorted(name for name in requested if name not in model.categories)
    if unknown:
        raise InputError(f"no plan has a {unknown[0]!r}")
    entry = model.types[room_type]
    references = nearest_plans(model, room_type, room_parts, k)
    usual = int(round(float(np.mean([len(set(p.counts) - set(requested)) for p in references]))))
    together = {tuple(pair.pair): pair.cooccurrence for pair in entry.pairs}
    candidates = sorted(name for name in entry.categories if name not in requested)
    score = {
        name: sum(together.get((min(name, r), max(name, r)), 0.0) for r in sorted(requested))
        for name in candidates
    }
    added = sorted(candidates, key=lambda name: (-score[name], -entry.probability(name), name))
    typical = {
        **_typical_counts(model.plans, room_type),
        **_typical_counts(references, room_type),
    }
    ordered = tuple(sorted(requested)) + tuple(added[:usual])
    counts = {name: requested.get(name, typical.get(name, 1)) for name in ordered}
    return Exploration(ordered, counts, 0.0, tuple(plan.id for plan in references))


def choose_categories(method: str):
    """The category step named ``method`` (``CATEGORY_METHODS``): ``usual_categories``
    for ``co-occurrence``, Algorithm 1 (``explore_categories``) for ``algorithm1``."""
    if method not in CATEGORY_METHODS:
        raise InputError(
            f"categories method {method!r}: choose one of {', '.join(CATEGORY_METHODS)}"
        )
    return usual_categories if method == "co-occurrence" else explore_categories
