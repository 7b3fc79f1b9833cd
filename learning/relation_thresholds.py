"""The thresholds and sample sizes of relation finding, in one place: the permutation
test's level and permutations, its tightness floors, how many scenes each form of the
test needs, the bounds of a fixed arrangement, and the knobs of pruning and of the angle
and co-occurrence tests. Why each value is what it is: docs/notes/design.md, "Relation
finding".
"""

from __future__ import annotations

import math

from scenewright.generator.layout.params import LayoutParams

#: The permutation test's level and its number of random relabellings.
ALPHA = 0.01
PERMUTATIONS = 199
#: The least tightness of a related pair (design notes): nearest-neighbour
#: tightness on halves of at least ``LOCAL_POSES`` poses, else the spread of all pairs.
MIN_LOCAL_TIGHTNESS = 0.35
MIN_TIGHTNESS = 0.25
#: The fewest poses in a half for the nearest-neighbour tightness (design notes).
LOCAL_POSES = 30
#: The fewest scenes holding a pair that the permutation test tests (two halves of 5).
MIN_SCENES = 10
#: The fewest scenes holding a pair that the permutation test tests on pairs of scenes
#: (halves below): 10 pairs, 2^9 = 512 distinct flip patterns up to the swap of the
#: two samples, so that p <= 0.01 can be reached.
PAIR_SCENES = 20
#: The fewest scenes holding a pair that the scene-pairing test (for fewer than
#: ``MIN_SCENES``) tests: 5! = 120 pairings, so p can reach 1 / 120 <= 0.01.
MIN_PAIRED_SCENES = 5
#: The fewest scenes holding a pair that is tested at all: from three to
#: ``MIN_PAIRED_SCENES`` no pairing reaches alpha, and a pair is related when the
#: examples' pairing of the poses with either side alike is the most extreme of all
#: (``relation_tests.paired_outcome``).
MIN_FEW_SCENES = 3
#: The least tightness of a pair related by the scene-pairing test: higher than the
#: others, because a handful of within-scene poses is tight by chance more often and a
#: set of few scenes is tested for many pairs (design notes, "Thresholds").
MIN_PAIRED_TIGHTNESS = 0.5
#: The scene-pairing test enumerates every pairing up to this many (7! = 5040), else
#: draws ``PAIRINGS`` at random.
EXACT_PAIRINGS = 5040
PAIRINGS = 1999
#: The most scenes of a pair the permutation test uses (a random subset beyond): its
#: distance matrix has (2 MAX_SCENES)^2 entries.
MAX_SCENES = 1000
#: A fixed arrangement (design notes): related when in at least ``FIXED_SHARE`` of
#: the scenes holding both, b stands within ``FIXED_OFFSET`` metres and ``FIXED_TURN``
#: radians of one pose in a's frame (the median pose) and next to a (footprints at most
#: the Table-1 NextTo distance apart, 2 m). Three scenes in four, not half: the verdict
#: has no test behind it, and hand-placed examples put furniture in roughly the same
#: spots (design notes, "Thresholds").
FIXED_SHARE = 0.75
FIXED_OFFSET = 0.25
FIXED_TURN = math.radians(15.0)
NEXT_TO_DISTANCE = LayoutParams().next_to_distance
#: A pair is pruned as indirect through a third type only when that type stands in at
#: least this share of the scenes holding the pair (design notes).
THIRD_SHARE = 0.75
#: Of a triangle's pairs found indirect, those whose informative directness is within
#: this much of the least are told apart by how far apart they stand (design notes,
#: "Choosing the indirect pair"). An effect size, as the floors are.
DIRECTNESS_MARGIN = 0.1
#: A path (a road) stands in triangles as points this many metres apart along it
#: (design notes, "Paths").
PATH_STEP = 1.0
#: Draws of scene pairs and random a's whose tightness is averaged into a pair's
#: strength and a composition's tightness (design notes, "Strength").
STRENGTH_DRAWS = 8
#: A pair's strength clears the floor when it does by this many standard errors of its
#: mean over the draws (design notes, "Strength").
STRENGTH_ERRORS = 2.0
#: The angle test: the share of points taken as centres, and the threshold on d.
ANGLE_SAMPLE = 0.1
ANGLE_THRESHOLD = 1.628
#: Co-occurrence: related when more than this share of the scenes hold both types.
COOCCURRENCE_SHARE = 0.5
#: A coordinate whose pooled standard deviation is below this is left unscaled (it is
#: constant: every pose has the same value there).
SCALE_FLOOR = 1e-9
#: The least tightness of a pair's within-scene poses against their composition
#: through a third type for the pair to be direct (design notes): the floor a pair
#: meets against independent placement (design notes, "Thresholds").
MIN_DIRECT_TIGHTNESS = MIN_LOCAL_TIGHTNESS
