"""The lower-bound solver (``fastpath.elastic.lower_bound``, the paper's steps, used for every
|eps| > 1 and by the "lower_bound" method), the departure checks of ``flight_from`` and the
gap's rate bound (``fastpath.elastic.gap.rate_error``), each at its exact thresholds.

Every expected value here follows from the docstrings' rules and exact float arithmetic (inputs
chosen so that the compared quantities are exact), or from an error bound derived below from the
unit roundoff u = 2**-53 and checked against mpmath; none is copied from the program's output.
Several tests call ``lower_bound_flight``'s plain-Python body (``py_func``; the function itself
under NUMBA_DISABLE_JIT, with ``lower_bound_steps``, ``elastic_gap_bounds`` and ``next_point`` as
plain Python too) with ``gap`` and ``certified_step`` wrapped, to count the evaluations and to
see the lower models each step is given; every other callee is the kernel itself (compiled
unless NUMBA_DISABLE_JIT).

``may_be_graze``'s tests ``curvature < 0`` and ``r < 0`` are not pinned at +-0: there the
shortcut's third condition reads 2*d_err < -r*(-curvature/|eps|) = +-0 (or NaN), false for every
d_err >= 0, so ``<`` and ``<=`` give the same answer (d_err = gap_error(t) >= 0 at every t >= 0,
and lower_bound_flight only visits t > 0).
"""

import ast
import importlib
import inspect
import math
from pathlib import Path

import numpy as np
import pytest
from fastpath_tolerances import U
from mpmath import mp

import fastpath
from fastpath.arithmetic.sincos import sin_cos
from fastpath.elastic.flight import AUTO, GENERAL, LOWER_BOUND, departure_phase, flight_from
from fastpath.elastic.gap import departure, gap, gap_error, gap_rate, rate_error
from fastpath.elastic.lower_bound import (
    GapBounds,
    elastic_gap_bounds,
    first_root,
    lower_bound_steps,
    may_be_graze,
)
from fastpath.elastic.lower_bound import lower_bound_flight as _lower_bound_flight
from fastpath.elastic.lower_bound import polish as _polish
from fastpath.physics import Dissipative, Elastic, dissipative, elastic
from fastpath.status import (
    CONVERGED,
    ITERATION_LIMIT,
    MAX_ITERATIONS,
    NOT_DEPARTING,
    OVERFLOW,
    UNCERTAIN,
    FlightStatus,
)

DPS = 40
flight_module = importlib.import_module("fastpath.elastic.lower_bound")


def lower_bound_flight(phi, v, eps, w0, start=0.0):
    """From t = start, or from the departure's step 2*w0/(1 + |eps|) (``solve_flight``)."""
    return _lower_bound_flight(phi, v, eps, start if start > 0.0 else 2.0 * w0 / (1.0 + abs(eps)))


def polish(phi, v, eps, t, d, r):
    return _polish(t, d, r, rate_error(phi, v, eps, t))


def _py(function):
    """The plain-Python body of a kernel (the function itself without numba)."""
    return getattr(function, "py_func", function)


def _traced_flight(monkeypatch, phi, v, eps, w0):
    """lower_bound_flight's result, the times t it evaluated the gap at, and (t, d, r, c) of
    every certified step it took (the lowered gap, slope and curvature it gave the models)."""
    times, steps = [], []
    real_gap, real_step = flight_module.gap, flight_module.certified_step

    def counted_gap(phi_, v_, eps_, t):
        times.append(t)
        return real_gap(phi_, v_, eps_, t)

    def seen_step(d, r, c, j, eps_, a):
        steps.append((times[-1], d, r, c))
        return real_step(d, r, c, j, eps_, a)

    monkeypatch.setattr(flight_module, "gap", counted_gap)
    monkeypatch.setattr(flight_module, "certified_step", seen_step)
    # the loop and the callees whose bodies call the two above, as plain Python (the loop's
    # model functions, ``bounds_at`` ..., are plain Python already)
    for name in ("lower_bound_steps", "elastic_gap_bounds", "next_point"):
        monkeypatch.setattr(flight_module, name, _py(getattr(flight_module, name)))
    result = _py(_lower_bound_flight)(phi, v, eps, 2.0 * w0 / (1.0 + abs(eps)))
    monkeypatch.undo()
    return result, times, steps


