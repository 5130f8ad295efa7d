"""Fast flight solver for |eps| < 1, where the gap is strictly concave (DESIGN fact 2).

With d'' <= -1 + |eps| < 0 the gap has exactly one positive root, so any point t with d(t) > 0 lies
before it and any point with d(t) < 0 after it: every evaluation narrows a certified bracket
[lo, hi], which starts as [2*w0/(1+|eps|), 2*w0/(1-|eps|)]. Inside it we take Halley steps

    t <- t - 2*d*d' / (2*d'**2 - d*d'')            (cubic convergence)

falling back to bisection if a step leaves the bracket. The last evaluation, within rounding of
the root, gets one Newton correction -d/d'. From the right (d < 0) concavity keeps it at or
beyond the root; from the left it passes the root by at most (1+|eps|)*s**2/(2|d'|) for a step s
that is itself at rounding level, i.e. by far less than one ulp: the result never oversteps by
more than rounding.

Two starts and two ways of evaluating the gap, each one libm sine and cosine per flight; later
iterates move the angles along by angle addition (``fastpath.rotation``):

- Unless the flight may be short (lower bound 2*w0/(1+|eps|) below 1), start at the Holmes
  flight time t = 2*v, where t*(v - t/2) vanishes, and
  write t = 2*v + delta: d = eps*(cos(phi) - cos(phi + t)) - t*delta/2, d' = -v - delta +
  eps*sin(phi + t), d'' = -1 + eps*cos(phi + t), with the angle phi + t = theta0 + delta,
  theta0 = phi + 2*v (its rounding error kept exactly by TwoSum). Here t >= 1, so the plate
  term's rounding error, ~|eps|*u, is within the gap's error bound (``fastpath.gap``).
- Otherwise start at the root of w0*t - (1 - eps*cos(phi))*t**2/2 (the plate's acceleration
  frozen at departure) and use the half angle t/2: d = 2*eps*sin(t/2)*sin(phi + t/2) +
  t*(v - t/2), free of cancellation at small t.

Both return sin and cos of phi + tau, which the collision needs and the next flight reuses.
"""

import math

from fastpath._jit import jit
from fastpath.gap import gap_error
from fastpath.rotation import rotate

ITERATION_LIMIT = 2200  # bisection alone exhausts any float64 bracket in < 2100 steps


@jit
def halley(t, d, d1, d2, lo, hi):
    """Narrow the bracket (lo, hi) by the sign of d at t, then step: (t_next, lo, hi).

    t_next is the Halley step from t, or the bracket's midpoint if that step leaves it.
    """
    if d > 0.0:
        lo = t
    else:
        hi = t
    t_next = t - 2.0 * d * d1 / (2.0 * d1 * d1 - d * d2)
    if not lo < t_next < hi:
        t_next = 0.5 * (lo + hi)
    return t_next, lo, hi


@jit
def two_sum(x, y):
    """(s, e) with s = fl(x + y) and x + y = s + e exactly (Knuth)."""
    s = x + y
    y_virtual = s - x
    return s, (x - (s - y_virtual)) + (y - y_virtual)


@jit
def concave_flight(phi, sin_phi, cos_phi, v, eps):
    """(tau, sin(phi + tau), cos(phi + tau), evaluations) for |eps| < 1 and w0 > 0, phi reduced.

    evaluations == ITERATION_LIMIT means the bracket did not close (never seen; reported).
    """
    if 2.0 * (v + eps * sin_phi) >= 1.0 + abs(eps):
        return _flight_from_holmes(phi, sin_phi, cos_phi, v, eps)
    return _flight_half_angle(phi, sin_phi, cos_phi, v, eps)


@jit
def _flight_from_holmes(phi, sin_phi, cos_phi, v, eps):
    w0 = v + eps * sin_phi
    a = 1.0 + abs(eps)
    lo, hi = 2.0 * w0 / a, 2.0 * w0 / (1.0 - abs(eps))
    two_v = 2.0 * v
    theta0, theta0_error = two_sum(phi, two_v)
    s, c = rotate(math.sin(theta0), math.cos(theta0), theta0, theta0_error)
    delta, t = 0.0, two_v
    evaluations = 0
    while evaluations < ITERATION_LIMIT:
        evaluations += 1
        d = eps * (cos_phi - c) - 0.5 * t * delta
        d1 = -v - delta + eps * s
        if abs(d) <= gap_error(phi, v, eps, t):
            break
        t_next, lo, hi = halley(t, d, d1, -1.0 + eps * c, lo, hi)
        if t_next == t:
            break
        delta_next = t_next - two_v
        s, c = rotate(s, c, theta0 + theta0_error + delta, delta_next - delta)
        delta, t = delta_next, t_next
    step = -d / d1
    return t + step, s + c * step, c - s * step, evaluations


@jit
def _flight_half_angle(phi, sin_phi, cos_phi, v, eps):
    w0 = v + eps * sin_phi
    a = 1.0 + abs(eps)
    lo, hi = 2.0 * w0 / a, 2.0 * w0 / (1.0 - abs(eps))
    t = 2.0 * w0 / (1.0 - eps * cos_phi)  # inside [lo, hi] since |eps*cos(phi)| <= |eps|
    sin_h, cos_h = math.sin(0.5 * t), math.cos(0.5 * t)
    evaluations = 0
    while evaluations < ITERATION_LIMIT:
        evaluations += 1
        sin_mid = sin_phi * cos_h + cos_phi * sin_h  # sin(phi + t/2)
        cos_mid = cos_phi * cos_h - sin_phi * sin_h
        s = sin_mid * cos_h + cos_mid * sin_h  # sin(phi + t)
        c = cos_mid * cos_h - sin_mid * sin_h
        d = 2.0 * eps * sin_h * sin_mid + t * (v - 0.5 * t)
        d1 = v - t + eps * s
        if abs(d) <= gap_error(phi, v, eps, t):
            break
        t_next, lo, hi = halley(t, d, d1, -1.0 + eps * c, lo, hi)
        if t_next == t:
            break
        sin_h, cos_h = rotate(sin_h, cos_h, 0.5 * t, 0.5 * (t_next - t))
        t = t_next
    step = -d / d1
    return t + step, s + c * step, c - s * step, evaluations
