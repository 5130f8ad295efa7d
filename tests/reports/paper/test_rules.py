"""Each decision rule of the paper's claims on synthetic data whose answer is known.

Curves are drawn from a known law (``reports.stats.calibration.draw``: one multinomial draw of
N particles over log bins, censored at n = 1e5), fitted by maximum likelihood on the whole
usable range and judged by the rule a claim of the register uses. Seeds are fixed; sizes are
chosen so that the known answer is far from the rule's edges (the widened interval's half
width at N = 10^6 is about 0.01 in beta), so the tests are deterministic in effect.
"""

import math

import numpy as np
import pytest

from reports.paper.claims import rules as R
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.start_claims import HR_BAND, HR_FAILS_BAND
from reports.paper.claims.transport_claims import finite_time_verdict
from reports.stats.analysis import usable_range
from reports.stats.calibration import draw
from reports.stats.hazard import hazard_ratio
from reports.stats.histogram import Curve, bin_means, survival_boundaries
from reports.stats.regime_fit import window_detail


def detail_of(law, params, n=10**6, seed=1):
    curve = draw(law, n, np.random.default_rng(seed), params)
    return curve, window_detail(curve, *usable_range(curve))


@pytest.fixture(scope="module")
def stretched_052():
    return detail_of("stretched_exponential", {"c": 0.5, "beta": 0.52})


def test_a_stretched_law_with_beta_052_is_close_to_sqrt(stretched_052):
    verdict, beta, *_ = R.form_verdict(stretched_052[1], "sqrt", R.MIN_ESCAPES_INTERMEDIATE,
                                       close=True)
    assert abs(beta - 0.52) < 0.02
    assert verdict == CONFIRMED


def test_a_stretched_law_with_beta_08_is_not_close_to_sqrt():
    _, d = detail_of("stretched_exponential", {"c": 0.2, "beta": 0.8})
    assert R.form_verdict(d, "sqrt", R.MIN_ESCAPES_INTERMEDIATE, close=True)[0] == REFUTED


def test_the_sqrt_law_is_neither_exponential_nor_algebraic(stretched_052):
    d = stretched_052[1]
    assert R.form_verdict(d, "exponential", R.MIN_ESCAPES_INTERMEDIATE)[0] == REFUTED
    assert R.form_verdict(d, "power_law", R.MIN_ESCAPES_TAIL)[0] == REFUTED


def test_exponential_data_are_exponential_and_not_algebraic():
    _, d = detail_of("exponential", {"gamma": 0.02})
    assert R.form_verdict(d, "exponential", R.MIN_ESCAPES_INTERMEDIATE)[0] == CONFIRMED
    assert R.form_verdict(d, "power_law", R.MIN_ESCAPES_TAIL)[0] == REFUTED


def test_power_law_data_are_algebraic():
    _, d = detail_of("power_law", {"alpha": 1.5})
    assert R.form_verdict(d, "power_law", R.MIN_ESCAPES_TAIL)[0] == CONFIRMED
    assert R.form_verdict(d, "exponential", R.MIN_ESCAPES_INTERMEDIATE)[0] == REFUTED


def test_a_window_with_too_few_escapes_is_inconclusive(stretched_052):
    curve, d = detail_of("stretched_exponential", {"c": 0.5, "beta": 0.52}, n=300, seed=4)
    assert d["escapes"] < R.MIN_ESCAPES_INTERMEDIATE
    assert R.form_verdict(d, "sqrt", R.MIN_ESCAPES_INTERMEDIATE, close=True)[0] == INCONCLUSIVE
    # the minimum decides even where the interval alone would (it rules out a lucky window)
    few = {**stretched_052[1], "escapes": R.MIN_ESCAPES_INTERMEDIATE - 1}
    assert R.form_verdict(few, "sqrt", R.MIN_ESCAPES_INTERMEDIATE, close=True)[0] == INCONCLUSIVE


def test_well_approximated_needs_the_law_to_win_and_to_stay_near_the_data(stretched_052):
    curve, d = stretched_052
    verdict, excess = R.well_approximated_verdict(curve, d, "stretched_exponential",
                                                  R.MIN_ESCAPES_TAIL)
    assert verdict == CONFIRMED and excess <= R.RESIDUAL_LEVEL
    curve, d = detail_of("power_law", {"alpha": 1.5}, seed=2)
    assert R.well_approximated_verdict(curve, d, "stretched_exponential",
                                       R.MIN_ESCAPES_TAIL)[0] == REFUTED


def test_the_noise_of_a_small_sample_is_not_a_departure_from_its_law():
    """1000 particles of a stretched law: the life table wanders by its statistical noise, which
    the 95% band absorbs (in this draw every boundary stays inside it: excess exactly 0)."""
    curve, d = detail_of("stretched_exponential", {"c": 0.5, "beta": 0.52}, n=1000, seed=8)
    verdict, excess = R.well_approximated_verdict(curve, d, "stretched_exponential",
                                                  R.MIN_ESCAPES_TAIL)
    assert excess == 0.0
    assert verdict in (CONFIRMED, INCONCLUSIVE)  # inconclusive if a simple law is not rejected


