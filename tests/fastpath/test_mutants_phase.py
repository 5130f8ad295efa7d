"""Tests written against the survivors of the solver mutation pass on ``fastpath/phase.py``
(issue 12, ``scripts/mutation.sh solver``, session 6): the phase reduction's tables and ties."""

import math

from mpmath import mp

from fastpath.phase import _E_MIN, _PIECE_BITS, _PIECES, _TURNS


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
    from fastpath.flight import phase_error_of
    from fastpath.phase import PAYNE_HANEK_ERROR, PI, TWO_PI, centre_phase, reduce_phase

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
