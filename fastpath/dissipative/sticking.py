"""Inelastic impacts, chattering and sticking (restitution r < 1), with or without drag.

Without drag.

Impact. With plate velocity u and incoming velocity v_in, restitution r gives v1 - u =
-r*(v_in - u), i.e. v1 = (1 + r)*u - r*v_in. We carry the relative velocity w = v - u instead
of forming it from v (see ``fastpath.dissipative.short_flight``): w1 = -r*w_in, v1 = u + w1.

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
impacts are computed one by one (``fastpath.dissipative.short_flight``), a relative error of a few u
in w per impact; an error delta in w moves t_acc by 2*delta/(a*(1 - r)) (T0's conditioning), and the
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
(``fastpath.elastic.lower_bound`` from t = t_c). Where d(t_c) ~ (8/3)*(|eps| - 1)**2
is within rounding (|eps| - 1 below ~1e-10) the flight is UNCERTAIN.

With drag (eta of the law's module in ``fastpath.dissipative.laws``).

Riding. A particle riding the plate moves with it: velocity u = -eps*sin(theta), acceleration
-eps*cos(theta). Its free acceleration is -1 - eta(u), so the plate pushes it with the force
(per unit mass)

    a(theta) = 1 + eta(u(theta)) - eps*cos(theta) = 1 - f(theta),

and it stays while a >= 0; it detaches where a falls through 0 (f rises through 1). Without
drag f = eps*cos(theta) (above).

Each law's f, the condition for detaching and the detachment phase theta'* and ride-curvature
window t_c in the frame e = |eps|, theta' = theta (eps > 0) or theta - pi (eps < 0), are in its
module of ``fastpath.dissipative.laws`` (``detach_discriminant``, ``detachment_frame``): linear
drag in closed form, f = E*cos(theta - beta), E = |eps|*sqrt(1 + k**2), beta = atan(k) (so drag
makes even |eps| <= 1 detach when |eps| > 1/sqrt(1 + k**2): the drag on the plate's upward
motion adds to the plate's deceleration); quadratic drag by bisection on the one root of
f = 1 on the rising side of its unimodal period. k -> 0 gives 2*pi - arccos(1/eps) and
pi - arccos(1/|eps|).

Deciding "never detaches". The sign of the law's discriminant (linear: E**2 - 1 = (e - 1)*(e + 1)
+ (e*k)**2; quadratic: (2ke - 1)**2 - 4k*(1 - e) or e - 1) is taken against its rounding bound
(``detach_kind``): DETACHES, NEVER, or UNDECIDED within rounding (the threshold itself,
|eps|*sqrt(1 + k**2) = 1 to ~1e-15); an accumulation with UNDECIDED stops the orbit as UNCERTAIN.

Departure from detachment. At theta* the relative velocity x = d' is 0 and d'' = 0. With the
free particle V = u + x, x' = d'' = -a(theta* + t) + (eta(u) - eta(u + x)). At any first return
of x to 0 at t0 in (0, t_c) (x > 0 before, just after 0 x ~ J*t**2/2 > 0, J = -a'(theta*) > 0)
x'(t0) = -a(theta* + t0) > 0, a contradiction: so x > 0 on (0, t_c) for every increasing eta,
and the gap d > 0 on (0, t_c]. The flight starts its certified lower-bound steps at t_c
(``fastpath.elastic.lower_bound.lower_bound_steps``) once d(t_c) exceeds its rounding
bound (the float state (theta*, u(theta*)) stands for the exact one, as without drag).

Accumulation tail with drag. Near accumulation at phase theta the relative motion x obeys x'' = A +
J*t - c*x' + (second order), with A = -a(theta), J = dA/dt = c*eps*cos(theta) - eps*sin(theta), c =
eta'(u) (the law's ``tail_terms``: k linear, 2k|u| quadratic). One flight from x' = w: x = w*t -
a*t**2/2 - c*(w*t**2/2 - a*t**3/6) + J*t**3/6 lasts tau0*(1 - c*tau0/6) + J*tau0**2/(3a) (tau0 =
2w/a) and returns with -w*(1 - c*tau0/3) + J*tau0**2/6. Summing over the impacts (w_k ~ r**k w), the
drag part gives -c*tau0**2*[r/(3(1 - r)**2(1 + r)) + 1/(6(1 - r**2))] = -c*T0**2/6, so

    T = T0 + J*T0**2/(3a) - c*T0**2/6 + R,     T0 = 2w/(a*(1 - r)),

(c = 0: ``elastic_accumulation_tail``). The remainder is of second order,
|R| <= C*q*T0, q = T0**2*(J**2/a**2 + |J|*c/a + c**2 + (|eps|*(1 + k) + eta2*eps**2)/a + p2*a),
with |A''| <= |eps|*(1 + k) (linear) or |eps| + 2k*eps**2 (quadratic: eta2 = 2k) and p2 = |eta''|
(0, resp. 2k: the x'**2 term). The tail is summed once q <= u; the tests hold C <= 1/2 against a
60-digit iteration of the impacts (tests/fastpath/test_drag_sticking.py).

``accumulation_tail`` and ``detachment`` take the physics description and choose between the two
(drag == 0: the formulas without drag, bit for bit).
"""

