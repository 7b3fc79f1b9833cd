"""The ``learned`` energy part: spatial priors learned from example scenes (a context).

A *context* (``LearnedContext``, written by ``scenewright fit --what context`` as
``NAME.context.json``) holds, per related pair *kind* ``(source type, target type,
labels)``, the maximum-entropy weights of the contextual constraints of Dema and
Sari-Sarraf, "A Relevancy, Hierarchical and Contextual Maximum Entropy Framework for a
Data-Driven 3D Scene Generation" (Entropy 2014): one weight per bin of a 2-D histogram
of where the source stands in the target's frame, and one per bin of a histogram of
the source's yaw relative to the target's. A related pair is two objects joined by one
or more relation edges of the rules (a chair ``NextToFront t FacingTowards t``: one
pair, kind ``(chair, table, FacingTowards+NextToFront)``); object-to-object edges only.

Per pair whose kind the context has, with (x, z) the source's base centre in the
target's frame (``core.frames.to_local``: along its left, along its forward) and
t = wrap(source yaw - target yaw):

    learned = position[cell(x, z)] + yaw[bin(t)]

``position`` has BINS x BINS cells over the rectangle ``bounds`` (row i along z, column k
along x, flattened i * BINS + k) and one more weight, its last, for anywhere outside the
rectangle; ``yaw`` has YAW_BINS bins over [-pi, pi). This is the paper's Gibbs energy
sum_l lambda_l . C_l for one scene (its histograms C_l counted over the scene's pairs),
with the 32 bins the paper uses per histogram. The weights are fitted
(``learning.context``) so that scenes laid out with them have the examples' histograms.

Each pair's value depends on the poses of its two boxes only, so a move re-evaluates
the pairs of the moved boxes (``Energy`` caches them per pair); a shared translation of
both leaves a pair's value as it was.

``LearnedMoves.propose`` is the matching proposal: a pair's source put at a pose drawn
from the pair's own learned distribution, exp(-weight) per cell and bin, uniform inside
them (the target stays). Its Hastings correction is the pair's own change in the
learned energy, which the sampler adds back, so such a move is accepted by what the
rest of the energy says: an independence sampler for that pair's factor. The draw
itself (``draw_source``) is shared with the constructive placement's templates
(``templates``). A share of these moves instead exchange the poses of two
interchangeable boxes (``interchangeable``: one type and size on one support, such as a
bed's two nightstands), each with what rests on it: a symmetric move, so it needs no
correction. Without it a nightstand that drifted to the other's side of the bed had to
cross the bed, through a collision, to get back. Half the chain's ordinary moves of a
learned target take the sources of its pairs along (``LearnedMoves.carry``), so that a
bed held by its nightstands' learned places can still move in the room.

While a pair's source stands on its kind's grid the learned weights stand in for the
pair's relation terms (the sampler takes both at temperature 1); off the grid the single
outside weight says nothing about where it stands, so there its relation terms are
annealed with the rest of the energy (``CompiledLearned.on_grid``,
``Energy.soft_delta``), which brings a source the grid cannot hold (a second nightstand
of the kind on the same side) back to where its relations hold.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.frames import to_local, to_world
from scenewright.core.relations import RELATIONS

from .motion import rigid, wrap

#: Bins per axis of the 2-D position histogram, and bins of the relative-yaw histogram
#: (the paper's 32-bin histograms).
BINS = 32
YAW_BINS = 32
#: What the file says it is, and the version of its layout.
FORMAT = "scenewright-context"
VERSION = 1
#: Largest weight magnitude a file may hold (the fit's weights are logs of shares of at
#: least 1e-7, so about 16; anything far beyond is not a file the fit wrote).
MAX_WEIGHT = 1e3

TAU = 2.0 * math.pi
#: The stop rule's wait for a pair's learned moves (``LearnedMoves.mixed``) ends after
#: this many proposals per sweep even if too few were accepted.
TRIES_PER_SWEEP = 5
#: The share of learned moves that exchange two interchangeable boxes (``LearnedMoves``)
#: when the problem has any.
SWAP_SHARE = 0.25
#: The share of ordinary moves of a learned pair's target that carry the pair's source
#: along (``LearnedMoves.carry``): half, neither kernel preferred.
CARRY_SHARE = 0.5


#: Bins of the visual-balance histogram over the balance offset in [0, 1] (the last bin
#: also holds anything beyond 1).
BALANCE_BINS = 16


@dataclass(frozen=True)
class BalanceContext:
    """The visual-balance term of Dema and Sari-Sarraf: one weight per bin of the
    *balance offset*, the distance of the floor pieces' centre of mass (each piece's
    footprint centre weighted by its footprint area) from the room's centre, over half
    the room's diagonal (``balance_offset``); ``examples`` the examples it was fitted to."""

    weights: np.ndarray
    examples: int = 0

    @staticmethod
    def bin(offset: float) -> int:
        return min(max(int(offset * BALANCE_BINS), 0), BALANCE_BINS - 1)

    def energy(self, offset: float) -> float:
        return float(self.weights[self.bin(offset)])

    def to_dict(self) -> dict:
        return {
            "examples": self.examples,
            "weights": [round(float(v), 6) for v in self.weights],
        }