@pytest.mark.slow
def test_a_sharp_bend_is_not_well_approximated_by_one_law():
    """An exponential followed by a much slower exponential (a sharp bend): the stretched law
    wins against both simple laws but misses the bend by far more than 10%."""
    edges = np.arange(1, 2001, dtype=float)
    x = survival_boundaries(edges, "collisions")
    s = 0.99 * np.exp(-0.05 * x[:-1]) + 0.01 * np.exp(-0.002 * x[:-1])
    probs = np.append(-np.diff(s), s[-1])
    counts = np.random.default_rng(3).multinomial(10**6, probs / probs.sum())
    escapes = np.append(counts[:-1], 0).astype(np.int64)
    censored = np.zeros(len(edges), np.int64)
    censored[-1] = counts[-1]
    curve = Curve("synthetic", "", "bend", "collisions", x, escapes,
                  np.zeros(len(edges), np.int64), censored, bin_means(edges, "collisions"),
                  10**6)
    d = window_detail(curve, 1, len(edges) - 1)
    assert d["best"] == "stretched_exponential"
    verdict, excess = R.well_approximated_verdict(curve, d, "stretched_exponential",
                                                  R.MIN_ESCAPES_TAIL)
    assert verdict == REFUTED and excess > R.RESIDUAL_LEVEL


@pytest.mark.parametrize(("lo", "hi", "expected"), [
    (0.45, 0.55, CONFIRMED), (0.61, 0.7, REFUTED), (0.55, 0.65, INCONCLUSIVE),
    (math.nan, 0.5, INCONCLUSIVE)])
def test_band_verdict(lo, hi, expected):
    assert R.band_verdict(lo, hi, 0.4, 0.6) == expected


def test_a_finite_time_curve_is_recognised_and_an_exponential_is_not():
    """Escape times uniform on [0, 30] end sharply (every law predicts survivors beyond the
    last escape); an exponential of the same mean does not end."""
    edges = np.concatenate([[0.0], np.geomspace(0.1, 1e7, 161)])
    x = survival_boundaries(edges, "time")
    rng = np.random.default_rng(5)

    def curve_of(s):
        probs = -np.diff(np.append(s, 0.0))
        counts = rng.multinomial(10**7, probs / probs.sum())
        return Curve("synthetic", "e", "all", "time", x, counts.astype(np.int64),
                     np.zeros(len(edges), np.int64), np.zeros(len(edges), np.int64),
                     bin_means(edges, "time"), 10**7)

    finite = curve_of(np.clip(1.0 - x[:-1] / 30.0, 0.0, 1.0))
    verdict, text, _ = finite_time_verdict(finite)
    assert verdict == CONFIRMED, text
    endless = curve_of(np.exp(-x[:-1] / 15.0))
    assert finite_time_verdict(endless)[0] == INCONCLUSIVE


def test_equal_hazards_are_the_same_and_a_30_percent_faster_one_is_not():
    rng = np.random.default_rng(6)
    a = draw("exponential", 10**6, rng, {"gamma": 0.02})
    b = draw("exponential", 10**6, rng, {"gamma": 0.02})
    c = draw("exponential", 10**6, rng, {"gamma": 0.026})
    lo_, hi_ = usable_range(a)
    hr, ci, _ = hazard_ratio(a, b, lo_, hi_ - 20)
    assert R.two_band_verdict(*ci, HR_BAND, HR_FAILS_BAND) == CONFIRMED and ci[0] < 1 < ci[1]
    hr, ci, _ = hazard_ratio(a, c, lo_, hi_ - 20)
    assert hr == pytest.approx(1.3, abs=0.02)
    assert R.two_band_verdict(*ci, HR_BAND, HR_FAILS_BAND) == REFUTED


@pytest.mark.parametrize(("k", "n", "expected_at_most"), [
    (0, 10**8, CONFIRMED), (1000, 10**8, REFUTED), (100, 10**8, INCONCLUSIVE)])
def test_a_share_left_at_the_horizon_against_its_floor(k, n, expected_at_most):
    from reports.runs.survival import wilson

    ci = tuple(float(v) for v in wilson(k, n))
    assert R.fraction_at_most(k, n, R.ESCAPED_TO, ci) == expected_at_most


def test_all_of():
    assert R.all_of([CONFIRMED, CONFIRMED]) == CONFIRMED
    assert R.all_of([CONFIRMED, REFUTED, INCONCLUSIVE]) == REFUTED
    assert R.all_of([CONFIRMED, INCONCLUSIVE]) == INCONCLUSIVE
    assert R.all_of([]) == INCONCLUSIVE


def test_close_to_is_narrower_than_the_form_word():
    """beta = 0.68: nearer the sqrt law than the others (its cell) but not close to 1/2."""
    _, d = detail_of("stretched_exponential", {"c": 0.3, "beta": 0.68}, seed=7)
    assert R.form_verdict(d, "sqrt", R.MIN_ESCAPES_INTERMEDIATE, close=True)[0] == REFUTED
    assert R.form_verdict(d, "sqrt", R.MIN_ESCAPES_INTERMEDIATE)[0] == CONFIRMED
