"""The physics-placed windows of an escape curve on synthetic data."""

import math

import numpy as np
import pytest

from reports.paper.studies.escape_regimes import diffusive_onset, escape_windows
from reports.stats.histogram import Curve, bin_means, survival_boundaries


def test_the_diffusive_onset_is_where_the_local_slope_reaches_the_law():
    """<v> flat to t = 1000, then ~ t^(1/3): the onset is the first grid point whose next half
    decade slopes within 10% of 1/3, half a decade before the bend at the latest."""
    t = np.logspace(0, 6, 61)
    v = np.where(t < 1e3, 3.0, 3.0 * (t / 1e3) ** (1 / 3))
    onset = diffusive_onset(t, v, 1 / 3)
    assert 1e3 / 10**0.5 <= onset <= 1e3
    assert math.isnan(diffusive_onset(t, np.full_like(t, 3.0), 1 / 3))


def curves(n=10**8, seed=0):
    """One population of particles with a per-collision escape rate 0.03 and a time per
    collision drawn per particle, plus a slow population (1e-5 of them) escaping as n^-1.5."""
    rng = np.random.default_rng(seed)
    fast = rng.geometric(0.03, n - n // 10**5)
    slow = np.floor(rng.pareto(1.5, n // 10**5) * 300 + 300).astype(np.int64)
    coll = np.concatenate([fast, slow])
    time = coll * rng.uniform(4.0, 8.0, len(coll)) * np.sqrt(coll) ** 0.5
    out = {}
    for clock, values in (("collisions", coll.astype(float)), ("time", time)):
        edges = (np.unique(np.round(np.logspace(0, 7, 141))) if clock == "collisions" else
                 np.concatenate([[0.0], np.logspace(-1, 8, 181)]))
        x = survival_boundaries(edges, clock)
        k = np.searchsorted(edges, values, side="right") - 1
        esc = np.bincount(k, minlength=len(edges)).astype(np.int64)
        out[clock] = Curve("synthetic", "h", "h", clock, x, esc, np.zeros_like(esc),
                           np.zeros_like(esc), bin_means(edges, clock), len(values))
    return out


@pytest.mark.slow
def test_the_intermediate_window_ends_before_the_slow_population_and_the_tail_after():
    c = curves(n=10**7)
    w = escape_windows("h", c["collisions"], c["time"], onset_t=100.0)
    a, b = w.n["intermediate"]
    ta, tb = w.n["tail"]
    assert c["collisions"].x[a] == pytest.approx(w.onset_n)
    assert c["collisions"].x[b] <= c["collisions"].x[ta]
    assert w.plateau == pytest.approx(-math.log(1 - 0.03), rel=0.05)
    assert w.level_fast > w.level_half >= w.level_tail
