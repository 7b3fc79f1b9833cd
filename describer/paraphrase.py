"""Seeded choices for paraphrase variants: variant 0 never varies, variant k is a fixed draw.

Every free choice the describer makes (a synonym, the order of list items or of
sentences whose order does not matter) goes through one ``Choices`` object, so variant
k of a scene is always the same text and variant 0 is the canonical one.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeVar

import numpy as np

from scenewright.core.seeds import MAX_SEED, stream

T = TypeVar("T")


class Choices:
    """Draws for one description. ``rng`` None means the canonical text: first options, given order."""

    def __init__(self, rng: np.random.Generator | None) -> None:
        self._rng = rng

    @classmethod
    def for_variant(cls, seed: int, variant: int) -> Choices:
        """Variant 0 is canonical; variant k draws from the describer's child stream k of
        the scene's seed (``core.seeds``), which no other stage shares."""
        # A scene.json written by hand may carry any integer: fold it into the seed range.
        return cls(None if variant == 0 else stream(seed % (MAX_SEED + 1), "describer", variant))

    def pick(self, options: Sequence[T]) -> T:
        """The first option in the canonical text, else one at random."""
        if self._rng is None or len(options) == 1:
            return options[0]
        return options[int(self._rng.integers(len(options)))]

    def shuffled(self, items: Sequence[T]) -> list[T]:
        """The items in the given order in the canonical text, else permuted."""
        if self._rng is None or len(items) < 2:
            return list(items)
        return [items[i] for i in self._rng.permutation(len(items))]
