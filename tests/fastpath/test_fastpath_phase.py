"""fastpath.phase.reduce_phase against mpmath (x mod 2*pi at 50 digits)."""

import math

from fastpath_tolerances import DPS, ULP_2PI, phase_distance
from hypothesis import example, given
from hypothesis import strategies as st
from mpmath import mp

from fastpath.phase import TWO_PI_HI, TWO_PI_LO, TWO_PI_MID, reduce_phase

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


def test_two_pi_split():
    with mp.workdps(DPS):
        total = mp.mpf(TWO_PI_HI) + mp.mpf(TWO_PI_MID) + mp.mpf(TWO_PI_LO)
        assert abs(total - 2 * mp.pi) <= mp.mpf(10) ** -30
    for part in (TWO_PI_HI, TWO_PI_MID):  # 31 significant bits: k*part exact for |k| < 2**21
        mantissa, _ = math.frexp(part)
        assert (mantissa * 2**31).is_integer()
