"""Variations of example scenes without learning, after "Structure-guided 3D interior
scene synthesis": match the examples' objects by their role in the layout, merge the
examples into one Augmented Graph, reshuffle.

- ``structure``: a scene's structure graph (objects, and per pair the relations
  support, facing, vertical contact, aligned, close, measured from the boxes);
- ``matching``: graph matching of two structure graphs as a quadratic assignment,
  solved spectrally under one-to-one constraints and discretised by the Hungarian method;
- ``augmented``: the Augmented Graph, the examples merged through their matchings;
- ``perturb``: disguised copies of a scene with the truth, to measure matching.
"""

from .augmented import AugmentedGraph, augment
from .matching import Matching, match_graphs
from .structure import StructureGraph, structure_graph

__all__ = [
    "AugmentedGraph",
    "Matching",
    "StructureGraph",
    "augment",
    "match_graphs",
    "structure_graph",
]