def _departure(phi, v, eps):
    """(centred phi, w0) as solve_flight computes them (a certain departure asserted)."""
    centred, phase_error = departure_phase(phi)
    w0, w0_error = departure(centred, sin_cos(centred)[0], v, eps, phase_error)
    assert w0 > w0_error
    return centred, w0


# --- first_root and the departure test, at their exact thresholds ---


def test_first_root_counts_a_discriminant_exactly_at_its_threshold_as_a_root():
    """"A discriminant within its rounding error of zero counts as zero (a root: the shorter step)";
    within means up to and including the bound, as everywhere in fastpath (a gap d <= d_err is
    within rounding of zero). r = -1.1180339887498947 has r*r = 1.25 - 2**-51 (exact float
    product), k = 1.25 + 3*2**-52, d = 1/2: disc = (1.25 - 2*2**-52) - (1.25 + 3*2**-52) =
    -5*2**-52 exactly, and 4u*(r*r + 2|k|d) = 2**-51 * fl(2.5 + 2**-52) = 2**-51 * 2.5 (a tie,
    rounded to even) = 5*2**-52: the discriminant sits exactly on its threshold. It counts as
    zero: the double root 2d/(sqrt(0) - r) = 1/|r|, not inf."""
    r, k, d = -1.1180339887498947, 1.25 + 3 * 2.0**-52, 0.5
    assert r * r == 1.25 - 2.0**-51
    disc = r * r - 2.0 * k * d
    assert disc == -5 * 2.0**-52 == -4.0 * U * (r * r + 2.0 * abs(k) * d)
    assert first_root(d, r, k) == 2.0 * d / (0.0 - r)


@pytest.mark.parametrize("eps", [1.0, 2.0, -2.0])
@pytest.mark.parametrize("method", [AUTO, LOWER_BOUND, GENERAL])
def test_a_departure_exactly_at_its_error_bound_is_uncertain(method, eps):
    """A departure whose w0 equals its error bound is not certain. phi = 0 (sin 0, cos 1), v = 1:
    w0 = 1 exactly, and with phase_error = (1 - 2**-52)/|eps| (exact: |eps| is 1 or 2) the bound is
    fl(2u*1 + 3u*0) + |eps|*phase_error = 2**-52 + (1 - 2**-52) = 1 = w0 exactly. The exact w0 lies
    in [w0 - bound, w0 + bound] = [0, 2]: it may be zero, so the departure is not certain:
    UNCERTAIN ("a w0 within its rounding bound of zero is UNCERTAIN"), decided before any
    evaluation (0 iterations, NaN results)."""
    phase_error = (1.0 - 2.0**-52) / abs(eps)
    w0, bound = departure(0.0, 0.0, 1.0, eps, phase_error)
    assert w0 == bound == 1.0
    tau, _, s, c, iterations, status = flight_from(0.0, 0.0, 1.0, 1.0, eps, method, phase_error)
    assert (status, iterations) == (UNCERTAIN, 0)
    assert math.isnan(tau) and math.isnan(s) and math.isnan(c)


@pytest.mark.parametrize("eps", [0.5, -0.75, 1.0, 2.0, -3.0])
def test_no_evaluation_before_a_non_departure_or_an_uncertain_departure(eps):
    """NOT_DEPARTING and UNCERTAIN report 0 iterations: both are decided from w0 and its bound
    alone, before the gap is evaluated once: 0 iterations. NOT_DEPARTING: phi = -+pi/2 with the sign
    of eps (sin(phi) = -+1 up to ~1e-33), v = |eps|/2: w0 = -|eps|/2 < 0 far beyond its bound,
    through the public fastpath.flight. UNCERTAIN: v = -fl(eps*sin(phi)) with the same float sine
    makes w0 = fl(v + fl(eps*sin(phi))) = 0 exactly (a float plus its negation), while the bound
    3u*|eps*sin(phi)| > 0."""
    for method in ("auto", "lower_bound"):
        result = fastpath.flight(-math.copysign(math.pi / 2, eps), abs(eps) / 2, eps, method=method)
        assert result.status == NOT_DEPARTING and result.iterations == 0
        assert math.isnan(result.tau)
    phi = 1.0
    s, c = sin_cos(phi)
    v = -(eps * s)
    w0, bound = departure(phi, s, v, eps, 0.0)
    assert w0 == 0.0 < bound
    for method in (AUTO, LOWER_BOUND, GENERAL):
        tau, _, _, _, iterations, status = flight_from(phi, s, c, v, eps, method, 0.0)
        assert (status, iterations) == (UNCERTAIN, 0) and math.isnan(tau)


