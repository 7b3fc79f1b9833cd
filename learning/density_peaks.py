"""Density-peak clustering: cluster centres are points denser than their neighbours and
far from any denser point (Rodriguez & Laio, "Clustering by fast search and find of
density peaks", Science 2014), with the outliers left out of every cluster, as Zhang
et al. use it to turn the relative poses of two object types into discrete templates
("Fast 3D Indoor Scene Synthesis by Learning Spatial Relation Priors of Objects",
IEEE TVCG 2021).

For n points (n, D) with pairwise distances d_ij:

    rho_i   = #{ j != i : d_ij < d_c }                      local density (cutoff kernel)
    delta_i = min { d_ij : j denser than i }                 distance to the nearest denser point
              (max_j d_ij for the densest point)
    gamma_i = rho_i * delta_i

"Denser" orders the points by rho, ties broken by a Gaussian-kernel density
sum_j exp(-(d_ij / d_c)^2) (the paper's other kernel, which is never tied on real data)
and then by index, so the result is a fixed function of the points.

The cutoff d_c is the ``NEIGHBOUR_SHARE`` quantile of the pairwise distances (the
paper's rule of thumb: about 2 % of the points are a point's neighbours), raised so
that a point has ``MIN_NEIGHBOURS`` neighbours on average when there are few points,
and never below ``scale``, the distance below which two points count as the same
(for poses: 10 cm).

Centres and outliers are read off the decision graph (rho against delta) as the paper
does by eye:

- a *centre* stands apart from every denser point, delta_i >= ``separation`` (by default
  ``SEPARATION`` cutoffs, and at least ``min_separation``), and has neighbours
  (rho_i >= 1): high delta and non-zero rho, hence high gamma;
- every other point, in order of decreasing density, joins the cluster of its nearest
  denser point (the paper's one-pass assignment);
- a point far from every denser point (delta_i >= separation) that is not dense enough
  to be a centre is an *outlier*; so is a point whose nearest denser point is one
  (it hangs off the outlier, not off a cluster);
- a cluster is split where it has a *gap*: its points fall into groups no two points
  of which, one from each, are closer than ``gap`` (single linkage), and each group is
  a cluster of its own, centred on its densest point. ``gap`` is ``SEPARATION`` times
  the median over the points of the distance to a point's k-th nearest other point
  (k = min_size - 1, at least 1), and at least ``min_separation``: a spread-out
  cluster has no gap that wide, but two modes with few points do, where the cutoff
  raised for few points (above) has joined them (six lamps on an armchair's left and
  three on its right, 1.4 m apart);
- a cluster smaller than ``min_size`` is dissolved: its points are outliers too. By
  default ``min_size`` is ``MIN_CLUSTER`` points, or ``MIN_CLUSTER_SHARE`` of all points
  when that is more, but never more than ``MIN_MODE_SHARE`` of all points (rounded up):
  with few points a mode of one or two (a lamp on the right in 1 of 3 examples) is a
  cluster, since leaving it out would move the shares by more than that. Two outliers
  next to each other among many points make no template.

Outliers carry the label -1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial.distance import pdist, squareform

#: The share of the points a point has as neighbours within d_c (the paper's 1-2 %).
NEIGHBOUR_SHARE = 0.02
#: ... but at least this many on average, when there are few points.
MIN_NEIGHBOURS = 5
#: A centre is at least this many cutoffs from any denser point.
SEPARATION = 2.0
#: The fewest points of a cluster, absolutely and as a share of all points.
MIN_CLUSTER = 3
MIN_CLUSTER_SHARE = 0.05
#: ... but a cluster holding at least this share of all points is always kept.
MIN_MODE_SHARE = 0.15
#: Two clusters are one when the density between them stays above this share of the
#: lower peak (``_merge_across_saddles``).
SADDLE_SHARE = 0.5


@dataclass(frozen=True)
class DensityPeaks:
    """The clustering of n points: ``rho`` (n,) neighbours within ``cutoff``, ``delta``
    (n,) distance to the nearest denser point, ``centres`` (k,) indices of the cluster
    centres (densest first), ``labels`` (n,) the cluster of each point (its index into
    ``centres``) or -1 for an outlier, ``separation`` the least delta of a centre."""

    rho: np.ndarray
    delta: np.ndarray
    centres: np.ndarray
    labels: np.ndarray
    cutoff: float
    separation: float

    @property
    def gamma(self) -> np.ndarray:
        """(n,) rho * delta, the paper's ranking of candidate centres."""
        return self.rho * self.delta

    @property
    def outliers(self) -> np.ndarray:
        """Indices of the points in no cluster."""
        return np.flatnonzero(self.labels < 0)

    def members(self, cluster: int) -> np.ndarray:
        """Indices of the points of cluster ``cluster``."""
        return np.flatnonzero(self.labels == cluster)


