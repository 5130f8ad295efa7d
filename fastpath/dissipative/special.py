"""Cancellation-free special functions of the closed forms of the drag laws
(``fastpath.dissipative.laws``).

Each is a quotient f(x)/x or a Taylor remainder that tends to a constant at x = 0, computed so
that no nearly equal numbers are subtracted:

    phi1(z) = expm1(z)/z,   phi2(z) = (expm1(z) - z)/z**2           (-> 1, 1/2 at z = 0),
    sinc, sinhc, tanc, tanhc, atanc, log1pc: f(x)/x                  (-> 1 at x = 0),
    s3(t) = t - sin(t),   s3h(x) = sinh(x) - x                       (series for t, x <= 1),
    log_rest(y) = (log1p(y) - y)/y**2                                (series for |y| < 1/2).

Rounding: expm1, sin, sinh, tan, tanh, atan, log1p are within an ulp (libm), so each quotient is
within a few u; phi2's series (|z| < 1, tail < 1/20! < 4e-19) and its direct form (|z| >= 1,
cancellation factor <= 2.7) are good to a few u; the series of s3, s3h (t <= 1: 10th term
< 1e-21) and log_rest (60 terms, |y| < 1/2) to < u relative.
"""

import math

from fastpath.arithmetic.jit import jit

# the closed forms' rounding bounds: C*u times the sum of the magnitudes of the terms, C covering
# <= 8 roundings of each term with a factor 2 to spare (``fastpath.dissipative.drag``)
ROUNDING_FACTOR = 16.0
SERIES_LIMIT = 1.0  # the Taylor series below are good to < u for t <= 1 (10th term < 1e-21)
# phi2(z) = sum z**n/(n+2)!, n = 0..17 (highest first, for Horner): for |z| < 1 the tail is
# < 1/20! < 4e-19
_PHI2_COEFFICIENTS = tuple(1.0 / math.factorial(n + 2) for n in range(17, -1, -1))


@jit
def phi1(z):
    """expm1(z)/z (1 at z = 0); expm1 is accurate to an ulp for every z, so is the quotient."""
    if z == 0.0:
        return 1.0
    return math.expm1(z) / z


@jit
def phi2(z):
    """(expm1(z) - z)/z**2 (1/2 at z = 0): Taylor series (Horner) for |z| < 1, else direct."""
    if abs(z) < 1.0:
        total = 0.0
        for c in _PHI2_COEFFICIENTS:
            total = c + z * total
        return total
    return (math.expm1(z) - z) / (z * z)


@jit
def sinc(x):
    """sin(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.sin(x) / x


@jit
def sinhc(x):
    """sinh(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.sinh(x) / x


@jit
def tanc(x):
    """tan(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.tan(x) / x


@jit
def tanhc(x):
    """tanh(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.tanh(x) / x


@jit
def atanc(x):
    """atan(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.atan(x) / x


@jit
def log1pc(x):
    """log1p(x)/x, 1 at 0."""
    return 1.0 if x == 0.0 else math.log1p(x) / x


@jit
def s3(t):
    """t - sin(t) = t**3/6 - t**5/120 + ... (series for t <= 1, cancellation-free)."""
    if t > SERIES_LIMIT:
        return t - math.sin(t)
    x = t * t
    s = 1.0 - x / 420.0
    for k in (342.0, 272.0, 210.0, 156.0, 110.0, 72.0, 42.0, 20.0):
        s = 1.0 - x / k * s
    return t * x / 6.0 * s


@jit
def s3h(x):
    """sinh(x) - x = x**3/6 + x**5/120 + ... (series for x <= 1)."""
    if x > SERIES_LIMIT:
        return math.sinh(x) - x
    y = x * x
    s = 1.0 + y / 420.0
    for n in (342.0, 272.0, 210.0, 156.0, 110.0, 72.0, 42.0, 20.0):
        s = 1.0 + y / n * s
    return x * y / 6.0 * s


@jit
def log_rest(y):
    """(log1p(y) - y)/y**2 = -1/2 + y/3 - y**2/4 + ... (series for |y| < 1/2, 60 terms)."""
    if abs(y) >= 0.5:
        return (math.log1p(y) - y) / (y * y)
    total = 0.0
    for n in range(61, 1, -1):
        total = (1.0 if n % 2 == 1 else -1.0) / n + y * total
    return total