# --- may_be_graze ---


@pytest.mark.parametrize("eps", [0.5, -0.5, 1.0, -1.0])
def test_no_graze_where_the_gap_is_concave_everywhere(eps):
    """For |eps| <= 1, d'' = -1 + eps*cos(phi + t) <= -1 + |eps| <= 0 everywhere: the gap is
    concave and has no dip, so a gap within rounding of zero is never a graze, whatever the slope
    (here r > 0, where the last test r > -2*sqrt(4*b*d_err) would say True for any b >= 0; at
    phi + t = 0 and eps = 1 the curvature bound is even positive)."""
    for phi, t in ((0.0, 0.0), (0.5, 1.0), (-2.0, 3.0)):
        assert not may_be_graze(phi, eps, t, 0.25, 1e-3)
        assert not may_be_graze(phi, eps, t, 0.25, 0.0)


@pytest.mark.parametrize("phi, t", [(0.0, 5.0 * math.pi / 3.0), (-1.5, 1.5)])
def test_the_concave_shortcut_needs_a_certainly_negative_curvature(phi, t):
    """``may_be_graze`` takes its concave shortcut only where the curvature -1 + eps*cos(phi + t),
    raised by its rounding margin, is certainly negative.

    "Where it is locally concave, d2 = d''(t) < 0, [...] with slope r < 0 it surely crosses zero
    within 2*d_err/|r| if that is shorter than R = -d2/|eps|"; otherwise the answer is whether
    r > -2*sqrt(4*b*d_err). eps = 2 (b = 1), r = -2**-116, d_err = 2**-171. At phi + t = 0,
    d'' = 1 > 0. At phi + t = fl(5*pi/3) (phi = 0: the sum is exact) the exact d'' ~ 1.4u > 0
    and d''' = -2*sin ~ 1.73 > 0 (mpmath), while the float -1 + 2*cos is within the margin
    4u|eps| = 8u of zero: only the curvature raised by that margin is an upper bound on d''
    that does not claim concavity. Both points are convex, and a near miss fits the data: the
    exact gap may be D = 2*d_err at t, and d(t + s) >= D + r*s + d''*s**2/2 + d'''*s**3/6 (less
    a quartic term < 2**-230 at the s <= 2**-57 where the minimum lies) stays positive: its
    minimum is above max(D - r**2/(2*d''), D - (2/3)|r|*sqrt(2|r|/d''')) > 0, and beyond it the
    slope grows. So the answer is the slope test's: r > -2*sqrt(4*d_err) = -2**-83.5: True
    (UNCERTAIN). Taking the shortcut says False, a certain crossing (2*d_err = 2**-170 < |r|*R
    for any R >= u/2)."""
    eps, r, d_err = 2.0, -(2.0**-116), 2.0**-171
    with mp.workdps(DPS):
        theta = mp.mpf(phi) + mp.mpf(t)
        d2, d3 = -1 + eps * mp.cos(theta), -eps * mp.sin(theta)
        assert d2 > 0 and d3 >= 0
        big_d, slope = 2 * mp.mpf(d_err), abs(mp.mpf(r))
        lowest = big_d - slope**2 / (2 * d2)
        if d3 > 0:
            lowest = max(lowest, big_d - 2 * slope * mp.sqrt(2 * slope / d3) / 3)
        assert lowest > 0
    assert phi + t == 0.0 or 0.0 <= -1.0 + eps * math.cos(phi + t) < 4.0 * U * abs(eps)
    assert r > -2.0 * math.sqrt(4.0 * (abs(eps) - 1.0) * d_err)
    assert may_be_graze(phi, eps, t, r, d_err)


