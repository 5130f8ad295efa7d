"""The gap near a short, nearly tangent root, with a rounding bound that scales with the terms.

``fastpath.elastic.gap.gap_error`` allows an absolute error of a few u in sin(phi + t/2) (the "+3"
of its plate term) and so about 12u*|eps|*t in d. Near a (near-)triple root of the concave solver
(eps -> 1, phi = -x, v = x, tau = 2x: docs/model.md) the gap is of order x**4/24 and its slope
x**3/6, while its terms are only of order t*x: there the generic bound is ~1e3-1e6 times the actual
rounding, the solver stopped 16% away from the root (x = 3e-5; the Newton correction from there
left a 4.8% error, 2.29 kappa*u), and for x < 2e-5 it could not tell the slope from its bound.
``tight_gap`` evaluates the half-angle form with fresh libm sin(t/2), cos(t/2) (not sines carried
by rotation, whose absolute error stems from larger angles) and a bound built from the sizes of
the actual terms.

Evaluation (t a float >= 2**-1000, so h = t/2 is exact; sh, ch = libm sin h, cos h):

    M  = sin(phi + h) = sin_phi*ch + cos_phi*sh         Cm = cos(phi + h) = cos_phi*ch - sin_phi*sh
    s  = sin(phi + t) = M*ch + Cm*sh                     c  = cos(phi + t) = Cm*ch - M*sh
    P  = 2*eps*sh*M      F = t*(v - h)      d = P + F    d' = (v - t) + eps*s     d'' = -1 + eps*c

Error bound (first order in u = 2**-53; libm's sin and cos within one ulp, <= 2u relative; each
float operation rounds by <= u of its computed result). The departure's sine and cosine have
absolute errors sig and gam beyond which nothing is known but this: the caller's w0 bound
``w0_error`` (``fastpath.elastic.gap.departure``) is >= |eps|*(2u|sin_phi| + phase error), so
|eps|*sig <= w0_error and |eps|*gam <= 2u|eps| + w0_error (the cosine of a carried pair is taken
to be as good as its sine, as ``gap_error`` does). Writing |.| of computed values,

    err M  <= u|M| + 3u(|sin_phi| + |sh|) + sig + gam*|sh|
              (products u each, sum u|M|, sh and ch 2u each, the departure's sig, gam)
    err Cm <= u|Cm| + 3u(|cos_phi| + |sin_phi|*|sh|) + gam + sig*|sh|
    err P  <= 2u|P| (two products) + 2|eps|*(|sh|*err M + |M|*2u|sh|)
           <= 5u|P| + 2|sh|*(u|eps|*(3|sin_phi| + 5|sh|) + w0_error*(1 + |sh|))
    err F  <= 2u|F|  (v - h and the product; h exact)
    E      =  u|d| + 5u|P| + 2u|F| + 2|sh|*(u|eps|*(3|sin_phi| + 5|sh|) + w0_error*(1 + |sh|))
    err s  <= u|s| + 3u|M| + 3u|Cm|*|sh| + err M + |sh|*err Cm
           <= u(|s| + 4|M| + 6|sin_phi| + 10|sh|) + sig*(1 + |sh|) + 2*gam*|sh|  (|Cm|, |sh| <= 1)
    R      =  u(|d'| + |v - t| + |eps|*(2|s| + 4|M| + 6|sin_phi| + 14|sh|)) + w0_error*(1 + 3|sh|)

so |d(computed) - d(exact)| <= E and |d'(computed) - d'(exact)| <= R, d and d' those of the
exact departure phase. The second-order terms (products of two roundings, relative size <= ~20u)
and the rounding of evaluating E and R themselves (a dozen operations on positive numbers) are
covered by the factor 1 + 64u; ``_UNDERFLOW`` covers the absolute error of subnormal results
(<= 2**-1075 for each of fewer than 32 operations, magnified at most 4x).

For the triple family at x = 3e-5, eps = 1 this gives E = 2.4e-24 against gap_error ~ 1e-19 (the
actual rounding is <= 5e-25 along the iteration), and R ~ 26u*x against rate_error ~ 4u.
The terms u*|eps|*(3|sin_phi| + 5|sh|) are dominated by the w0_error ones for libm sines
(w0_error >= 3u|eps*sin_phi|) but are kept: a caller's w0_error need not contain them.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF

U = UNIT_ROUNDOFF
SMALLEST_T = 2.0**-1000  # t/2 exact, and every term far above the subnormal range's rounding
_SLACK = 1.0 + 64.0 * U
_UNDERFLOW = 2.0**-1060


@jit
def tight_gap(sin_phi, cos_phi, v, eps, w0_error, t):
    """(d, d', d'', sin(phi + t), cos(phi + t), E, R) at t >= SMALLEST_T (module docstring)."""
    sin_h, cos_h = math.sin(0.5 * t), math.cos(0.5 * t)
    sin_mid = sin_phi * cos_h + cos_phi * sin_h
    cos_mid = cos_phi * cos_h - sin_phi * sin_h
    s = sin_mid * cos_h + cos_mid * sin_h
    c = cos_mid * cos_h - sin_mid * sin_h
    plate = 2.0 * eps * sin_h * sin_mid
    flight = t * (v - 0.5 * t)
    d = plate + flight
    d1 = (v - t) + eps * s
    sh, sp, e = abs(sin_h), abs(sin_phi), abs(eps)
    d_err = U * (abs(d) + 5.0 * abs(plate) + 2.0 * abs(flight)) + 2.0 * sh * (
        U * e * (3.0 * sp + 5.0 * sh) + w0_error * (1.0 + sh))
    d1_err = U * (abs(d1) + abs(v - t) + e * (2.0 * abs(s) + 4.0 * abs(sin_mid) + 6.0 * sp
                                             + 14.0 * sh)) + w0_error * (1.0 + 3.0 * sh)
    return (d, d1, -1.0 + eps * c, s, c, d_err * _SLACK + _UNDERFLOW,
            d1_err * _SLACK + _UNDERFLOW)
