"""The concave solver (``fastpath.elastic.concave``, |eps| <= 1): answers and helpers.

The solver behind ``fastpath.flight`` answers most |eps| <= 1 flights in the lockstep lanes
(``fastpath.elastic.lockstep``); ``fastpath.elastic.concave`` is reached from orbits, the ensembles'
fallback and the flights the lanes give up. These tests call ``concave_flight`` (and ``flight_from``
with GENERAL) directly, and hold every answer to plain facts: CONVERGED, inside the certified
bracket 2*w0/(1 + |eps|) <= tau <= min(2*w0/(1 - |eps|), v + sqrt(v**2 + 4|eps|)) (exact,
mpmath), within K*kappa*u of the root (``fastpath_tolerances``), the returned sine and cosine of
phi + tau within the carried-sine bound the collision assumes
(``fastpath.elastic.collision.CARRIED_SINE_ERROR``), and eps = 0 exactly tau = 2v. The helpers
(``classify``, ``halley``, ``newton_is_final``, ``bracket``) are held to their docstrings at
their exact thresholds.
"""

import math

import numpy as np
import pytest
from fastpath_tolerances import K, U, kappa
from mpmath import mp

from fastpath.arithmetic.rounding import two_sum
from fastpath.elastic.collision import CARRIED_SINE_ERROR
from fastpath.elastic.concave import concave_flight
from fastpath.elastic.flight import GENERAL, certified_flight
from fastpath.elastic.gap import departure
from fastpath.status import CONVERGED, ITERATION_LIMIT, FlightStatus

DPS = 40


def _solve(phi, v, eps):
    """concave_flight with libm's sine and cosine of phi (exact phase: phase_error 0)."""
    s, c = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, s, v, eps, 0.0)
    assert w0 > w0_error
    return concave_flight(phi, s, c, v, eps, w0_error)


def _exact_gap(phi, v, eps, t):
    phi, v, eps, t = (mp.mpf(x) for x in (phi, v, eps, t))
    return 2 * eps * mp.sin(phi + t / 2) * mp.sin(t / 2) + t * (v - t / 2)  # no cancellation


def _exact_root(phi, v, eps, tau):
    """The positive root of the exact gap, by Newton from the fast tau, checked: the gap changes
    sign around it (|eps| <= 1: the gap is concave, its only positive root)."""
    with mp.workdps(DPS):
        p, w, e = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        t = mp.mpf(tau)
        for _ in range(60):
            step = _exact_gap(p, w, e, t) / (w - t + e * mp.sin(p + t))
            t -= step
            if abs(step) <= t * mp.mpf(10) ** (-DPS + 3):
                break
        delta = t * mp.mpf(10) ** (-DPS + 6)
        assert _exact_gap(p, w, e, t - delta) > 0 > _exact_gap(p, w, e, t + delta)
        return t


def _exact_bracket(phi, v, eps):
    """2*w0/(1 + |eps|) <= tau <= min(2*w0/(1 - |eps|), v + sqrt(v**2 + 4|eps|)), exact."""
    with mp.workdps(DPS):
        w0 = mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi))
        e = abs(mp.mpf(eps))
        hi = mp.mpf(v) + mp.sqrt(mp.mpf(v) ** 2 + 4 * e)
        if e < 1:
            hi = min(hi, 2 * w0 / (1 - e))
        return 2 * w0 / (1 + e), hi


def _check(phi, v, eps, answer, units=K):
    tau, s, c, evaluations, status = answer
    assert status == CONVERGED, (phi, v, eps, answer)
    assert 1 <= evaluations <= ITERATION_LIMIT
    lo, hi = _exact_bracket(phi, v, eps)
    assert lo <= tau <= hi, (phi, v, eps, tau, lo, hi)
    root = _exact_root(phi, v, eps, tau)
    with mp.workdps(DPS):
        err = abs(mp.mpf(tau) - root) / root
        assert err <= units * kappa(phi, v, eps, root) * U, (phi, v, eps, tau, float(err))
        angle = mp.mpf(phi) + mp.mpf(tau)
        assert abs(s - mp.sin(angle)) <= CARRIED_SINE_ERROR, (phi, v, eps, tau, s)
        assert abs(c - mp.cos(angle)) <= CARRIED_SINE_ERROR, (phi, v, eps, tau, c)


def _cases(seed, n, w0_range):
    """(phi, v, eps) with log10(w0) uniform in w0_range, eps over the concave range."""
    rng = np.random.default_rng(seed)
    out = []
    for eps in (0.3, -0.6, 0.9, -0.999, 1.0, -1.0, 1e-9):
        for _ in range(n):
            phi = float(rng.uniform(-math.pi, math.pi))
            w0 = float(10.0 ** rng.uniform(*w0_range))
            out.append((phi, w0 - eps * math.sin(phi), eps))
    return out


