"""Colour words: the basic English colour term for an sRGB colour, or none when it is unclear.

An object's catalog colour (sRGB in [0, 1], the main colour its mesh is drawn in) is
named by the nearest of the eleven basic colour terms of English (Berlin and Kay,
"Basic Color Terms", 1969), each given by a typical sRGB value (``COLOUR_TERMS``),
distances taken in CIELAB (D65), where they follow what people see better than in
RGB. A colour between two terms (its nearest is not nearer than the runner-up by the
factor ``CLEAR_RATIO``) has no word: a question never asks for it.
"""

from __future__ import annotations

import numpy as np

#: Each basic colour term and a typical sRGB value of it (in [0, 1]).
COLOUR_TERMS: dict[str, tuple[float, float, float]] = {
    "black": (0.08, 0.08, 0.08),
    "white": (0.95, 0.95, 0.93),
    "grey": (0.55, 0.55, 0.55),
    "red": (0.7, 0.15, 0.15),
    "orange": (0.93, 0.52, 0.12),
    "yellow": (0.95, 0.85, 0.25),
    "green": (0.25, 0.5, 0.25),
    "blue": (0.22, 0.32, 0.6),
    "purple": (0.5, 0.2, 0.6),
    "pink": (0.95, 0.6, 0.72),
    "brown": (0.5, 0.32, 0.16),
}
#: A colour is named only when the runner-up term is at least this many times farther.
CLEAR_RATIO = 1.3


def _lab(srgb) -> np.ndarray:
    """CIELAB (D65) of sRGB colours in [0, 1]: (..., 3) -> (..., 3)."""
    c = np.clip(np.asarray(srgb, dtype=float), 0.0, 1.0)
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    xyz = linear @ np.array(
        [
            [0.4124564, 0.2126729, 0.0193339],
            [0.3575761, 0.7151522, 0.1191920],
            [0.1804375, 0.0721750, 0.9503041],
        ]
    )
    t = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack(
        [116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])],
        axis=-1,
    )


_TERM_NAMES = tuple(COLOUR_TERMS)
_TERM_LAB = _lab(list(COLOUR_TERMS.values()))


def colour_word(srgb) -> str | None:
    """The basic colour term of an sRGB colour (3,) in [0, 1], or None when two terms
    are about as near (``CLEAR_RATIO``)."""
    distances = np.linalg.norm(_TERM_LAB - _lab(srgb), axis=1)
    nearest, runner_up = np.argsort(distances)[:2]
    if distances[runner_up] < CLEAR_RATIO * distances[nearest]:
        return None
    return _TERM_NAMES[nearest]
