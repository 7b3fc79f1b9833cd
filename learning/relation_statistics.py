"""The statistics behind the relation tests: the energy distance of two samples of poses
(Szekely & Rizzo) with its permutation tests (random relabellings, flips of scene pairs,
pairings of scenes), the tightness of the within-scene poses against the across-scene
ones, and the angle statistic of the test of complete spatial randomness (Assuncao 1994).
Design notes: docs/notes/design.md, "Relation finding".
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.spatial import cKDTree
from scipy.spatial.distance import cdist

from .relation_thresholds import EXACT_PAIRINGS, LOCAL_POSES, PAIRINGS, SCALE_FLOOR


def scaled_distances(pooled: np.ndarray) -> np.ndarray:
    """(N, N) distances between the poses ``pooled`` (N, D), each coordinate divided by
    its standard deviation over them (left as it is when constant)."""
    scale = pooled.std(axis=0)
    scale[scale < SCALE_FLOOR] = 1.0
    return cdist(pooled / scale, pooled / scale)


def energy_permutations(distances: np.ndarray, labels: np.ndarray) -> tuple[float, float]:
    """The energy distance of a split of N poses into X (label 1, n poses) and Y (label
    0, m), from their (N, N) ``distances``, for each labelling of ``labels`` (K + 1, N),
    row 0 the observed one: its value and p-value, (1 + #{rows k >= 1 with E_k >= E_0})
    / (K + 1). Every labelling puts the same n poses in X."""
    n = int(labels[0].sum())
    m = labels.shape[1] - n
    row_sums = distances.sum(axis=1)
    first_first = np.einsum(
        "kn,nk->k", labels, distances @ labels.T
    )  # sum of |X - X'| per labelling
    first_second = labels @ row_sums - first_first
    second_second = row_sums.sum() - 2.0 * first_second - first_first
    energy = 2.0 * first_second / (n * m) - first_first / n**2 - second_second / m**2
    observed = energy[0]
    # A relabelling as far apart as the observed split counts, within rounding.
    as_large = np.count_nonzero(energy[1:] >= observed - 1e-12 * abs(observed))
    return float(observed), float((1 + as_large) / len(labels))


def tightness(distances: np.ndarray, n: int) -> float:
    """The tightness of the first n of the poses whose (N, N) ``distances`` are given
    against the other N - n (design notes): nearest-neighbour distances when n >=
    ``LOCAL_POSES``, else the spread of all pairs; 0 when the others all coincide.
    Overwrites the diagonal of ``distances``."""
    if n < LOCAL_POSES:  # the spread of all pairs
        among_first, among_second = distances[:n, :n].mean(), distances[n:, n:].mean()
        return float(1.0 - among_first / among_second) if among_second > 0 else 0.0
    np.fill_diagonal(distances, np.inf)  # a pose is not its own nearest neighbour
    nearest_first = distances[:n, :n].min(axis=1).mean()
    nearest_second = distances[n:, n:].min(axis=1).mean()
    return float(1.0 - nearest_first / nearest_second) if nearest_second > 0 else 0.0


def sample_tightness(within: np.ndarray, across: np.ndarray) -> float:
    """``tightness`` of the poses ``within`` (n, D) against ``across`` (m, D), each
    coordinate scaled by its pooled standard deviation: the same figure as the tests
    give, with nearest neighbours found by a k-d tree, so that further draws cost
    little."""
    pooled = np.vstack([within, across])
    if len(within) < LOCAL_POSES:
        return tightness(scaled_distances(pooled), len(within))
    scale = pooled.std(axis=0)
    scale[scale < SCALE_FLOOR] = 1.0
    first, second = within / scale, across / scale
    nearest_first = cKDTree(first).query(first, k=2)[0][:, 1].mean()
    nearest_second = cKDTree(second).query(second, k=2)[0][:, 1].mean()
    return float(1.0 - nearest_first / nearest_second) if nearest_second > 0 else 0.0


def energy_test(
    within: np.ndarray, across: np.ndarray, permutations: int, rng: np.random.Generator
) -> tuple[float, float, float]:
    """The energy distance of two samples (n, D) and (m, D) of independent poses, each
    coordinate scaled by its pooled standard deviation; its permutation p-value over
    ``permutations`` random relabellings of the pooled sample; and the first sample's
    ``tightness`` against the second."""
    distances = scaled_distances(np.vstack([within, across]))  # (N, N)
    n, total = len(within), len(within) + len(across)
    labels = np.zeros((permutations + 1, total))  # row 0: the observed split, then the relabellings
    labels[0, :n] = 1.0
    firsts = np.argsort(rng.random((permutations, total)), axis=1)[:, :n]
    np.put_along_axis(labels[1:], firsts, 1.0, axis=1)
    energy, p_value = energy_permutations(distances, labels)
    return energy, p_value, tightness(distances, n)


def flip_test(
    within: np.ndarray, across: np.ndarray, permutations: int, rng: np.random.Generator
) -> tuple[float, float, float]:
    """The energy test of scene pairs (design notes) on ``within`` and ``across``
    (2K, D): for the K pairs of scenes k, rows k and K + k of ``within`` trade places
    with the same rows of ``across`` when the pair's b's are swapped. The energy
    distance of the two samples, its p-value over ``permutations`` random flip patterns
    (each pair swapped with probability 1/2), and ``within``'s tightness."""
    pairs = len(within) // 2
    distances = scaled_distances(np.vstack([within, across]))  # (4K, 4K)
    kept = np.vstack(
        [np.ones(pairs, dtype=bool), rng.random((permutations, pairs)) >= 0.5]
    )  # row 0: as observed
    kept = np.hstack([kept, kept])  # a flip swaps both scenes' b's: rows k and K + k
    labels = np.hstack([kept, ~kept]).astype(float)
    energy, p_value = energy_permutations(distances, labels)
    return energy, p_value, tightness(distances, 2 * pairs)


def pairing_test(poses: np.ndarray, rng: np.random.Generator) -> tuple[float, float, float]:
    """The scene-pairing test (design notes) on ``poses`` (n, n, D), P[i, j]: the
    energy distance of the diagonal {P[i, i]} from all n^2 poses, its p-value over the
    pairings of scenes, and the diagonal's tightness against all poses."""
    n = poses.shape[0]
    distances = scaled_distances(poses.reshape(n * n, -1))  # (n^2, n^2)
    if math.factorial(n) <= EXACT_PAIRINGS:
        pairings = np.array(list(itertools.permutations(range(n))))  # the identity first
    else:
        pairings = np.vstack([np.arange(n), np.argsort(rng.random((PAIRINGS, n)), axis=1)])
    chosen = np.arange(n) * n + pairings  # (K, n): P[i, sigma(i)] as rows of ``pooled``
    to_all = distances.mean(axis=1)[chosen].mean(axis=1)  # mean |X - Y| per pairing
    among = distances[chosen[:, :, None], chosen[:, None, :]].mean(axis=(1, 2))  # mean |X - X'|
    spread = distances.mean()  # mean |Y - Y'|
    energy = 2.0 * to_all - among - spread
    observed = energy[0]
    as_large = np.count_nonzero(
        energy >= observed - 1e-12 * abs(observed)
    )  # the identity counts itself
    tightness = 1.0 - among[0] / spread if spread > 0 else 0.0
    return float(observed), float(as_large / len(pairings)), float(tightness)


def nearest_neighbour_angles(points: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """For each centre index O of ``points`` (n, 2), the angle in [0, pi] between the
    directions to its two nearest other points (0 when one of them coincides with O)."""
    _, neighbours = cKDTree(points).query(points[centres], k=3)
    # Drop the centre itself; among coincident points it need not come first.
    is_self = neighbours == centres[:, None]
    is_self[~is_self.any(axis=1), 2] = True
    pairs = neighbours[~is_self].reshape(len(centres), 2)
    first = points[pairs[:, 0]] - points[centres]
    second = points[pairs[:, 1]] - points[centres]
    lengths = np.linalg.norm(first, axis=1) * np.linalg.norm(second, axis=1)
    cosine = np.divide(
        np.einsum("ij,ij->i", first, second), lengths, out=np.ones(len(centres)), where=lengths > 0
    )
    return np.arccos(np.clip(cosine, -1.0, 1.0))


def angle_statistic(angles: np.ndarray) -> float:
    """d = sqrt(m) sup |theta / pi - F_e(theta)| of m angles in [0, pi]."""
    m = len(angles)
    uniform = np.sort(angles) / np.pi
    steps = np.arange(1, m + 1) / m
    return float(np.sqrt(m) * max(np.max(steps - uniform), np.max(uniform - (steps - 1.0 / m))))
