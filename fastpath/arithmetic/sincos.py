"""Sine and cosine together, in straight-line arithmetic that the compiler can vectorise.

libm's ``sin`` and ``cos`` are calls, which stop LLVM from vectorising a loop over particles
(``fastpath.elastic.lockstep``). ``sin_cos`` computes both from one reduction, with no call and no
branch that is not a select:

1. Quadrant: k = floor(x*(2/pi) + 1/2), r = x - k*pi/2 with pi/2 = P1 + P2 + P3 (P1 and P2 with
   33 significant bits, P3 a double; the rest of pi/2 is below 1.1e-37). For |x| < 2**20,
   |k| < 2**20, so k*P1 and k*P2 are exact (at most 53 bits), x - k*P1 is exact (Sterbenz:
   x and k*P1 lie within a factor 2 of each other for k != 0), and the two remaining
   subtractions round once each: |r - (x - k*pi/2)| <= 2u*|r| + 1e-30. A k off by one where
   x*(2/pi) rounds across a half-integer leaves |r| <= pi/4 + 3e-10 < 0.786.
2. Taylor polynomials on |r| < 0.786: sin to r**17, cos to r**18, truncation below
   0.786**19/19! < 9e-20 and 0.786**20/20! < 4e-21. The leading terms r and 1 are added last, to
   a tail of at most |r|**3/6 < 0.081 (sin) and r**2/2 < 0.31 (cos) whose own rounding is a few
   u of the tail (each tail is a sum of terms decreasing by r**2/12 < 0.06, evaluated in pairs by
   Estrin's scheme for a short dependency chain).
3. sin x and cos x are (+-sin r, +-cos r) by the quadrant k mod 4 (exact sign swaps).

Error: |sin_cos(x) - (sin x, cos x)| <= SIN_COS_ERROR = 4u in each component for |x| < 2**20
(u = 2**-53; the reduction's 1.6u times |cos r| <= 1, the tail's ~0.5u, the final addition's u;
checked against mpmath at quadrant boundaries and at random in the tests). libm's error is
below one ulp. For |x| >= 2**20 use libm (``phase.MODERATE_LIMIT``).

Near zero the error is relative, as libm's: for x*(2/pi) in [-1/2, 1/2) (k = 0) the reduction
is exact (r = x), the sine's tail T = r**3*(...) has |T| <= r**2/6*|r| <= 0.103|r| and a relative
rounding of at most 5u, and |r| <= 1.11|sin r| on |r| <= pi/4: the sine's error is at most
(1 + 5*0.103*1.11)u < 1.6u relative to sin x, the cosine's at most 1.6u absolute (its tail
r**2/2 <= 0.31 with 3u, plus the final rounding). Both are within the one ulp that the flight's
error bounds allow for libm, so ``sin_cos_error`` adds nothing there (a departure at phi = -1e-5
keeps its w0 ~ 1.7e-16 decidable).
"""


import numpy as np

from fastpath.arithmetic.jit import inline_jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF

SIN_COS_ERROR = 4.0 * UNIT_ROUNDOFF

_TWO_OVER_PI = 0.6366197723675814
_P1 = 1.5707963267341256  # pi/2 = _P1 + _P2 + _P3 + O(1.1e-37)
_P2 = 6.077100506303966e-11
_P3 = 2.0222662487959506e-21

# (-1)**k/(2k+1)! and (-1)**k/(2k)!, multiplied rather than divided by
_S3, _S5, _S7, _S9 = -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0
_S11, _S13, _S15, _S17 = (-1.0 / 39916800.0, 1.0 / 6227020800.0, -1.0 / 1307674368000.0,
                          1.0 / 355687428096000.0)
_C2, _C4, _C6, _C8, _C10 = -0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0, -1.0 / 3628800.0
_C12, _C14, _C16, _C18 = (1.0 / 479001600.0, -1.0 / 87178291200.0, 1.0 / 20922789888000.0,
                          -1.0 / 6402373705728000.0)


@inline_jit
def sin_cos(x):
    """(sin x, cos x) for |x| < 2**20, each within SIN_COS_ERROR (module docstring)."""
    k = np.floor(x * _TWO_OVER_PI + 0.5)  # a float: the lanes convert no integers
    r = ((x - k * _P1) - k * _P2) - k * _P3
    r2 = r * r
    # Estrin's scheme: the terms in pairs, so that the dependent chain is 4 steps, not 8
    r4 = r2 * r2
    r8 = r4 * r4
    s_tail = ((_S3 + r2 * _S5) + r4 * (_S7 + r2 * _S9)) + r8 * (
        (_S11 + r2 * _S13) + r4 * (_S15 + r2 * _S17))
    c_tail = ((_C2 + r2 * _C4) + r4 * (_C6 + r2 * _C8)) + r8 * (
        ((_C10 + r2 * _C12) + r4 * (_C14 + r2 * _C16)) + r8 * _C18)
    sin_r = r + r * r2 * s_tail
    cos_r = 1.0 + r2 * c_tail
    q = k - 4.0 * np.floor(0.25 * k)  # k mod 4, exact
    s = sin_r if q == 0.0 else (cos_r if q == 1.0 else (-sin_r if q == 2.0 else -cos_r))
    c = cos_r if q == 0.0 else (-sin_r if q == 1.0 else (-cos_r if q == 2.0 else sin_r))
    return s, c


@inline_jit
def sin_cos_error(x):
    """The absolute error of ``sin_cos(x)`` beyond what libm's one ulp would have: 0 where
    x*(2/pi) is in [-1/2, 1/2) (module docstring), else SIN_COS_ERROR."""
    return 0.0 if -0.5 <= x * _TWO_OVER_PI < 0.5 else SIN_COS_ERROR


__all__ = ["SIN_COS_ERROR", "sin_cos", "sin_cos_error"]
