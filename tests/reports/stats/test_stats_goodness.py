"""Pearson's chi-squared of a fitted law: it rejects a wrong law and not the true one."""

import numpy as np

from reports.stats.analysis import fit_all, usable_range
from reports.stats.calibration import draw
from reports.stats.goodness import pearson
from reports.stats.likelihood import window_of


def fits(law, params, seed, n=10**5):
    c = draw(law, n, np.random.default_rng(seed), params)
    return fit_all(window_of(c, *usable_range(c)), intervals=False)


def test_the_true_law_is_rejected_at_five_percent_about_one_time_in_twenty():
    ps = [pearson(fits("stretched_exponential", {"c": 0.5, "beta": 0.5}, s)
                  ["stretched_exponential"]).p for s in range(30)]
    assert 0.2 < np.median(ps) < 0.8
    assert np.mean(np.array(ps) < 0.05) <= 0.2


def test_a_wrong_law_is_rejected_beyond_doubt():
    f = fits("stretched_exponential", {"c": 0.5, "beta": 0.5}, 1)
    for law in ("exponential", "power_law"):
        g = pearson(f[law])
        assert g.p < 1e-6 and g.chi2 / g.dof > 5


def test_degrees_of_freedom_are_the_groups_less_the_parameters():
    g = pearson(fits("power_law", {"alpha": 1.5}, 2)["power_law"])
    assert g.dof == g.groups - 1 and g.groups >= 5
