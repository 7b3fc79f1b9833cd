"""Variations of example scenes without learning, after "Structure-guided 3D interior
scene synthesis": match the examples' objects by their role in the layout, merge the
examples into one Augmented Graph, reshuffle.

- ``structure``: a scene's structure graph (objects, and per pair the relations
  support, facing, vertical contact, aligned, close, measured from the boxes);
- ``matching``: graph matching of two structure graphs as a quadratic assignment,
  solved spectrally under one-to-one constraints and discretised by the Hungarian method;
- ``perturb``: disguised copies of a scene with the truth, to measure matching.
"""

from .matching import Matching, match_graphs
from .structure import StructureGraph, structure_graph

__all__ = ["Matching", "StructureGraph", "match_graphs", "structure_graph"]
