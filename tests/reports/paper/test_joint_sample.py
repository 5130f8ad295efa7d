"""Joint (n, t) data as weighted points: a study's particles, a joint histogram's cells."""

import math

import numpy as np

from reports.paper.joint_sample import (
    binned_slope,
    bootstrap_interval,
    from_joint,
    weighted_quantile,
)


def test_weighted_quantiles_count_each_point_by_its_weight():
    assert weighted_quantile(np.array([1.0, 2.0, 3.0]), np.array([1.0, 1.0, 10.0]), 0.5) == 3.0
    assert weighted_quantile(np.array([1.0, 2.0, 3.0]), np.ones(3), 0.5) == 2.0


def test_a_binned_slope_finds_a_power_law():
    rng = np.random.default_rng(0)
    t = 10 ** rng.uniform(2, 4, 20000)
    n = t ** 0.5 * rng.lognormal(0, 0.2, len(t))
    slope, bins = binned_slope(t, n, np.ones(len(t)), 100.0, 1e4)
    assert abs(slope - 0.5) < 0.02 and bins == 8


def test_a_joint_histogram_gives_the_same_slope_as_its_particles():
    """The median of a cell-binned variable is interpolated inside its cell: its bootstrap
    interval does not collapse onto the cell's centre."""
    rng = np.random.default_rng(1)
    t = 10 ** rng.uniform(2, 4, 50000)
    n = np.maximum(1, np.round(t ** 0.5 * rng.lognormal(0, 0.2, len(t))))
    n_edges = np.unique(np.round(np.geomspace(1, 1e3, 61)))
    t_edges = np.concatenate([[0.0], np.geomspace(0.1, 1e5, 121)])
    counts = np.zeros((2, len(n_edges), len(t_edges)), np.int64)
    np.add.at(counts, (0, np.searchsorted(n_edges, n, "right") - 1,
                       np.searchsorted(t_edges, t, "right") - 1), 1)
    s = from_joint(n_edges, t_edges, counts, len(t), "synthetic joint record")
    assert s.count == len(t) and np.all(s.exit == 0)
    particles = binned_slope(t, n, np.ones(len(t)), 100.0, 1e4)[0]

    def slope(x):
        return binned_slope(x.t, x.n, x.weight, 100.0, 1e4, y_width=x.dn)[0]
    assert abs(slope(s) - particles) < 0.02
    lo, hi = bootstrap_interval(s, slope, reps=40)
    assert lo < slope(s) < hi and math.isfinite(lo)