def balance_boxes(problem) -> tuple[np.ndarray, np.ndarray]:
    """The boxes the balance counts (objects standing on the floor, floor coverings
    left out) and their footprint areas."""
    boxes = [
        b
        for b in range(problem.n_boxes)
        if not problem.is_junction[b]
        and problem.support[b] == -1
        and not (problem.covering and problem.covering[b])
    ]
    areas = [4.0 * problem.half_width[b] * problem.half_depth[b] for b in boxes]
    return np.array(boxes, dtype=int), np.array(areas, dtype=float)


def balance_offset(extent, xs, zs, areas) -> float:
    """How far the area-weighted centre of footprints at (xs, zs) lies from the centre
    of the scene's extent (its origin), over half the extent's diagonal; 0 for none."""
    total = float(np.sum(areas))
    if total <= 0.0:
        return 0.0
    cx = float(np.dot(areas, xs)) / total
    cz = float(np.dot(areas, zs)) / total
    width, depth = extent
    return math.hypot(cx, cz) / (0.5 * math.hypot(width, depth))


def pair_kind_name(source: str, target: str, labels: Sequence[str]) -> str:
    """How reports and errors name a pair kind: ``chair -FacingTowards+NextToFront-> table``."""
    return f"{source} -{'+'.join(labels)}-> {target}"


@dataclass(frozen=True)
class PairContext:
    """The learned weights of one pair kind: ``position`` (BINS * BINS + 1,) over
    ``bounds`` (x0, z0, x1, z1) in the target's frame, the last for outside; ``yaw``
    (YAW_BINS,) over [-pi, pi); ``examples`` the pairs of the examples they were fitted to."""

    source: str
    target: str
    labels: tuple[str, ...]
    bounds: tuple[float, float, float, float]
    position: np.ndarray
    yaw: np.ndarray
    examples: int = 0

    @property
    def kind(self) -> tuple[str, str, tuple[str, ...]]:
        return self.source, self.target, self.labels

    def cell(self, x: float, z: float) -> int:
        """The position weight's index of a relative position: its cell, or BINS * BINS outside."""
        x0, z0, x1, z1 = self.bounds
        k = math.floor((x - x0) / (x1 - x0) * BINS)
        i = math.floor((z - z0) / (z1 - z0) * BINS)
        if 0 <= k < BINS and 0 <= i < BINS:
            return i * BINS + k
        return BINS * BINS

    @staticmethod
    def yaw_bin(turn: float) -> int:
        """The yaw weight's index of a relative yaw (radians, any value)."""
        return min(int((wrap(turn) + math.pi) / TAU * YAW_BINS), YAW_BINS - 1)

    def energy(self, pose: tuple[float, float, float]) -> float:
        """The learned energy of a relative pose (x, z, turn)."""
        return float(self.position[self.cell(pose[0], pose[1])] + self.yaw[self.yaw_bin(pose[2])])

    def to_dict(self) -> dict:
        return {
            "source": self.source,
            "target": self.target,
            "labels": list(self.labels),
            "examples": self.examples,
            "bounds": [round(float(v), 6) for v in self.bounds],
            "position": [round(float(v), 6) for v in self.position],
            "yaw": [round(float(v), 6) for v in self.yaw],
        }


