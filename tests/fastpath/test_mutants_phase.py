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
