"""Reduction of a phase (a time) to [0, 2*pi), exact up to the rounding of the result (and, for
|x| >= 2**20, an absolute 2**-70: see Accuracy below).

Moderate phases, |x| < 2**20: a three-part Cody-Waite reduction, 2*pi = TWO_PI_HI + TWO_PI_MID +
TWO_PI_LO, the first two parts with 31 significant bits, so that k*TWO_PI_HI and k*TWO_PI_MID are
exact for |k| < 2**21; the result is good to a few ulps of 2*pi.

Every larger finite phase: a Payne-Hanek reduction in turns. A double is x = m * 2**e with an
integer m < 2**53; split m = m1 * 2**26 + m0 (m1 < 2**27, m0 < 2**26). Then

    x / (2*pi) = m1 * 2**(e+26) / (2*pi) + m0 * 2**e / (2*pi)  (mod 1)
               = m1 * F(e + 26) + m0 * F(e)                     (mod 1),

where F(j) = frac(2**j / (2*pi)) is tabulated as six 26-bit pieces (``_TURNS``, pieces of weight
2**-26, ..., 2**-156, from 1/(2*pi) to 1300 bits computed with Python integers by Machin's formula).
A 27-bit integer times a 26-bit piece has at most 53 bits: every product is exact, and so is its
fractional part. The first two pieces give the turns to 2**-52 exactly; the rest, all positive,
are added with relative rounding only. The tail left off is < 2**53 * 2**-156 = 2**-103 turns. The
turns r in [0, 1) (or [-1/2, 1/2) for a centred phase) are then multiplied by 2*pi in
double-double arithmetic (Dekker's product, ``rounding.two_product``).

Accuracy: the rounding of the result, plus an absolute error below PAYNE_HANEK_ERROR = 2**-70
from the small pieces (lo < 2**-23 turns, summed with relative rounding) and the inner sum of the
product: it matters only for results near 0 or near a turn, where the relative error can be
large (measured 1.4e-23 absolute at x = 1.5312731109035593e60, whose remainder is 1.3e-17:
``tests/fastpath/test_fastpath_phase.py`` builds such arguments from continued fractions).
"""

import math

import numpy as np

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.rounding import two_product

PI = math.pi
TWO_PI = 2.0 * math.pi
PI_LOW = 1.2246467991473532e-16  # pi - PI (the float's representation error)
TWO_PI_LOW = 2.4492935982947064e-16  # 2*pi - TWO_PI
# 2*pi = HI + MID + LO to ~1e-35 (HI and MID have 31 significant bits; checked in the tests).
TWO_PI_HI = 6.2831853069365025
TWO_PI_MID = 2.430840201437384e-10
TWO_PI_LO = 1.1650928224373424e-19
# |x| below it is a moderate phase: a Cody-Waite reduction (here, and in ``sincos``) has
# |k| < 2**21 turns, and k times a 31- or 33-bit part of 2*pi is exact
MODERATE_LIMIT = 2.0**20
# Payne-Hanek table: rows j = _E_MIN .. 1023 (x >= 2**20 has e >= 20 - 52; e + 26 <= 971 + 26)
_E_MIN = -40
_PIECES = 6
_PIECE_BITS = 26


