"""Sines and cosines moved along by angle addition instead of fresh libm calls.

An iteration that moves from angle x to x + h needs sin and cos at the new point; for |h| small
the Taylor polynomials of sin h and cos h are cheaper than two libm calls and as accurate:

    sin(x + h) = sin(x)*cos(h) + cos(x)*sin(h),   cos(x + h) = cos(x)*cos(h) - sin(x)*sin(h)

With |h| <= SMALL_ANGLE = 0.125 the truncation errors h**11/11! and h**12/12! are below 3e-18
(a fortieth of the unit roundoff relative to sin h, and far below it for cos h).
"""

import math

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.rounding import two_sum

SMALL_ANGLE = 0.125


# Taylor coefficients (-1)**k/(2k+1)! and (-1)**k/(2k)!, multiplied rather than divided by:
# without fastmath the compiler keeps a division by a constant as a (slow) division.
_S3, _S5, _S7, _S9 = -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0
_C2, _C4, _C6, _C8, _C10 = -0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0, -1.0 / 3628800.0


@inline_jit
def small_sin_cos(h):
    """(sin h, cos h) for |h| <= SMALL_ANGLE by Taylor polynomials (Horner form)."""
    h2 = h * h
    s = h + h * h2 * (_S3 + h2 * (_S5 + h2 * (_S7 + h2 * _S9)))
    c = 1.0 + h2 * (_C2 + h2 * (_C4 + h2 * (_C6 + h2 * (_C8 + h2 * _C10))))
    return s, c


@jit
def sin_cos_of_sum(x, y):
    """(sin(x + y), cos(x + y)) of the EXACT sum of two doubles.

    With a = fl(x + y) and the remainder e = x + y - a (``two_sum``, exact, |e| <= ulp(a)/2),

        sin(x + y) = sin(a)*cos(e) + cos(a)*sin(e),   cos(x + y) = cos(a)*cos(e) - sin(a)*sin(e),

    libm at a and the Taylor polynomials at e. The error is libm's (< 1 ulp) plus a few
    roundings, whatever |x + y|: libm's sine of fl(x + y) alone is off by up to |e|, which is
    16u at x + y ~ 24. e = 0 gives libm's values unchanged.
    """
    a, e = two_sum(x, y)
    sin_a, cos_a = math.sin(a), math.cos(a)
    if abs(e) > SMALL_ANGLE:  # only for |x + y| >= 2**51, where the angle is mostly noise
        sin_e, cos_e = math.sin(e), math.cos(e)
    else:
        sin_e, cos_e = small_sin_cos(e)
    return sin_a * cos_e + cos_a * sin_e, cos_a * cos_e - sin_a * sin_e


@jit
def rotate(sin_x, cos_x, h, phi, t):
    """(sin(phi + t), cos(phi + t)) from the sine and cosine at phi + t - h.

    Angle addition for small steps, |h| <= SMALL_ANGLE; a longer step takes libm afresh at the
    exact sum phi + t (``sin_cos_of_sum``), never at a rounded angle.
    """
    if abs(h) > SMALL_ANGLE:
        return sin_cos_of_sum(phi, t)
    s, c = small_sin_cos(h)
    return sin_x * c + cos_x * s, cos_x * c - sin_x * s
