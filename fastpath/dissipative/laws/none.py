"""No drag, eta(V) = 0: the law code NONE of the elastic descriptions (``fastpath.physics``).

The kernels take the drag-free formulas of ``fastpath.elastic`` and ``fastpath.dissipative``
wherever drag == 0; this module gives the law's functions for a description that reaches the
drag formulas with law NONE (drag 0), so that each is the k = 0 limit of the others:

    V(t) = v - t,   Y(t) = t*(v - t/2),   Y - v*t = -t**2/2,   V - v = -t           (``motion``,
                                                                                   ``offset``)

with the rounding scales t*(|v| + t) and |v| + t; no drift, jerk or shortening of the landing
time; the particle's acceleration is -1 throughout (``acceleration_sup``); riding, f = e*cos,
detaches iff e = |eps| > 1, at theta'* = -alpha with t_c = 2*alpha, alpha = arccos(1/e)
(``fastpath.dissipative.sticking``); the tail's terms c = 0, |A''| <= |eps|, |eta''| = 0.
"""

import math

from fastpath.arithmetic.jit import jit


@jit
def eta(v, k):
    """No drag deceleration."""
    return 0.0


@jit
def motion(v, k, t):
    """(Y, V, Y_scale, V_scale) without drag (module docstring)."""
    return t * (v - 0.5 * t), v - t, t * (abs(v) + t), abs(v) + t


@jit
def offset(v, k, t):
    """(Y(t) - v*t, V(t) - v) without drag."""
    return -0.5 * t * t, -t


@jit
def window_drift(v, k, h, p):
    """No drift of the particle's acceleration (-1 throughout)."""
    return 0.0


@jit
def landing_drop(v, k):
    """The landing time 2*v is not shortened."""
    return 0.0


@jit
def jerk_rate(vel, v_err, k, p_size):
    """The particle's acceleration does not change."""
    return 0.0


@jit
def acceleration_sup(p, p_err, k):
    """The particle's acceleration: -1."""
    return -1.0


@jit
def tight_particle_errors(v, k, t, vel, y_err, v_err):
    """``motion``'s bounds."""
    return y_err, v_err


@jit
def tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err):
    """``fastpath.dissipative.drag.gap_state``'s bounds."""
    return d_err, d1_err, v_err


@jit
def detach_discriminant(e, k):
    """(g, rounding bound of g): g = e - 1 (exact for e in [1/2, 2], of the right sign beyond)."""
    return e - 1.0, 0.0


@jit
def detachment_frame(e, k):
    """(theta'*, t_c) = (-alpha, 2*alpha), alpha = arccos(1/e) = atan(sqrt((e - 1)*(e + 1)))."""
    alpha = math.atan(math.sqrt((e - 1.0) * (e + 1.0)))
    return -alpha, 2.0 * alpha


@jit
def tail_terms(eps, k, u):
    """(c, |A''| bound, |eta''|) of the accumulation tail: (0, |eps|, 0)."""
    return 0.0, abs(eps), 0.0
