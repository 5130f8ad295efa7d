"""fastpath.arithmetic.phase.reduce_phase against mpmath (x mod 2*pi at 50 digits)."""

import math

from fastpath_tolerances import DPS, ULP_2PI, phase_distance
from hypothesis import example, given
from hypothesis import strategies as st
from mpmath import mp

from fastpath.arithmetic.phase import (
    TWO_PI_HI,
    TWO_PI_LO,
    TWO_PI_MID,
    _inverse_two_pi_fixed,
    centre_phase,
    reduce_phase,
)

TWO_PI = 2.0 * math.pi


@given(st.floats(min_value=-1e7, max_value=1e7))
@example(0.0)
@example(-0.0)
@example(TWO_PI)
@example(math.nextafter(TWO_PI, 0.0))
@example(math.nextafter(0.0, -1.0))
@example(-1e-20)
@example(1e7)
@example(-1e7)
@example(1e6 + 0.3)
@example(-50.0)
@example(1_000_000 * TWO_PI)
@example(-123_456 * TWO_PI)
def test_reduce_phase_matches_mpmath(x):
    r = reduce_phase(x)
    assert 0.0 <= r < TWO_PI
    with mp.workdps(DPS):
        exact = mp.mpf(x) % (2 * mp.pi)
        # 4 ulps of 2*pi, distance taken mod 2*pi (a result of 0 for x just below 2*pi*k is fine)
        assert phase_distance(r, exact) <= 4 * ULP_2PI, (x, r, exact)


@given(st.floats(allow_nan=False, allow_infinity=False))
@example(1e12)
@example(1e17)
@example(-1e300)
@example(1.7976931348623157e308)
@example(-1.7976931348623157e308)
@example(2.0**20)
@example(6381956970095103 * 2.0**797)  # a double within ~1e-19 of a multiple of pi/2
def test_reduce_any_finite_phase_to_half_an_ulp(x):
    """Payne-Hanek range: exact up to the rounding of the result (0.5 ulp, plus 0.5 ulp slack
    for the double-double product), and always in [0, 2*pi)."""
    r = reduce_phase(x)
    assert 0.0 <= r < TWO_PI
    with mp.workdps(400):  # 1e308 / 2*pi needs ~310 digits before the fraction
        exact = mp.mpf(x) % (2 * mp.pi)
        if abs(x) < 2.0**20:
            assert phase_distance(r, exact) <= 4 * ULP_2PI, (x, r, exact)
        else:
            assert abs(mp.mpf(r) - exact) <= math.ulp(float(exact)), (x, r, exact)


def test_centre_phase_compensates_the_float_two_pi():
    with mp.workdps(400):
        for x in (4.0, 6.0, 1e12, -1e300):
            exact = mp.mpf(x) % (2 * mp.pi)
            exact = exact - 2 * mp.pi if exact >= mp.pi else exact
            assert abs(mp.mpf(centre_phase(x)) - exact) <= math.ulp(float(exact)), x


def test_inverse_two_pi_table_matches_mpmath():
    with mp.workprec(1400):
        assert _inverse_two_pi_fixed(1300) == int(mp.floor(mp.mpf(2) ** 1300 / (2 * mp.pi)))


def test_two_pi_split():
    with mp.workdps(DPS):
        total = mp.mpf(TWO_PI_HI) + mp.mpf(TWO_PI_MID) + mp.mpf(TWO_PI_LO)
        assert abs(total - 2 * mp.pi) <= mp.mpf(10) ** -30
    for part in (TWO_PI_HI, TWO_PI_MID):  # 31 significant bits: k*part exact for |k| < 2**21
        mantissa, _ = math.frexp(part)
        assert (mantissa * 2**31).is_integer()
