"""The factor functions against the paper's formulas (Equation 1 and 5)."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from scenewright.generator.layout.factors import (
    equals,
    greater,
    less,
    log_sigmoid,
    pointing_same_direction,
    range_,
)

finite = st.floats(-50, 50, allow_nan=False)


def sig(x, h):
    return 1.0 / (1.0 + math.exp(-h * x))


def normal(x, mu, s2):
    return math.exp(-((x - mu) ** 2) / (2 * s2)) / math.sqrt(2 * math.pi * s2)


@given(finite, finite)
def test_equals_is_the_normalised_gaussian(x, y):
    expected = normal(0.0, abs(x - y), 0.1) / normal(0.0, 0.0, 0.1)
    if expected > 1e-300:
        assert equals(x, y, 0.1) == pytest.approx(math.log(expected), rel=1e-9, abs=1e-9)
    assert equals(x, x) == 0.0


@given(st.floats(-5, 5), st.floats(-5, 5))
def test_greater_and_less_are_log_sigmoids(x, y):
    assert greater(x, y, 3.0) == pytest.approx(math.log(sig(x - y, 3.0)), abs=1e-12)
    assert less(x, y, 3.0) == pytest.approx(math.log(sig(y - x, 3.0)), abs=1e-12)


def test_steepness_and_midpoint():
    assert greater(2.0, 2.0) == pytest.approx(math.log(0.5))
    assert less(0.0, 2.0) > -0.01  # well below: nearly 1
    assert less(4.0, 2.0) < -5.0  # well above: nearly 0


@given(st.floats(-5, 5), st.floats(-3, 0), st.floats(0.1, 3))
def test_range_is_greater_plus_less(x, low, width):
    high = low + width
    assert range_(x, low, high, 3.0) == pytest.approx(
        math.log(sig(x - low, 3.0) * sig(high - x, 3.0)), abs=1e-9
    )


def test_log_sigmoid_does_not_overflow():
    assert log_sigmoid(1000.0) == 0.0
    assert log_sigmoid(-1000.0) == pytest.approx(-1000.0)


@given(st.floats(-math.pi, math.pi), st.floats(-math.pi, math.pi))
def test_pointing_same_direction_is_equals_of_the_angle(a, b):
    v, w = (math.sin(a), math.cos(a)), (math.sin(b), math.cos(b))
    angle = math.acos(max(-1.0, min(1.0, v[0] * w[0] + v[1] * w[1])))
    assert pointing_same_direction(*v, *w, 0.1) == pytest.approx(-(angle**2) / 0.2, abs=1e-9)
    assert pointing_same_direction(*v, *v) == pytest.approx(0.0, abs=1e-6)
