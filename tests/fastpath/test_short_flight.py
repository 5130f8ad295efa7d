"""The short-flight solver (``fastpath.dissipative.short_flight``): the relative-coordinate gap of
chattering impacts, its series and closed forms, the window it is used in, and its iterations.

The solver only evaluates S3 and C4 for t <= SERIES_LIMIT = 1 (the window h <= 1), so their
closed forms for t > 1 were never run by the flight tests; they are public helpers (the drag
solver calls ``s3`` too) and are held to their formulas here. Bounds from the precision:
u = 2**-53, libm's sine within 1 ulp (<= 2u below 1 in magnitude).
"""

import math

import pytest
from mpmath import mp

from fastpath.arithmetic.rounding import UNIT_ROUNDOFF as U
from fastpath.dissipative.short_flight import c4, departure_deceleration, s3
from fastpath.dissipative.short_flight import elastic_short_window as short_window
from fastpath.physics import NONE, dissipative

DPS = 50


def _dps(t):
    """Enough digits for t - sin(t) ~ t**3/6 and 1 - cos(t) - t**2/2 ~ t**4/24 at tiny t."""
    return DPS + (4 * int(-math.log10(t)) if 0.0 < t < 1.0 else 0)


def _s3(t):
    with mp.workdps(_dps(t)):
        return mp.mpf(t) - mp.sin(mp.mpf(t))


def _c4(t):
    with mp.workdps(_dps(t)):
        t = mp.mpf(t)
        return 1 - mp.cos(t) - t * t / 2


@pytest.mark.parametrize("t", [math.nextafter(1.0, 2.0), 1.5, 2.0, 3.0, 7.5, 40.0])
def test_closed_forms_beyond_the_series(t):
    """The closed forms of S3 = t - sin(t) and C4 = 1 - cos(t) - t**2/2 for t > 1: t - sin(t) has
    the error of libm's sine (<= 2u) and one subtraction (u*|S3|); 2*sin(t/2)**2 - t**2/2 that of
    the sine squared and doubled (<= 3*2u*2*sin**2... bounded by 8u*2*sin(t/2)**2) and of t*t/2 and
    the subtraction (u*t**2/2 each, and u*|C4|)."""
    s_ref, c_ref = _s3(t), _c4(t)
    assert abs(s3(t) - s_ref) <= 2 * U + U * abs(s_ref)
    sq = 2.0 * math.sin(0.5 * t) ** 2
    assert abs(c4(t) - c_ref) <= 8 * U * sq + U * t * t + U * abs(c_ref)


@pytest.mark.parametrize("t", [0.0, 1e-70, 1e-8, 0.01, 0.3, 0.75, 1.0])
def test_series_within_a_few_u_relative(t):
    """The series branch (t <= 1), relative to the exact values: cancellation-free, so a few u
    relative (eight Horner steps, each with a term below 1/20 of the sum, and three roundings
    at the end: < 5u). At t = 0 both are exactly 0."""
    s_ref, c_ref = _s3(t), _c4(t)
    assert abs(s3(t) - s_ref) <= 5 * U * abs(s_ref)
    assert abs(c4(t) - c_ref) <= 5 * U * abs(c_ref)


@pytest.mark.parametrize("eps", [0.3, -0.9, 1.5, -4.0, 20.0])
@pytest.mark.parametrize("cos_phi", [-1.0, -0.4, 0.0, 0.3, 0.999])
def test_departure_deceleration_is_a_lower_bound_by_the_documented_margin(eps, cos_phi):
    """a = 1 - eps*cos(phi) lowered by 8u*(1 + 14|eps|): below the exact value of the given
    cosine (so the margin is subtracted, and positive: 1 + 14|eps|, not 1 - 14|eps|, which
    turns it negative for |eps| > 1/14), and not by more than the margin plus the
    rounding of the products (2u*(1 + |eps|))."""
    a = departure_deceleration(cos_phi, eps)
    with mp.workdps(DPS):
        exact = 1 - mp.mpf(eps) * mp.mpf(cos_phi)
        margin = 8 * U * (1 + 14 * abs(eps))
        assert a < exact
        assert exact - a <= margin + 2 * U * (1 + abs(eps))
        assert exact - a >= margin - 2 * U * (1 + abs(eps))


@pytest.mark.parametrize("sin_phi, cos_phi, w, eps", [
    (0.0, -1.0, 1e-3, 1.5), (0.6, -0.8, 1e-5, 1.5), (-0.28, -0.96, 3e-2, 3.0),
    (0.8, 0.6, 1e-4, -1.2), (0.1, 0.3, 1e-10, 0.5),
])
def test_short_window_rounds_its_bound_up(sin_phi, cos_phi, w, eps):
    """The window is 2*w/m_h (m_h from the lowered deceleration a, h = 4w/a) rounded UP by the
    factor 1 + 4u: never below the exact quotient of the float w and m_h (a factor 1 - 4u
    would give at most (1 + u)*(1 - 4u) < 1 times it). m_h is formed here as the docstring
    defines it, from a and h, each exact quotient rounded once (relative 1e-15 of m_h at most,
    covered by the 2u below the 4u factor)."""
    upper = short_window(sin_phi, cos_phi, w, eps)
    assert upper > 0.0
    a = departure_deceleration(cos_phi, eps)
    h = 4.0 * w / a
    m_h = a - abs(eps * sin_phi) * h - 0.5 * abs(eps) * h * h
    with mp.workdps(DPS):
        quotient = 2 * mp.mpf(w) / mp.mpf(m_h)
        assert upper >= quotient
        assert upper <= quotient * (1 + 6 * U)