def _inverse_two_pi_fixed(bits):
    """floor(2**bits / (2*pi)) as a Python integer (Machin: pi = 16 atan(1/5) - 4 atan(1/239))."""
    guard = bits + 64
    one = 1 << guard

    def arctan_inverse(n):
        total, term, k, sign = 0, one // n, 1, 1
        while term:
            total += sign * (term // k)
            term //= n * n
            k += 2
            sign = -sign
        return total

    pi_fixed = 16 * arctan_inverse(5) - 4 * arctan_inverse(239)  # pi * 2**guard (+- a few units)
    return (1 << (bits + guard)) // (2 * pi_fixed)


def _turn_table():
    """_TURNS[j - _E_MIN, i] = piece i of frac(2**j / (2*pi)), weight 2**(-26*(i+1))."""
    frac_bits = _PIECES * _PIECE_BITS
    scale = 1300
    inverse = _inverse_two_pi_fixed(scale)  # 1/(2*pi) * 2**scale
    table = np.zeros((1024 - _E_MIN, _PIECES))
    mask = (1 << frac_bits) - 1
    for j in range(_E_MIN, 1024):
        shift = scale - frac_bits - j
        fixed = (inverse >> shift if shift >= 0 else inverse << -shift) & mask
        for i in range(_PIECES):
            chunk = (fixed >> (frac_bits - _PIECE_BITS * (i + 1))) & ((1 << _PIECE_BITS) - 1)
            table[j - _E_MIN, i] = math.ldexp(chunk, -_PIECE_BITS * (i + 1))
    return table


_TURNS = _turn_table()
PAYNE_HANEK_ERROR = 2.0**-70  # absolute error of a reduction of |x| >= 2**20, beyond its rounding


@jit
def _frac(x):
    return x - math.floor(x)


@jit
def _turns(x):
    """(hi, lo): |x| / (2*pi) mod 1 = hi + lo, hi exact in [0, 1), 0 <= lo < 2**-23 (docstring)."""
    mantissa, exponent = math.frexp(abs(x))
    m = math.ldexp(mantissa, 53)  # integer < 2**53
    e = exponent - 53
    m1 = math.floor(m * 2.0**-26)
    m0 = m - m1 * 2.0**26
    row1, row0 = _TURNS[e + 26 - _E_MIN], _TURNS[e - _E_MIN]
    hi = _frac(_frac(m1 * row1[0]) + _frac(m0 * row0[0]))
    hi = _frac(hi + _frac(_frac(m1 * row1[1]) + _frac(m0 * row0[1])))
    lo = 0.0
    for i in range(_PIECES - 1, 1, -1):  # smallest first
        lo += m1 * row1[i] + m0 * row0[i]
    return hi, lo


@jit
def _payne_hanek(x, centred):
    """x mod 2*pi for |x| >= 2**20 (module docstring): in [0, 2*pi), or [-pi, pi) if centred."""
    hi, lo = _turns(x)
    if x < 0.0:
        hi, lo = -hi, -lo
    # hi + lo against the range's ends, decided exactly: lo (< 2**-23) can carry hi past an
    # end, and the differences below are exact wherever they are close (Sterbenz)
    bottom, top = (-0.5, 0.5) if centred else (0.0, 1.0)
    if lo >= top - hi:
        hi -= 1.0  # exact
    elif lo < bottom - hi:
        hi += 1.0  # exact
        if lo < bottom - hi:  # x < 0 with turns just below -1 (only [0, 1) can need it)
            hi += 1.0
    p, e = two_product(hi, TWO_PI)
    r = p + (e + hi * TWO_PI_LOW + lo * TWO_PI)
    if not centred and r >= TWO_PI:  # rounded up from just below 2*pi
        r = 0.0
    if centred and r >= PI:
        r = -PI
    return r


@inline_jit
def _cody_waite(x, k):
    """x - k*2*pi for |k| < 2**21 (three-part 2*pi, module docstring)."""
    return ((x - k * TWO_PI_HI) - k * TWO_PI_MID) - k * TWO_PI_LO


@jit
def reduce_phase(x):
    """Return x mod 2*pi in [0, 2*pi) for any finite x (NaN and inf give NaN)."""
    if 0.0 <= x < TWO_PI:
        return x
    if not abs(x) < math.inf:
        return math.nan
    if abs(x) >= MODERATE_LIMIT:
        return _payne_hanek(x, False)
    return reduce_moderate(x)


@inline_jit
def reduce_moderate(x):
    """``reduce_phase`` for |x| < 2**20, with selects instead of branches (it is also used in
    the vectorised lanes of the ensembles: the same arithmetic, the same bits)."""
    r = _cody_waite(x, np.floor(x / TWO_PI))  # np.floor: a float, no conversion to integers
    # k from the float quotient can be off by one at the boundaries.
    r = r + TWO_PI if r < 0.0 else (r - TWO_PI if r >= TWO_PI else r)
    # r was -tiny and r + 2*pi rounded up to 2*pi
    r = 0.0 if r >= TWO_PI else r
    return x if 0.0 <= x < TWO_PI else r


@jit
def centre_phase(x):
    """Return x mod 2*pi in [-pi, pi); a phase already in that range is returned unchanged.

    The flight kernels take centred phases: the rounding error of sin(phi + t/2) grows with
    |phi|, and a departure given as -0.3 must not be moved to 2*pi - 0.3 (which also costs the
    representation error of 2*pi). The reduction is done to the centred range directly.
    """
    if -PI <= x < PI:
        return x
    if not abs(x) < math.inf:
        return math.nan
    if abs(x) >= MODERATE_LIMIT:
        return _payne_hanek(x, True)
    return centre_moderate(x)


@inline_jit
def centre_moderate(x):
    """``centre_phase`` for |x| < 2**20, with selects instead of branches (``reduce_moderate``)."""
    r = _cody_waite(x, np.floor(x / TWO_PI + 0.5))
    r = r + TWO_PI if r < -PI else (r - TWO_PI if r >= PI else r)
    return x if -PI <= x < PI else r