def default_min_size(n: int) -> int:
    """The fewest points of a cluster among ``n`` (module docstring)."""
    largest = max(MIN_CLUSTER, math.ceil(MIN_CLUSTER_SHARE * n))
    return max(1, min(largest, math.ceil(MIN_MODE_SHARE * n - 1e-9)))


def gap_distance(distances: np.ndarray, min_size: int, least: float) -> float:
    """The width of a gap that splits a cluster (module docstring)."""
    n = len(distances)
    if n < 2:
        return max(least, 1e-12)
    k = min(max(1, min_size - 1), n - 1)
    kth = np.sort(distances, axis=1)[:, k]  # column 0 is the point itself
    return max(SEPARATION * float(np.median(kth)), least, 1e-12)


def cutoff_distance(distances: np.ndarray, scale: float = 0.0) -> float:
    """d_c for the (n, n) ``distances`` (module docstring); ``scale`` is its floor."""
    n = len(distances)
    if n < 2:
        return max(scale, 1e-12)
    pairs = distances[np.triu_indices(n, k=1)]
    share = min(1.0, max(NEIGHBOUR_SHARE, MIN_NEIGHBOURS / (n - 1)))
    return max(float(np.quantile(pairs, share)), scale, 1e-12)


def density_peaks(
    points: np.ndarray,
    *,
    scale: float = 0.0,
    min_separation: float = 0.0,
    min_size: int | None = None,
) -> DensityPeaks:
    """Cluster ``points`` (n, D) by density peaks (module docstring). ``scale``: the
    least cutoff (distances below it are one place); ``min_separation``: the least
    distance of a centre from any denser point; ``min_size``: the fewest points of a
    cluster (default: ``default_min_size(n)``)."""
    points = np.asarray(points, dtype=float)
    if points.ndim != 2:
        raise ValueError(f"points must be (n, D), got shape {points.shape}")
    n = len(points)
    if min_size is None:
        min_size = default_min_size(n)
    if n == 0:
        empty = np.zeros(0)
        return DensityPeaks(
            empty, empty, np.zeros(0, dtype=int), np.zeros(0, dtype=int), max(scale, 1e-12), 0.0
        )
    distances = squareform(pdist(points)) if n > 1 else np.zeros((1, 1))
    cutoff = cutoff_distance(distances, scale)
    rho = (distances < cutoff).sum(axis=1) - 1.0  # not counting the point itself
    smooth = np.exp(-((distances / cutoff) ** 2)).sum(axis=1)
    order = np.lexsort((np.arange(n), -smooth, -rho))  # densest first
    delta = np.empty(n)
    nearest_denser = np.full(n, -1)
    delta[order[0]] = distances[order[0]].max() if n > 1 else 0.0
    for rank in range(1, n):
        point, denser = order[rank], order[:rank]
        k = int(np.argmin(distances[point, denser]))
        delta[point], nearest_denser[point] = distances[point, denser[k]], denser[k]
    separation = max(SEPARATION * cutoff, min_separation)

    labels = np.full(n, -1)
    centres: list[int] = []
    for point in order:
        if delta[point] >= separation or nearest_denser[point] < 0:
            if rho[point] >= min(1, min_size - 1):  # a density peak standing apart: a centre
                labels[point] = len(centres)
                centres.append(int(point))
            # else: far from every denser point and alone: an outlier (-1)
        else:
            labels[point] = labels[nearest_denser[point]]  # -1 when that one is an outlier

    labels, centres = _merge_across_saddles(labels, centres, distances < cutoff, smooth)
    gap = gap_distance(distances, min_size, max(min_separation, scale))
    labels, centres = _split_at_gaps(labels, centres, distances, gap, order)
    sizes = np.bincount(labels[labels >= 0], minlength=len(centres))
    kept = [c for c in range(len(centres)) if sizes[c] >= min_size]
    renumber = np.full(len(centres) + 1, -1)
    renumber[kept] = np.arange(len(kept))
    labels = renumber[labels]  # labels -1 index the trailing -1
    return DensityPeaks(
        rho, delta, np.array([centres[c] for c in kept], dtype=int), labels, cutoff, separation
    )