@pytest.mark.parametrize("w0_range", [(-6.0, -0.35), (0.05, 2.5)], ids=["short", "holmes"])
def test_concave_flights_are_in_the_bracket_and_accurate(w0_range):
    """Both starts (half-angle for 2*w0 < 1 + |eps|, Holmes otherwise): CONVERGED, in the exact
    bracket, within K*kappa*u, sine and cosine of phi + tau within the carried-sine bound."""
    for phi, v, eps in _cases(12 if w0_range[0] < 0 else 13, 6, w0_range):
        s = math.sin(phi)
        w0, w0_error = departure(phi, s, v, eps, 0.0)
        if not w0 > w0_error:
            continue
        _check(phi, v, eps, _solve(phi, v, eps))


@pytest.mark.parametrize("v", [2.0**-30, 1e-7, 0.1, 0.25, 0.7, 1.0, 3.0, 12.5, 1e3, 2.0**40])
@pytest.mark.parametrize("phi", [-3.0, -0.5, 0.0, 1.0, 2.5])
def test_eps_zero_gives_exactly_twice_v(phi, v):
    """eps = 0: d(t) = t*(v - t/2), tau = 2v exactly, for both starts, and the
    sine and cosine of phi + 2v."""
    tau, s, c, evaluations, status = _solve(phi, v, 0.0)
    assert status == CONVERGED and tau == 2.0 * v
    assert evaluations == 1  # either start is the root itself
    with mp.workdps(DPS):
        angle = mp.mpf(phi) + 2 * mp.mpf(v)
        assert abs(s - mp.sin(angle)) <= CARRIED_SINE_ERROR
        assert abs(c - mp.cos(angle)) <= CARRIED_SINE_ERROR


def test_general_method_is_the_concave_solver():
    """certified_flight(..., GENERAL) for |eps| <= 1 is concave_flight, bit for bit."""
    for phi, v, eps in _cases(14, 3, (-4.0, 1.5)):
        s, c = math.sin(phi), math.cos(phi)
        w0, w0_error = departure(phi, s, v, eps, 0.0)
        if not w0 > w0_error:
            continue
        assert certified_flight(phi, s, c, v, eps, GENERAL, 0.0) == concave_flight(
            phi, s, c, v, eps, w0_error)


# --- the concave solver's helpers at their boundaries (exact floats, no tolerance needed) ---


def test_classify_at_the_error_bounds():
    """A gap exactly at +-E (or a slope exactly at +-R) proves nothing: d > E is needed for
    "before", d < -E for "after", d' < -R for "at the root", d' > R for "before"; else flat."""
    from fastpath.elastic.concave import AFTER, AT_ROOT, BEFORE, FLAT, classify
    from fastpath.elastic.gap import gap_error, rate_error

    phi, v, eps, t = 0.5, 1.0, 0.5, 1.0
    e, r = gap_error(phi, v, eps, t), rate_error(phi, v, eps, t)
    assert classify(phi, v, eps, t, e, 0.0) == FLAT
    assert classify(phi, v, eps, t, -e, 0.0) == FLAT
    assert classify(phi, v, eps, t, 0.0, -r) == FLAT
    assert classify(phi, v, eps, t, 0.0, r) == FLAT
    assert classify(phi, v, eps, t, math.nextafter(e, 1.0), 0.0) == BEFORE
    assert classify(phi, v, eps, t, math.nextafter(-e, -1.0), 0.0) == AFTER
    assert classify(phi, v, eps, t, 0.0, math.nextafter(-r, -1.0)) == AT_ROOT
    assert classify(phi, v, eps, t, 0.0, math.nextafter(r, 1.0)) == BEFORE