@dataclass(frozen=True)
class LearnedContext:
    """Every learned pair kind, and what the fit reported (kept as it is, for people)."""

    pairs: tuple[PairContext, ...]
    fit: dict | None = None
    #: The sha256 of the rules file the context was fitted to (``rules_digest``); None
    #: for a context made without rules (by hand, or through the Python API).
    rules_digest: str | None = None
    #: The sha256 of the example files it was fitted to, one after another (a record for
    #: people and tools: which examples made it); None when not known.
    examples_digest: str | None = None
    #: The visual-balance term (None: the context has none).
    balance: BalanceContext | None = None

    def for_rules(self, text: str, examples: Sequence[bytes] = ()) -> LearnedContext:
        """This context, recorded as fitted to the rules file of ``text`` and to the
        example files of the bytes ``examples`` (in the order they were given)."""
        digest = hashlib.sha256()
        for data in examples:
            digest.update(hashlib.sha256(data).digest())
        return replace(
            self,
            rules_digest=rules_digest(text.encode("utf-8")),
            examples_digest=digest.hexdigest() if examples else None,
        )

    def to_dict(self) -> dict:
        document = {"format": FORMAT, "version": VERSION, "bins": BINS, "yaw_bins": YAW_BINS}
        if self.rules_digest is not None:
            document["rules_digest"] = self.rules_digest
        if self.examples_digest is not None:
            document["examples_digest"] = self.examples_digest
        document["pairs"] = [pair.to_dict() for pair in self.pairs]
        if self.balance is not None:
            document["balance"] = self.balance.to_dict()
        if self.fit is not None:
            document["fit"] = self.fit
        return document

    def check_rules(self, rules_path: str | os.PathLike[str] | None, where: str) -> None:
        """Refuse (``InputError``) a context fitted to another rules file than the one at
        ``rules_path``: its layouts would follow rules no longer in use. A context that
        records no digest, or rules that are no file (shipped by name), are not checked."""
        if self.rules_digest is None or rules_path is None:
            return
        try:
            data = Path(rules_path).read_bytes()
        except OSError:
            return  # the rules' own loading reports a file that cannot be read
        if rules_digest(data) != self.rules_digest:
            raise InputError(
                f"{where}: the context was fitted to another version of {rules_path}; fit it again "
                "('scenewright fit RULES EXAMPLES --what context' or 'scenewright learn'), or leave it "
                "out (--no-context)"
            )

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=1) + "\n"

    @classmethod
    def from_dict(cls, document: object, where: str = "context") -> LearnedContext:
        """A context from its JSON document; ``InputError`` (one line, naming ``where``
        and the field) for anything a fit would not have written."""
        if not isinstance(document, dict) or document.get("format") != FORMAT:
            raise InputError(f'{where}: not a context file (no "format": "{FORMAT}")')
        if document.get("version") != VERSION:
            raise InputError(
                f"{where}: context version {document.get('version')!r}; this scenewright reads {VERSION}"
            )
        if document.get("bins") != BINS or document.get("yaw_bins") != YAW_BINS:
            raise InputError(f"{where}: bins must be {BINS} and yaw_bins {YAW_BINS}")
        pairs = document.get("pairs")
        if not isinstance(pairs, list):
            raise InputError(f'{where}: "pairs" must be a list')
        parsed, seen = [], set()
        for k, entry in enumerate(pairs):
            pair = _parse_pair(entry, f"{where}: pairs[{k}]")
            if pair.kind in seen:
                raise InputError(
                    f"{where}: pairs[{k}]: {pair_kind_name(*pair.kind)} is given twice"
                )
            seen.add(pair.kind)
            parsed.append(pair)
        fit = document.get("fit")
        digests = []
        for key in ("rules_digest", "examples_digest"):
            digest = document.get(key)
            if digest is not None and (
                not isinstance(digest, str) or re.fullmatch("[0-9a-f]{64}", digest) is None
            ):
                raise InputError(f'{where}: "{key}" must be 64 hexadecimal digits (a sha256)')
            digests.append(digest)
        balance = _parse_balance(document.get("balance"), f"{where}: balance")
        return cls(
            tuple(parsed),
            fit if isinstance(fit, dict) else None,
            rules_digest=digests[0],
            examples_digest=digests[1],
            balance=balance,
        )


