"""Quadratic drag, eta(V) = k*V*|V| (k = drag > 0): every formula of fastpath that depends on
the law.

The particle's motion, V' = -1 - k*V*|V|, V(0) = v, Y(0) = 0, with s = sqrt(k) and f_c(x) =
f(x)/x (-> 1 at x = 0; tanc, tanhc, sinc, sinhc, atanc, log1pc of
``fastpath.dissipative.special``). Rising, v > 0 and t <= t_top = atan(s*v)/s = v*atanc(s*v)
(the tangent subtraction formula, tan(atan(s v) - s t) = (s v - tan(s t))/(1 + s v tan(s t))):

    V(t) = (v - t*tanc(s t)) / (1 + k*v*t*tanc(s t)),
    Y(t) = ln(cos(atan(s v) - s t)/cos(atan(s v)))/k = ln(1 + k*g)/k = g*log1pc(k*g),
    k*g = s*v*sin(s t) - 2*sin(s t/2)**2,  g = t*(v*sinc(s t) - (t/2)*sinc(s t/2)**2).

Falling, v <= 0, any v (also faster than the terminal speed 1/s, reached after an impact on a
plate moving down fast): V' = -1 + k*V**2 and, by the tanh addition formula (``fall``),

    V(t) = (v - t*tanhc(s t)) / (1 - k*v*t*tanhc(s t)),
    Y(t) = -ln(cosh(s t) - s*v*sinh(s t))/k = -G*log1pc(k*G),
    k*G = 2*sinh(s t/2)**2 - s*v*sinh(s t),  G = t*((t/2)*sinhc(s t/2)**2 - v*sinhc(s t)) >= 0,

every term of one sign (no cancellation). For s t > 20 (sinh near overflow) the logarithm is
s t + ln((1 - s v)/2) + log1p((1 + s v)/(1 - s v)*exp(-2 s t)). After the top (v > 0,
t > t_top) the particle falls from rest: Y = Y(t_top) + Y_fall(t - t_top), Y(t_top) =
(v**2/2)*log1pc(k v**2). (``motion``, with the rounding scales: the sums of the magnitudes of
the terms plus t*max|V| for Y and t*max|V'| for V, max|V'| = max(|1 + k*v*|v||, 1).)

Short flights (``offset``: the offsets from uniform motion of ``fastpath.dissipative.short_flight``,
for s*t <= 1), x = s*t, L(y) = (log1p(y) - y)/y**2 (``log_rest``), S3(x) = x - sin(x),
S3h(x) = sinh(x) - x:

  rising (v > 0, t <= t_top): g = t*(v*sinc(x) - (t/2)*sinc(x/2)**2),
      Y - v*t = -v*t*S3(x)/x - (t**2/2)*sinc(x/2)**2 + k*g**2*L(k*g),
      V - v = -t*tanc(x)*(1 + k*v**2)/(1 + k*v*t*tanc(x));
  falling (v <= 0): G = t*((t/2)*sinhc(x/2)**2 - v*sinhc(x)),
      Y - v*t = -((t**2/2)*sinhc(x/2)**2 - v*t*S3h(x)/x) - k*G**2*L(k*G),
      V - v = -t*tanhc(x)*(1 - k*v**2)/(1 - k*v*t*tanhc(x));
  after the top (v > 0, t > t_top): the rising offset at t_top plus the fall from rest over
      t - t_top, minus v*(t - t_top) (v <= t_top*(1 + k*v**2) there: a term of the gap's own
      size t**2, not a cancellation of larger ones).

The drift of the particle's acceleration over a short window [0, h], |p(V(s)) - p(v)| <= D*s
with eta' = 2k|V| and |V(s) - v| <= s*|p(v)|: D = 2k*(|v| + h*|p(v)|)*|p(v)| (``window_drift``).

Flight solver (``fastpath.dissipative.drag_flight``): the landing time 2*v of a long flight
shortens to first order by the relative amount k*v**2/4 (Y(2v) = -k*v**4/2, divided by
|Y'(2v)| = v): ``landing_drop`` returns 3 times it, 0.75*k*v**2. The jerk of the particle,
|p'| = 2k|V|*|p| <= 2*max(k*|V(t)|, sqrt(k))*|p(t)| (V stays between V(t) and the terminal
velocity; ``jerk_rate``); the supremum of p after t: max(p(t), 0) (``acceleration_sup``). No
tighter error bounds than ``motion``'s (``tight_particle_errors``, ``tight_gap_errors`` return
theirs).

Riding the plate (``fastpath.dissipative.sticking``): in the frame e = |eps|, theta' = theta
(eps > 0) or theta - pi (eps < 0), f = e*cos(theta') + k*e**2*sin(theta')*|sin(theta')|
(``frame_force``). With c = cos(theta'): on sin >= 0 f = e*c + k*e**2*(1 - c**2) (largest
k*e**2 + 1/(4k) at c = 1/(2ke) if 2ke > 1, else e at c = 1); on sin < 0 f <= e*c <= e. So
max f = e if 2ke <= 1, else k*e**2 + 1/(4k), and the particle can detach iff
(``detach_discriminant``, with its rounding bound)

    g = (2ke - 1)**2 - 4k*(1 - e) > 0   (2ke > 1),        g = e - 1 > 0   (2ke <= 1).

f is unimodal per period, increasing from its minimum at theta'_min = -arccos(-1/(2ke)) to its
maximum at theta'_max = arccos(1/(2ke)) (2ke > 1; else from -pi to 0). The detachment phase
is the one root of f = 1 in [theta'_min, theta'_max], and the end of the ride-curvature window
the one root in [theta'_max, theta'_min + 2*pi]: both by bisection to adjacent floats
(``bisect``), the sign of f - 1 taken only where it exceeds the rounding bound of f,
F = 4u*(e + k*e**2)*(1 + |theta'|) (``detachment_frame``).

Accumulation tail (``tail_terms``): c = eta'(u) = 2k|u|, |A''| <= |eps| + 2k*eps**2,
|eta''| = 2k.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import PI, TWO_PI
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.special import (
    atanc,
    log1pc,
    log_rest,
    s3,
    s3h,
    sinc,
    sinhc,
    tanc,
    tanhc,
)

_TAIL_SWITCH = 20.0  # s*t above which ln cosh uses its exponential tail form


@jit
def eta(v, k):
    """The drag deceleration k*v*|v|."""
    return k * v * abs(v)


@jit
def fall(v, k, t):
    """(Y, V, Y_scale) from V(0) = v <= 0 (module docstring); one-signed terms."""
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
def motion(v, k, t):
    """(Y, V, Y_scale, V_scale): closed forms and error scales (module docstring)."""
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
def _rising_offset(v, k, t):
    s = math.sqrt(k)
    x = s * t
    ratio = s3(x) / x if x > 0.0 else 0.0
    g = t * (v * sinc(x) - 0.5 * t * sinc(0.5 * x) ** 2)
    dy = -v * t * ratio - 0.5 * t * t * sinc(0.5 * x) ** 2 + k * g * g * log_rest(k * g)
    tc = t * tanc(x)
    dv = -tc * (1.0 + k * v * v) / (1.0 + k * v * tc)
    return dy, dv


@jit
def _falling_offset(v, k, t):
    s = math.sqrt(k)
    x = s * t
    ratio = s3h(x) / x if x > 0.0 else 0.0
    big_g = t * (0.5 * t * sinhc(0.5 * x) ** 2 - v * sinhc(x))
    dy = -(0.5 * t * t * sinhc(0.5 * x) ** 2 - v * t * ratio) - k * big_g * big_g * log_rest(
        k * big_g)
    th = t * tanhc(x)
    dv = -th * (1.0 - k * v * v) / (1.0 - k * v * th)
    return dy, dv


@jit
def offset(v, k, t):
    """(Y(t) - v*t, V(t) - v) for s*t <= 1 (module docstring)."""
    if v <= 0.0:
        return _falling_offset(v, k, t)
    top = v * math.atan(math.sqrt(k) * v) / (math.sqrt(k) * v)
    if t <= top:
        return _rising_offset(v, k, t)
    dy_top, _ = _rising_offset(v, k, top)
    rest = t - top
    dy_fall, v_fall = _falling_offset(0.0, k, rest)
    return dy_top + dy_fall - v * rest, v_fall - v


@jit
def window_drift(v, k, h, p):
    """D: the drift rate of the particle's acceleration over [0, h], p = |1 + eta(v)|."""
    return 2.0 * k * (abs(v) + h * p) * p