def test_halley_steps_and_its_bisections():
    """The Halley step t - 2*d*d'/(2*d'**2 - d*d''); a step onto or beyond a bracket end is
    replaced by the arithmetic midpoint, or the geometric one where lo > 0 and hi > 4*lo (both
    strict: at lo = 0 the geometric mean is lo itself, a step that ends the flight at lo)."""
    from fastpath.elastic.concave import AFTER, BEFORE, halley

    # inside: the Halley point (d'' = -1: 1 + 0.25/0.75)
    t_next, lo, hi = halley(1.0, 0.25, -0.5, -1.0, BEFORE, 0.5, 3.0)
    assert (lo, hi) == (1.0, 3.0)
    with mp.workdps(DPS):
        assert abs(t_next - mp.mpf(4) / 3) <= 2 * U
    # d'' = 0: the Newton step, exactly onto hi (before) or lo (after): bisected
    assert halley(1.0, 0.25, -0.5, 0.0, BEFORE, 0.5, 1.5) == (1.25, 1.0, 1.5)
    assert halley(1.5, -0.25, -0.5, 0.0, AFTER, 1.0, 2.0) == (1.25, 1.0, 1.5)
    # beyond the bracket: lo = 0 takes the arithmetic midpoint, hi = 4*lo too, hi > 4*lo not
    assert halley(8.0, -1.0, 0.1, 0.0, AFTER, 0.0, 9.0) == (4.0, 0.0, 8.0)
    assert halley(4.0, -1.0, 0.1, 0.0, AFTER, 1.0, 9.0) == (2.5, 1.0, 4.0)
    assert halley(8.0, -1.0, 0.1, 0.0, AFTER, 1.0, 9.0) == (math.sqrt(8.0), 1.0, 8.0)


def test_newton_is_final_at_its_threshold():
    """(1 + |eps|)/2*h**2 + |h|*R <= E/16, equality included (docstring)."""
    from fastpath.elastic.concave import newton_is_final

    assert newton_is_final(1.0, 16.0, 0.0, 1.0)  # 1 <= 1
    assert not newton_is_final(1.0, 8.0, 0.0, 1.0)  # 1 > 0.5
    assert not newton_is_final(-1.0, 16.0, 1.0, 0.0)  # 0.5 + 1 > 1
    assert newton_is_final(-1.0, 24.0, 1.0, 0.0)  # 1.5 <= 1.5


def test_two_sum_is_exact():
    """s + e == x + y exactly (Knuth's TwoSum), the Holmes start's angle phi + 2v."""
    from fractions import Fraction


    assert two_sum(1.0, 2.0**-60) == (1.0, 2.0**-60)
    rng = np.random.default_rng(3)
    for _ in range(200):
        x, y = (float(a) for a in rng.uniform(-1e3, 1e3, 2) * 10.0 ** rng.integers(-8, 8, 2))
        s, e = two_sum(x, y)
        assert s == x + y and Fraction(s) + Fraction(e) == Fraction(x) + Fraction(y)


# --- concave.bracket: the documented bounds, exactly as documented ---


def _documented_bracket(v, w0, w0_error, eps):
    """(lo, hi) of ``bracket_from_root``'s docstring in mpmath: lo from w0 - w0_error (0 if that
    is not positive), hi the concave bound 2*(w0 + w0_error)/(1 - |eps|) unless that exceeds
    2|v| + 2, then the smaller of it and the energy bound v + sqrt(v**2 + 4|eps|)."""
    with mp.workdps(DPS):
        w0, we, v, e = (mp.mpf(x) for x in (w0, w0_error, v, abs(eps)))
        lo = 2 * max(w0 - we, 0) / (1 + e)
        concave = 2 * (w0 + we) / (1 - e) if e < 1 else mp.inf
        energy = v + mp.sqrt(v * v + 4 * e)
        hi = concave if concave <= 2 * abs(v) + 2 else min(concave, energy)
        return lo, hi


@pytest.mark.parametrize("v, w0, w0_error, eps", [
    (1.0, 1.25, 0.25, 0.5),  # a large w0_error: lo and hi move by it
    (0.3, 0.1, 0.2, 0.6),  # w0 <= w0_error: lo = 0, never negative
    (-0.25, 0.5, 1e-16, 1.0),  # v < 0, |eps| = 1: the energy bound 4|eps|/(root - v)
    (-0.5, 0.2, 1e-16, 0.9),  # v < 0: the concave bound 4 > 2|v| + 2 = 3: the smaller one
    (0.5, 0.6, 1e-16, 0.9),  # concave 12 > 3: min(12, energy)
    (2.0, 1.2, 1e-16, 0.5),  # concave 4.8 <= 6: the concave bound alone
    (1e-151, 0.5, 1e-16, 1.0),  # tiny v: hypot
])
def test_bracket_is_the_documented_one(v, w0, w0_error, eps):
    """Sound (lo below, hi above the documented bounds) and tight: lo within (1 - 4u) and a few
    u of its formula, hi within (1 + 4u) and a few u of its own."""
    from fastpath.elastic.concave import bracket

    lo, hi = bracket(v, w0, w0_error, eps)
    doc_lo, doc_hi = _documented_bracket(v, w0, w0_error, eps)
    assert lo >= 0.0
    with mp.workdps(DPS):
        assert doc_lo * (1 - 8 * U) <= lo <= doc_lo, (lo, doc_lo)
        assert doc_hi <= hi <= doc_hi * (1 + 8 * U), (hi, doc_hi)


