"""Bin grid and clock conventions of ``reports.stats.histogram`` against the run's producer."""

import json

import numpy as np
import pytest

from fastpath.kernels.histogram import bin_index, log_edges
from reports.stats.histogram import bin_means, read_run, run_edges, survival_boundaries
from tests.reports.cli.test_fit_cli import manifest_of

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


def _write_time_run(folder, nudge=0):
    """A run directory in the runner's format, one experiment of three particles on the time
    clock, its recorded lower edges the grid's edges; ``nudge`` moves the second recorded edge
    by that many units in the last place."""
    edges = run_edges(BINS, "time")
    second = float(edges[40])
    for _ in range(abs(nudge)):
        second = float(np.nextafter(second, np.inf if nudge > 0 else -np.inf))
    rows = ["experiment,clock,outcome,lower_edge,count",
            f"exp,time,A,{float(edges[20])!r},1", f"exp,time,A,{second!r},1",
            f"exp,time,censored,{float(edges[60])!r},1"]
    folder.mkdir()
    manifest = manifest_of("escape", {"exp": {"particles_done": 3, "censored": 1, "stuck": 0,
                                              "escaped": {"A": 2}}}, 3)
    (folder / "manifest.json").write_text(json.dumps(manifest))
    (folder / "counts.csv").write_text("\n".join(rows) + "\n")
    return folder


def test_a_recorded_edge_must_be_the_grids_edge_exactly(tmp_path):
    """The grid is the correctly rounded one on every machine (``log_edges``), so a recorded
    edge one unit in the last place off it is not a grid edge: refused, never matched."""
    (curve,) = read_run(_write_time_run(tmp_path / "exact"), clocks=("time",))
    assert curve.escapes.sum() == 2 and curve.censored.sum() == 1
    for nudge in (1, -1):
        with pytest.raises(ValueError, match="is not on the manifest's bin grid"):
            read_run(_write_time_run(tmp_path / f"off{nudge}", nudge), clocks=("time",))