import math
from typing import NamedTuple

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import PI, PI_LOW, TWO_PI, TWO_PI_LOW, centre_phase, reduce_phase
from fastpath.arithmetic.rotation import sin_cos_of_sum
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative import laws
from fastpath.dissipative.drag import gap_state
from fastpath.dissipative.drag_flight import lower_bound_steps  # with the drag's model registered
from fastpath.dissipative.laws import detach_discriminant, eta, tail_terms
from fastpath.dissipative.short_flight import departure_deceleration
from fastpath.elastic.gap import gap, gap_error
from fastpath.elastic.lower_bound import lower_bound_flight
from fastpath.physics import DISSIPATIVE, model_of
from fastpath.status import CONVERGED, UNCERTAIN

TAIL_Q = UNIT_ROUNDOFF  # sum the tail once its second-order size q is <= u (docstring)
NEVER, DETACHES, UNDECIDED = 0, 1, -1  # whether a riding particle ever leaves (``detach_kind``)


class Detachment(NamedTuple):
    """The flight from a detachment, the same after every sticking episode (``detachment``)."""

    tau: float
    iterations: int
    status: int
    phase: float  # theta*
    velocity: float  # u(theta*)
    kind: int  # NEVER, DETACHES or UNDECIDED


@jit
def inelastic_impact(u, w_in, r):
    """(v1, w1): v1 = (1 + r)*u - r*v_in written as u + w1, w1 = -r*w_in, w_in = v_in - u."""
    w1 = -r * w_in
    return u + w1, w1


@jit
def elastic_accumulation_tail(sin_theta, cos_theta, w, eps, r):
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
    tau, iterations, status = lower_bound_flight(phi, v, eps, t_c)
    if status != CONVERGED:
        return tau, math.nan, math.nan, iterations, status
    sin1, cos1 = sin_cos_of_sum(phi, tau)
    return tau, sin1, cos1, iterations, status


@jit
def riding_force(sin_theta, cos_theta, eps, k, law):
    """a(theta) = 1 + eta(u) - eps*cos(theta), u = -eps*sin(theta) (module docstring)."""
    return 1.0 + eta(-eps * sin_theta, k, law) - eps * cos_theta


@jit
def detach_kind(eps, k, law):
    """DETACHES, NEVER or UNDECIDED (module docstring: the discriminant against its rounding)."""
    g, bound = detach_discriminant(abs(eps), k, law)
    if g > bound:
        return DETACHES
    if g < -bound:
        return NEVER
    return UNDECIDED


@jit
def detachment_frame(eps, k, law):
    """(theta'*, t_c) in the eps > 0 frame: detachment phase and ride-curvature window; NaN if the
    particle never detaches (or the decision is within rounding)."""
    if detach_kind(eps, k, law) != DETACHES:
        return math.nan, math.nan
    return laws.detachment_frame(abs(eps), k, law)