def _parse_balance(entry: object, where: str) -> BalanceContext | None:
    if entry is None:
        return None
    if not isinstance(entry, dict):
        raise InputError(f"{where}: must be an object")
    weights = entry.get("weights")
    if (
        not isinstance(weights, list)
        or len(weights) != BALANCE_BINS
        or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and abs(v) <= MAX_WEIGHT
            for v in weights
        )
    ):
        raise InputError(
            f'{where}: "weights" must be {BALANCE_BINS} numbers of at most {MAX_WEIGHT:g} in size'
        )
    examples = entry.get("examples", 0)
    if not isinstance(examples, int) or isinstance(examples, bool) or examples < 0:
        raise InputError(f'{where}: "examples" must be a whole number from 0')
    return BalanceContext(np.array(weights, dtype=float), examples)


def _parse_pair(entry: object, where: str) -> PairContext:
    if not isinstance(entry, dict):
        raise InputError(f"{where}: must be an object")
    names = []
    for field in ("source", "target"):
        value = entry.get(field)
        if not isinstance(value, str) or not value:
            raise InputError(f'{where}: "{field}" must be a type name')
        names.append(value)
    labels = entry.get("labels")
    if (
        not isinstance(labels, list)
        or not labels
        or not all(isinstance(v, str) and v for v in labels)
    ):
        raise InputError(f'{where}: "labels" must be a non-empty list of relation labels')
    unknown = [label for label in labels if label not in RELATIONS]
    if unknown:
        raise InputError(
            f'{where}: "labels": {_clipped(unknown[0])} is not a relation label '
            "(docs/rules-language.md lists them)"
        )
    if labels != sorted(set(labels)):
        raise InputError(f'{where}: "labels" must be sorted and without repeats')
    bounds = _numbers(entry.get("bounds"), 4, where, "bounds")
    if not (bounds[2] > bounds[0] and bounds[3] > bounds[1]):
        raise InputError(f'{where}: "bounds" [x0, z0, x1, z1] must have x1 > x0 and z1 > z0')
    position = _numbers(entry.get("position"), BINS * BINS + 1, where, "position")
    yaw = _numbers(entry.get("yaw"), YAW_BINS, where, "yaw")
    examples = entry.get("examples", 0)
    if isinstance(examples, bool) or not isinstance(examples, int) or examples < 0:
        raise InputError(f'{where}: "examples" must be a whole number >= 0')
    return PairContext(
        names[0],
        names[1],
        tuple(labels),
        (bounds[0], bounds[1], bounds[2], bounds[3]),
        np.array(position),
        np.array(yaw),
        examples,
    )


def _clipped(text: str) -> str:
    """``text`` quoted, shortened to 40 characters: a message never repeats a long input."""
    shown = repr(text)
    return shown if len(shown) <= 40 else shown[:37] + "..."