def test_the_window_is_open_at_h_exactly_one():
    """The window needs h = 4w/a <= SERIES_LIMIT = 1 (the series hold for t <= 1, and the flight
    ends before 2w/m_h <= h): at h = 1 exactly it is open. w = a/4 is
    an exact scaling, so h = 4w/a is exactly 1; eps = 0.1 at cos(phi) = -1 keeps m_h >= a/2."""
    eps, sin_phi, cos_phi = 0.1, 0.0, -1.0
    a = departure_deceleration(cos_phi, eps)
    w = a / 4.0
    assert 4.0 * w / a == 1.0
    assert short_window(sin_phi, cos_phi, w, eps) > 0.0


def test_the_window_is_open_at_m_h_exactly_half_a():
    """The window needs m_h >= a/2; at equality it is open. With sin(phi) = 0,
    m_h = a - (|eps|/2)*h*h, and a - X is exact for X near a/2 (Sterbenz), so m_h == a/2
    exactly when the rounded X is a/2: h is searched among the floats next to sqrt(a/|eps|),
    then w such that fl(4w/a) is that h."""
    eps, cos_phi = 2.0, 0.3
    a = departure_deceleration(cos_phi, eps)
    h0 = math.sqrt(a / abs(eps))
    found = None
    for k in range(-2000, 2000):
        h = h0 + k * math.ulp(h0)
        if a - 0.5 * abs(eps) * h * h == 0.5 * a:
            for j in range(-50, 51):
                w = h * a / 4.0 + j * math.ulp(h * a / 4.0)
                if 4.0 * w / a == h:
                    found = w
                    break
        if found is not None:
            break
    assert found is not None
    assert short_window(0.0, cos_phi, found, eps) > 0.0


def _count_gap_evaluations(monkeypatch, gap=None, rate=None):
    """Run ``short_flight`` as plain Python (``py_func``) with its gap (optionally replaced)
    counted: returns (the solver, the list of evaluation times)."""
    import fastpath.dissipative.short_flight as module

    calls = []
    real_gap = module.relative_gap

    def counted_gap(sin_phi, cos_phi, w, eps, accel, t):
        calls.append(t)
        return (gap or real_gap)(sin_phi, cos_phi, w, eps, accel, t)

    monkeypatch.setattr(module, "relative_gap", counted_gap)
    if rate is not None:
        monkeypatch.setattr(module, "relative_rate", rate)
    for name in ("relative_gap_and_rate", "incoming_rate"):  # their bodies call the two above
        kernel = getattr(module, name)
        monkeypatch.setattr(module, name, getattr(kernel, "py_func", kernel))
    short_flight = getattr(module.short_flight, "py_func", module.short_flight)

    def solve(sin_phi, cos_phi, w, eps, upper):  # without drag the absolute v is not read
        return short_flight(sin_phi, cos_phi, w, 0.0, dissipative(eps, 0.0, NONE, 0.5), upper)

    return solve, calls


def test_reported_iterations_are_the_gap_evaluations(monkeypatch):
    """The iterations returned are the number of gap evaluations (not one fewer
    than it made)."""
    solve, calls = _count_gap_evaluations(monkeypatch)
    sin_phi, cos_phi, w, eps = 0.6, -0.8, 1e-5, 1.5
    upper = short_window(sin_phi, cos_phi, w, eps)
    tau, rate, iterations = solve(sin_phi, cos_phi, w, eps, upper)
    assert 0.0 < tau < upper and rate < 0.0
    assert iterations == len(calls) >= 2


def test_at_most_sixty_evaluations_then_the_limit(monkeypatch):
    """A gap that stays negative while Newton keeps moving down (a stand-in: d = -1, d' = -1e3,
    every step 1e-3) exhausts the solver: exactly ITERATION_LIMIT = 60 evaluations, reported as
    60 (not 59 or 61, nor 60 made and 59 reported)."""
    from fastpath.status import ITERATION_LIMIT

    solve, calls = _count_gap_evaluations(
        monkeypatch, gap=lambda *args: -1.0, rate=lambda *args: -1e3)
    _, _, iterations = solve(0.0, -1.0, 1.0, 0.5, 10.0)
    assert ITERATION_LIMIT == 60
    assert len(calls) == 60 and iterations == 60


def test_a_step_below_the_spacing_ends_newton(monkeypatch):
    """Newton stops when the step no longer decreases t (docstring): a stand-in gap d = -1e-30,
    d' = -1 at t = 1 gives t - d/d' == t, so the answer is t after one evaluation
    (not the same point repeated 60 times)."""
    solve, calls = _count_gap_evaluations(
        monkeypatch, gap=lambda *args: -1e-30, rate=lambda *args: -1.0)
    tau, rate, iterations = solve(0.0, -1.0, 1.0, 0.5, 1.0)
    assert (tau, rate, iterations) == (1.0, -1.0, 1) and len(calls) == 1
