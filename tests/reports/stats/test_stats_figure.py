"""The fit figure draws what a reader can see, not every bin; interval ends the data do not
bound are printed in words."""

import io

import numpy as np
import pytest

from reports.stats import figure
from reports.stats.analysis import analyse, interval_text
from reports.stats.histogram import Curve, bin_means, survival_boundaries
from reports.stats.likelihood import BETA_MAX


def test_a_window_of_few_bins_is_drawn_bin_by_bin():
    x = np.geomspace(1.0, 100.0, 51)
    assert np.array_equal(figure.display_boundaries(x), np.arange(51))


def test_many_bins_are_thinned_evenly_in_log_x_keeping_both_ends():
    x = np.geomspace(1.0, 1e6, 100_001)
    kept = figure.display_boundaries(x)
    assert kept[0] == 0 and kept[-1] == len(x) - 1
    assert len(kept) <= figure.DISPLAY_POINTS + 1 and np.all(np.diff(kept) > 0)
    steps = np.diff(np.log10(x[kept]))
    assert steps.max() <= 1.01 * 6 / figure.DISPLAY_POINTS  # no gap wider than one step


def test_group_sums_add_every_bin_once():
    values = np.arange(1.0, 11.0)
    kept = np.array([0, 3, 4, 10])
    assert figure.group_sums(values, kept).tolist() == [6.0, 4.0, 45.0]
    assert figure.group_sums(values, np.arange(11)).tolist() == values.tolist()


def stretched_curve(bins, n=10**9, seed=1):
    edges = np.concatenate([[0.0], np.geomspace(1.0, 1e6, bins)])
    s = np.exp(-np.sqrt(edges / 1.9e3))
    probs = np.append(-np.diff(s), s[-1])
    counts = np.random.default_rng(seed).multinomial(n, probs / probs.sum())
    escapes = np.append(counts[:-1], 0).astype(np.int64)
    censored = np.zeros(len(edges), np.int64)
    censored[-1] = counts[-1]
    return Curve("s.csv", "", "s", "time", survival_boundaries(edges, "time"), escapes,
                 np.zeros(len(edges), np.int64), censored, bin_means(edges, "time"), n)


@pytest.mark.slow
def test_the_figure_draws_no_more_points_for_ten_times_more_bins(monkeypatch):
    """At most DISPLAY_POINTS survival points and residual groups per law, LAW_POINTS per law's
    line, whatever the number of bins; the PNG is valid."""
    figures = []
    monkeypatch.setattr(figure.plt, "close", figures.append)
    drawn = {}
    for bins in (1000, 10_000):
        curve = stretched_curve(bins)
        result = analyse(curve)
        buffer = io.BytesIO()
        figure.plot_curve(result, curve, buffer)
        assert buffer.getvalue()[:8] == b"\x89PNG\r\n\x1a\n"
        axes = figures.pop().axes
        drawn[bins] = sum(len(line.get_xdata()) for ax in axes for line in ax.lines) + sum(
            len(c.get_segments()) for ax in axes for c in ax.collections)
    laws = 3
    bound = laws * (figure.LAW_POINTS + figure.DISPLAY_POINTS) + 2 * (figure.DISPLAY_POINTS + 1)
    assert drawn[1000] <= bound + 10 and drawn[10_000] <= bound + 10, drawn


@pytest.mark.parametrize(("model", "name", "text"), [
    ({"c": 8.9, "c_ci95": (1.156, 7.888e15), "beta": 0.065, "beta_ci95": (0.0, 0.28)}, "c",
     "[1.156, unbounded: beta's interval reaches 0, the power law]"),
    ({"c": 8.9, "c_ci95": (1.156, 7.888e15), "beta": 0.065, "beta_ci95": (0.0, 0.28)}, "beta",
     "[0 (the power law), 0.28]"),
    ({"c": 0.1, "c_ci95": (0.05, 0.2), "beta": 4.0, "beta_ci95": (2.8, BETA_MAX)}, "beta",
     "[2.8, 4 (the largest beta fitted)]"),
    ({"c": 0.1, "c_ci95": (0.05, 0.2), "beta": 0.5, "beta_ci95": (0.4, 0.6)}, "c",
     "[0.05, 0.2]"),
    ({"gamma": 0.1, "gamma_ci95": (0.05, None)}, "gamma", "[0.05, unbounded]"),
    ({"gamma": 0.1, "gamma_ci95": (0.05, float("inf"))}, "gamma", "[0.05, unbounded]"),
])
def test_interval_ends_the_data_do_not_bound_are_words(model, name, text):
    assert interval_text(model, name) == text
