"""The sine and cosine that a flight returns are those of the exact angle phi + tau.

``fastpath.arithmetic.rotation.sin_cos_of_sum`` takes libm at a = fl(x + y) and adds the TwoSum
remainder e = x + y - a by angle addition. Its error bound, from the precision: libm's sine and
cosine are within 1 ulp (<= 2u for values below 1), the two products and the sum add 1.5u, the
Taylor polynomials' truncation is below u/40: 4u in all (u = 2**-53). libm at fl(x + y) alone is
off by up to |e| = ulp(x + y)/2, 16u at x + y ~ 24 and growing with the angle, more than the 8u a
collision allows for a carried sine (``CARRIED_SINE_ERROR``).
"""

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from mpmath import mp

from fastpath.arithmetic.phase import centre_phase
from fastpath.arithmetic.rotation import SMALL_ANGLE, rotate, sin_cos_of_sum, small_sin_cos
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, two_sum
from fastpath.elastic.collision import CARRIED_SINE_ERROR
from fastpath.elastic.flight import flight_from
from fastpath.status import CONVERGED

SUM_ERROR = 4.0 * UNIT_ROUNDOFF

angles = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)


def _exact(x, y):
    with mp.workdps(60):
        angle = mp.mpf(x) + mp.mpf(y)
        return mp.sin(angle), mp.cos(angle)


@settings(max_examples=300)
@given(angles, angles)
def test_sin_cos_of_sum_is_of_the_exact_sum(x, y):
    s, c = sin_cos_of_sum(x, y)
    s_ref, c_ref = _exact(x, y)
    assert abs(s - s_ref) <= SUM_ERROR and abs(c - c_ref) <= SUM_ERROR, (x, y)


def test_the_rounded_angle_alone_is_not_enough():
    """The witness: libm at fl(x + y) misses by more than the carried bound, the sum does not."""
    x, y = 2.8535527917488874, 21.44700044166408  # phi and 2v of a long Holmes step
    assert two_sum(x, y)[1] != 0.0
    found = False
    for k in range(-64, 65):  # neighbours of y: some give a remainder near ulp/2
        yk = y + k * math.ulp(y)
        s_ref, c_ref = _exact(x, yk)
        if abs(math.sin(x + yk) - s_ref) > CARRIED_SINE_ERROR:
            found = True
        s, c = sin_cos_of_sum(x, yk)
        assert abs(s - s_ref) <= SUM_ERROR and abs(c - c_ref) <= SUM_ERROR
    assert found  # the old way exceeds 8u for at least one of them


def test_sin_cos_of_sum_without_a_remainder_is_libm():
    for x, y in [(0.0, 24.0), (1.5, 0.25), (-3.0, 3.0), (0.0, 1e300)]:
        assert two_sum(x, y)[1] == 0.0
        assert sin_cos_of_sum(x, y) == (math.sin(x + y), math.cos(x + y))


def test_rotate_small_steps_by_angle_addition_long_ones_afresh():
    phi, t = 0.7, 3.0
    s0, c0 = math.sin(phi + t - 0.1), math.cos(phi + t - 0.1)
    sh, ch = small_sin_cos(0.1)
    assert rotate(s0, c0, 0.1, phi, t) == (s0 * ch + c0 * sh, c0 * ch - s0 * sh)
    h = math.nextafter(SMALL_ANGLE, 1.0)  # just longer than SMALL_ANGLE: the given sine is unused
    assert rotate(0.0, 1.0, h, phi, t) == sin_cos_of_sum(phi, t)
    assert rotate(0.0, 1.0, -h, phi, t) == sin_cos_of_sum(phi, t)
    sh, ch = small_sin_cos(SMALL_ANGLE)
    assert rotate(0.0, 1.0, SMALL_ANGLE, phi, t) == (sh, ch)  # at SMALL_ANGLE itself: addition


@pytest.mark.parametrize("eps", [1.2, 2.0, 4.0, -3.0])
@settings(max_examples=60, deadline=None)
@given(phi=st.floats(-math.pi, math.pi, exclude_max=True), v=st.floats(5.0, 40.0))
def test_long_flights_carry_the_sine_of_the_exact_angle(eps, phi, v):
    """|eps| > 1 (lower-bound steps): long flights, angles phi + tau up to ~90, where libm at the
    rounded angle was off by up to 64u. Every returned sine and cosine is within the bound the
    next flight assumes for it."""
    phi = centre_phase(phi)
    tau, tau_lo, s, c, _, status = flight_from(phi, math.sin(phi), math.cos(phi), v, eps)
    assume(status == CONVERGED)
    with mp.workdps(60):
        angle = mp.mpf(phi) + mp.mpf(tau) + mp.mpf(tau_lo)  # the root as an unevaluated sum
        assert abs(s - mp.sin(angle)) <= CARRIED_SINE_ERROR, (phi, v, eps, tau)
        assert abs(c - mp.cos(angle)) <= CARRIED_SINE_ERROR, (phi, v, eps, tau)


def test_collide_from_counts_the_carried_sine_error():
    """``collide_from`` counts the carried sine's error in the departure's: ``sine_error`` bounds
    the error of the given sine (CARRIED_SINE_ERROR, 8u, by default), and ``flight_from`` says
    NOT_DEPARTING only where w0 <= 0 is certain: a w0 within the carried sine's error of 0 but
    beyond its other error terms (2u|w0| + 3u|eps sin|, 1.5u here) is UNCERTAIN. phi = the float
    next to pi/6 (already centred: no reduction error), the given sine 0.5 (mpmath: within u of
    sin(phi)), eps = 1, v = -0.5 + j*u: w0 = j*u exactly, for j = -6 .. 6 (|w0| <= 6u < 8u)."""
    from fastpath.elastic.collision import CARRIED_SINE_ERROR, collide_from
    from fastpath.status import UNCERTAIN

    u = 2.0**-53
    phi = math.pi / 6
    with mp.workprec(200):
        assert abs(mp.sin(mp.mpf(phi)) - mp.mpf(0.5)) <= u
    assert CARRIED_SINE_ERROR >= 8 * u
    for j in (-6, -4, -2, 2, 4, 6):
        v = -0.5 + j * u
        assert v + 0.5 == j * u
        status = collide_from(phi, 0.5, math.sqrt(3.0) / 2, v, 1.0)[6]
        assert status == UNCERTAIN, (j, status)
