"""Hazards, survival levels, quantiles and the log-rank hazard ratio of binned curves."""

import math

import numpy as np
import pytest

from reports.stats.calibration import draw
from reports.stats.hazard import (
    all_cause_survival,
    curve_probability,
    hazard,
    hazard_fall,
    hazard_ratio,
    quantile,
)
from reports.stats.histogram import Curve, bin_means, survival_boundaries


def mixture_curve(n=10**7, seed=0):
    """S = 0.999 exp(-0.03 x) + 0.001/x on integer collision bins to 10^4: a fast population
    that empties at a constant rate and a slow one that takes over."""
    edges = np.arange(1, 10_001, dtype=float)
    x = survival_boundaries(edges, "collisions")
    s = 0.999 * np.exp(-0.03 * x[:-1]) + 0.001 / np.maximum(x[:-1], 1.0)
    s[0] = 1.0
    probs = np.append(-np.diff(s), s[-1])
    counts = np.random.default_rng(seed).multinomial(n, probs / probs.sum())
    escapes = np.append(counts[:-1], 0).astype(np.int64)
    censored = np.zeros(len(edges), np.int64)
    censored[-1] = counts[-1]
    return Curve("synthetic", "", "mixture", "collisions", x, escapes,
                 np.zeros(len(edges), np.int64), censored, bin_means(edges, "collisions"), n)


def test_the_hazard_of_an_exponential_is_its_rate():
    curve = draw("exponential", 10**7, np.random.default_rng(1), {"gamma": 0.02})
    groups, lam = hazard(curve)
    big = [v for (a, b), v in zip(groups, lam, strict=True)
           if curve.escapes[a:b].sum() > 10**5]
    assert len(big) >= 5
    assert np.allclose(big, 0.02, rtol=0.01)


def true_fall(factor):
    """x where the exact hazard -S'/S of ``mixture_curve`` first falls to factor * 0.03."""
    x = np.linspace(10, 5000, 200_000)
    s = 0.999 * np.exp(-0.03 * x) + 0.001 / x
    h = (0.03 * 0.999 * np.exp(-0.03 * x) + 0.001 / x**2) / s
    return x[np.argmax(h <= factor * 0.03)]


def test_the_hazard_falls_where_the_slow_population_takes_over():
    """The found boundaries lie within one quarter-decade group of the exact crossings."""
    curve = mixture_curve()
    k_half, plateau = hazard_fall(curve, 10, 0.5)
    k_tenth, _ = hazard_fall(curve, 10, 0.1)
    assert plateau == pytest.approx(0.03, rel=0.05)
    for k, factor in ((k_half, 0.5), (k_tenth, 0.1)):
        assert true_fall(factor) / 10**0.25 <= curve.x[k] <= true_fall(factor) * 10**0.25


def test_survival_and_quantiles():
    curve = mixture_curve(seed=2)
    s = all_cause_survival(curve)
    assert s[0] == 1.0 and np.all(np.diff(s) <= 0)
    assert np.array_equal(curve_probability(curve)[:-1] + 0,
                          curve.escapes[::-1].cumsum()[::-1] / curve.particles)
    q = quantile(curve.x, s, 0.5)
    assert q == pytest.approx(math.log(2 * 0.999) / 0.03, rel=0.02)
    assert quantile(curve.x[:50], s[:50], 1e-3) is None  # not reached within the first bins


def test_hazard_ratio_of_a_curve_with_itself_is_one():
    curve = draw("exponential", 10**6, np.random.default_rng(3), {"gamma": 0.02})
    hr, (lo, hi), used = hazard_ratio(curve, curve, 2, 200)
    assert hr == pytest.approx(1.0, abs=1e-12) and lo < 1 < hi and used > 0
    with pytest.raises(ValueError, match="same bin boundaries"):
        hazard_ratio(curve, mixture_curve(n=1000), 2, 200)
