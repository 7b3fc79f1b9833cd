"""The layout's tunable constants, in one plain dataclass."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .factors import DEFAULT_H, DEFAULT_SIGMA2


@dataclass(frozen=True)
class LayoutParams:
    """Named constants of the energy and the sampler.

    Energy: ``h`` and ``sigma2`` are the factor functions' steepness (paper: 3.0, 0.1);
    ``gamma`` the path turn / junction angle limit (paper: 60 degrees);
    ``collision_intensity`` the paper's c in -c log(1 - penetration);
    ``next_to_distance`` the distance NextTo* asks for (paper: 2 m);
    ``mask_weight`` the ``mask`` part's weight per box (``mask_term``; a box standing
    where the layout mask is 0 costs this much more than where it is 1).

    Sampler: ``steps`` is the step budget of one run, raised to ``steps_per_box`` times
    the number of boxes for big scenes (``patience`` grows alike); ``min_steps`` the steps always
    taken (the chain polishes even a constructive placement that is already fine);
    ``check_every`` how often the stop rule is tested; it stops once the layout is ok
    (every relation satisfied, nothing overlapping, all inside) and its energy is at most
    ``target_energy``; it gives up early when its count of problems has not fallen for
    ``patience`` steps (``repair_patience`` for a chain that a repairing restart follows,
    outdoors: mending the items it is stuck on is quicker than waiting it out;
    ``restart_patience``, when set, for every chain after the first). ``restarts``
    more runs are made while the result is not ok (``layout_scene`` says from where), and the
    best is kept. The temperature falls geometrically from
    ``temperature_start`` to ``temperature_end`` over ``steps``. ``initial_candidates``
    poses are tried for each item during the constructive initial placement, and
    ``path_candidates`` for each road and junction laid around pinned or started things
    (few, and everything else is placed by them, so they get more tries).
    ``incremental=False`` recomputes the full energy every step (for comparison).

    Learned context (``learned_term``; no effect without one): ``tempered`` samples the
    learned part and the relations of its pairs at temperature 1 while the rest is
    annealed (False anneals everything, for comparison); ``learned_share`` of the steps
    are learned moves; the stop rule waits until ``learned_sweeps`` of them were
    accepted for every learned pair, or five times as many proposed
    (``learned_term.TRIES_PER_SWEEP``; ``sampler``): 2, since 3 cost 1.8-2.3x the
    layout time without a context and 1 let single chairs stray (``bench_diversity``).
    ``template_init`` draws the constructive placement of a learned pair's source from
    the pair's learned template (``templates``) instead of from its relations.

    Group decomposition (``decompose``): ``workers`` processes lay out the groups' own
    frames (1: in this process; the result is the same for any number);
    ``decompose=False`` never decomposes (one chain over the whole scene, for
    comparison), True follows the documented rule of ``decompose.decomposes``.
    """

    h: float = DEFAULT_H
    sigma2: float = DEFAULT_SIGMA2
    gamma: float = math.radians(60.0)
    collision_intensity: float = 30.0
    next_to_distance: float = 2.0
    mask_weight: float = 1.0
    steps: int = 4000
    steps_per_box: int = 100
    min_steps: int = 50
    check_every: int = 25
    patience: int = 1200
    repair_patience: int = 400
    restart_patience: int | None = None
    target_energy: float = math.inf
    restarts: int = 4
    temperature_start: float = 0.05
    temperature_end: float = 0.002
    initial_candidates: int = 8
    path_candidates: int = 16
    incremental: bool = True
    tempered: bool = True
    learned_share: float = 0.5
    learned_sweeps: int = 2
    template_init: bool = False
    decompose: bool = True
    workers: int = 1