def _merge_across_saddles(
    labels: np.ndarray, centres: list[int], near: np.ndarray, rho: np.ndarray
) -> tuple[np.ndarray, list[int]]:
    """Clusters joined where the density between them does not dip: two peaks are two
    modes only if every path of neighbouring points from one to the other passes
    through points much sparser than both peaks.

    The *saddle* of two clusters is the highest min(rho_i, rho_j) over neighbouring
    points i, j (``near``, (n, n): within the cutoff) of the two (the paper's border
    density). Taking saddles from the highest down, two clusters are merged when
    their saddle is at least ``SADDLE_SHARE`` of the lower of their two peaks; the
    merged cluster keeps the denser centre. Returns the new labels and centres."""
    if len(centres) < 2:
        return labels, centres
    first, second = np.nonzero(np.triu(near, k=1))
    across = (labels[first] >= 0) & (labels[second] >= 0) & (labels[first] != labels[second])
    first, second = first[across], second[across]
    saddles: dict[tuple[int, int], float] = {}
    for i, j in zip(first.tolist(), second.tolist(), strict=False):
        key = (min(labels[i], labels[j]), max(labels[i], labels[j]))
        saddles[key] = max(saddles.get(key, 0.0), float(min(rho[i], rho[j])))
    owner = list(range(len(centres)))

    def root(cluster: int) -> int:
        while owner[cluster] != cluster:
            cluster = owner[cluster]
        return cluster

    for (u, v), height in sorted(saddles.items(), key=lambda item: (-item[1], item[0])):
        ru, rv = root(u), root(v)
        if ru != rv and height >= SADDLE_SHARE * min(rho[centres[ru]], rho[centres[rv]]):
            owner[max(ru, rv)] = min(ru, rv)  # centres are listed densest first
    roots = sorted({root(c) for c in range(len(centres))})
    renumber = np.full(len(centres) + 1, -1)
    for c in range(len(centres)):
        renumber[c] = roots.index(root(c))
    return renumber[labels], [centres[r] for r in roots]


def _split_at_gaps(
    labels: np.ndarray, centres: list[int], distances: np.ndarray, gap: float, order: np.ndarray
) -> tuple[np.ndarray, list[int]]:
    """Each cluster split into its single-linkage groups at ``gap`` (module docstring);
    a group's centre is its densest point (first in ``order``). Clusters are numbered
    by their centres' density, densest first, as before."""
    rank = np.empty(len(order), dtype=int)
    rank[order] = np.arange(len(order))
    groups: list[np.ndarray] = []
    for cluster in range(len(centres)):
        members = np.flatnonzero(labels == cluster)
        linked = csr_matrix(distances[np.ix_(members, members)] < gap)
        count, parts = connected_components(linked, directed=False)
        groups.extend(members[parts == part] for part in range(count))
    if len(groups) == len(centres):
        return labels, centres
    heads = [int(group[np.argmin(rank[group])]) for group in groups]
    new_labels = np.full(len(labels), -1)
    new_centres: list[int] = []
    for number_, index in enumerate(sorted(range(len(groups)), key=lambda g: rank[heads[g]])):
        new_labels[groups[index]] = number_
        new_centres.append(heads[index])
    return new_labels, new_centres
