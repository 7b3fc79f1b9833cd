"""Template initialisation: the constructive placement draws learned pairs' sources from
their relative-pose templates instead of from the rules' hand-set relation placements.

With a learned context (``learned_term``) every related pair of a kind it has carries a
*template*: the learned distribution of the source's pose in its target's frame (a
position over the kind's BINS x BINS grid and a relative yaw), as the pairwise
relationships learned from examples in Yu et al., "Make it home: automatic
optimization of furniture arrangement" (SIGGRAPH 2011) give a related object's distance
and orientation relative to its partner. When ``params.template_init`` is on and a box about to be placed
(``initial._place_box``) is the source of such a pair whose target is already placed,
each of its ``initial_candidates`` candidates is drawn from that template
(``learned_term.draw_source``, the draw the sampler's learned moves make: a cell by its
learned share, a point uniform inside it, a yaw from the yaw bins), relative to where
the target stands; the best candidate by energy is kept as for any other box. A source
with several such pairs draws each candidate from one of them, picked uniformly. The
template gives the turn too, so the facing relations of its learned pairs do not turn
it afterwards (``not_templated``; while sampling the learned part stands in for them).

Without a context, with the option off, or for a box that is no placed target's
source, ``template_draw`` returns None before drawing anything, so the placement draws
exactly the numbers it drew before.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from .energy import Energy
from .learned_term import cumulative_shares, draw_source
from .terms import RelationTerm


def template_draw(
    energy: Energy, rng: np.random.Generator, box: int
) -> Callable[[], tuple[dict, dict]] | None:
    """A candidate drawer for ``box`` from its learned templates (``(box poses, {})`` per
    call, as ``initial._place_box``'s own drawer returns), or None when it has none:
    no context, ``template_init`` off, or no learned pair with ``box`` as its source and
    a target already placed."""
    problem, state = energy.problem, energy.state
    if problem.learned is None or not energy.params.template_init:
        return None
    pairs = [
        (source, target, table)
        for source, target, table in problem.learned.pairs
        if source == box and energy.active[target]
    ]
    if not pairs:
        return None
    shares = {id(table): cumulative_shares(table) for _, _, table in pairs}

    def draw() -> tuple[dict, dict]:
        source, target, table = pairs[int(rng.integers(len(pairs)))] if len(pairs) > 1 else pairs[0]
        return draw_source(problem, state, rng, source, target, table, shares[id(table)]), {}

    return draw


def not_templated(energy: Energy, facing: Sequence[RelationTerm]) -> list[RelationTerm]:
    """The facing relations of a template-drawn box that are left to turn it: those not
    of its learned pairs (the template drew its turn relative to those targets)."""
    problem = energy.problem
    assert problem.learned is not None  # a template is drawn from a context only
    stood_in = {id(problem.relations[index]) for index in problem.learned.tempered}
    return [term for term in facing if id(term) not in stood_in]
