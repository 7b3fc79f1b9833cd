"""Metropolis-Hastings with annealing over box poses and path control points.

One run: a constructive initial placement, then up to ``params.steps`` steps (at least
``steps_per_box`` per box, so big scenes get a bigger budget). Each step draws a
proposal (``moves.Mover``), gets its energy change from ``Energy.propose`` and accepts
it with probability min(1, exp(-delta / T)), T falling geometrically from
``temperature_start`` to ``temperature_end`` (``metropolis``; in a room the costly
access part is computed only when the rest of the change has not decided the step
already, with the same draws and decisions). Every ``check_every`` steps (after
``min_steps``) the stop rule is tested: the layout is ok (``report.assess``) and its
energy is at most ``target_energy``. A chain whose count of problems has not fallen
for ``patience`` steps stops early, since a fresh start does better than waiting. The
caller makes restarts.

With ``pins`` (``pinning.Pins``) pinned boxes and paths are placed first and never
moved, and warm-started ones are placed at their start poses before the constructive
placement puts the rest around them.

In a room a share RELOCATE_SHARE of the steps is a ``Relocator`` move instead: a
troubled box (in a door's swing, in a kept-free zone or owning one that is taken,
across a wall, out of reach or hemming in one that is) goes wherever one of its own
relations puts it, with everything placed only by it carried along rigidly: a bed whose
free side the desk takes moves to another corner with its nightstands and rug, where a
lone bed jump would break their relations and be refused. Outdoors no such step is
drawn, so village layouts draw the same random numbers as before.

With a learned context (``learned_term``) the chain *samples* instead of optimising
what the context models: a proposal is accepted with probability

    min(1, exp(-(delta - soft) / T - learned + correction))

``learned`` is the proposal's change in the ``learned`` part, taken at temperature 1;
``soft`` is that plus the change in the relation terms of the learned pairs whose
source stands on the pair's grid (``Energy.soft_delta``), which the learned part stands
in for: the examples, not the rules' hand-set factors, say where a learned pair's
source stands (in Dema and Sari-Sarraf's model the learned histograms and the hard
intersection constraint are the whole energy); off the grid the learned part has one
weight for anywhere, and the relation terms are annealed with the rest. The rest
(collisions, extent, paths, the room's terms, the other relations) is annealed as
always, and the verdict still checks every relation. ``correction`` is the Hastings
term of a learned move (0 for the others; an ordinary move of a learned pair's target
takes the pair's source along half the time, ``LearnedMoves.carry``). A share
``params.learned_share`` of the steps is a learned move (``LearnedMoves``: a pair's
source drawn from the pair's learned distribution, or an exchange of two
interchangeable boxes), and the stop rule waits until every pair has had
``params.learned_sweeps`` such draws accepted (drawing the pairs still short of it
first), so that no source is left where the constructive placement put it (those
leftovers, not the learned terms, would set the spread); a pair whose moves the rest of
the energy keeps refusing (a nightstand held against its wall) stops the wait after
``learned_term.TRIES_PER_SWEEP`` proposals a sweep.
``params.tempered=False`` anneals the learned terms with the rest (the
optimiser's way, which collapses every scene onto the most likely pose: for
comparison). Without a context nothing here changes a single random draw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.relations import Relation

from .energy import Energy
from .families import LAYOUT_FAMILIES
from .initial import place_initial
from .learned_term import LearnedMoves
from .motion import draw_index, rigid, wrap
from .moves import Mover
from .params import LayoutParams
from .pinning import Pins
from .problem import Problem
from .report import assess, unsatisfied_terms
from .state import State
from .terms import Endpoint

#: In a room, the share of steps that are ``Relocator`` moves (when some box is troubled).
RELOCATE_SHARE = 0.05


@dataclass
class Run:
    """The outcome of one chain."""

    energy: Energy
    relations: list[Relation]
    problems: list[str]
    steps: int
    accepted: int

    @property
    def ok(self) -> bool:
        return not self.problems


def start_chain(
    problem: Problem, params: LayoutParams, rng: np.random.Generator, pins: Pins | None = None
) -> tuple[Energy, Mover]:
    """A fresh state after the constructive initial placement, with its energy and mover."""
    pins = pins or Pins.none(problem)
    state = State(problem)
    pins.set_heights(problem, state)
    energy = Energy(problem, state, params)
    mover = Mover(problem, state, rng, params, pins)
    place_initial(energy, mover, rng, pins)
    return energy, mover


def run_chain(
    problem: Problem, params: LayoutParams, rng: np.random.Generator, pins: Pins | None = None
) -> Run:
    """Place, then anneal until the stop rule holds or the step budget is spent."""
    energy, mover = start_chain(problem, params, rng, pins)
    return anneal(
        energy, mover, params, rng, max(params.steps, params.steps_per_box * problem.n_boxes)
    )


def anneal(
    energy: Energy, mover: Mover, params: LayoutParams, rng: np.random.Generator, budget: int
) -> Run:
    """Anneal the placed state with ``mover``'s proposals for at most ``budget`` steps,
    under the stop rule (ok and at most ``target_energy``) and the patience rule (which
    grows with the budget as the budget grows past ``params.steps``)."""
    problem = energy.problem
    relocator = Relocator(problem, energy.state, mover) if problem.room is not None else None
    learned = None
    if problem.learned is not None:
        learned = LearnedMoves(
            problem.learned, problem, energy.state, rng, mover.movable_box, params.learned_sweeps
        )
    relations, problems = assess(energy)
    accepted = steps = 0
    fewest, since = len(problems), 0  # stagnation: steps since the problem count last fell
    patience = params.patience * budget // max(params.steps, 1)
    cooling = math.log(params.temperature_end / params.temperature_start) / max(budget, 1)
    uniform = rng.random
    # In a room, the access part (the costliest) waits until the rest has not already
    # decided the step (``metropolis``).
    defer = energy.room is not None and params.incremental
    for step in range(budget):
        if (
            step >= params.min_steps
            and step % params.check_every == 0
            and (learned is None or learned.mixed())
        ):
            relations, problems = assess(energy)
            if not problems and energy.total <= params.target_energy:
                break
            mover.focus(unsatisfied_terms(energy, relations), energy.troubled_boxes())
            if len(problems) < fewest:
                fewest, since = len(problems), step
            elif step - since >= patience:
                break
        steps = step + 1
        if learned is not None:
            if learned_step(
                energy,
                mover,
                relocator,
                learned,
                params,
                params.temperature_start * math.exp(cooling * step),
            ):
                accepted += 1
            continue
        proposal = ordinary_proposal(energy, mover, relocator, uniform)
        if proposal is None:
            continue
        temperature = params.temperature_start * math.exp(cooling * step)
        if metropolis(energy, proposal, temperature, uniform, defer):
            energy.accept()
            accepted += 1
        else:
            energy.reject()
    else:
        relations, problems = assess(energy)
    return Run(energy, relations, problems, steps, accepted)


def metropolis(energy: Energy, proposal, temperature: float, uniform, defer: bool) -> bool:
    """Propose and decide (True: accept) with probability min(1, exp(-delta / T)),
    drawing ``uniform()`` only when delta > 0, exactly as the plain rule does.

    With ``defer`` the room's access part is left out at first: it can lower the energy
    by at most all of it there is now (``Energy.access_floor``), so when the rest minus
    that is already above 0, the draw is made (the plain rule makes it too: delta is
    above 0) and a draw that rejects even that lower bound rejects the step without
    computing reachability; otherwise the access part is added (``Energy.complete``) and
    the same draw decides. Same draws, same decisions, same layouts."""
    delta = energy.propose(*proposal, defer_access=defer)
    if defer:
        lower = delta - energy.access_floor()
        if lower > 0.0:
            draw = uniform()
            if not draw < math.exp(-lower / temperature):
                return False
            delta = energy.complete()
            return delta <= 0.0 or draw < math.exp(-delta / temperature)
        delta = energy.complete()
    return delta <= 0.0 or uniform() < math.exp(-delta / temperature)


def ordinary_proposal(energy: Energy, mover: Mover, relocator: Relocator | None, uniform):
    """A proposal of the mover's, or now and then (``RELOCATE_SHARE``, indoors, while
    some box is in trouble; ``uniform`` the chain's draw) a relocation of a troubled
    box; None when there is none."""
    if relocator is not None and mover.focus_boxes and uniform() < RELOCATE_SHARE:
        proposal = relocator.propose(mover.focus_boxes)
        if proposal is not None:
            return proposal
    return mover.propose(energy.relation)


def learned_step(
    energy: Energy,
    mover: Mover,
    relocator: Relocator | None,
    learned: LearnedMoves,
    params: LayoutParams,
    temperature: float,
) -> bool:
    """One step of a chain with a learned context (module docstring); True when accepted."""
    uniform = mover.rng.random
    proposal: tuple[dict, dict] | None = None
    correction = 0.0
    pair = None
    if learned.pairs and uniform() < params.learned_share:
        drawn = learned.propose()
        if drawn is not None:
            proposal, correction, pair = (drawn[0], {}), drawn[1], drawn[2]
    if proposal is None:
        proposal = ordinary_proposal(energy, mover, relocator, uniform)
        if proposal is None:
            return False
        proposal = (learned.carry(proposal[0]), proposal[1])
    delta = energy.propose(*proposal)
    if params.tempered:
        exponent = -(delta - energy.soft_delta) / temperature - energy.learned_delta + correction
    else:
        exponent = -delta / temperature + correction
    if exponent >= 0.0 or uniform() < math.exp(exponent):
        energy.accept()
        if pair is not None:
            learned.redrawn[pair] += 1
        return True
    energy.reject()
    return False


class Relocator:
    """A room's move for a troubled box: put it where one of its own relations holds
    (the mover's data-driven placement), and carry its satellites along rigidly.

    A box's satellites are the movable ground objects whose every relation points at
    the box or at its other satellites (a bed's nightstands and rug), with what stands on
    them; they keep their places relative to the box, so their relations still hold.
    """

    def __init__(self, problem: Problem, state: State, mover: Mover):
        self.problem, self.state, self.mover = problem, state, mover
        self.satellites = [self._satellites(box) for box in range(problem.n_boxes)]

    def _satellites(self, box: int) -> list[int]:
        problem, movable = self.problem, self.mover.movable_box
        held = set(problem.carried(box))
        found: list[int] = []
        grew = True
        while grew:
            grew = False
            for term in problem.relations:
                if term.a.kind != "object" or not term.b.members or not set(term.b.members) <= held:
                    continue
                other = term.a.index
                if other in held or not movable[other] or problem.support[other] != -1:
                    continue
                own = problem.outgoing.get(("object", other), [])
                if all(t.b.members and set(t.b.members) <= held for t in own):
                    carried = problem.carried(other)
                    held.update(carried)
                    found.extend(carried)
                    grew = True
        return found

    def propose(self, troubled: list[int]) -> tuple[dict, dict] | None:
        """New poses for a troubled box (drawn from ``troubled``) placed by its relations,
        and for its satellites; None when it has no relation that places it."""
        problem, state, mover = self.problem, self.state, self.mover
        box = troubled[draw_index(mover.rng, len(troubled))]
        placing = [
            t
            for t in problem.outgoing.get(("object", box), [])
            if LAYOUT_FAMILIES[t.spec.family].places
        ]
        if not placing:
            return None
        end = Endpoint("object", box, (box,))
        if len(placing) > 1:
            boxes = mover.place_for_all(end)
        else:
            boxes = mover.place_for_relation(placing[0])
        if not boxes or box not in boxes:
            return None
        x, z, yaw = state.pose(box)
        new_x, new_z, new_yaw = boxes[box]
        carried = [b for b in self.satellites[box] if b not in boxes]
        boxes.update(rigid(state, carried, (x, z), wrap(new_yaw - yaw), (new_x - x, new_z - z)))
        return boxes, {}
