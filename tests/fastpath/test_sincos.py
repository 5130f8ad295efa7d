"""fastpath.arithmetic.sincos: sine and cosine in straight-line code, against mpmath."""

import math

import mpmath
import numpy as np
import pytest

from fastpath.arithmetic.phase import MODERATE_LIMIT as SIN_COS_LIMIT
from fastpath.arithmetic.sincos import SIN_COS_ERROR, sin_cos, sin_cos_error

U = 2.0**-53


def _errors(x):
    s, c = sin_cos(float(x))
    with mpmath.workprec(200):
        xs = mpmath.mpf(float(x))
        return abs(mpmath.mpf(s) - mpmath.sin(xs)), abs(mpmath.mpf(c) - mpmath.cos(xs)), s, c


def _quadrant_edges():
    xs = []
    with mpmath.workprec(200):
        for k in list(range(-40, 41)) + [2**10 + 1, 2**16 - 3, 2**19 + 7, 666_665]:
            edge = float(k * mpmath.pi / 4)
            if abs(edge) < SIN_COS_LIMIT:
                xs += [edge, np.nextafter(edge, math.inf), np.nextafter(edge, -math.inf)]
    return xs


@pytest.mark.parametrize("which", ["quadrant edges", "random", "large"])
def test_absolute_error_within_the_stated_bound(which):
    rng = np.random.default_rng(3)
    xs = {"quadrant edges": _quadrant_edges(), "random": rng.uniform(-40, 40, 2000),
          "large": rng.uniform(-SIN_COS_LIMIT, SIN_COS_LIMIT, 1000)}[which]
    worst = max(max(_errors(x)[:2]) for x in xs)
    assert worst <= SIN_COS_ERROR, worst / U


def test_relative_error_near_zero_is_within_one_ulp():
    """Where sin_cos_error says 0, the sine is as good as libm's (relative, < 1.6u)."""
    rng = np.random.default_rng(4)
    xs = np.concatenate([10.0 ** rng.uniform(-300, 0, 2000) * rng.choice([-1, 1], 2000),
                         rng.uniform(-0.78, 0.78, 1000)])
    for x in xs:
        if sin_cos_error(x) != 0.0:
            continue
        es, ec, s, _ = _errors(x)
        assert es <= 1.6 * U * abs(s) and ec <= 1.6 * U, (x, es / (U * abs(s)), ec / U)


def test_extra_error_only_away_from_zero():
    assert sin_cos_error(0.0) == 0.0 and sin_cos_error(-0.7) == 0.0
    assert sin_cos_error(math.pi / 4 * 1.001) == SIN_COS_ERROR
    assert sin_cos_error(-3.0) == SIN_COS_ERROR


def test_quadrants_map_to_the_right_signs():
    for x in np.linspace(-10, 10, 401):
        s, c = sin_cos(x)
        assert abs(s - math.sin(x)) < 1e-15 and abs(c - math.cos(x)) < 1e-15
