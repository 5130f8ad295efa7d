"""Linear drag, eta(V) = k*V (k = drag > 0): every formula of fastpath that depends on the law.

The particle's motion, V' = -1 - k*V, V(0) = v, Y(0) = 0, with z = -k*t, phi1(z) = expm1(z)/z,
phi2(z) = (expm1(z) - z)/z**2 (``fastpath.dissipative.special``; -> 1, 1/2 as k -> 0, so the
limit t*(v - t/2) comes out with no cancellation):

    V(t) = v*exp(z) - t*phi1(z),        Y(t) = v*t*phi1(z) - t**2*phi2(z).          (``motion``)

Rounding scales (``motion``; ``fastpath.dissipative.drag.particle`` multiplies them by
ROUNDING_FACTOR*u): the sums of the magnitudes of the terms, plus t*max|V| for Y and
t*max|V'| = t*max(|1 + k*v|, |1 + k*V|) for V (the rounding of z = -k*t, a relative change of a
few u of the time), and |v|*exp(z)*|z| for exp(z)'s relative sensitivity |z| to it.

Tighter bounds near the root of a long descent (``tight_particle_errors``, ``tight_gap_errors``;
the argument is in ``fastpath.dissipative.drag_flight``'s docstring): V' = -(1 + k*v)*exp(-k*t)
is monotone, so over the perturbed times t*(1 + theta), |theta| <= 16u,

    |V'| <= |1 + k*v|*e*(1 + 2*|z|*u + 8u) + SUBNORMAL,   e = fl(exp(z)),

and |Y'| = |V| <= |V(t)| + its own bound: the local values replace the departure's. Each result
is the smaller of the two bounds (both are valid).

Short flights (``offset``: the offsets from uniform motion of ``fastpath.dissipative.short_flight``,
every term proportional to t**2 or t, no v*t formed and subtracted):

    Y - v*t = -(1 + k*v)*t**2*phi2(z),      V - v = -(1 + k*v)*t*phi1(z),

and the drift of the particle's acceleration over a short window, |p(V(s)) - p(v)| <= D*s with
p = -1 - eta and |V(s) - v| <= s*|p(v)|: D = k*|p(v)| (``window_drift``).

Flight solver (``fastpath.dissipative.drag_flight``): the landing time 2*v of a long flight
shortens to first order by the relative amount k*v/3 (Y(2v) = -k*v**3*2/3, divided by
|Y'(2v)| = v): ``landing_drop`` returns 3 times it, k*v. The jerk of the particle,
|p'| = eta'(V)*|p| = k*|p| (``jerk_rate``); the supremum of p after t (p moves monotonically
towards 0): max(p(t), 0) (``acceleration_sup``).

Riding the plate (``fastpath.dissipative.sticking``): f(theta) = eps*cos(theta) - eta(u(theta))
with u = -eps*sin(theta) is eps*(cos(theta) + k*sin(theta)) = E*cos(theta - beta) for eps > 0,
E = eps*sqrt(1 + k**2), beta = atan(k) (for eps < 0 the same with theta - beta - pi). The
particle can detach iff E > 1, i.e. (``detach_discriminant``, with its rounding bound)

    g = (e - 1)*(e + 1) + (e*k)**2 > 0,       e = |eps|,

and in the eps > 0 frame, alpha = arccos(1/E) = atan(sqrt(g)) (``detachment_frame``):
theta'* = beta - alpha, the ride-curvature window t_c = 2*alpha.

Accumulation tail (``tail_terms``): c = eta'(u) = k, |A''| <= |eps|*(1 + k), |eta''| = 0.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rounding import SUBNORMAL, UNIT_ROUNDOFF, plus_underflow
from fastpath.dissipative.special import ROUNDING_FACTOR, phi1, phi2


@jit
def eta(v, k):
    """The drag deceleration k*v."""
    return k * v


@jit
def motion(v, k, t):
    """(Y, V, Y_scale, V_scale): closed forms and error scales (module docstring)."""
    z = -k * t
    e = math.exp(z)
    p1, p2 = phi1(z), phi2(z)
    y = v * t * p1 - t * t * p2
    vel = v * e - t * p1
    y_scale = abs(v) * t * p1 + t * t * p2 + t * max(abs(v), abs(vel))
    v_scale = abs(v) * e * (1.0 + abs(z)) + t * p1 + t * max(abs(1.0 + k * v), abs(1.0 + k * vel))
    return y, vel, y_scale, v_scale


@jit
def offset(v, k, t):
    """(Y(t) - v*t, V(t) - v) (module docstring)."""
    z = -k * t
    p = 1.0 + k * v
    return -p * t * t * phi2(z), -p * t * phi1(z)


@jit
def window_drift(v, k, h, p):
    """D: the drift rate of the particle's acceleration over [0, h], p = |1 + eta(v)|."""
    return k * p