def _numbers(value: object, count: int, where: str, field: str) -> list[float]:
    if not isinstance(value, list) or len(value) != count:
        raise InputError(f'{where}: "{field}" must be a list of {count} numbers')
    numbers = []
    for v in value:
        if (
            isinstance(v, bool)
            or not isinstance(v, (int, float))
            or not math.isfinite(v)
            or abs(v) > MAX_WEIGHT
        ):
            raise InputError(
                f'{where}: "{field}" must hold finite numbers of size at most {MAX_WEIGHT:g}'
            )
        numbers.append(float(v))
    return numbers


def context_path(rules_output: str | Path) -> Path:
    """Where the context of a fitted rules file goes: ``NAME.context.json`` beside
    ``NAME.rules`` (or beside ``NAME`` when the name has no ``.rules``)."""
    path = Path(rules_output)
    stem = path.name[: -len(".rules")] if path.name.endswith(".rules") else path.name
    return path.with_name(stem + ".context.json")


def rules_digest(data: bytes) -> str:
    """The digest a context records of its rules file's bytes."""
    return hashlib.sha256(data).hexdigest()


def read_context(path: str) -> LearnedContext:
    """The context a file holds; ``InputError`` naming the file when it cannot be read or is not one."""
    from scenewright.core.files import UnusableFile, load_json, read_regular_file
    from scenewright.core.limits import MAX_SCENE_JSON_BYTES

    try:
        text = read_regular_file(path, MAX_SCENE_JSON_BYTES, "a context file").decode("utf-8")
        document = load_json(text)
    except UnusableFile as problem:
        raise InputError(f"{path}: cannot read: it {problem}") from None
    except OSError as error:
        raise InputError(f"{path}: cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text") from None
    except ValueError as error:
        raise InputError(f"{path}: not JSON: {error}") from None
    return LearnedContext.from_dict(document, str(path))


def related_pairs(
    problem, types: Sequence[str]
) -> list[tuple[int, int, tuple[str, str, tuple[str, ...]]]]:
    """Every related pair of a problem: (source box, target box, kind), in the order of
    their first edge. ``types`` (n_boxes,) is each box's type."""
    labels: dict[tuple[int, int], set[str]] = {}
    for term in problem.relations:
        if term.a.kind == "object" and term.b.kind == "object" and term.spec.family != "structural":
            labels.setdefault((term.a.index, term.b.index), set()).add(term.label)
    return [(a, b, (types[a], types[b], tuple(sorted(names)))) for (a, b), names in labels.items()]


def relative_pose(
    source: tuple[float, float, float], target: tuple[float, float, float]
) -> tuple[float, float, float]:
    """(x, z, turn) of a source pose (x, z, yaw) in a target's frame."""
    x, z = to_local(target[0], target[1], target[2], source[0], source[1])
    return x, z, wrap(source[2] - target[2])


@dataclass(frozen=True)
class CompiledLearned:
    """A context for one problem: the pairs it has a kind for (``pairs``: source box,
    target box, the kind's ``PairContext``), per box the pairs touching it, the
    relation terms those pairs stand for (``tempered``: term -> its pair; sampled with
    the pair while it stands on its grid, ``on_grid``), and the ``swaps``: pairs of
    interchangeable boxes (``interchangeable``) whose poses a learned move may exchange."""

    pairs: tuple[tuple[int, int, PairContext], ...]
    pairs_of_box: tuple[tuple[int, ...], ...]
    tempered: dict[int, int]
    swaps: tuple[tuple[int, int], ...] = ()
    #: The visual-balance term: its weights, the boxes it counts and their areas (None:
    #: the context has none, or the problem no floor piece). The energy keeps its value
    #: after the pairs' (``Energy.learned``, index ``len(pairs)``).
    balance: tuple[BalanceContext, np.ndarray, np.ndarray] | None = None

    def balance_value(self, problem, state, active) -> float:
        """The balance term at ``state``, over the placed (``active``) boxes it counts."""
        assert self.balance is not None
        table, boxes, areas = self.balance
        placed = np.array([active[b] for b in boxes], dtype=bool)
        if not placed.any():
            return 0.0
        chosen = boxes[placed]
        offset = balance_offset(
            problem.extent,
            np.asarray(state.x)[chosen],
            np.asarray(state.z)[chosen],
            areas[placed],
        )
        return table.energy(offset)

    def value(self, pair: int, state) -> float:
        """The pair's learned energy at the state's poses."""
        source, target, table = self.pairs[pair]
        return table.energy(relative_pose(state.pose(source), state.pose(target)))

    def on_grid(
        self, pair: int, source: tuple[float, float, float], target: tuple[float, float, float]
    ) -> bool:
        """Whether the pair's source stands on its kind's grid (not in the outside bin)
        relative to the target, at the given poses (x, z, yaw). There the learned
        weights say where it stands and its relation terms are sampled with them; off
        the grid the one outside weight says nothing about where, and the relation
        terms are annealed with the rest (``Energy.soft_delta``)."""
        x, z = to_local(target[0], target[1], target[2], source[0], source[1])
        return self.pairs[pair][2].cell(x, z) < BINS * BINS


