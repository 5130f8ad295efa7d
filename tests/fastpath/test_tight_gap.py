"""``fastpath.elastic.tight_gap``: its bounds E and R hold against the exact gap and slope (mpmath).

The bound is the certificate of the concave solver's refinement near (near-)triple roots, so it
is tested where it is tight and where the departure's sine is not libm's: the given sine and
cosine may each be off by the phase error pe that the caller put into w0_error
(``fastpath.elastic.gap.departure``), as they are when carried along an orbit. The exact gap is
taken at the exact departure phase phi_e, with the given pair within pe (+ 1 ulp) of sin and cos of
phi_e.
"""

import math

import pytest
from fastpath_tolerances import U
from hypothesis import example, given
from hypothesis import strategies as st
from mpmath import mp

from fastpath.elastic.gap import departure, gap_error, rate_error
from fastpath.elastic.tight_gap import tight_gap

DPS = 60


def exact_gap_and_rate(phi_e, v, eps, t):
    """d(t) and d'(t) at the exact phase phi_e (an mpf), product form, DPS digits."""
    with mp.workdps(DPS):
        v, eps, t = mp.mpf(v), mp.mpf(eps), mp.mpf(t)
        d = 2 * eps * mp.sin(phi_e + t / 2) * mp.sin(t / 2) + t * (v - t / 2)
        return d, v - t + eps * mp.sin(phi_e + t)


def check_bounds(phi, v, eps, t, pe=0.0, a=0.0, b=0.0, theta=0.0):
    """The given sine/cosine: libm's at phi, or (pe > 0) those of phi_e = phi + theta*pe moved
    by a*pe and b*pe (|a|, |b|, |theta| <= 1). Asserts |computed - exact| <= bound for d, d'."""
    with mp.workdps(DPS):
        phi_e = mp.mpf(phi) + mp.mpf(theta) * mp.mpf(pe)
        if pe > 0.0:
            sin_phi = float(mp.sin(phi_e) + a * mp.mpf(pe))
            cos_phi = float(mp.cos(phi_e) + b * mp.mpf(pe))
        else:
            sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    _, w0_error = departure(phi, sin_phi, v, eps, pe)
    d, d1, _, _, _, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, eps, w0_error, t)
    exact_d, exact_d1 = exact_gap_and_rate(phi_e, v, eps, t)
    with mp.workdps(DPS):
        assert abs(mp.mpf(d) - exact_d) <= d_err, (d, float(exact_d), d_err)
        assert abs(mp.mpf(d1) - exact_d1) <= d1_err, (d1, float(exact_d1), d1_err)
    return d_err, d1_err


phases = st.floats(min_value=-math.pi, max_value=math.pi, exclude_max=True)
small_eps = st.floats(min_value=-1.0, max_value=1.0)


@given(phi=phases, v=st.floats(min_value=-3.0, max_value=30.0), eps=small_eps,
       t=st.floats(min_value=1e-12, max_value=60.0))
@example(phi=-1e-3, v=1e-3, eps=1.0, t=2e-3)
def test_bound_holds_for_libm_sines(phi, v, eps, t):
    check_bounds(phi, v, eps, t)


@given(log_x=st.floats(min_value=-8.0, max_value=0.0),
       gap=st.one_of(st.just(0.0), st.floats(min_value=2.0**-53, max_value=1e-3)),
       rel=st.floats(min_value=-1e-3, max_value=1e-3))
@example(log_x=-4.5, gap=0.0, rel=0.0)  # phi = -x, v = x, t = 2x exactly: a root
@example(log_x=-6.0, gap=0.0, rel=1e-9)
def test_bound_holds_near_triple_roots(log_x, gap, rel):
    """phi = -x, v = x, t = 2x*(1 + rel): the terms ~t*x cancel to ~x**4/24."""
    x = 10.0**log_x
    check_bounds(-x, x, 1.0 - gap, 2.0 * x * (1.0 + rel))


@given(phi=phases, v=st.floats(min_value=-3.0, max_value=30.0), eps=small_eps,
       t=st.floats(min_value=1e-12, max_value=60.0),
       pe=st.sampled_from([2.0**-53, 8.0 * U, 1e-12]),
       a=st.sampled_from([-1.0, 1.0]), b=st.sampled_from([-1.0, 1.0]),
       theta=st.floats(min_value=-1.0, max_value=1.0))
def test_bound_holds_for_carried_sines(phi, v, eps, t, pe, a, b, theta):
    """Sine and cosine each off by the full phase error (the orbit's carried pair)."""
    check_bounds(phi, v, eps, t, pe, a, b, theta)


