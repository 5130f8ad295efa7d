"""Maximum likelihood on binned, censored counts: exactness, intervals, independent cross-checks.

Exactness: fitted to the *expected* counts N p_j of a law (non-integer counts are fine), the
maximum-likelihood estimate is the true parameter (it minimises the Kullback-Leibler divergence,
zero at the truth), up to the optimiser's resolution: the scale to rtol ~1e-13 (Newton in a
bracket); beta by a golden section on l(beta), which resolves beta only to
sqrt(2 m u |l| / |l''|) (function values carry m u |l| of rounding over m bins).
"""

import math

import numpy as np
import pytest

from reports.stats.calibration import draw, grid_edges, survival
from reports.stats.histogram import Curve, bin_means, survival_boundaries
from reports.stats.likelihood import Q95, cell_log_probs, fit_law, window_of

U = 2.0**-53


def expected_curve(law, params, n=1e6, horizon=1e4):
    """Curve holding the expected counts of ``law`` (collision grid, censored at horizon)."""
    edges = grid_edges()
    x = survival_boundaries(edges, "collisions")
    h = int(np.searchsorted(edges, horizon))
    s = survival(law, params, x[: h + 1])
    escapes = np.zeros(len(edges))
    censored = np.zeros(len(edges))
    escapes[:h] = -np.diff(s) * n
    censored[h] = s[-1] * n
    return Curve("expected", "", law, "collisions", x, escapes, 0 * escapes, censored,
                 bin_means(edges, "collisions"), int(n)), h


@pytest.mark.parametrize("law, params", [
    ("exponential", {"gamma": 0.02}),
    ("power_law", {"alpha": 1.5}),
])
def test_one_parameter_laws_recover_the_truth_from_expected_counts(law, params):
    curve, h = expected_curve(law, params)
    fit = fit_law(law, window_of(curve, 1, h))
    (name, true), = params.items()
    assert fit.params[name] == pytest.approx(true, rel=1e-12)
    lo, hi = fit.ci95[name]
    assert lo < true < hi


def test_stretched_law_recovers_the_truth_from_expected_counts():
    true = {"c": 0.5, "beta": 0.5}
    curve, h = expected_curve("stretched_exponential", true)
    w = window_of(curve, 1, h)
    fit = fit_law("stretched_exponential", w)
    lo, hi = fit.ci95["beta"]
    curvature = (2 * 1.959963984540054 / (hi - lo)) ** 2  # |l''| from the interval's width
    resolution = math.sqrt(2 * len(w.escapes) * U * abs(fit.loglik) / curvature)
    assert abs(fit.params["beta"] - true["beta"]) <= 10 * resolution
    # c = s/beta (x_a = 1) inherits beta's error through 1/beta and the ridge of l in (s, beta),
    # whose slope d log s / d beta is at most the log-range of the window
    log_range = math.log(w.end / w.start)
    assert fit.params["c"] == pytest.approx(true["c"],
                                            rel=10 * resolution * (1 / true["beta"] + log_range))
    assert fit.ci95["c"][0] < true["c"] < fit.ci95["c"][1]


def test_stretched_law_is_the_exponential_at_beta_one_and_the_power_law_at_zero():
    curve, h = expected_curve("exponential", {"gamma": 0.02})
    w = window_of(curve, 1, h)
    s, e = fit_law("stretched_exponential", w), fit_law("exponential", w)
    assert s.loglik >= e.loglik - 1e3 * U * abs(e.loglik)
    assert s.loglik - e.loglik < 1e-6  # nothing to gain: the truth is inside both
    curve, h = expected_curve("power_law", {"alpha": 1.5})
    w = window_of(curve, 1, h)
    s, p = fit_law("stretched_exponential", w), fit_law("power_law", w)
    assert s.params["beta"] == 0.0 and s.params["c"] == math.inf
    assert s.loglik == pytest.approx(p.loglik, rel=1e3 * U)
    assert s.ci95["c"][1] == math.inf


def test_profile_interval_ends_are_where_the_likelihood_drops_by_q95():
    rng = np.random.default_rng(3)
    curve = draw("exponential", 10_000, rng)
    w = window_of(curve, 1, int(np.flatnonzero(curve.escapes)[-1]) + 1)
    fit = fit_law("exponential", w)
    for end in fit.ci95["gamma"]:
        at = fit_law("exponential", w, intervals=False)
        bins, points = cell_log_probs("exponential", end, None, w)  # the log-likelihood at end
        at_end = float(np.dot(w.escapes, bins) + np.dot(w.weights, points))
        assert at.loglik - at_end == pytest.approx(Q95, rel=1e-8)


def test_interval_width_scales_as_one_over_root_n():
    widths = []
    for n in (1e4, 1e6):
        curve, h = expected_curve("power_law", {"alpha": 1.5}, n=n)
        lo, hi = fit_law("power_law", window_of(curve, 1, h)).ci95["alpha"]
        widths.append(hi - lo)
    assert widths[0] / widths[1] == pytest.approx(10.0, rel=0.01)  # O(1/sqrt(N)) asymmetry