def test_may_be_graze_at_its_two_thresholds():
    """``may_be_graze``'s slope test ``r > -2*sqrt(4*b*d_err)`` and concave shortcut
    ``2*d_err < -r*R`` at equality: both comparisons are strict in the docstring.

    Slope test: eps = 2 (b = 1), d_err = 1/16, r = -1 = -2*sqrt(4*1/16) exactly, at a convex
    point (phi + t = 0, d'' = 1): r is not > the threshold: False (a dip of depth <= 2*d_err
    needs r > -sqrt(4*b*d_err) = -1/2; here r**2/(2b) = 1/2 > 2*d_err, so the gap crosses).
    Concave shortcut: phi + t = fl(pi), cos = -1 exactly in float64, curvature bound
    -1 - 2 + 8u = -(3 - 2**-50) (exact), R = (3 - 2**-50)/2; r = -1 and d_err = R/2 make
    2*d_err/|r| = R exactly: not shorter than R, so no shortcut, and the slope test says True
    (|r| = 1 < 2*sqrt(4*d_err) ~ 3.5)."""
    assert not may_be_graze(0.0, 2.0, 0.0, -1.0, 1.0 / 16.0)
    assert -2.0 * math.sqrt(4.0 * 1.0 * (1.0 / 16.0)) == -1.0
    assert math.cos(math.pi) == -1.0
    big_r = (3.0 - 2.0**-50) / 2.0
    assert -(-1.0 + 2.0 * -1.0 + 4.0 * U * 2.0) / 2.0 == big_r
    assert may_be_graze(math.pi, 2.0, 0.0, -1.0, big_r / 2.0)


# --- lower_bound_flight: iteration counts, the stop, overflow, the lower models ---


@pytest.mark.parametrize("phi", [-3.0, 0.0, 2.5, 7.0])
@pytest.mark.parametrize("v", [1e-7, 0.3, 1.0, 12.5, 2.0**40])
def test_lower_bound_flight_at_eps_zero_is_twice_v_in_one_evaluation(phi, v):
    """eps = 0 by the lower-bound steps: a = 1, the first iterate is 2*w0/a = 2v (w0 = v exactly),
    where
    d = 0*sin*sin + 2v*(v - v) = 0 exactly: within rounding, no dip (|eps| <= 1), and the polish
    t - 0/(-v) leaves 2v: tau = 2v (exact at eps = 0) after one evaluation, reported as one."""
    result = fastpath.flight(phi, v, 0.0, method="lower_bound")
    assert (result.tau, result.iterations, result.status) == (2.0 * v, 1, CONVERGED)


# chatter-graze-elastic-eps=1.5-w=1e-09-c=1e-16 (verify.hard_cases): its steps crawl past a
# shallow dip and run out of their 60 iterations (documented in test_fastpath_chattering.py).
OUT_OF_ITERATIONS = (5.4420677987249695, 1.1180828263046108, 1.5)
FLIGHTS = [OUT_OF_ITERATIONS, (0.3, 6.0, 1.5), (-2.0, 4.0, 3.0), (1.0, 3.0, -2.5),
           (2.0, 0.05, 1.2), (0.7, 1.0, 10.0)]


@pytest.mark.parametrize("phi, v, eps", FLIGHTS)
def test_reported_iterations_are_the_gap_evaluations(monkeypatch, phi, v, eps):
    """"At most ITERATION_LIMIT evaluations for any input (then MAX_ITERATIONS)": the iterations a
    flight reports are the gap evaluations it made (counted here), never more than 60, and a
    flight stopped by the limit has made exactly 60. The first flight is one that the limit
    stops (its row in test_fastpath_chattering.py); the others end CONVERGED or UNCERTAIN."""
    centred, w0 = _departure(phi, v, eps)
    (tau, iterations, status), times, _ = _traced_flight(monkeypatch, centred, v, eps, w0)
    assert iterations == len(times) <= ITERATION_LIMIT
    if (phi, v, eps) == OUT_OF_ITERATIONS:
        assert status == MAX_ITERATIONS
    if status == MAX_ITERATIONS:
        assert len(times) == ITERATION_LIMIT
    else:
        assert status in (CONVERGED, UNCERTAIN)