@given(log_x=st.floats(min_value=-6.0, max_value=-1.0),
       a=st.sampled_from([-1.0, 1.0]), b=st.sampled_from([-1.0, 1.0]),
       theta=st.floats(min_value=-1.0, max_value=1.0))
def test_bound_holds_near_triple_roots_with_carried_sines(log_x, a, b, theta):
    x = 10.0**log_x
    check_bounds(-x, x, 1.0, 2.0 * x, 8.0 * U, a, b, theta)


def test_bound_is_far_below_the_generic_one_near_a_triple_root():
    """The point of the module: at phi = -x, v = x, eps = 1, t = 2x the generic gap bound
    ``gap_error`` exceeds the gap's scale x**4/24 (and ``rate_error`` the slope x**3/6 for
    x = 1e-5), so the solver cannot place the root with them. The tight ones are below an eighth
    of the scales: E < x**4/192 puts the root within 3*E/x**4 < 1/64 (relative) of where the
    computed gap vanishes (|d'(2x)|*2x = x**4/3), R < x**3/48 decides the slope's sign."""
    for x in (1e-6, 1e-5, 3e-5):
        t = 2.0 * x
        d_err, d1_err = check_bounds(-x, x, 1.0, t)
        assert gap_error(-x, x, 1.0, t) > x**4 / 24
        assert d_err < x**4 / 24 / 8 and d1_err < x**3 / 6 / 8, (x, d_err, d1_err)
    assert rate_error(-1e-5, 1e-5, 1.0, 2e-5) > 1e-15 / 6


@pytest.mark.parametrize("sin_phi, cos_phi, v, eps, w0_error, t", [
    (math.sin(1.0), math.cos(1.0), 0.7, 0.8, 3e-16, 0.9),
    (math.sin(-2.5), math.cos(-2.5), 3.0, -0.95, 1e-15, 5.5),
    (math.sin(-3e-5), math.cos(-3e-5), 3e-5, 1.0, 2e-21, 6e-5),  # the triple family's scale
    (math.sin(2.0), math.cos(2.0), -0.4, 0.3, 5e-17, 0.2),
    (0.0, 1.0, 2.0**-1000, 0.5, 0.0, 2.0**-1000),  # SMALLEST_T: the underflow allowance shows
])
def test_tight_bounds_are_the_documented_ones(sin_phi, cos_phi, v, eps, w0_error, t):
    """``tight_gap``'s E and R are the module docstring's formulas (its proof), evaluated on the
    computed terms, times 1 + 64u plus the underflow allowance; and d, d', d'', sin and cos of
    phi + t are those of the half-angle form. Every term of E and R is of order u here (the
    w0_error ones too), so a dropped or subtracted term moves E or R by far more than the few u
    of evaluation order allowed. At t = SMALLEST_T the terms underflow and E is the allowance
    2**-1060 alone (a positive bound)."""
    from fastpath.elastic.tight_gap import tight_gap

    d, d1, d2, s, c, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, eps, w0_error, t)
    with mp.workdps(DPS):
        sp, cp, w, e, we, tt = (mp.mpf(x) for x in (sin_phi, cos_phi, v, eps, w0_error, t))
        sh, ch = mp.sin(tt / 2), mp.cos(tt / 2)
        m, cm = sp * ch + cp * sh, cp * ch - sp * sh
        s_x, c_x = m * ch + cm * sh, cm * ch - m * sh
        plate, flight = 2 * e * sh * m, tt * (w - tt / 2)
        d_x, d1_x = plate + flight, (w - tt) + e * s_x
        close = 64 * U
        for got, want in ((d, d_x), (d1, d1_x), (d2, -1 + e * c_x), (s, s_x), (c, c_x)):
            assert abs(got - want) <= close * (abs(plate) + abs(flight) + abs(w) + tt + 1), (
                got, want)
        ash, asp, ae = abs(sh), abs(sp), abs(e)
        e_doc = U * (abs(d_x) + 5 * abs(plate) + 2 * abs(flight)) + 2 * ash * (
            U * ae * (3 * asp + 5 * ash) + we * (1 + ash))
        r_doc = U * (abs(d1_x) + abs(w - tt) + ae * (2 * abs(s_x) + 4 * abs(m) + 6 * asp
                                                     + 14 * ash)) + we * (1 + 3 * ash)
        for got, doc in ((d_err, e_doc), (d1_err, r_doc)):
            want = doc * (1 + 64 * mp.mpf(U)) + mp.mpf(2) ** -1060  # docstring's factor, allowance
            assert abs(got - want) <= close * want, (got, want)
