"""The regime search on many bins: a bounded grid of merged bins, the same counts, the right
crossover, progress reported, and its cost (``bouncer fit`` on 10^4 bins in seconds)."""

import time

import numpy as np
import pytest

from reports.stats import regimes as rg
from reports.stats.analysis import analyse, best_law_text
from reports.stats.histogram import Curve, bin_means, survival_boundaries


def two_regime_curve(bins=5000, n=10**8, seed=0):
    """Log-spaced time bins over [1, 1e6]: exponential decay exp(-(t - 1)/20) to t = 100, then
    a power law t^-2 (continuous at t = 100)."""
    edges = np.concatenate([[0.0], np.geomspace(1.0, 1e6, bins)])
    x = survival_boundaries(edges, "time")
    t = np.maximum(x[:-1], 1.0)
    s100 = np.exp(-99 / 20)
    s = np.where(t < 100, np.exp(-(t - 1) / 20), s100 * (t / 100) ** -2.0)
    probs = np.append(-np.diff(s), s[-1])
    counts = np.random.default_rng(seed).multinomial(n, probs / probs.sum())
    escapes = np.append(counts[:-1], 0).astype(np.int64)
    censored = np.zeros(len(edges), np.int64)
    censored[-1] = counts[-1]
    return Curve("synthetic", "", f"two regimes {bins}", "time", x, escapes,
                 np.zeros(len(edges), np.int64), censored, bin_means(edges, "time"), n)


def test_the_search_grid_is_bounded_and_merging_keeps_every_count():
    curve = two_regime_curve()
    grid = rg.search_grid(curve, 1, 2000)
    assert len(grid) - 1 <= rg.SEARCH_BINS and grid[0] == 1 and grid[-1] == 2000
    coarse = rg.merged(curve, grid)
    assert curve.escapes[2000] > 0  # the bin after the grid must not leak in
    assert coarse.escapes.sum() == curve.escapes[1:2000].sum()
    assert coarse.escapes[0] == curve.escapes[1:grid[1]].sum()
    assert np.array_equal(coarse.x, curve.x[grid])
    small = rg.search_grid(curve, 10, 100)
    assert np.array_equal(small, np.arange(10, 101))


@pytest.mark.slow
def test_the_crossover_is_found_on_the_merged_grid_and_progress_is_reported():
    curve = two_regime_curve()
    said = []
    result = analyse(curve, progress=said.append)
    xs = [c["x"] for c in result["crossovers"]]
    assert any(80 <= x <= 125 for x in xs), xs
    assert said[0].startswith("regime search over") and "merged bins" in said[0]
    assert any(s.startswith("crossover at x =") for s in said)
    assert result["best"] in ("power_law", "stretched_exponential")


def test_a_boundary_fit_is_shown_as_the_power_law_never_as_c_inf():
    result = {"best": "stretched_exponential",
              "models": {"stretched_exponential": {"c": None, "c_ci95": [None, None],
                                                   "beta": 0.0, "beta_ci95": [0.0, 0.01]},
                         "power_law": {"alpha": 2.0, "alpha_ci95": [1.9, 2.1]},
                         "exponential": {"gamma": 0.1, "gamma_ci95": [0.09, 0.11]}}}
    text = best_law_text(result)
    assert text.startswith("power law (alpha=2") and "c=inf" not in text
    result["best"] = "inconclusive"
    text = best_law_text(result)
    assert text.startswith("inconclusive") and "c=" not in text


@pytest.mark.slow
def test_ten_thousand_bins_are_analysed_in_seconds():
    """The cost of ``analyse`` (what ``bouncer fit`` runs per curve) on 10^4 bins, after the
    kernels are compiled: under 10 s on two cores (about 5 s measured on a shared machine)."""
    analyse(two_regime_curve(bins=300, seed=1))
    curve = two_regime_curve(bins=10_000, seed=2)
    t0 = time.perf_counter()
    analyse(curve)
    assert time.perf_counter() - t0 < 10.0
