"""Metropolis-Hastings with annealing over box poses and path control points.

One run: a constructive initial placement, then up to ``params.steps`` steps (at least
``steps_per_box`` per box, so big scenes get a bigger budget). Each step draws a
proposal (``moves.Mover``), gets its energy change from ``Energy.propose`` and accepts
it with probability min(1, exp(-delta / T)), T falling geometrically from
``temperature_start`` to ``temperature_end``. Every ``check_every`` steps (after
``min_steps``) the stop rule is tested: the layout is ok (``report.assess``) and its
energy is at most ``target_energy``. A chain whose count of problems has not fallen
for ``patience`` steps stops early, since a fresh start does better than waiting. The
caller makes restarts.

With ``pins`` (``pinning.Pins``) pinned boxes and paths are placed first and never
moved, and warm-started ones are placed at their start poses before the constructive
placement puts the rest around them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.relations import Relation

from .energy import Energy
from .initial import place_initial
from .moves import Mover
from .params import LayoutParams
from .pinning import Pins
from .problem import Problem
from .report import assess
from .state import State


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


def run_chain(problem: Problem, params: LayoutParams, rng: np.random.Generator, pins: Pins | None = None) -> Run:
    """Place, then anneal until the stop rule holds or the step budget is spent."""
    energy, mover = start_chain(problem, params, rng, pins)
    relations, problems = assess(energy)
    accepted = steps = 0
    fewest, since = len(problems), 0  # stagnation: steps since the problem count last fell
    budget = max(params.steps, params.steps_per_box * problem.n_boxes)
    patience = params.patience * budget // max(params.steps, 1)
    cooling = math.log(params.temperature_end / params.temperature_start) / max(budget, 1)
    uniform = rng.random
    for step in range(budget):
        if step >= params.min_steps and step % params.check_every == 0:
            relations, problems = assess(energy)
            if not problems and energy.total <= params.target_energy:
                break
            mover.focus([t for t, r in enumerate(relations) if not r.satisfied], energy.troubled_boxes())
            if len(problems) < fewest:
                fewest, since = len(problems), step
            elif step - since >= patience:
                break
        steps = step + 1
        proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        delta = energy.propose(*proposal)
        temperature = params.temperature_start * math.exp(cooling * step)
        if delta <= 0.0 or uniform() < math.exp(-delta / temperature):
            energy.accept()
            accepted += 1
        else:
            energy.reject()
    else:
        relations, problems = assess(energy)
    return Run(energy, relations, problems, steps, accepted)