def compile_learned(context: LearnedContext, problem, types: Sequence[str]) -> CompiledLearned:
    """The pairs of a problem whose kind ``context`` has (``types``: each box's type)."""
    by_kind = {pair.kind: pair for pair in context.pairs}
    pairs = []
    for source, target, kind in related_pairs(problem, types):
        if kind in by_kind:
            pairs.append((source, target, by_kind[kind]))
    pairs_of_box: list[list[int]] = [[] for _ in range(problem.n_boxes)]
    for k, (source, target, _) in enumerate(pairs):
        pairs_of_box[source].append(k)
        pairs_of_box[target].append(k)
    joined = {(source, target): k for k, (source, target, _) in enumerate(pairs)}
    tempered = {
        t: joined[term.a.index, term.b.index]
        for t, term in enumerate(problem.relations)
        if term.a.kind == "object"
        and term.b.kind == "object"
        and (term.a.index, term.b.index) in joined
    }
    sources = {source for source, _, _ in pairs}
    balance = None
    if context.balance is not None:
        boxes, areas = balance_boxes(problem)
        balance = (context.balance, boxes, areas) if len(boxes) else None
    return CompiledLearned(
        tuple(pairs),
        tuple(tuple(p) for p in pairs_of_box),
        tempered,
        interchangeable(problem, types, sources),
        balance,
    )


def interchangeable(
    problem, types: Sequence[str], sources: set[int]
) -> tuple[tuple[int, int], ...]:
    """Pairs (a, b), a < b, of boxes of one type and size resting on the same thing (the
    ground, or one box), at least one of them a learned pair's source: pieces the rules
    tell apart only by their relations (the two nightstands of a bed, one to its left
    and one to its right). Exchanging their poses (``LearnedMoves.propose``) moves each
    piece, with what rests on it, to where the other stood."""
    found = []
    for a in range(problem.n_boxes):
        for b in range(a + 1, problem.n_boxes):
            if (
                (a in sources or b in sources)
                and types[a] == types[b]
                and _same_footing(problem, a, b)
            ):
                found.append((a, b))
    return tuple(found)


def _same_footing(problem, a: int, b: int) -> bool:
    """Whether boxes a and b are objects of one footprint and height on the same support."""
    return (
        not problem.is_junction[a]
        and not problem.is_junction[b]
        and problem.support[a] == problem.support[b]
        and (problem.half_width[a], problem.half_depth[a], problem.height[a])
        == (problem.half_width[b], problem.half_depth[b], problem.height[b])
    )


def cumulative_shares(table: PairContext) -> tuple[np.ndarray, np.ndarray]:
    """Cumulative shares exp(-weight) of a kind's grid cells (BINS * BINS,) and of its
    yaw bins (YAW_BINS,): what a draw from its learned distribution searches."""
    cells = np.exp(-(table.position[:-1] - table.position[:-1].min()))
    turns = np.exp(-(table.yaw - table.yaw.min()))
    return np.cumsum(cells) / cells.sum(), np.cumsum(turns) / turns.sum()


