"""The paper's factor functions in log space (Equation 1 and 5 of the supplement).

Each function returns the logarithm of a factor in (0, 1]: 0 means the constraint holds
perfectly, more negative means worse. The layout energy is minus the sum of these. With
Sig(x, h) = 1 / (1 + e^(-h x)) and N the normal density:

- equals(x, y, s2)      = log N(0, |x - y|, s2) / N(0, 0, s2) = -(x - y)^2 / (2 s2)
- greater(x, y, h)      = log Sig(x - y, h)
- less(x, y, h)         = log Sig(y - x, h)
- range_(x, lo, hi, h)  = greater(x, lo, h) + less(x, hi, h)
- pointing_same_direction(v, w, s2) = equals(acos(v . w), 0, s2) for unit vectors

Scalar pure-Python maths on purpose: the sampler calls these a few times per step on
single numbers, where numpy's per-call overhead would dominate.
"""

from __future__ import annotations

import math

#: The paper's steepness constants (taken from Yeh et al. 2012).
DEFAULT_H = 3.0
DEFAULT_SIGMA2 = 0.1


def log_sigmoid(t: float) -> float:
    """log(1 / (1 + e^-t)), accurate and overflow-free for any t."""
    if t >= 0.0:
        return -math.log1p(math.exp(-t))
    return t - math.log1p(math.exp(t))


def equals(x: float, y: float, sigma2: float = DEFAULT_SIGMA2) -> float:
    """log Equals: a Gaussian bump, 0 when x == y."""
    difference = x - y
    return -(difference * difference) / (2.0 * sigma2)


def greater(x: float, y: float, h: float = DEFAULT_H) -> float:
    """log Greater: close to 0 when x is well above y, log(1/2) at x == y."""
    return log_sigmoid(h * (x - y))


def less(x: float, y: float, h: float = DEFAULT_H) -> float:
    """log Less: close to 0 when x is well below y, log(1/2) at x == y."""
    return log_sigmoid(h * (y - x))


def range_(x: float, low: float, high: float, h: float = DEFAULT_H) -> float:
    """log Range: close to 0 when low < x < high with margin."""
    return greater(x, low, h) + less(x, high, h)


def angle_between(vx: float, vz: float, wx: float, wz: float) -> float:
    """The angle in radians between two unit vectors (clamped against rounding)."""
    dot = vx * wx + vz * wz
    return math.acos(max(-1.0, min(1.0, dot)))


def pointing_same_direction(
    vx: float, vz: float, wx: float, wz: float, sigma2: float = DEFAULT_SIGMA2
) -> float:
    """log factor that two unit vectors (x, z) point the same way: equals(angle, 0)."""
    return equals(angle_between(vx, vz, wx, wz), 0.0, sigma2)
