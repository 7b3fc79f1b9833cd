"""Graph matching of two layout subgraphs, as the paper's quadratic assignment.

The energy of a matching f of the objects of G onto those of G' is

    E(f) = sum_i phi_i(f(v_i)) + lambda * sum_(e_ij) phi(e_ij, f(e_ij)),   lambda = 0.5

written ``E = x^T W x`` for the assignment vector x (x_ik = 1 when i matches k). Terms:

- object similarity ``phi_i(k) = exp((1 - prod_a g(theta_a, theta'_a)) / sigma)`` with
  ``g(x, y) = 1 + |x - y| / |x + y|`` over the box's width, height and depth. ``g`` is a
  ratio, so the term is dimensionless; the paper divides by a length (sigma = the
  scene's diagonal), which makes it depend on the unit. We take ``sigma`` =
  ``UNARY_SIGMA`` (1, no unit). Type names enter only as an optional soft prior
  (``type_prior``: phi is multiplied by 1 - type_prior when the names differ);
- a tie-break, beyond the paper: ``PLACE_WEIGHT`` (1e-6) times how near the matched
  objects stand in their rooms (centres as shares of the room's extent,
  ``place_similarity``). It is far below any difference the similarities make, so it
  only chooses between matchings they score alike: two identical chairs standing
  alone, or two alike corners, are kept each on its own rather than swapped;
- edge similarity ``phi(e, e') = d_V + d_A + d_F + d_C``: d_A = 1 when both are
  aligned; d_V = exp(-(|da| + |db|) / 2 pi) over the two contact angles (the paper's
  exp(-|d alpha_v| / pi) of their mean, where the mean is defined); d_F =
  exp(-|d alpha_f| / pi) when both face (the paper's indicator tests V there, a typo);
  d_C = exp(-|d - d'| / s) when both are close, s the mean half diagonal of the four
  objects (the paper's sigma_c is a length: this makes it dimensionless). Beyond the
  paper, "when both hold" is graded: each term weighs the geometric mean of the two
  edges' memberships of its relation (``structure``: a smooth fall-off around each
  threshold), so a pair a small move carried across a threshold keeps most of its
  score, and an edge matched to itself scores its summed memberships. Edges are
  directed: the pairs (i, j) -> (k, l) and (j, i) -> (l, k) each weigh lambda / 2, so a
  pair matched in reverse compares the reversed edge (``structure``).

The maximiser is found as SMAC does (Cour, Srinivasan and Shi, "Balanced graph
matching", 2006): the one-to-one constraints (each row and each column of the
assignment sums to 1, the smaller graph padded with dummy objects, which are "no
match") are affine, ``C x = b``; they are made homogeneous, the symmetric affinity is
projected on their null space, its leading eigenvector is the relaxed solution, scaled
so the constraints hold. The Hungarian method (``scipy.optimize.linear_sum_assignment``)
makes it a one-to-one assignment. Written x^T W x, as the paper does, the object
similarities u sit on W's diagonal; on a 0/1 vector that is the linear term u^T x,
and we give it to the relaxation as one: a homogeneous coordinate t with one more
affine constraint, t = 1, makes it quadratic (``spectral_solution``). On the diagonal
it would only count x_ik^2, small where the relaxed vector spreads, and the edges
would drown it. ``solve`` takes the better of both readings' assignments, and
(beyond the paper) starts local search from both relaxations, keeping the best.

A pair's *confidence* is the share of its best possible score it gets: its object
similarity plus lambda times its matched edges' similarities, over 1 + lambda times
the mean of the two objects' own edge scores (what each gets matched to a copy of
itself). The paper keeps a match whose confidence exceeds gamma = 0.8 and withdraws
the rest; its confidence is the leading eigenvalue, which has no fixed scale, so we
use this per-pair share, with its own threshold (``CONFIDENCE``, 0.6; docs/notes/design.md
gives the measurements behind it). A pair below half the threshold is taken as
objects without a counterpart (``withdraw``), as is an object left to a dummy, and the
others' shares are counted without their edges to them: an object that gained a neighbour the other scene does not
have (or lost one) is not held to a relation no pairing could match.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from networkx.utils import UnionFind
from scipy import sparse
from scipy.optimize import linear_sum_assignment
from scipy.sparse.linalg import LinearOperator, eigsh

from scenewright.core.geometry import wrap_angles

from .structure import GRADED_CODES, StructureGraph

LAMBDA = 0.5
UNARY_SIGMA = 1.0
CONFIDENCE = 0.6
#: Weight of the place tie-break (``place_similarity``): far below any difference the
#: similarities make, so it only decides between matchings they score alike.
PLACE_WEIGHT = 1e-6

#: Columns of ``EdgeTable.grades``.
_V, _A, _F, _C = (GRADED_CODES.index(code) for code in "VAFC")


@dataclass
class EdgeTable:
    """The directed edges among some nodes, as arrays (E edges): ``source``, ``target``
    (E,) node positions; ``grades`` (E, 4) memberships of the graded relations
    (``structure.GRADED_CODES``); ``facing`` (E,); ``contact`` (E, 2); ``gap`` (E,);
    ``scale`` (E,) metres."""

    source: np.ndarray
    target: np.ndarray
    grades: np.ndarray
    facing: np.ndarray
    contact: np.ndarray
    gap: np.ndarray
    scale: np.ndarray

    @classmethod
    def of(cls, graph: StructureGraph, nodes: list[int]) -> EdgeTable:
        """The edges of ``graph`` between ``nodes`` (positions in ``nodes``) with a graded
        layout relation, the fringe's included."""
        where = {node: position for position, node in enumerate(nodes)}
        rows = [
            (
                where[i],
                where[j],
                *edge.grades,
                edge.facing_angle,
                *edge.contact_angles,
                edge.gap,
                edge.scale,
            )
            for (i, j), edge in sorted({**graph.edges, **graph.fringe}.items())
            if i in where and j in where and max(edge.grades) > 0.0
        ]
        return cls.from_rows(rows)

    @classmethod
    def from_rows(cls, rows: list) -> EdgeTable:
        """From rows (source, target, 4 grades, facing, 2 contact angles, gap, scale)."""
        table = np.array(rows, dtype=float).reshape(-1, 11)
        return cls(
            table[:, 0].astype(int),
            table[:, 1].astype(int),
            table[:, 2:6],
            table[:, 6],
            table[:, 7:9],
            table[:, 9],
            table[:, 10],
        )

    def row(self, r: int) -> list:
        """Edge r as a row of ``from_rows``."""
        return [
            self.source[r],
            self.target[r],
            *self.grades[r],
            self.facing[r],
            *self.contact[r],
            self.gap[r],
            self.scale[r],
        ]

    def __len__(self) -> int:
        return len(self.source)

    def self_scores(self, count: int, counted: np.ndarray | None = None) -> np.ndarray:
        """(count,) each node's edge score matched to itself: its edges' summed
        memberships (only the edges ``counted`` (E,) when given)."""
        scores = np.zeros(count)
        weights = np.ones(len(self)) if counted is None else counted
        np.add.at(scores, self.source, self.grades.sum(axis=1) * weights)
        return scores