def draw_source(
    problem,
    state,
    rng: np.random.Generator,
    source: int,
    target: int,
    table: PairContext,
    cumulative: tuple[np.ndarray, np.ndarray],
) -> dict[int, tuple[float, float, float]]:
    """A pose for a pair's source drawn from its kind's learned distribution, relative to
    the target where it stands now: a cell by its share exp(-weight) and a point uniform
    inside it, a yaw bin likewise (``cumulative``: ``cumulative_shares(table)``). Returns
    the new poses (box -> (x, z, yaw)) of the source and what rests on it, moved rigidly.
    Five draws from ``rng``, always in this order."""
    cells, turns = cumulative
    cell = min(int(np.searchsorted(cells, rng.random(), side="right")), BINS * BINS - 1)
    turn_bin = min(int(np.searchsorted(turns, rng.random(), side="right")), YAW_BINS - 1)
    x0, z0, x1, z1 = table.bounds
    i, k = divmod(cell, BINS)
    lx = x0 + (k + rng.random()) * (x1 - x0) / BINS
    lz = z0 + (i + rng.random()) * (z1 - z0) / BINS
    turn = -math.pi + (turn_bin + rng.random()) * TAU / YAW_BINS
    tx, tz, tyaw = state.pose(target)
    x, z = to_world(tx, tz, tyaw, lx, lz)
    yaw = wrap(tyaw + turn)
    sx, sz, syaw = state.pose(source)
    return rigid(state, problem.carried(source), (sx, sz), wrap(yaw - syaw), (x - sx, z - sz))