def test_a_gap_exactly_at_its_error_bound_ends_the_steps():
    """"The iteration stops when the gap is within its rounding error of zero" (equality
    included). Start at t = 1 with phi = -1/2, eps = 2**50, v = 2.75 + 2**-49: the plate term is
    2*eps*sin(0)*sin(1/2) = 0, so d = 1*(v - 1/2) = 2.25 + 2**-49 exactly; gap_error =
    4u*(2**50*1*(1/2 + 1 + 3) + 1*(v + 1)) = 2**-51*fl(4.5*2**50 + 3.75 + 2**-49), whose sum
    rounds to the integer 4.5*2**50 + 4 (ulp 1 there): 2.25 + 2**-49, the same float. The
    steps stop at the first evaluation; the gap is convex there (d'' = -1 + eps*cos(1/2) > 0)
    and its slope r ~ eps*sin(1/2) > 0, so it may be a graze: (1, 1, UNCERTAIN)."""
    phi, v, eps = -0.5, 2.75 + 2.0**-49, 2.0**50
    assert gap(phi, v, eps, 1.0) == gap_error(phi, v, eps, 1.0) == 2.25 + 2.0**-49
    assert lower_bound_flight(phi, v, eps, 1.0, 1.0) == (1.0, 1, UNCERTAIN)


def test_an_overflowing_first_evaluation_is_an_overflow():
    """"A non-finite intermediate (v**2, t*v overflowing) gives OVERFLOW", at the evaluation where
    it happens. Gap: v = 5e307, eps = 2 (a = 3): the first iterate t = 2*w0/3 ~ 3.3e307, and
    t*(v - t/2) ~ 1.1e615 overflows while the slope v - t + eps*sin ~ 1.7e307 is finite.
    Slope: from start = 1e-300 with v = 1.7e308, eps = 8e307, phi = 1.5: the slope
    v - t + eps*sin(1.5) ~ 2.5e308 overflows while the gap ~ 2.5e8 is finite (2*eps = 1.6e308
    does not overflow). Either way (NaN, 1, OVERFLOW): one evaluation."""
    for method in ("auto", "lower_bound"):
        result = fastpath.flight(1.0, 5e307, 2.0, method=method)
        assert (result.iterations, result.status) == (1, OVERFLOW) and math.isnan(result.tau)
    assert math.isfinite(gap(1.5, 1.7e308, 8e307, 1e-300))
    assert math.isinf(gap_rate(1.5, 1.7e308, 8e307, 1e-300))
    tau, iterations, status = lower_bound_flight(1.5, 1.7e308, 8e307, 1.0, 1e-300)
    assert (iterations, status) == (1, OVERFLOW) and math.isnan(tau)


def _curvature_margin_holds(phi, t):
    """Whether 4u|eps|*(1 + t) covers the rounding of -1 + eps*cos(phi + t) as computed (|eps| >
    1), by the bound of ``test_the_lower_models_are_below_the_exact_slope_and_curvature``."""
    return 3.0 * t >= abs(phi) + 3.0 + 1e-6


LONG_FLIGHTS = [(0.3, 6.0, 1.5), (-2.0, 4.0, 3.0), (1.0, 3.0, -2.5), (-1.0, 8.0, 2.0),
                (2.5, 5.0, -1.1)]


@pytest.mark.parametrize("phi, v, eps", LONG_FLIGHTS)
def test_the_lower_models_are_below_the_exact_slope_and_curvature(monkeypatch, phi, v, eps):
    """"The models take the worst values within rounding: d, d' and d'' lowered by their bounds":
    at every step the slope r and curvature c given to certified_step are <= the exact d'(t) and
    d''(t) (mpmath). Why they are, from u (each float operation is within u of its exact
    result, libm's sine and cosine within one ulp, 2u): the computed d' = fl(fl(v - t) +
    fl(eps*sin(fl(phi + t)))) is off by at most u(|v| + t) (v - t) + |eps|*u(|phi| + t) (the
    argument) + 2u|eps| (sine) + u|eps| (product) + u(|v| + t + |eps|) (sum), and forming
    r -+ rate_error rounds by u(|v| + t + |eps| + R) more (R = rate_error = 4u(|v| + t +
    |eps|(1 + |phi| + t))): in all R - u((|v| + t) + |eps|(3|phi| + 3t - 1)) + O(u*R) < R
    wherever 3(|phi| + t) > 1, true at every step here (|phi| >= 1, or phi = 0.3 and every
    t >= 2*w0/a > 5). So r - R < d' < r + R. Likewise -1 + eps*cos(fl(phi + t)) is off by at
    most u|eps|(|phi| + t + 3) + u(1 + |eps|), and subtracting the margin m rounds by
    u(1 + |eps| + m): in all <= u|eps|(|phi| + t + 7)
    (|eps| > 1), which m = 4u|eps|(1 + t) exceeds once 3t >= |phi| + 3: there c < d'' is
    certain, and c + m (the margin added instead) > d''. A margin 4u|eps|*(1 - t) would raise
    the curvature by 4u|eps|(t - 1), above d'' once 3t > |phi| + 11: each flight here lasts
    longer than that (tau > 6 > (pi + 11)/3), so its last steps tell the two apart."""
    centred, w0 = _departure(phi, v, eps)
    _, _, steps = _traced_flight(monkeypatch, centred, v, eps, w0)
    assert steps
    with mp.workdps(DPS):
        p, w, e = mp.mpf(centred), mp.mpf(v), mp.mpf(eps)
        checked = 0
        for t, _, r_low, c in steps:
            tt = mp.mpf(t)
            assert r_low < w - tt + e * mp.sin(p + tt), (t, r_low)
            if _curvature_margin_holds(centred, t):
                assert c < -1 + e * mp.cos(p + tt), (t, c)
                checked += 1 if 3.0 * t > abs(centred) + 11.0 + 1e-6 else 0
        assert checked >= 1  # a step late enough to tell (1 - t) from (1 + t)