@jit
def drag_detachment_phase(eps, k, law):
    """theta* in [0, 2*pi) (module docstring); NaN if the particle never detaches."""
    theta, _ = detachment_frame(eps, k, law)
    if theta != theta:
        return math.nan
    if eps < 0.0:
        return reduce_phase((theta + PI) + PI_LOW)
    if theta < 0.0:
        return (TWO_PI + theta) + TWO_PI_LOW
    return theta


@jit
def drag_detachment(physics):
    """(tau, iterations, status, theta*, u(theta*), kind): the flight from detachment (module
    docstring), the same after every episode; kind from ``detach_kind``."""
    eps, k, law = physics.eps, physics.drag, physics.drag_law
    kind = detach_kind(eps, k, law)
    if kind != DETACHES:
        return math.nan, 0, UNCERTAIN, math.nan, math.nan, kind
    theta_star = drag_detachment_phase(eps, k, law)
    _, t_c = detachment_frame(eps, k, law)
    phi = centre_phase(theta_star)
    v = -eps * math.sin(theta_star)
    d, _, _, d_err, _, _, _ = gap_state(phi, v, eps, k, law, t_c)
    if not d > d_err:
        return math.nan, 0, UNCERTAIN, theta_star, v, kind
    tau, iterations, status = lower_bound_steps(phi, v, physics, t_c, 0)
    return tau, iterations, status, theta_star, v, kind


@jit
def drag_accumulation_tail(sin_theta, cos_theta, w, eps, k, law, r):
    """T = T0 + J*T0**2/(3a) - c*T0**2/6 if the impacts from (theta, w) accumulate within
    q <= u, else NaN (module docstring)."""
    u = -eps * sin_theta
    a = riding_force(sin_theta, cos_theta, eps, k, law)
    a_low = a - 8.0 * UNIT_ROUNDOFF * (1.0 + abs(eps) * 14.0 + abs(eta(u, k, law)))
    if not (a_low > 0.0 and w > 0.0 and r < 1.0):
        return math.nan
    c, a2, p2 = tail_terms(eps, k, law, u)
    jerk = c * eps * cos_theta - eps * sin_theta
    t0 = 2.0 * w / (a * (1.0 - r))
    q = t0 * t0 * (jerk * jerk / (a * a) + abs(jerk) * c / a + c * c + a2 / a + p2 * a)
    if not q <= TAIL_Q:
        return math.nan
    return t0 + jerk * t0 * t0 / (3.0 * a) - c * t0 * t0 / 6.0


@jit
def accumulation_tail(sin_theta, cos_theta, w, physics):
    """T if the impacts from (theta, w) accumulate within q <= u, else NaN: with drag
    ``drag_accumulation_tail``, without ``elastic_accumulation_tail`` (module docstring)."""
    if physics.drag != 0.0:
        return drag_accumulation_tail(sin_theta, cos_theta, w, physics.eps, physics.drag,
                                      physics.drag_law, physics.restitution)
    return elastic_accumulation_tail(sin_theta, cos_theta, w, physics.eps, physics.restitution)


@jit
def detachment(physics):
    """The ``Detachment`` of a particle that rides the plate, computed once per physics: with
    drag ``drag_detachment``; without, ``detachment_flight`` with theta* = ``detachment_phase``
    and u = ``detachment_velocity``. (NaN, 0, UNCERTAIN, NaN, NaN, kind) where there is none
    (elastic impacts never stick; |eps| <= 1 without drag never detaches)."""
    eps = physics.eps
    if model_of(physics) == DISSIPATIVE and physics.restitution != 1.0 and physics.drag != 0.0:
        return Detachment(*drag_detachment(physics))
    kind = DETACHES if can_detach(eps) else NEVER
    if model_of(physics) != DISSIPATIVE or physics.restitution == 1.0 or not can_detach(eps):
        return Detachment(math.nan, 0, UNCERTAIN, math.nan, math.nan, kind)
    tau, _, _, iterations, status = detachment_flight(eps)
    return Detachment(tau, iterations, status, detachment_phase(eps), detachment_velocity(eps),
                      kind)
