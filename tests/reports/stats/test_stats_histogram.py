"""Bin grid and clock conventions of ``reports.stats.histogram`` against the run's producer."""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from fastpath.kernels.histogram import bin_index, log_edges
from reports.stats.histogram import bin_means, grid_index, read_run, run_edges, survival_boundaries

ROOT = Path(__file__).resolve().parents[3]

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


def test_a_recorded_edge_a_few_ulps_off_the_grid_is_that_grid_edge():
    """numpy's vectorised power can differ in the last bits between machines: a run's counts
    stay readable on another machine, and an edge truly off the grid is still refused."""
    edges = run_edges(BINS, "time")
    k = 50
    assert grid_index(edges, edges[k]) == k
    assert grid_index(edges, float(np.nextafter(np.nextafter(edges[k], 0), 0))) == k
    assert grid_index(edges, edges[k] * (1 + 1e-9)) is None
    assert grid_index(edges, 0.0) == 0


def test_a_run_whose_edges_differ_in_the_last_bits_reads_the_same(tmp_path):
    src = ROOT / "docs" / "report" / "runs" / "escape-island-start-20000"
    shutil.copytree(src, tmp_path / "run")
    counts = tmp_path / "run" / "counts.csv"
    rows = counts.read_text().splitlines()
    moved = [rows[0]] + [",".join([*r.split(",")[:3], repr(float(np.nextafter(
        float(r.split(",")[3]), math.inf))), r.split(",")[4]]) for r in rows[1:]]
    counts.write_text("\n".join(moved) + "\n")
    before, after = read_run(src), read_run(tmp_path / "run")
    assert len(before) == len(after)
    for a, b in zip(before, after, strict=True):
        assert np.array_equal(a.escapes, b.escapes) and np.array_equal(a.censored, b.censored)
    rows[1] = ",".join([*rows[1].split(",")[:3], "1.2345", rows[1].split(",")[4]])
    counts.write_text("\n".join(rows) + "\n")
    with pytest.raises(ValueError, match="not on the manifest's bin grid"):
        read_run(tmp_path / "run")
