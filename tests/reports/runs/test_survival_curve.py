"""Survival from histograms, Wilson bands and fits."""

import numpy as np
import pytest

from reports.runs.survival import survival_curve, wilson
from reports.stats.least_squares import fit_survival

EDGES = np.array([1.0, 2.0, 3.0, 5.0, 10.0])


def test_wilson_matches_the_formula():
    lo, hi = wilson(50, 100)
    assert lo == pytest.approx(0.4038, abs=1e-4) and hi == pytest.approx(0.5962, abs=1e-4)
    lo, hi = wilson(0, 100)
    assert lo == 0.0 and hi == pytest.approx(0.0370, abs=1e-4)


def test_escape_survival_counts_later_escapes_and_censored():
    esc = np.array([5, 3, 0, 1, 0])  # escape index 1 (x5), 2 (x3), 5..9 (x1)
    x, surv, p = survival_curve(esc, np.zeros(5, np.int64), EDGES, 10, "collisions", True)
    # P(n) = fraction escaping at an index > n, at n = edge - 1
    assert list(x) == [0, 1, 2, 4, 9]
    assert list(surv) == [9, 4, 1, 1, 0]
    censored = np.array([0, 0, 0, 1, 0])  # one censored in bin [5, 10)
    x, surv, p = survival_curve(esc, censored, EDGES, 10, "collisions", True)
    assert list(x) == [0, 1, 2, 4]  # exact only up to the censoring bin's lower edge
    assert list(surv) == [10, 5, 2, 2]
    assert p[0] == 1.0


def test_transport_curves_do_not_count_the_censored():
    esc = np.array([2, 1, 0, 0, 0])
    x, surv, p = survival_curve(esc, np.array([0, 0, 0, 0, 1]), EDGES, 10, "time", False)
    assert list(x) == [1.0, 2.0, 3.0] and list(surv) == [3, 1, 0]


@pytest.mark.parametrize(("model", "g"), [("exponential", lambda x: x),
                                          ("stretched", np.sqrt), ("power", np.log)])
def test_fits_recover_the_parameters(model, g):
    x = np.linspace(10, 1000, 40)
    p = 0.7 * np.exp(-0.01 * g(x) if model != "power" else -1.5 * g(x))
    n = 10**7
    lo, hi = wilson(np.round(p * n), n)
    fit = fit_survival(x, p, lo, hi, model, (10, 1000))
    b = -1.5 if model == "power" else -0.01
    assert fit.b == pytest.approx(b, rel=1e-3) and fit.a == pytest.approx(0.7, rel=1e-2)
    assert fit.b_err > 0 and fit.points == 40
    with pytest.raises(ValueError, match="fewer than 3"):
        fit_survival(x, p, lo, hi, model, (2000, 3000))
