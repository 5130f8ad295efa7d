"""The phase reduction (``fastpath.arithmetic.phase``) against mpmath.

x mod 2*pi (``reduce_phase``) and its centred form in [-pi, pi) (``centre_phase``,
``centre_moderate``): at random, at the boundary between the Cody-Waite and Payne-Hanek ranges,
next to whole and half turns (continued fractions of 2**e/(2*pi)), next to +-pi, and the tables
the reduction is built from, bit for bit.
"""

import math

from fastpath_tolerances import DPS, ULP_2PI, U, phase_distance
from hypothesis import example, given
from hypothesis import strategies as st
from mpmath import mp

from fastpath.arithmetic.phase import (
    _E_MIN,
    _PIECE_BITS,
    _PIECES,
    _TURNS,
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


def test_turn_table_is_the_fraction_of_two_to_the_j_over_two_pi():
    """``_TURNS[j - _E_MIN, i]`` is piece i of frac(2**j / (2*pi)) (module docstring): the six
    26-bit pieces, weights 2**-26 ... 2**-156, are exactly floor(frac * 2**156) read in 26-bit
    chunks, for every row j = _E_MIN .. 1023, and the table has no other rows. Reference:
    mpmath at 1400 bits (2**1023/(2*pi) has 1021 integer bits, plus 156 fraction bits and
    guard). Every bit counts: the last bit of piece six alone is set in 563 entries."""
    bits = _PIECES * _PIECE_BITS
    assert _TURNS.shape == (1024 - _E_MIN, _PIECES)
    with mp.workprec(1400):
        inverse = 1 / (2 * mp.pi)
        for j in range(_E_MIN, 1024):
            scaled = mp.ldexp(inverse, j)
            fixed = int(mp.floor((scaled - mp.floor(scaled)) * mp.mpf(2) ** bits))
            for i in range(_PIECES):
                chunk = (fixed >> (bits - _PIECE_BITS * (i + 1))) & ((1 << _PIECE_BITS) - 1)
                assert _TURNS[j - _E_MIN, i] == math.ldexp(chunk, -_PIECE_BITS * (i + 1)), (j, i)


def _near_turns(exponents=range(30, 300, 7), least=2**40):
    """Doubles x = q*2**e (q < 2**53) whose x/(2*pi) lies within ~1e-17 of an integer: q runs
    over the continued-fraction denominators of frac(2**e/(2*pi)). The remainders x mod 2*pi
    are ~1e-17 or 2*pi - 1e-17: the hardest arguments of a reduction (cancellation to the
    last piece of the table)."""
    out = []
    with mp.workprec(1500):
        for e in exponents:
            alpha = mp.ldexp(1 / (2 * mp.pi), e)
            x_cf = alpha - mp.floor(alpha)
            p0, q0, p1, q1 = 0, 1, 1, 0
            for _ in range(200):
                a = int(mp.floor(x_cf))
                p0, q0, p1, q1 = p1, q1, a * p1 + p0, a * q1 + q0
                if q1 >= 2**53:
                    break
                if q1 >= least:
                    out.append(math.ldexp(q1, e))
                fraction = x_cf - a
                if fraction == 0:
                    break
                x_cf = 1 / fraction
    return out


def _circle(y, exact):
    """Distance from the float y to the exact remainder on the circle of length 2*pi."""
    d = (mp.mpf(y) - exact) % (2 * mp.pi)
    return min(d, 2 * mp.pi - d)


def test_reductions_next_to_a_whole_turn():
    """x whose remainder mod 2*pi is ~1e-17 or 2*pi - 1e-17, where the turns' small pieces can
    carry the fraction past 1 (e.g. 1.5312731109035593e60, remainder 1.34e-17: not 0.0, and
    for -x not -1.3e-17, outside [0, 2*pi)). Both reductions, for x and -x over
    ~100 such arguments: in range, and within the rounding of the result (u*2*pi for
    [0, 2*pi), which may round 2*pi - 1e-17 to 0; 2u*|r| for the centred result) plus
    PAYNE_HANEK_ERROR, measured as a distance on the circle against mpmath at 1500 bits; and
    ``phase_error_of`` bounds the centred error."""
    from fastpath.arithmetic.phase import PAYNE_HANEK_ERROR, PI, TWO_PI, centre_phase, reduce_phase
    from fastpath.elastic.flight import phase_error_of

    xs = _near_turns()
    assert len(xs) > 40
    u = 2.0**-53
    with mp.workprec(1500):
        two_pi = 2 * mp.pi
        for x in xs + [-x for x in xs]:
            exact = mp.mpf(x) - two_pi * mp.floor(mp.mpf(x) / two_pi)
            r, c = reduce_phase(x), centre_phase(x)
            assert 0.0 <= r < TWO_PI and -PI <= c < PI, x
            assert _circle(r, exact) <= u * TWO_PI + PAYNE_HANEK_ERROR, (x, r, float(exact))
            assert _circle(c, exact) <= 2 * u * abs(c) + PAYNE_HANEK_ERROR, (x, c, float(exact))
            assert _circle(c, exact) <= phase_error_of(x, c), x


def test_reductions_next_to_a_half_turn():
    """x whose x/(2*pi) lies within ~1e-18 of a half turn (x/2 for the whole-turn
    arguments of ``_near_turns``, whose turn count is odd for about half of them) have a centred
    remainder pi - 1e-17 that rounds to the float PI, outside [-pi, pi) as the code's own range
    check reads it (``-PI <= x < PI``): it must come back as -PI (same point on the circle up to
    the rounding). For x and -x: both reductions in range and, against mpmath at 1500 bits,
    within the rounding of the result plus PAYNE_HANEK_ERROR (module docstring, Accuracy)."""
    from fastpath.arithmetic.phase import PAYNE_HANEK_ERROR, PI, TWO_PI, centre_phase, reduce_phase

    xs = [x / 2 for x in _near_turns()]
    u = 2.0**-53
    rounded_to_pi = 0
    with mp.workprec(1500):
        two_pi = 2 * mp.pi
        for x in xs + [-x for x in xs]:
            exact = mp.mpf(x) - two_pi * mp.floor(mp.mpf(x) / two_pi)
            r, c = reduce_phase(x), centre_phase(x)
            assert 0.0 <= r < TWO_PI and -PI <= c < PI, (x, r, c)
            assert _circle(r, exact) <= u * TWO_PI + PAYNE_HANEK_ERROR, (x, r, float(exact))
            assert _circle(c, exact) <= 2 * u * abs(c) + PAYNE_HANEK_ERROR, (x, c, float(exact))
            rounded_to_pi += c == -PI and abs(exact - mp.pi) < 2 * u
    assert rounded_to_pi >= 5  # the tie the test is for is met


def test_payne_hanek_at_two_to_the_twenty():
    """x = +-2**20 belongs to Payne-Hanek (module docstring: |x| >= 2**20), whose
    result is exact up to its rounding plus PAYNE_HANEK_ERROR, |r - exact| <= ulp(r)/2 +
    PAYNE_HANEK_ERROR; Cody-Waite ("a few ulps") is one ulp off there (0x1.58e8ec12c0aa9p-2 for
    an exact 0.33682602753121184659...). Reference: mpmath at 200 bits."""
    from fastpath.arithmetic.phase import MODERATE_LIMIT as CODY_WAITE_LIMIT
    from fastpath.arithmetic.phase import PAYNE_HANEK_ERROR, centre_phase, reduce_phase

    assert CODY_WAITE_LIMIT == 2.0**20
    with mp.workprec(200):
        two_pi = 2 * mp.pi
        for x in (2.0**20, -(2.0**20)):
            exact = mp.mpf(x) - two_pi * mp.floor(mp.mpf(x) / two_pi)
            centred = exact - two_pi if exact >= mp.pi else exact
            for got, want in ((reduce_phase(x), exact), (centre_phase(x), centred)):
                assert abs(mp.mpf(got) - want) <= math.ulp(got) / 2 + PAYNE_HANEK_ERROR, (x, got)


def _next(x, n, towards):
    for _ in range(n):
        x = math.nextafter(x, towards)
    return x


def test_centring_next_to_plus_and_minus_pi():
    """``centre_phase`` and ``centre_moderate`` next to +-pi and odd multiples of pi, where each
    of their range tests (strict or not) and wraps by 2*pi decides the result. It is in
    [-pi, pi) as the code reads it (``-PI <= c < PI``; a phase already there is returned
    unchanged, so the float PI, just below pi, is not: it is taken as out of range) and good to a
    few ulps of 2*pi (module docstring; 2 ulps here) on the circle, against mpmath. The ties are
    met at the floats next to +-PI and 3*PI: PI itself (Cody-Waite gives r < -PI), the float
    above PI (r rounds to exactly -PI), the float below -PI (r rounds to exactly PI), and
    91.106186954104 (29*pi + 1.2e-18, r rounds to -PI with k = 15). ``centre_moderate``, used
    by the lanes, gives the same bits as ``centre_phase`` (the same arithmetic)."""
    from fastpath.arithmetic.phase import PI, TWO_PI, centre_moderate, centre_phase

    xs = [91.106186954104, -91.106186954104]
    for c in (PI, -PI, 3 * PI, -3 * PI, 5 * PI, 29 * PI):
        xs += [_next(c, n, math.inf) for n in range(4)] + [_next(c, n, -math.inf) for n in range(4)]
    with mp.workprec(200):
        two_pi = 2 * mp.pi
        for x in xs:
            exact = mp.mpf(x) - two_pi * mp.floor(mp.mpf(x) / two_pi)
            c = centre_phase(x)
            m = centre_moderate(x)
            assert -PI <= c < PI and -PI <= m < PI, (x, c, m)
            assert math.copysign(1.0, c) == math.copysign(1.0, m) and c == m, (x, c, m)
            assert _circle(c, exact) <= 2 * math.ulp(TWO_PI), (x, c)
            if -PI <= x < PI:
                assert c == x


def test_phase_error_of_a_centred_phase():
    """0 for a phase used as given, one ulp-scale bound 2u*|centred| for a reduced one."""
    from fastpath.arithmetic.phase import centre_phase
    from fastpath.elastic.flight import phase_error_of

    assert phase_error_of(1.0, 1.0) == 0.0
    centred = centre_phase(7.0)
    assert centred != 7.0 and phase_error_of(7.0, centred) == 2.0 * U * abs(centred)
