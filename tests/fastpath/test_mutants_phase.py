"""Tests written against the survivors of the solver mutation pass on ``fastpath/phase.py``
(issue 12, ``scripts/mutation.sh solver``, session 6): the phase reduction's tables and ties."""

import math

from mpmath import mp

from fastpath.arithmetic.phase import _E_MIN, _PIECE_BITS, _PIECES, _TURNS


def test_turn_table_is_the_fraction_of_two_to_the_j_over_two_pi():
    """``_TURNS[j - _E_MIN, i]`` is piece i of frac(2**j / (2*pi)) (module docstring): the six
    26-bit pieces, weights 2**-26 ... 2**-156, are exactly floor(frac * 2**156) read in 26-bit
    chunks, for every row j = _E_MIN .. 1023, and the table has no other rows. Reference:
    mpmath at 1400 bits (2**1023/(2*pi) has 1021 integer bits, plus 156 fraction bits and
    guard). Kills the fraction's mask ``(1 << 156) - 1`` -> ``- 2`` (the last bit of piece six
    dropped in 563 entries)."""
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
    """Found by the phase mutants (session 6): reduce_phase(1.5312731109035593e60), whose
    remainder is 1.34e-17, returned 0.0 (the turns' small pieces carried hi past 1, a case the
    range check missed), and for negative such x it returned -1.3e-17, outside [0, 2*pi). Now
    the ends are decided exactly (``lo >= top - hi``). Both reductions, for x and -x over
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
    """Kills ``_payne_hanek``'s ``centred and r >= PI`` -> ``r > PI`` (session 6's phase
    mutants): x whose x/(2*pi) lies within ~1e-18 of a half turn (x/2 for the whole-turn
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
    """Kills ``reduce_phase``'s and ``centre_phase``'s ``abs(x) >= CODY_WAITE_LIMIT`` -> ``>``
    (session 6): x = +-2**20 belongs to Payne-Hanek (module docstring: |x| >= 2**20), whose
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
    """Kills, in ``centre_moderate``, ``r < -PI`` -> ``r <= -PI``, ``r + TWO_PI`` -> ``r - TWO_PI``,
    ``r >= PI`` -> ``r > PI``, ``r - TWO_PI`` -> ``r + TWO_PI`` and the final ``x < PI`` ->
    ``x <= PI``, and ``centre_phase``'s ``x < PI`` -> ``x <= PI`` (session 6). The result is in
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


def test_collide_from_counts_the_carried_sine_error():
    """Kills ``collide_from``'s ``phase_error_of(phi, centred) + sine_error`` -> ``-`` (collision
    mutant 0, session 6). ``sine_error`` bounds the error of the given sine (CARRIED_SINE_ERROR,
    8u, by default), and ``flight_from`` says NOT_DEPARTING only where w0 <= 0 is certain: a w0
    within the carried sine's error of 0 but beyond its other error terms (2u|w0| + 3u|eps sin|,
    1.5u here) is UNCERTAIN. phi = the float next to pi/6 (already centred: no reduction error),
    the given sine 0.5 (mpmath: within u of sin(phi)), eps = 1, v = -0.5 + j*u: w0 = j*u exactly,
    for j = -6 .. 6 (|w0| <= 6u < 8u)."""
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