def test_polish_needs_a_slope_beyond_its_error():
    """"One certified Newton correction [...] taken only where the slope d1 < 0 beyond its error":
    at r = -rate_error exactly the exact slope may be 0, so no correction: t itself; just beyond
    (the next float below) the correction t - d/r."""
    phi, v, eps, t, d = 0.5, 1.0, 2.0, 1.0, 1e-10
    r = -rate_error(phi, v, eps, t)
    assert polish(phi, v, eps, t, d, r) == t
    beyond = math.nextafter(r, -1.0)
    assert polish(phi, v, eps, t, d, beyond) == t - d / beyond != t


# --- gap.rate_error against the actual rounding of gap_rate ---


def _rate_points(seed):
    """(phi, v, eps, t) where each term of rate_error matters: t much larger than |v| (the t of
    |v| + t), long flights with |eps| >= 1 (the |eps|*t term: fl(phi + t) drops phi's low bits),
    |phi| near pi at moderate t (the |eps|*|phi| term)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(40):
        t = float(rng.uniform(16.0, 64.0))
        out.append((float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(0.3, 0.5) * t),
                    0.5, t))
        t = float(rng.uniform(16.0, 64.0))
        out.append((float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(0.0, 1.0)),
                    float(rng.choice([1.0, -1.25])), t))
        out.append((float(rng.choice([-1.0, 1.0]) * rng.uniform(2.5, math.pi)),
                    float(rng.uniform(0.0, 0.5)), float(rng.choice([3.0, -1.5])),
                    float(rng.uniform(0.5, 2.0))))
    return out


def test_rate_error_covers_the_rounding_of_gap_rate():
    """rate_error covers the actual rounding error of gap_rate. gap_rate computes
    fl(fl(v - t) + fl(eps*fl(sin(fl(phi + t))))). Each float operation is within u of its exact
    result (libm's sine within one ulp, 2u), so |computed - exact d'| <=
    u(|v| + t) (v - t) + |eps|u(|phi| + t) (the argument; sin is 1-Lipschitz) + 2u|eps| (sine)
    + u|eps| (product) + u(1 + u)(|v| + t + |eps|) (sum)
    <= B = u(1 + 2u)*(2(|v| + t) + |eps|(|phi| + t + 4)). The test measures the actual error
    against mpmath, holds it to B (the derivation), and holds rate_error to at least B: a bound on
    the error must cover its worst case. At these points a bound with |v| - t, (1 + |phi|) - t or
    1 - |phi| in place of its terms is below B, at some of them below the measured error itself."""
    worst = 0.0
    with mp.workdps(DPS):
        for phi, v, eps, t in _rate_points(21):
            p, w, e, tt = (mp.mpf(x) for x in (phi, v, eps, t))
            err = abs(mp.mpf(gap_rate(phi, v, eps, t)) - (w - tt + e * mp.sin(p + tt)))
            bound = U * (1 + 2 * U) * (2 * (abs(v) + t) + abs(eps) * (abs(phi) + t + 4))
            assert err <= bound, (phi, v, eps, t, float(err / U), bound / U)
            assert rate_error(phi, v, eps, t) >= bound, (phi, v, eps, t)
            worst = max(worst, float(err / bound))
    assert worst > 0.1  # the points exercise the rounding (not all exact)


def test_the_concave_shortcut_allows_for_the_rounding_of_a_long_angle():
    """``may_be_graze``'s curvature margin covers the rounding of the angle: cos is taken of
    fl(phi + t), off by up to ulp(phi + t)/2 (16u at t ~ 26), and d'' moves by |eps*sin| times that,
    more than a margin of 4u|eps| alone. Here phi + t is one such sum: the exact d'' is
    +5u > 0 (mpmath, exact sum) while -1 + 2*cos(fl(phi + t)) + 8u is -13u. The shortcut ("locally
    concave, so it surely crosses within 2*d_err/|r|") does not apply: over [0, 2*d_err/|r|] the
    gap's Taylor model with its remainder bounds (|d'''| and |eps|*s**4/24) stays positive at 60
    digits (checked on a fine grid; the quadratic part alone has its minimum D - r**2/(2*d'') > 0 at
    s = |r|/d''), so a crossing there is not certain, and the answer is the slope test's: True. The
    margin includes the argument's rounding, 4u|eps|*(1 + t), as in lower_bound_flight."""
    phi, t, eps = 0.5000000000000019, 25.67993877991494, 2.0
    r, d_err = -1e-32, 1e-48  # |r| between 2*d_err/R (4u|eps| margin) and sqrt(4*d_err*d'')
    assert -1.0 + eps * math.cos(phi + t) + 4.0 * U * abs(eps) < 0.0  # a margin of 4u|eps| alone
    with mp.workdps(DPS):
        theta = mp.mpf(phi) + mp.mpf(t)
        d2, d3 = -1 + eps * mp.cos(theta), -eps * mp.sin(theta)
        assert 0 < d2 < 8 * U
        big_d, s_max = 2 * mp.mpf(d_err), 2 * mp.mpf(d_err) / abs(mp.mpf(r))
        assert big_d - mp.mpf(r) ** 2 / (2 * d2) > 0
        for k in range(0, 401):
            s = s_max * mp.mpf(10) ** (-k / 20)
            low = big_d + r * s + d2 * s**2 / 2 - abs(d3) * s**3 / 6 - abs(eps) * s**4 / 24
            assert low > 0, s
    assert r > -2.0 * math.sqrt(4.0 * (abs(eps) - 1.0) * d_err)
    assert may_be_graze(phi, eps, t, r, d_err)


def test_first_root_without_a_root_and_at_its_rounding_threshold():
    """d + r*s + k*s**2/2 with d > 0: r = k = 0 (or r >= 0, k >= 0) has no root: inf. A
    discriminant r**2 - 2*k*d that is negative by less than 4u*(r**2 + 2|k|*d) counts as zero:
    r = -1, k*d = (1 + 2**-51)/2 gives -2**-51 (exact), within 4u*2: the double root 2*d/(-r)."""
    from fastpath.elastic.lower_bound import first_root

    assert first_root(1.0, 0.0, 0.0) == math.inf
    assert first_root(1.0, 0.5, 0.0) == math.inf
    assert first_root(0.5, -1.0, 1.0 + 2.0**-51) == 1.0
    assert first_root(0.5, -1.0, 1.0 + 2.0**-40) == math.inf  # clearly negative: no root


def test_an_overflowing_w0_is_an_overflow():
    """w0 = v + eps*sin(phi) = inf: OVERFLOW (not UNCERTAIN), before any evaluation."""
    s, c = math.sin(1.0), math.cos(1.0)
    for method in (0, GENERAL):
        tau, _, _, _, evaluations, status = flight_from(1.0, s, c, 1.5e308, 1e308, method, 0.0)
        assert status == int(FlightStatus.OVERFLOW) and evaluations == 0 and math.isnan(tau)


def test_the_gap_bounds_are_named_by_what_they_hold():
    """``elastic_gap_bounds`` returns a ``GapBounds``: each field is the quantity its name says
    (the gap, its slope, their rounding bounds; eps; a = 1 + |eps|)."""
    phi, v, eps, t = 0.7, 3.0, 0.6, 1.25
    bounds = elastic_gap_bounds(phi, v, eps, t)
    assert isinstance(bounds, GapBounds)
    assert bounds.gap == gap(phi, v, eps, t)
    assert bounds.rate == gap_rate(phi, v, eps, t)
    assert bounds.gap_error == gap_error(phi, v, eps, t)
    assert bounds.rate_error == rate_error(phi, v, eps, t)
    assert bounds.jerk == -eps * math.sin(phi + t)
    assert (bounds.eps, bounds.curvature_bound) == (eps, 1.0 + abs(eps))
    assert bounds.curvature < -1.0 + eps * math.cos(phi + t)


# --- one loop of lower-bound steps for every description ---

FASTPATH = Path(fastpath.__file__).resolve().parent


def _callers(name):
    """(module path, innermost function) of every call of ``name`` in fastpath's sources."""
    found = []

    def visit(node, where, path):
        if isinstance(node, ast.FunctionDef):
            where = node.name
        if isinstance(node, ast.Call):
            called = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(
                node.func, "id", None)
            if called == name:
                found.append((path, where))
        for child in ast.iter_child_nodes(node):
            visit(child, where, path)

    for path in sorted(FASTPATH.rglob("*.py")):
        visit(ast.parse(path.read_text()), None, path.relative_to(FASTPATH).as_posix())
    return found


def test_one_loop_takes_the_lower_bound_steps_of_every_description():
    """The certified step is taken in one place: ``next_point`` is called once, by
    ``lower_bound_steps`` (the elastic and the drag flights run that loop), and the step itself,
    ``certified_step``, by ``next_point`` only."""
    assert _callers("next_point") == [("elastic/lower_bound.py", "lower_bound_steps")]
    assert _callers("certified_step") == [("elastic/lower_bound.py", "next_point")]


def test_each_description_class_that_flies_registers_its_model_of_the_loop():
    """The loop's model functions of ``Elastic`` and ``Dissipative`` descriptions (the classes
    whose flights take lower-bound steps) take the parameters of the functions they stand for
    (numba compiles the registered function in their place)."""
    models = flight_module._MODELS
    assert set(models) == {Elastic, Dissipative}
    for model in models.values():
        for name in ("bounds_at", "jumps_of", "jump"):
            stub = inspect.signature(getattr(flight_module, name)).parameters
            assert inspect.signature(getattr(model, name)).parameters.keys() == stub.keys(), name


@pytest.mark.parametrize("physics", [elastic(2.0), dissipative(2.0, 0.01, 1, 1.0)],
                         ids=["elastic", "linear drag"])
def test_evaluations_already_used_count_against_the_one_budget(physics):
    """``used`` evaluations spent before the steps (the drag's concave solver hands over its
    count) come out of the same ITERATION_LIMIT: a flight that takes k evaluations from a start
    reports k + used, and with none left it ends MAX_ITERATIONS at its start, unevaluated."""
    phi, v, t = 0.5, 2.0, 1e-3  # w0 = 2 + 2*sin(0.5) > 0: d > 0 on (0, 1e-3]
    tau, k, status = lower_bound_steps(phi, v, physics, t, 0)
    assert status == CONVERGED and 1 < k < ITERATION_LIMIT - 10
    assert lower_bound_steps(phi, v, physics, t, 10) == (tau, k + 10, CONVERGED)
    short, evaluations, status = lower_bound_steps(phi, v, physics, t, ITERATION_LIMIT - k + 1)
    assert (evaluations, status) == (ITERATION_LIMIT, MAX_ITERATIONS) and t < short < tau
    assert lower_bound_steps(phi, v, physics, t, ITERATION_LIMIT) == (t, ITERATION_LIMIT,
                                                                       MAX_ITERATIONS)


@pytest.mark.parametrize("physics", [elastic(2.0), dissipative(2.0, 0.01, 1, 1.0)],
                         ids=["elastic", "linear drag"])
def test_the_loop_as_plain_python_takes_the_compiled_loops_steps(physics):
    """The model table is read by the plain-Python loop too (its callees compiled): the same
    flight, bit for bit, as the loop compiled for the class."""
    phi, v, t = 0.5, 2.0, 1e-3
    assert _py(lower_bound_steps)(phi, v, physics, t, 3) == lower_bound_steps(phi, v, physics, t, 3)
