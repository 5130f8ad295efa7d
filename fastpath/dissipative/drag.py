"""Flights with air drag: the particle's motion in closed form and the gap to the plate.

Gravity 1 and a drag deceleration eta(V), k = drag >= 0 (``fastpath.physics``):

    V' = -1 - eta(V),   V(0) = v,   Y(0) = 0;      eta(V) = k*V (LINEAR), k*V*|V| (QUADRATIC).

Law codes (``fastpath.physics``): NONE (no drag), LINEAR, QUADRATIC.

Linear drag, z = -k*t, phi1(z) = expm1(z)/z, phi2(z) = (expm1(z) - z)/z**2 (both -> 1, 1/2 as
k -> 0, so the limit t*(v - t/2) comes out with no cancellation):

    V(t) = v*exp(z) - t*phi1(z),        Y(t) = v*t*phi1(z) - t**2*phi2(z).

Quadratic drag, s = sqrt(k), f_c(x) = f(x)/x (-> 1 at x = 0; tanc, tanhc, sinc, sinhc, atanc,
log1pc). Rising, v > 0 and t <= t_top = atan(s*v)/s = v*atanc(s*v) (the tangent subtraction
formula, tan(atan(s v) - s t) = (s v - tan(s t))/(1 + s v tan(s t))):

    V(t) = (v - t*tanc(s t)) / (1 + k*v*t*tanc(s t)),
    Y(t) = ln(cos(atan(s v) - s t)/cos(atan(s v)))/k = ln(1 + k*g)/k = g*log1pc(k*g),
    k*g = s*v*sin(s t) - 2*sin(s t/2)**2,  g = t*(v*sinc(s t) - (t/2)*sinc(s t/2)**2).

Falling, v <= 0, any v (also faster than the terminal speed 1/s, reached after an impact on a
plate moving down fast): V' = -1 + k*V**2 and, by the tanh addition formula,

    V(t) = (v - t*tanhc(s t)) / (1 - k*v*t*tanhc(s t)),
    Y(t) = -ln(cosh(s t) - s*v*sinh(s t))/k = -G*log1pc(k*G),
    k*G = 2*sinh(s t/2)**2 - s*v*sinh(s t),  G = t*((t/2)*sinhc(s t/2)**2 - v*sinhc(s t)) >= 0,

every term of one sign (no cancellation). For s t > 20 (sinh near overflow) the logarithm is
s t + ln((1 - s v)/2) + log1p((1 + s v)/(1 - s v)*exp(-2 s t)). After the top (v > 0,
t > t_top) the particle falls from rest: Y = Y(t_top) + Y_fall(t - t_top), Y(t_top) =
(v**2/2)*log1pc(k v**2). At k = 0 every formula reduces to V = v - t, Y = t*(v - t/2).

Rounding (``particle``): every formula is a short chain of correctly rounded operations and libm
calls (<= 1 ulp) whose terms have one sign, or whose cancellation is the problem's own (v - t
near the top, Y_top - Y_fall near the landing, as t*(v - t/2) without drag); phi2's series
(|z| < 1) and its direct form (|z| >= 1, cancellation factor <= 2.7) are good to a few u. So the
error is at most C*u times the sum of the magnitudes of the terms (C = ROUNDING_FACTOR = 16
covers <= 8 roundings of each term with a factor 2 to spare), plus the effect of the rounded
arguments z = -k*t, s*t, t - t_top (a relative change of a few u of the time, or of t and
t_top): the scales add t*max|V| to Y's terms and t*max|V'| to V's (V and V' are monotone
in a flight: the maxima are at the ends), and exp(z)'s relative sensitivity |z| to the
rounding of z. The tests hold these bounds to a 60-digit reference. The gap adds the plate's
terms with the bounds of ``fastpath.elastic.gap``.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, plus_underflow
from fastpath.physics import LINEAR, QUADRATIC

ROUNDING_FACTOR = 16.0
_TAIL_SWITCH = 20.0  # s*t above which ln cosh uses its exponential tail form
# phi2(z) = sum z**n/(n+2)!, n = 0..17 (highest first, for Horner): for |z| < 1 the tail is
# < 1/20! < 4e-19
_PHI2_COEFFICIENTS = tuple(1.0 / math.factorial(n + 2) for n in range(17, -1, -1))


@jit
def eta(v, k, law):
    """Drag deceleration: 0 (NONE), k*v (LINEAR), k*v*|v| (QUADRATIC)."""
    if law == LINEAR:
        return k * v
    if law == QUADRATIC:
        return k * v * abs(v)
    return 0.0


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
def linear_motion(v, k, t):
    """(Y, V, Y_scale, V_scale) with linear drag: closed forms and error scales (docstring)."""
    z = -k * t
    e = math.exp(z)
    p1, p2 = phi1(z), phi2(z)
    y = v * t * p1 - t * t * p2
    vel = v * e - t * p1
    y_scale = abs(v) * t * p1 + t * t * p2 + t * max(abs(v), abs(vel))
    v_scale = abs(v) * e * (1.0 + abs(z)) + t * p1 + t * max(abs(1.0 + k * v), abs(1.0 + k * vel))
    return y, vel, y_scale, v_scale


@jit
def fall(v, k, t):
    """(Y, V, Y_scale) with quadratic drag from V(0) = v <= 0 (docstring); one-signed terms."""
    s = math.sqrt(k)
    x = s * t
    th = t * tanhc(x)
    vel = (v - th) / (1.0 - k * v * th)
    if x <= _TAIL_SWITCH:
        g = t * (0.5 * t * sinhc(0.5 * x) ** 2 - v * sinhc(x))
        y = -g * log1pc(k * g)
        return y, vel, abs(y)
    sv = s * v
    log_term = math.log(0.5 * (1.0 - sv))
    y = -(x + log_term + math.log1p((1.0 + sv) / (1.0 - sv) * math.exp(-2.0 * x))) / k
    return y, vel, (x + abs(log_term) + 1.0) / k


@jit
def quadratic_motion(v, k, t):
    """(Y, V, Y_scale, V_scale) with quadratic drag (docstring)."""
    accel = max(abs(1.0 + k * v * abs(v)), 1.0)  # max |V'| = max |1 + eta(V)| over the flight
    if v <= 0.0:
        y, vel, y_scale = fall(v, k, t)
        return y, vel, y_scale + t * max(abs(v), abs(vel)), abs(vel) + t * accel
    s = math.sqrt(k)
    top = v * atanc(s * v)
    if t <= top:
        tc = t * tanc(s * t)
        vel = (v - tc) / (1.0 + k * v * tc)
        g = t * (v * sinc(s * t) - 0.5 * t * sinc(0.5 * s * t) ** 2)
        y = g * log1pc(k * g)
        y_scale = t * (abs(v) + 0.5 * t) + abs(y) + t * abs(v)
        return y, vel, y_scale, (abs(v) + tc) / (1.0 + k * v * tc) + (top + t) * accel
    y_top = 0.5 * v * v * log1pc(k * v * v)
    y_fall, vel, fall_scale = fall(0.0, k, t - top)
    y_scale = y_top + fall_scale + (top + t) * max(abs(v), abs(vel))
    return y_top + y_fall, vel, y_scale, abs(vel) + (top + t) * accel


@jit
def particle(v, k, law, t):
    """(Y, V, Y_error, V_error): displacement and velocity at time t >= 0 from velocity v, with
    bounds on their rounding errors (module docstring). NONE: Y = t*(v - t/2), V = v - t."""
    if law == LINEAR:
        y, vel, y_scale, v_scale = linear_motion(v, k, t)
    elif law == QUADRATIC:
        y, vel, y_scale, v_scale = quadratic_motion(v, k, t)
    else:
        y, vel = t * (v - 0.5 * t), v - t
        y_scale, v_scale = t * (abs(v) + t), abs(v) + t
    u = UNIT_ROUNDOFF
    return y, vel, ROUNDING_FACTOR * u * y_scale, ROUNDING_FACTOR * u * v_scale


@jit
def gap_state(phi, v, eps, k, law, t):
    """(d, d1, d2, d_error, d1_error, V, V_error) at time t of a flight from phase phi (reduced).

        d(t)   = Y(t) + 2*eps*sin(phi + t/2)*sin(t/2)     (= Y + eps*(cos(phi) - cos(phi + t)))
        d'(t)  = V(t) + eps*sin(phi + t)
        d''(t) = -1 - eta(V(t)) + eps*cos(phi + t)

    d_error and d1_error bound the rounding errors of d and d': the particle's (``particle``),
    the plate's as in ``fastpath.elastic.gap``, and the final sums.
    """
    y, vel, y_err, v_err = particle(v, k, law, t)
    theta = phi + t
    plate = 2.0 * eps * math.sin(phi + 0.5 * t) * math.sin(0.5 * t)
    plate_rate = eps * math.sin(theta)
    d = y + plate
    d1 = vel + plate_rate
    d2 = -1.0 - eta(vel, k, law) + eps * math.cos(theta)
    u = UNIT_ROUNDOFF
    # subnormal results round in absolute terms: <= 8 roundings of each of the particle's terms,
    # the plate's sines scaled by |eps| (``fastpath.elastic.gap``)
    d_err = plus_underflow(y_err + 4.0 * u * abs(eps) * min(t, 2.0) * (abs(phi) + t + 3.0)
                           + 2.0 * u * (abs(y) + abs(plate)), 16.0 + 2.0 * abs(eps))
    d1_err = plus_underflow(v_err + 4.0 * u * abs(eps) * (1.0 + abs(phi) + t)
                            + 2.0 * u * abs(vel), 16.0 + abs(eps))
    return d, d1, d2, d_err, d1_err, vel, v_err
