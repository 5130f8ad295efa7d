"""Inelastic impacts, chattering and sticking (restitution r < 1, no drag; DESIGN fact 12).

Impact. With plate velocity u and incoming velocity v_in, restitution r gives v1 - u =
-r*(v_in - u), i.e. v1 = (1 + r)*u - r*v_in. We carry the relative velocity w = v - u instead
of forming it from v (see ``fastpath.short_flight``): w1 = -r*w_in, v1 = u + w1.

Accumulation. After an impact at phase theta with relative velocity w, while the plate's
acceleration is locally constant, the particle's relative acceleration is A = -1 + eps*cos(theta)
= -a; with a > 0 every flight lasts 2*w/a and returns with -w, so the velocities shrink by r per
impact and the impacts accumulate after the time T0 = 2*w/(a*(1 - r)) (a geometric series).
The first correction comes from the jerk J = -eps*sin(theta) (dA/dt): a flight from w lasts
tau0 + J*tau0**2/(3a) and returns with -w + J*tau0**2/6, and a drifts by -J*tau per flight;
summing the first-order terms over the impacts gives (derivation in the project notes; checked
against a 60-digit iteration in tests/fastpath/test_sticking_accumulation.py)

    T = T0 + J*T0**2/(3*a) + R,        T0 = 2*w/(a*(1 - r)),

independent of r at this order once written in T0. The remainder R is of second order,
|R| = C*q*T0 with q = T0**2*(J**2/a**2 + |eps|/a); C is not derived in closed form: over
eps in {0.5, 1.01, 1.5, 3}, r in [0.01, 0.99] and phases from a = 0.06 to 2.5 the 60-digit
reference gives 0.04 <= C <= 0.21 (we bound it by 1/2 with room). The tail is summed as soon
as q <= u (``TAIL_Q``), so |R| <= u*T0/2: below half an ulp of the tail itself. Before that the
impacts are computed one by one (``fastpath.short_flight``), a relative error of a few u in w
per impact; an error delta in w moves t_acc by 2*delta/(a*(1 - r)) (T0's conditioning), and the
errors of the impacts shrink with the w they are relative to, so the summed flights carry an
error of a few u times the chattering sequence's duration (measured in the tests).

Detection: an impact is the last one computed, and the accumulation point is t + T, when a > 0
(a lowered by its rounding bound) and q <= u. Then J*T0/a <= sqrt(u): A stays negative to the
accumulation point and the geometric model is the one above.

Sticking and detachment. From the accumulation point the particle rides the plate (relative
velocity 0) while the gap's curvature A(theta) = -1 + eps*cos(theta) <= 0. It leaves where A
turns positive: at theta* = 2*pi - arccos(1/eps) for eps > 1, pi - arccos(1/|eps|) for
eps < -1 (there J = -eps*sin(theta*) > 0), the next such phase after the accumulation point.
For |eps| <= 1, A <= 0 for ever (at |eps| = 1 it touches 0 with d''' = 0): stuck for good.

Departure from detachment. At theta* the relative velocity is 0 and A = 0, so the gap is

    d(t) = sqrt(eps**2 - 1)*(t - sin(t)) - (t**2/2 - 1 + cos(t))          (eps*cos(theta*) = 1)

for either sign of eps: d(0) = d'(0) = d''(0) = 0, the same flight after every detachment.
d'' = A(theta* + t) > 0 on (0, t_c), t_c = 2*arccos(1/|eps|) (where eps*cos returns to 1), so
d > 0 on (0, t_c]: no collision there. The flight solver cannot start from d = d' = 0, so it
starts at t_c, where it evaluates d (with v = u(theta*) = sqrt(eps**2 - 1)) and requires it to
exceed its rounding bound, and continues with the certified lower-bound steps from there
(``fastpath.flight.lower_bound_flight`` with start = t_c). Where d(t_c) ~ (8/3)*(|eps| - 1)**2
is within rounding (|eps| - 1 below ~1e-10) the flight is UNCERTAIN.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import PI, PI_LOW, TWO_PI, TWO_PI_LOW, centre_phase
from fastpath.arithmetic.rotation import sin_cos_of_sum
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.short_flight import departure_deceleration
from fastpath.elastic.gap import gap, gap_error
from fastpath.elastic.lower_bound import lower_bound_flight
from fastpath.status import CONVERGED, UNCERTAIN

TAIL_Q = UNIT_ROUNDOFF  # sum the tail once its second-order size q is <= u (docstring)


@jit
def inelastic_impact(u, w_in, r):
    """(v1, w1): v1 = (1 + r)*u - r*v_in written as u + w1, w1 = -r*w_in, w_in = v_in - u."""
    w1 = -r * w_in
    return u + w1, w1


@jit
def accumulation_tail(sin_theta, cos_theta, w, eps, r):
    """T = T0*(1 + J*T0/(3a)) if the impacts from (theta, w) accumulate within q <= u, else NaN.

    T0 = 2*w/(a*(1 - r)), a = 1 - eps*cos(theta), J = -eps*sin(theta) (module docstring).
    """
    if not (departure_deceleration(cos_theta, eps) > 0.0 and w > 0.0 and r < 1.0):
        return math.nan
    a = 1.0 - eps * cos_theta  # the value, not lowered by its rounding bound as in the test
    t0 = 2.0 * w / (a * (1.0 - r))
    jerk = -eps * sin_theta
    q = t0 * t0 * (jerk * jerk / (a * a) + abs(eps) / a)
    if not q <= TAIL_Q:
        return math.nan
    return t0 + jerk * t0 * t0 / (3.0 * a)


@jit
def can_detach(eps):
    """Whether a particle riding the plate ever leaves it: |eps| > 1 (module docstring)."""
    return abs(eps) > 1.0


@jit
def detachment_angle(eps):
    """arccos(1/|eps|) for |eps| > 1, as atan(sqrt((|eps| - 1)*(|eps| + 1))) (accurate near 1)."""
    e = abs(eps)
    return math.atan(math.sqrt((e - 1.0) * (e + 1.0)))


@jit
def detachment_phase(eps):
    """theta* in [0, 2*pi): 2*pi - arccos(1/eps) (eps > 1), pi - arccos(1/|eps|) (eps < -1).

    The float constants' representation errors are added back (one rounding in all). NaN if
    |eps| <= 1 (never detaches).
    """
    if not can_detach(eps):
        return math.nan
    alpha = detachment_angle(eps)
    if eps > 0.0:
        return (TWO_PI - alpha) + TWO_PI_LOW
    return (PI - alpha) + PI_LOW


@jit
def detachment_velocity(eps):
    """The plate's (and particle's) velocity at detachment: u(theta*) = sqrt(eps**2 - 1)."""
    e = abs(eps)
    return math.sqrt((e - 1.0) * (e + 1.0))


@jit
def detachment_flight(eps):
    """(tau, sin, cos of theta* + tau, iterations, status): the flight from detachment.

    Departure at theta* with relative velocity 0 (module docstring): certified start at t_c.
    """
    phi = centre_phase(detachment_phase(eps))
    v = detachment_velocity(eps)
    t_c = 2.0 * detachment_angle(eps)
    if not gap(phi, v, eps, t_c) > gap_error(phi, v, eps, t_c):
        return math.nan, math.nan, math.nan, 0, UNCERTAIN
    tau, iterations, status = lower_bound_flight(phi, v, eps, 0.0, t_c)
    if status != CONVERGED:
        return tau, math.nan, math.nan, iterations, status
    sin1, cos1 = sin_cos_of_sum(phi, tau)
    return tau, sin1, cos1, iterations, status
