"""Bin grid and clock conventions of ``reports.stats.histogram`` against the run's producer."""

import numpy as np

from fastpath.kernels.histogram import bin_index, log_edges
from reports.stats.histogram import bin_means, run_edges, survival_boundaries

BINS = {"collisions": {"first": 1, "decades": 8, "per_decade": 20, "integer": True},
        "time": {"first": 0.1, "decades": 9, "per_decade": 20, "below_first": [0.0, 0.1]}}


def test_grid_is_rebuilt_bit_for_bit_as_the_runner_builds_it():
    assert np.array_equal(run_edges(BINS, "collisions"), log_edges(1.0, 8, 20, integer=True))
    assert np.array_equal(run_edges(BINS, "time"),
                          np.concatenate([[0.0], log_edges(0.1, 9, 20)]))


def test_collision_clock_survival_boundaries_count_escape_indices_exactly():
    """An escape at index N lands in the bin k with x_k < N <= x_{k+1}, so that
    #(N > x_k) = escapes in bins >= k: the survival clock is exact on integers."""
    edges = run_edges(BINS, "collisions")
    x = survival_boundaries(edges, "collisions")
    for n in range(1, 5000):
        k = bin_index(edges, float(n))
        assert x[k] < n <= x[k + 1]


def test_bin_means_of_one_value_bins_are_the_value():
    edges = run_edges(BINS, "collisions")
    means = bin_means(edges, "collisions")
    single = np.flatnonzero(np.diff(edges) == 1)
    assert np.array_equal(means[single], edges[single])
    assert np.isinf(means[-1])