def _both(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """How far a relation holds in both edges: the geometric mean of the memberships."""
    return np.sqrt(a * b)


def _angle_gap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|a - b| wrapped into [0, pi]."""
    return np.abs(wrap_angles(a - b))


def edge_similarity(first: EdgeTable, second: EdgeTable) -> np.ndarray:
    """(E1, E2) phi(e, e') for every directed edge of ``first`` against every one of
    ``second``: each relation's term weighs how far it holds in both (``_both``)."""
    shared = _both(first.grades[:, None, :], second.grades[None, :, :])
    contact = _angle_gap(first.contact[:, None, 0], second.contact[None, :, 0])
    contact = contact + _angle_gap(first.contact[:, None, 1], second.contact[None, :, 1])
    direction = np.exp(-contact / (2.0 * math.pi))
    facing = _angle_gap(first.facing[:, None], second.facing[None, :])
    scale = (first.scale[:, None] + second.scale[None, :]) / 2.0
    close = np.abs(first.gap[:, None] - second.gap[None, :]) / np.maximum(scale, 1e-9)
    return (
        shared[..., _A]
        + shared[..., _V] * direction
        + shared[..., _F] * np.exp(-facing / math.pi)
        + shared[..., _C] * np.exp(-close) * direction
    )


def box_similarity(sizes: np.ndarray, other: np.ndarray, sigma: float = UNARY_SIGMA) -> np.ndarray:
    """(m, n) object similarity of boxes ``sizes`` (m, 3) against ``other`` (n, 3)."""
    a, b = sizes[:, None, :], other[None, :, :]
    g = 1.0 + np.abs(a - b) / np.maximum(np.abs(a + b), 1e-12)
    return np.exp((1.0 - g.prod(axis=-1)) / sigma)


def place_similarity(places: np.ndarray, other: np.ndarray) -> np.ndarray:
    """(m, n) how near places (m, 2) are to places (n, 2), shares of their rooms' extents:
    1 - distance / sqrt(2), so a linear assignment on it minimises the summed distance."""
    distance = np.linalg.norm(places[:, None, :] - other[None, :, :], axis=-1)
    return np.maximum(1.0 - distance / math.sqrt(2.0), 0.0)


@dataclass
class Problem:
    """A quadratic assignment: ``unary`` (m, n), pairwise terms between matched edges
    (``first`` and ``second`` edge tables, ``pairwise`` (E1, E2) their similarities);
    ``place`` (m, n), when given, adds ``PLACE_WEIGHT`` times the matched objects'
    place similarity: a tie-break between objects nothing else tells apart (two
    identical chairs with the same relations), which no similarity outweighs."""

    unary: np.ndarray
    first: EdgeTable
    second: EdgeTable
    pairwise: np.ndarray
    lam: float = LAMBDA
    place: np.ndarray | None = None

    @property
    def linear(self) -> np.ndarray:
        """(m, n) the linear term of the energy: the object similarities and the tie-break."""
        return self.unary if self.place is None else self.unary + PLACE_WEIGHT * self.place

    @property
    def size(self) -> int:
        """N: the larger side; the smaller is padded with dummies to N."""
        return max(self.unary.shape)

    def affinity(self) -> sparse.csr_matrix:
        """(N*N, N*N) symmetric sparse W with E = x^T W x, x indexed i * N + k (i in the
        first graph, k in the second, dummies included)."""
        size = self.size
        m, n = self.unary.shape
        diagonal = (np.arange(m)[:, None] * size + np.arange(n)[None, :]).ravel()
        e1, e2 = np.nonzero(self.pairwise)
        a = self.first.source[e1] * size + self.second.source[e2]
        b = self.first.target[e1] * size + self.second.target[e2]
        rows = np.concatenate([diagonal, a])
        columns = np.concatenate([diagonal, b])
        values = np.concatenate([self.linear.ravel(), self.lam / 2.0 * self.pairwise[e1, e2]])
        matrix = sparse.coo_matrix(
            (values, (rows, columns)), shape=(size * size, size * size)
        ).tocsr()
        return ((matrix + matrix.T) / 2.0).tocsr()

    def energy(self, assignment: np.ndarray) -> float:
        """E of a full assignment (``assignment[i]`` = k, over the padded N)."""
        m, n = self.unary.shape
        rows = np.flatnonzero(assignment[:m] < n)
        total = self.linear[rows, assignment[rows]].sum()
        return float(total + self.lam / 2.0 * self.pairwise[self.matched_edges(assignment)].sum())

    def matched_edges(self, assignment: np.ndarray) -> np.ndarray:
        """(E1, E2) whether ``assignment`` maps first-graph edge e onto second-graph edge e'."""
        return (assignment[self.first.source][:, None] == self.second.source[None, :]) & (
            assignment[self.first.target][:, None] == self.second.target[None, :]
        )


def spectral_solution(affinity: sparse.spmatrix, size: int, *, lifted: bool = True) -> np.ndarray:
    """(N, N) relaxed assignment: SMAC's leading eigenvector under the affine one-to-one
    constraints (rows and columns sum to 1), with the unary terms as a linear term
    (``lifted``, the default) or, with ``lifted=False``, left on W's diagonal.

    On a 0/1 vector x_ik^2 = x_ik, so W's diagonal u (the object similarities) is the
    linear term of E = x^T (W - diag u) x + u^T x. It is made quadratic with a
    homogeneous coordinate t and one more affine constraint, t = 1: the lifted vector
    y = (x, t) (N*N + 1,) has E = y^T L y, L = [[W - diag u, u / 2], [u^T / 2, 0]].
    Left on the diagonal, a unary term only counts x_ik^2, which is small where the
    relaxation spreads its mass, so the pairwise terms drown the object similarities
    (measured in docs/variation.md). The eigenvector of P L P (P the projection on the
    constraints' null space) is found by Lanczos iteration (``eigsh``) from a fixed
    start, so it is deterministic; it is scaled so t = 1, which makes every constraint
    hold. Unlifted, it is the eigenvector of P W P, scaled so the last column sums to 1
    (every row and column then does), or negated when its negative's Hungarian
    assignment scores higher."""
    count = size * size
    if not lifted:

        def centre(vector: np.ndarray) -> np.ndarray:
            # Made homogeneous, the constraints say "all row and column sums are equal";
            # projecting their row space out of X leaves X - row means - column means
            # + 2 * grand mean.
            matrix = np.reshape(vector, (size, size))
            grand = matrix.mean()
            return (
                matrix
                - matrix.mean(axis=1, keepdims=True)
                - matrix.mean(axis=0, keepdims=True)
                + 2.0 * grand
            ).ravel()

        vector = _leading(lambda v: centre(affinity @ centre(np.ravel(v))), centre, count).reshape(
            size, size
        )
        total = vector[:, -1].sum()
        vector = vector / total if abs(total) > 1e-12 else vector
        # The common row sum can be tiny beside the rest, and then its sign says little:
        # of the eigenvector and its negative, the one whose assignment scores higher.
        return max(
            (vector, -vector), key=lambda relaxed: _score(affinity, _indicator(discretise(relaxed)))
        )
    unary = np.asarray(affinity.diagonal()).ravel()
    pairwise = affinity - sparse.diags(unary)

    def project(vector: np.ndarray) -> np.ndarray:
        # Made homogeneous against t = 1, the constraints say "every row and column of
        # X sums to t". Their null space is X = t / N + Z, Z with zero row and column
        # sums: the direction (1/N, ..., 1/N, 1) (squared length 2) and the doubly
        # centred matrices, which are orthogonal to it.
        matrix, homogeneous = np.reshape(vector[:count], (size, size)), vector[count]
        centred = (
            matrix
            - matrix.mean(axis=1, keepdims=True)
            - matrix.mean(axis=0, keepdims=True)
            + matrix.mean()
        )
        along = (matrix.sum() / size + homogeneous) / 2.0
        return np.append(centred.ravel() + along / size, along)

    def apply(vector: np.ndarray) -> np.ndarray:
        projected = project(np.ravel(vector))
        assignment, homogeneous = projected[:count], projected[count]
        lifted = np.append(
            pairwise @ assignment + homogeneous / 2.0 * unary, unary @ assignment / 2.0
        )
        return project(lifted)

    vector = _leading(apply, project, count + 1)
    if abs(vector[count]) > 1e-12:  # t = 0: no part along the constraints' solutions to scale
        vector = vector / vector[count]  # t = 1: every row and column then sums to 1
    return vector[:count].reshape(size, size)


def _leading(apply, project, dimension: int) -> np.ndarray:
    """The leading eigenvector of the symmetric operator ``apply`` (dense when small,
    else Lanczos from the projected fixed start ``project(linspace(1, 2))``)."""
    if dimension <= 65:  # small: a dense eigensolver is exact and as fast
        dense = np.stack([apply(column) for column in np.eye(dimension)], axis=1)
        values, vectors = np.linalg.eigh((dense + dense.T) / 2.0)
        return vectors[:, np.argmax(values)]
    operator = LinearOperator((dimension, dimension), matvec=apply, dtype=float)
    start = project(np.linspace(1.0, 2.0, dimension))
    _, vectors = eigsh(operator, k=1, which="LA", v0=start, tol=1e-8, maxiter=20 * dimension)
    return vectors[:, 0]


def refine(affinity: sparse.spmatrix, relaxed: np.ndarray, iterations: int = 50) -> np.ndarray:
    """(N,) the best one-to-one assignment the Integer Projected Fixed Point method
    (Leordeanu, Hebert and Sukthankar, 2009) reaches from the relaxed solution: each
    step moves x towards the Hungarian assignment b maximising b^T W x, with an exact
    line search; the best discrete b seen is kept."""
    size = relaxed.shape[0]
    current = relaxed.ravel().copy()
    best, best_score = None, -math.inf
    for _ in range(iterations):
        target = discretise((affinity @ current).reshape(size, size))
        vector = _indicator(target)
        score = _score(affinity, vector)
        if score > best_score + 1e-12:
            best, best_score = target, score
        step = vector - current
        slope = float(current @ (affinity @ step))
        curvature = float(step @ (affinity @ step))
        rate = 1.0 if curvature >= 0.0 else min(-slope / curvature, 1.0)
        if np.abs(rate * step).max() < 1e-9:
            break
        current = current + rate * step
    assert best is not None  # the first step's assignment always beats -inf
    return best


def _indicator(assignment: np.ndarray) -> np.ndarray:
    """(N*N,) the 0/1 vector x of an assignment."""
    size = len(assignment)
    vector = np.zeros(size * size)
    vector[np.arange(size) * size + assignment] = 1.0
    return vector


def _score(affinity: sparse.spmatrix, vector: np.ndarray) -> float:
    """x^T W x of an assignment's 0/1 vector x (``_indicator``): its energy."""
    return float(vector @ (affinity @ vector))


def discretise(relaxed: np.ndarray) -> np.ndarray:
    """(N,) the one-to-one assignment nearest the relaxed one (Hungarian method)."""
    rows, columns = linear_sum_assignment(-relaxed)
    assignment = np.empty(len(rows), dtype=int)
    assignment[rows] = columns
    return assignment


def exhaustive_solution(problem: Problem) -> tuple[np.ndarray, float]:
    """The best assignment by trying every permutation (for small graphs: the yardstick)."""
    from itertools import permutations

    best, best_energy = None, -math.inf
    for order in permutations(range(problem.size)):
        assignment = np.array(order)
        energy = problem.energy(assignment)
        if energy > best_energy:
            best, best_energy = assignment, energy
    assert best is not None  # a problem has at least one order, and its energy beats -inf
    return best, best_energy


def interchangeable(graph: StructureGraph) -> dict[str, int]:
    """Layout objects the energy cannot tell apart, as object id -> group number (the
    same for objects of one group; every object has one, most a group of their own).
    Two objects are interchangeable when matching the layout subgraph onto itself with
    the two swapped scores exactly what the identity does: the same box and the same
    relations, with the same measures, to every other object (two identical chairs with
    no neighbour). A matching that swaps them is as good as any: nothing in the
    structure graph says which is which."""
    problem, nodes, _ = layout_problem(graph, graph)
    problem.place = None  # the tie-break tells them apart, by design
    identity = np.arange(problem.size)
    energy = problem.energy(identity)
    groups = UnionFind(range(len(nodes)))
    for p in range(len(nodes)):
        for q in range(p + 1, len(nodes)):
            if groups[p] == groups[q] or not np.array_equal(
                graph.sizes[nodes[p]], graph.sizes[nodes[q]]
            ):
                continue
            swapped = identity.copy()
            swapped[[p, q]] = [q, p]
            if problem.energy(swapped) >= energy - 1e-9 * max(energy, 1.0):
                groups.union(p, q)
    return {graph.ids[nodes[p]]: int(groups[p]) for p in range(len(nodes))}


@dataclass
class Correspondence:
    """One matched pair: ids in the first and the second scene, confidence in [0, 1]."""

    a: str
    b: str
    confidence: float
    object_similarity: float


@dataclass
class Matching:
    """The result of ``match_graphs``: the pairs kept (confidence at least the
    threshold), those withdrawn, the objects left unmatched, the energy and time."""

    pairs: list[Correspondence]
    withdrawn: list[Correspondence]
    unmatched_a: list[str]
    unmatched_b: list[str]
    energy: float
    seconds: float
    threshold: float = CONFIDENCE

    def mapping(self) -> dict[str, str]:
        """First-scene id -> second-scene id of the kept pairs."""
        return {pair.a: pair.b for pair in self.pairs}

    def lines(self) -> list[str]:
        """The matching for people: one line per pair, then what was left out."""
        width = max([len(p.a) for p in self.pairs + self.withdrawn] + [1])
        other = max([len(p.b) for p in self.pairs + self.withdrawn] + [1])
        shown = [
            f"  {p.a:<{width}}  ->  {p.b:<{other}}  confidence {p.confidence:.2f}, boxes {p.object_similarity:.2f}"
            for p in self.pairs
        ]
        shown += [
            f"  {p.a:<{width}}  ?>  {p.b:<{other}}  confidence {p.confidence:.2f} < {self.threshold:g}: withdrawn"
            for p in self.withdrawn
        ]
        for side, ids in (("first", self.unmatched_a), ("second", self.unmatched_b)):
            if ids:
                shown.append(f"  unmatched in the {side}: {', '.join(ids)}")
        return shown

    def to_dict(self) -> dict:
        return {
            "pairs": [_pair_dict(p) for p in self.pairs],
            "withdrawn": [_pair_dict(p) for p in self.withdrawn],
            "unmatched_a": self.unmatched_a,
            "unmatched_b": self.unmatched_b,
            "energy": round(self.energy, 6),
            "threshold": self.threshold,
        }


def _pair_dict(pair: Correspondence) -> dict:
    return {
        "a": pair.a,
        "b": pair.b,
        "confidence": round(pair.confidence, 4),
        "object_similarity": round(pair.object_similarity, 4),
    }


def layout_problem(
    first: StructureGraph, second: StructureGraph, *, lam: float = LAMBDA, type_prior: float = 0.0
) -> tuple[Problem, list[int], list[int]]:
    """The quadratic assignment between two layout subgraphs, and their node lists."""
    nodes_a, nodes_b = first.layout_nodes(), second.layout_nodes()
    unary = box_similarity(first.sizes[nodes_a], second.sizes[nodes_b])
    if type_prior:
        same = np.array(
            [[first.types[i] == second.types[k] for k in nodes_b] for i in nodes_a], dtype=float
        )
        unary = unary * (1.0 - type_prior * (1.0 - same.reshape(unary.shape)))
    table_a, table_b = EdgeTable.of(first, nodes_a), EdgeTable.of(second, nodes_b)
    place = place_similarity(first.places[nodes_a], second.places[nodes_b])
    return (
        Problem(unary, table_a, table_b, edge_similarity(table_a, table_b), lam, place),
        nodes_a,
        nodes_b,
    )


def solve(problem: Problem, *, refined: bool = True) -> np.ndarray:
    """The assignment (N,) of a problem: spectral, then Hungarian, for each of the two
    relaxations (the unary terms lifted to a linear term, and left on W's diagonal),
    which go wrong on different scenes (docs/variation.md); without ``refined``, the
    better of the two assignments. With ``refined`` (the default), the best of four
    starts, each improved by pairwise exchanges: the two assignments and the
    fixed-point refinements started from the two relaxations."""
    size = problem.size
    if size == 0:
        return np.zeros(0, dtype=int)
    affinity = problem.affinity()
    relaxed = spectral_solution(affinity, size)
    diagonal = spectral_solution(affinity, size, lifted=False)
    assignments = [discretise(relaxed), discretise(diagonal)]
    if not refined:
        return max(assignments, key=problem.energy)
    starts = (assignments[0], refine(affinity, relaxed), assignments[1], refine(affinity, diagonal))
    candidates = [exchange(problem, start) for start in starts]
    energies = [problem.energy(candidate) for candidate in candidates]
    return candidates[int(np.argmax(energies))]  # the first on a tie: deterministic


def exchange(problem: Problem, assignment: np.ndarray, passes: int = 10) -> np.ndarray:
    """``assignment`` improved by swapping the partners of two objects while any swap
    raises the energy (first improvement, in index order: deterministic)."""
    current = assignment.copy()
    energy = problem.energy(current)
    for _ in range(passes):
        improved = False
        for i in range(problem.size):
            for j in range(i + 1, problem.size):
                current[i], current[j] = current[j], current[i]
                trial = problem.energy(current)
                if trial > energy + 1e-9:
                    energy, improved = trial, True
                else:
                    current[i], current[j] = current[j], current[i]
        if not improved:
            break
    return current


def confidences(
    problem: Problem, assignment: np.ndarray, kept: np.ndarray | None = None
) -> np.ndarray:
    """(m,) each first-graph node's confidence under ``assignment`` (0 for a dummy match),
    counting only edges between kept pairs (``kept`` (m,), all pairs matched to an object
    when not given): what an object's withdrawn or unmatched neighbours do is no evidence
    for or against its own pair."""
    m, n = problem.unary.shape
    first, second = problem.first, problem.second
    if kept is None:
        kept = assignment[:m] < n
    partner = np.zeros(n, dtype=bool)
    partner[assignment[:m][kept]] = True
    matched = (problem.pairwise * problem.matched_edges(assignment)).sum(axis=1)
    gained = np.zeros(m)
    np.add.at(gained, first.source, matched * kept[first.target])
    own_a = first.self_scores(m, kept[first.target])
    own_b = second.self_scores(n, partner[second.target])
    result = np.zeros(m)
    for i in np.flatnonzero(kept):
        k = assignment[i]
        best = 1.0 + problem.lam * (own_a[i] + own_b[k]) / 2.0
        result[i] = (problem.unary[i, k] + problem.lam * gained[i]) / best
    return result


def withdraw(
    problem: Problem, assignment: np.ndarray, threshold: float
) -> tuple[np.ndarray, np.ndarray]:
    """(m,) confidences and (m,) which pairs are kept (confidence at least ``threshold``).
    A pair below half the threshold is taken as objects without a counterpart (on a
    disguised copy, the removed object paired with the added one); the others'
    confidences are then counted without its edges, which say nothing about their own
    pairs. It keeps the confidence it had."""
    m, n = problem.unary.shape
    confidence = confidences(problem, assignment)
    context = (assignment[:m] < n) & (confidence >= threshold / 2.0)
    confidence = np.where(context, confidences(problem, assignment, context), confidence)
    return confidence, context & (confidence >= threshold)


def match_graphs(
    first: StructureGraph,
    second: StructureGraph,
    *,
    lam: float = LAMBDA,
    threshold: float = CONFIDENCE,
    type_prior: float = 0.0,
) -> Matching:
    """Match the layout subgraphs of two structure graphs (see the module docstring)."""
    started = time.process_time()
    problem, nodes_a, nodes_b = layout_problem(first, second, lam=lam, type_prior=type_prior)
    assignment = solve(problem)
    confidence, keep = withdraw(problem, assignment, threshold)
    m, n = problem.unary.shape
    kept: list[Correspondence] = []
    withdrawn: list[Correspondence] = []
    for i in range(m):
        k = int(assignment[i])
        if k >= n:
            continue
        pair = Correspondence(
            first.ids[nodes_a[i]],
            second.ids[nodes_b[k]],
            float(confidence[i]),
            float(problem.unary[i, k]),
        )
        (kept if keep[i] else withdrawn).append(pair)
    matched_a, matched_b = {p.a for p in kept}, {p.b for p in kept}
    return Matching(
        pairs=kept,
        withdrawn=withdrawn,
        unmatched_a=[first.ids[i] for i in nodes_a if first.ids[i] not in matched_a],
        unmatched_b=[second.ids[k] for k in nodes_b if second.ids[k] not in matched_b],
        energy=problem.energy(assignment) if problem.size else 0.0,
        seconds=time.process_time() - started,
        threshold=threshold,
    )