def test_competing_escapes_censor_at_their_bin_mean():
    """Two independent exponential risks with rates g1, g2 on one-value bins (n = 1..30, where
    the bin mean is exact): cause 1 alone, the other cause as censoring, recovers g1."""
    g1, g2, n = 0.05, 0.15, 1e7
    edges = np.arange(1.0, 40.0)
    x = survival_boundaries(edges, "collisions")
    k = np.arange(len(edges), dtype=np.float64)  # x_k = k: survive k collisions of both
    both = np.exp(-(g1 + g2) * k)
    # collision m = k + 1 leaves through cause 1 if X1 = m (X2 >= m), through cause 2 if X2 = m
    # and X1 > m: a particle that left through hole 2 at m was not in hole 1 at m
    p1 = both * (1 - np.exp(-g1))
    p2 = both * np.exp(-g1) * (1 - np.exp(-g2))
    e1, e2 = p1 * n, p2 * n
    cens = np.zeros(len(edges))
    cens[-1] = n - e1[:-1].sum() - e2[:-1].sum()
    e1[-1] = e2[-1] = 0
    curve = Curve("two-risk", "", "P1", "collisions", x, e1, e2, cens,
                  bin_means(edges, "collisions"), int(n))
    fit = fit_law("exponential", window_of(curve, 1, 30))
    assert fit.params["gamma"] == pytest.approx(g1, rel=1e-10)


@pytest.mark.slow
def test_lifelines_weibull_agrees_on_a_censored_sample():
    lifelines = pytest.importorskip("lifelines")
    rng = np.random.default_rng(11)
    c, beta, n, x0, horizon = 0.3, 0.6, 20_000, 0.5, 200.0
    t = (rng.exponential(size=n) / c) ** (1 / beta)
    t = t[t > x0]  # left-truncated at x0 for both fitters
    observed = t < horizon
    t_obs = np.minimum(t, horizon)
    fitter = lifelines.WeibullFitter().fit(t_obs, observed, entry=np.full(len(t), x0))
    rho, lam = fitter.rho_, fitter.lambda_  # S = exp(-(t/lam)**rho)
    sd_rho = float(fitter.summary.loc["rho_", "se(coef)"])
    per_decade = 400
    edges = x0 * 10 ** (np.arange(0, int(per_decade * math.log10(horizon / x0)) + 1)
                        / per_decade)
    edges[-1] = horizon
    escapes = np.histogram(t[observed], np.append(edges, np.inf))[0]
    censored = np.zeros(len(edges), dtype=np.int64)
    censored[-1] = (~observed).sum()
    curve = Curve("sample", "", "weibull", "time", survival_boundaries(edges, "time"), escapes,
                  0 * escapes, censored, bin_means(edges, "time"), len(t))
    fit = fit_law("stretched_exponential", window_of(curve, 0, len(edges) - 1))
    # binning at relative width d = 10**(1/400) - 1 = 0.58% loses O(d**2) of the information:
    # the two estimates differ by a small fraction of the standard error
    assert abs(fit.params["beta"] - rho) < 0.1 * sd_rho
    # log c = -rho log lam: its standard error from lifelines' covariance (delta method)
    cov = fitter.variance_matrix_.loc[["lambda_", "rho_"], ["lambda_", "rho_"]].to_numpy()
    grad = np.array([-rho / lam, -math.log(lam)])
    sd_log_c = math.sqrt(grad @ cov @ grad)
    assert abs(math.log(fit.params["c"]) + rho * math.log(lam)) < 0.1 * sd_log_c


def test_powerlaw_package_agrees_on_a_continuous_sample():
    powerlaw = pytest.importorskip("powerlaw")
    rng = np.random.default_rng(12)
    alpha, x0, n = 1.5, 2.0, 20_000
    sample = x0 * rng.random(n) ** (-1 / alpha)
    exponent = powerlaw.Fit(sample, xmin=x0, discrete=False, verbose=False).power_law.alpha
    sd = (exponent - 1) / math.sqrt(n)  # of the pdf exponent alpha + 1 (CSN eq. 3.2)
    per_decade = 400
    edges = x0 * 10 ** (np.arange(0, 8 * per_decade + 1) / per_decade)
    escapes = np.histogram(sample, np.append(edges, np.inf))[0]
    curve = Curve("sample", "", "power", "time", survival_boundaries(edges, "time"), escapes,
                  0 * escapes, 0 * escapes, bin_means(edges, "time"), n)
    last = int(np.flatnonzero(escapes)[-1]) + 1
    fit = fit_law("power_law", window_of(curve, 0, last))
    assert abs(fit.params["alpha"] + 1 - exponent) < 0.1 * sd


def test_a_stretched_fit_with_its_exponent_fixed_recovers_c_within_its_interval():
    """exp(-c t^(1/2)) with beta = 1/2 held: the paper's c_2 is such a fit."""
    from reports.stats.analysis import usable_range
    from reports.stats.calibration import draw
    from reports.stats.likelihood import fit_stretched_fixed, window_of

    c = draw("stretched_exponential", 10**6, np.random.default_rng(0), {"c": 0.5, "beta": 0.5})
    fit = fit_stretched_fixed(window_of(c, *usable_range(c)), 0.5)
    lo, hi = fit.ci95["c"]
    assert fit.params["beta"] == 0.5 and lo < 0.5 < hi and hi - lo < 0.01
    with pytest.raises(ValueError, match="must be > 0"):
        fit_stretched_fixed(window_of(c, *usable_range(c)), 0.0)