@jit
def landing_drop(v, k):
    """3 times the relative shortening of the landing time 2*v to first order: k*v."""
    return k * v


@jit
def jerk_rate(vel, v_err, k, p_size):
    """Bound on |p'| = eta'(V)*|p| after t: k*|p|, p_size >= |p(t)|."""
    return k * p_size


@jit
def acceleration_sup(p, p_err, k):
    """Supremum of the particle's acceleration p after t (p +- p_err at t): max(p, 0), -1 at
    k = 0."""
    return max(p + p_err, 0.0) if k > 0.0 else -1.0


@jit
def tight_particle_errors(v, k, t, vel, y_err, v_err):
    """(Y_error, V_error) at t with the argument's rounding charged with the local |V'| and |V|
    (module docstring); each the smaller of that and the given bound."""
    u = UNIT_ROUNDOFF
    z = -k * t
    e = math.exp(z)
    local_rate = abs(1.0 + k * v) * (e * (1.0 + 2.0 * abs(z) * u + 8.0 * u) + SUBNORMAL)
    p1 = phi1(z)
    tight_v = ROUNDING_FACTOR * u * (abs(v) * e * (1.0 + abs(z)) + t * p1 + t * local_rate)
    tight_y = ROUNDING_FACTOR * u * (abs(v) * t * p1 + t * t * phi2(z)
                                     + t * (abs(vel) + tight_v))
    return min(y_err, tight_y), min(v_err, tight_v)


@jit
def tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err):
    """(d_err, d1_err, v_err) of ``fastpath.dissipative.drag.gap_state`` at t with the particle's
    bounds of ``tight_particle_errors`` (gap_state's plate terms and final sums as they are
    there); each the smaller of the two."""
    u = UNIT_ROUNDOFF
    y_err, tight_v = tight_particle_errors(v, k, t, vel, math.inf, v_err)
    # gap_state's final sums: 2u*(|Y| + |plate|) <= 2u*(|d| + 4|eps|), 2u*|V|
    tight_d = plus_underflow(y_err + 4.0 * u * abs(eps) * min(t, 2.0) * (abs(phi) + t + 3.0)
                             + 2.0 * u * (abs(d) + 4.0 * abs(eps)), 16.0 + 2.0 * abs(eps))
    tight_d1 = plus_underflow(tight_v + 4.0 * u * abs(eps) * (1.0 + abs(phi) + t)
                              + 2.0 * u * (abs(vel) + abs(d1) + abs(eps)), 16.0 + abs(eps))
    return min(d_err, tight_d), min(d1_err, tight_d1), tight_v


@jit
def detach_discriminant(e, k):
    """(g, rounding bound of g): the particle riding the plate can detach iff g > 0, e = |eps|."""
    x, y = (e - 1.0) * (e + 1.0), (e * k) * (e * k)
    return x + y, 8.0 * UNIT_ROUNDOFF * (abs(x) + y)


@jit
def detachment_frame(e, k):
    """(theta'*, t_c) in the eps > 0 frame for a particle that detaches (module docstring)."""
    x, y = (e - 1.0) * (e + 1.0), (e * k) * (e * k)
    alpha = math.atan(math.sqrt(x + y))
    return math.atan(k) - alpha, 2.0 * alpha


@jit
def tail_terms(eps, k, u):
    """(c, |A''| bound, |eta''|) of the accumulation tail at plate velocity u."""
    return k, abs(eps) * (1.0 + k), 0.0
