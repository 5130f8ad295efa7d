"""The claims added from the paper's Sections 2-4 on inputs whose answer is known."""

import math

import numpy as np
import pytest
from mpmath import mp

from reports.paper.claims import lifetime_claims, method_claims, saddle_claims
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.runs.scenes import parse_scene


def test_the_lower_bound_iteration_converges_quadratically_on_a_typical_flight():
    t = method_claims.lower_bound_iterates(4.0, 3.0, 0.6)
    assert all(b >= a for a, b in zip(t, t[1:], strict=False))  # never back
    with mp.workdps(method_claims.ITERATE_DPS):  # never past the root, up to 80-digit rounding
        assert method_claims._gap(mp.mpf(4.0), mp.mpf(3.0), mp.mpf(0.6), t[-1]) > -1e-70
    assert abs(method_claims.convergence_order(4.0, 3.0, 0.6) - 2.0) < 0.05


def test_a_gaussian_tail_has_exponent_two_and_an_exponential_one():
    rng = np.random.default_rng(0)
    gauss = np.abs(rng.standard_normal(200_000))
    expo = rng.exponential(1.0, 200_000)
    assert abs(saddle_claims.tail_exponent(gauss, 1e-1, 1e-3) - 2.0) < 0.3
    assert abs(saddle_claims.tail_exponent(expo, 1e-1, 1e-3) - 1.0) < 0.15
    # c_1 of exp(-c_1 x^2): |N(0, 1)| has c_1 = 1/2 in its tail
    assert abs(saddle_claims.gaussian_c1(gauss) - 0.5) < 0.1


def test_c2_follows_the_saddle_point():
    """-n/n_0 - (c_1/a_0^2) t^2/n^3 is largest at n* = (3 c_1 n_0 t^2 / a_0^2)^(1/4), where it
    is -(4/3) n*/n_0 = -c_2 sqrt(t)."""
    c1, a0, n0, t = 0.8, 0.9, 30.0, 4000.0
    n = np.linspace(1, 2000, 400_000)
    best = np.max(-n / n0 - (c1 / a0 ** 2) * t ** 2 / n ** 3)
    assert best == pytest.approx(-saddle_claims.predicted_c2(c1, a0, n0) * math.sqrt(t),
                                 rel=1e-6)


def test_the_sweep_scene_is_the_papers_transport_scene_with_other_widths():
    scene = parse_scene(lifetime_claims.sweep_scene())
    assert scene.name == "transport-width-sweep"
    widths = sorted(round(w, 9) for w in scene.hole_widths)
    assert widths == sorted(lifetime_claims.SWEEP_WIDTHS)
    assert not set(widths) & {0.1, 0.4, 1.0, 2.2}  # only widths the paper does not show


@pytest.mark.parametrize(("share", "verdict"), [(4 / 6, CONFIRMED), (2 / 6, INCONCLUSIVE),
                                                (1 / 6, REFUTED)])
def test_many_is_half_the_widths_and_not_many_is_one_in_six(share, verdict):
    from reports.paper.claims import family as F
    from reports.paper.claims import rules as R
    del R
    a = F.word_member("w", "share", share, share, share, lifetime_claims.MANY,
                      lifetime_claims.MANY_FAILS)
    assert a.verdict == verdict
