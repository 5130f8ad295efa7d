"""Flights with air drag: the particle's motion in closed form and the gap to the plate.

Gravity 1 and a drag deceleration eta(V), k = drag >= 0 (``fastpath.physics``):

    V' = -1 - eta(V),   V(0) = v,   Y(0) = 0;      eta(V) = k*V (LINEAR), k*V*|V| (QUADRATIC).

Each law's closed forms V(t), Y(t) are in its module of ``fastpath.dissipative.laws``
(``linear``, ``quadratic``; ``none`` without drag: V = v - t, Y = t*(v - t/2)), reached through
``fastpath.dissipative.laws.motion``. At k = 0 every formula reduces to the drag-free one.

Rounding (``particle``): every formula is a short chain of correctly rounded operations and libm
calls (<= 1 ulp) whose terms have one sign, or whose cancellation is the problem's own (v - t
near the top, Y_top - Y_fall near the landing, as t*(v - t/2) without drag); the special
functions of ``fastpath.dissipative.special`` are good to a few u. So the error is at most C*u
times the sum of the magnitudes of the terms (C = ROUNDING_FACTOR = 16 covers <= 8 roundings of
each term with a factor 2 to spare), plus the effect of the rounded arguments z = -k*t, s*t,
t - t_top (a relative change of a few u of the time, or of t and t_top): the scales add
t*max|V| to Y's terms and t*max|V'| to V's (V and V' are monotone in a flight: the maxima are
at the ends), and exp(z)'s relative sensitivity |z| to the rounding of z. The law's ``motion``
returns these scales. The tests hold these bounds to a 60-digit reference. The gap adds the
plate's terms with the bounds of ``fastpath.elastic.gap``.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, plus_underflow
from fastpath.dissipative.laws import eta, motion
from fastpath.dissipative.special import ROUNDING_FACTOR


@jit
def particle(v, k, law, t):
    """(Y, V, Y_error, V_error): displacement and velocity at time t >= 0 from velocity v, with
    bounds on their rounding errors (module docstring): the law's ``motion`` and its scales."""
    y, vel, y_scale, v_scale = motion(v, k, law, t)
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