@jit
def landing_drop(v, k):
    """3 times the relative shortening of the landing time 2*v to first order: 0.75*k*v**2."""
    return 0.75 * k * v * v


@jit
def jerk_rate(vel, v_err, k, p_size):
    """Bound on |p'| = 2k|V|*|p| after t: 2*max(k*|V(t)|, sqrt(k))*|p|, p_size >= |p(t)|."""
    return 2.0 * max(k * (abs(vel) + v_err), math.sqrt(k)) * p_size


@jit
def acceleration_sup(p, p_err, k):
    """Supremum of the particle's acceleration p after t (p +- p_err at t): max(p, 0), -1 at
    k = 0."""
    return max(p + p_err, 0.0) if k > 0.0 else -1.0


@jit
def tight_particle_errors(v, k, t, vel, y_err, v_err):
    """``motion``'s bounds: none tighter for this law."""
    return y_err, v_err


@jit
def tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err):
    """``fastpath.dissipative.drag.gap_state``'s bounds: none tighter for this law."""
    return d_err, d1_err, v_err


@jit
def detach_discriminant(e, k):
    """(g, rounding bound of g): the particle riding the plate can detach iff g > 0, e = |eps|."""
    if 2.0 * k * e > 1.0:
        m = 2.0 * k * e - 1.0
        x, y = m * m, 4.0 * k * (1.0 - e)
        return x - y, 8.0 * UNIT_ROUNDOFF * (2.0 * k * e * abs(m) + x + abs(y))
    return e - 1.0, 0.0  # e - 1 is exact for e in [1/2, 2] and of the right sign beyond