def test_an_infinite_bracket_is_an_overflow_before_any_evaluation():
    """hi = inf (v + sqrt(v**2 + 4|eps|) overflows): OVERFLOW with 0 evaluations."""
    for v, eps in ((1e308, 1.0), (1.7e308, 0.6)):
        tau, s, c, evaluations, status = _solve(0.5, v, eps)
        assert status == int(FlightStatus.OVERFLOW) and evaluations == 0
        assert math.isnan(tau) and math.isnan(s) and math.isnan(c)


def test_holmes_start_at_equality():
    """The Holmes start is taken unless the lower bound 2*w0/(1 + |eps|) is below 1 (module
    docstring): at 2*w0 = 1 + |eps| exactly (phi = 0, w0 = v) it is the Holmes start's answer."""
    from fastpath.elastic.concave import bracket, flight_from_holmes

    for v, eps in ((0.75, 0.5), (1.0, 1.0), (0.5, 0.0), (0.625, -0.25)):
        w0, w0_error = departure(0.0, 0.0, v, eps, 0.0)
        assert 2.0 * w0 == 1.0 + abs(eps)
        lo, hi = bracket(v, w0, w0_error, eps)
        assert _solve(0.0, v, eps) == flight_from_holmes(0.0, 0.0, 1.0, v, eps, lo, hi)


@pytest.mark.parametrize("phi, v", [(-2.0, 0.75), (0.4, 0.75), (1.3, 0.75), (-2.0, 1.0),
                                    (0.4, 1.0), (2.9, 1.0), (-2.0, 3.5), (1.3, 3.5)])
def test_a_first_evaluation_at_the_root_takes_the_newton_correction(phi, v):
    """eps tiny: at the Holmes start t = 2v the gap d = eps*(cos(phi) - cos(phi + 2v)) is within
    its bound E, d' = -v + eps*sin ~ -v beyond its bound: the root is t - d/d' (one Newton
    correction, unclamped: it lies inside the bracket). Its error is the rounding of t - d/d' and
    of d, d' (u*eps and u*v: below an ulp of t), and the neglected second order
    (d/d')**2/(2v) ~ 1e-30: within one ulp of the exact root. eps is chosen so that d/d' is
    several ulps of t: a stop at t itself is off by that much."""
    eps = 3.0 * math.ulp(2.0 * v) * v / abs(math.cos(phi) - math.cos(phi + 2.0 * v))
    tau, s, c, evaluations, status = _solve(phi, v, eps)
    assert status == CONVERGED and evaluations == 1
    root = _exact_root(phi, v, eps, tau)
    with mp.workdps(DPS):
        assert abs(mp.mpf(tau) - root) <= math.ulp(tau), (tau, float(root), 2.0 * v)
        assert abs(root - 2 * v) >= 2 * math.ulp(tau)  # the correction matters
        # sin, cos moved by h = tau - 2v to first order (|h| < 1e-8): within the carried bound
        angle = mp.mpf(phi) + mp.mpf(tau)
        assert abs(s - mp.sin(angle)) <= CARRIED_SINE_ERROR, (s, float(mp.sin(angle)))
        assert abs(c - mp.cos(angle)) <= CARRIED_SINE_ERROR, (c, float(mp.cos(angle)))


# --- fastpath.flight helpers (the lower-bound steps of |eps| > 1, the departure) ---


def test_long_holmes_step_sine_within_the_carried_bound():
    """A step from the Holmes start 2v longer than SMALL_ANGLE = 0.125 returns the sine of the
    exact sum phi + tau within the 8u that ``collide_from`` adds to the next departure's phase
    error (``CARRIED_SINE_ERROR``). Here the angle is ~24 (ulp 32u): libm's sine of the angle
    rounded twice, fl(fl(theta0 + theta0_error) + delta) + h, with the TwoSum remainder lost,
    would be 9.07u off; ``rotate`` takes it of the exact sum (``sin_cos_of_sum``)."""
    phi, v, eps = 2.8535527917488874, 10.72350022083204, 1.0
    tau, s, _, _, status = _solve(phi, v, eps)
    assert status == CONVERGED
    with mp.workdps(DPS):
        assert abs(s - mp.sin(mp.mpf(phi) + mp.mpf(tau))) <= CARRIED_SINE_ERROR