class LearnedMoves:
    """Proposals drawn from the learned pairs' own distributions (see the module docstring)."""

    def __init__(
        self,
        learned: CompiledLearned,
        problem,
        state,
        rng: np.random.Generator,
        movable: Sequence[bool],
        sweeps: int,
    ):
        self.learned, self.problem, self.state, self.rng, self.sweeps = (
            learned,
            problem,
            state,
            rng,
            sweeps,
        )
        # Only pairs whose source a move may place by itself (free, not in a rigid group).
        self.pairs = [k for k, (source, _, _) in enumerate(learned.pairs) if movable[source]]
        self.swaps = [(a, b) for a, b in learned.swaps if movable[a] and movable[b]]
        self.followers = self._followers(movable)
        #: Per learned pair, how many of its moves the chain accepted, and proposed.
        self.redrawn = [0] * len(learned.pairs)
        self.tried = [0] * len(learned.pairs)
        self._cumulative: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def _followers(self, movable: Sequence[bool]) -> dict[int, list[int]]:
        """Per learned target, the movable sources of its pairs, theirs in turn, and what
        rests on them: the boxes ``carry`` moves along with it."""
        sources: dict[int, list[int]] = {}
        for source, target, _ in self.learned.pairs:
            if movable[source]:
                sources.setdefault(target, []).append(source)
        followers = {}
        for target, own in sources.items():
            found: list[int] = []
            queue = list(own)
            for box in queue:  # ``queue`` grows while it is walked: sources of sources
                for item in self.problem.carried(box):
                    if item != target and item not in found:
                        found.append(item)
                        queue.extend(sources.get(item, ()))
            followers[target] = found
        return followers

    def carry(
        self, boxes: dict[int, tuple[float, float, float]]
    ) -> dict[int, tuple[float, float, float]]:
        """An ordinary proposal's new poses; a share CARRY_SHARE of the time with every
        moved learned target's followers (``followers``) moved rigidly along with it,
        where the proposal does not move them itself. The learned part holds a source
        near one place in its target's frame, so a target that moves alone breaks its
        pairs and is refused: a bed a few centimetres off its wall stayed there while
        its nightstands held it (only a move of the whole cluster that happened to land
        at the wall freed it). Moving alone, a target still lets its sources' relative
        poses change. Either kernel is symmetric when the proposal is (a rigid move of
        what it moves), and so is their mixture. One draw from the stream per call."""
        if self.rng.random() >= CARRY_SHARE:
            return boxes
        state, followers = self.state, self.followers
        moved = dict(boxes)
        for box, (nx, nz, nyaw) in boxes.items():
            carried = [item for item in followers.get(box, ()) if item not in moved]
            if carried:
                x, z, yaw = state.pose(box)
                moved.update(rigid(state, carried, (x, z), wrap(nyaw - yaw), (nx - x, nz - z)))
        return moved

    def _tables(self, table: PairContext) -> tuple[np.ndarray, np.ndarray]:
        """``cumulative_shares`` of a kind, cached per kind."""
        key = id(table)
        if key not in self._cumulative:
            self._cumulative[key] = cumulative_shares(table)
        return self._cumulative[key]

    def mixed(self) -> bool:
        """Whether every pair a move may redraw had ``sweeps`` of its moves accepted, or
        ``TRIES_PER_SWEEP * sweeps`` proposed: a source the rest of the energy holds
        tightly (a nightstand against its wall, 5 cm and 2 degrees, which a draw from
        a 20 cm cell all but never meets) is where that energy wants it, and waiting
        for its draws to be accepted only spends the step budget."""
        cap = TRIES_PER_SWEEP * self.sweeps
        return all(
            self.redrawn[pair] >= self.sweeps or self.tried[pair] >= cap for pair in self.pairs
        )

    def propose(self) -> tuple[dict, float, int | None] | None:
        """A new pose for one pair's source (with what rests on it), the Hastings
        correction (the pair's learned energy after the move less before) and the pair.
        None when no pair's source may move.

        With interchangeable boxes (``swaps``), a share SWAP_SHARE of the moves exchange
        the poses of one such pair instead (``swap``; correction 0, pair None)."""
        if not self.pairs:
            return None
        rng, state = self.rng, self.state
        if self.swaps and rng.random() < SWAP_SHARE:
            return self.swap(*self.swaps[int(rng.integers(len(self.swaps)))]), 0.0, None
        # Until every pair has been redrawn (``mixed``), the pairs still short of it are
        # drawn: the burn-in then ends after a few tries per pair, not when the unluckiest
        # of a uniform draw's pairs has caught up.
        cap = TRIES_PER_SWEEP * self.sweeps
        lagging = [
            pair
            for pair in self.pairs
            if self.redrawn[pair] < self.sweeps and self.tried[pair] < cap
        ]
        choices = lagging or self.pairs
        pair = choices[int(rng.integers(len(choices)))]
        self.tried[pair] += 1
        source, target, table = self.learned.pairs[pair]
        boxes = draw_source(self.problem, state, rng, source, target, table, self._tables(table))
        tx, tz, tyaw = state.pose(target)
        # The correction is read where the source really lands (rounding may cross a bin edge).
        nx, nz, nyaw = boxes[source]
        after = table.energy(relative_pose((nx, nz, nyaw), (tx, tz, tyaw)))
        return boxes, after - self.learned.value(pair, state), pair

    def swap(self, a: int, b: int) -> dict[int, tuple[float, float, float]]:
        """New poses exchanging boxes a and b, each with what rests on it carried
        rigidly. The move is its own inverse and drawn with the same probability from
        either side, so it is symmetric and needs no Hastings correction."""
        state, problem = self.state, self.problem
        pose_a, pose_b = state.pose(a), state.pose(b)
        boxes = {}
        for box, (x, z, yaw), (nx, nz, nyaw) in ((a, pose_a, pose_b), (b, pose_b, pose_a)):
            boxes.update(
                rigid(state, problem.carried(box), (x, z), wrap(nyaw - yaw), (nx - x, nz - z))
            )
            boxes[box] = (nx, nz, nyaw)
        return boxes