@jit
def frame_force(x, e, k):
    """f in the eps > 0 frame: e*cos(x) + k*e**2*sin(x)*|sin(x)|."""
    s = math.sin(x)
    return e * math.cos(x) + k * e * e * s * abs(s)


@jit
def bisect(lo, hi, e, k, rising):
    """Root of f - 1 in [lo, hi] (frame), f increasing (rising) or decreasing there: bisection to
    adjacent floats, stopping early where |f - 1| is within its rounding bound."""
    sign = 1.0 if rising else -1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not (lo < mid < hi):
            break
        g = sign * (frame_force(mid, e, k) - 1.0)
        if abs(g) <= 4.0 * UNIT_ROUNDOFF * (e + k * e * e) * (1.0 + abs(mid)):
            return mid
        if g < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@jit
def extrema(e, k):
    """(theta'_min, theta'_max) of f in the frame (module docstring), theta'_min < theta'_max."""
    if 2.0 * k * e > 1.0:
        c = 1.0 / (2.0 * k * e)
        return -math.acos(-c), math.acos(c)
    return -PI, 0.0


@jit
def detachment_frame(e, k):
    """(theta'*, t_c) in the eps > 0 frame for a particle that detaches (module docstring)."""
    lo, hi = extrema(e, k)
    theta = bisect(lo, hi, e, k, True)
    end = bisect(hi, lo + TWO_PI, e, k, False)
    return theta, end - theta


@jit
def tail_terms(eps, k, u):
    """(c, |A''| bound, |eta''|) of the accumulation tail at plate velocity u."""
    return 2.0 * k * abs(u), abs(eps) + 2.0 * k * eps * eps, 2.0 * k
