"""One flight with drag: the smallest positive root of the gap of ``fastpath.dissipative.drag``.

Bounds on the gap's curvature (the paper's Section 2 with friction). d'' = p(t) + eps*cos(phi + t)
with the particle's acceleration p(t) = -1 - eta(V(t)). V moves monotonically towards the terminal
velocity (p = 0 there): from above it (the usual case, 1 + eta(v) >= 0) V decreases, so eta(V)
decreases and p increases towards 0; from below (falling faster than terminal after an impact
on a plate moving down fast) p > 0 decreases towards 0. Either way, for s >= t,

    p(s) >= min(p(t), 0),   so   d''(s) >= -a(t),   a(t) = max(1 + eta(V(t)), 0) + |eps|.

At departure a(0) = max(1 + eta(v), 0) + |eps|: 1 + eta(v) + |eps| as the paper writes it when
v >= terminal (v < 0 included: then eta(v) < 0 and the bound is below 1 + |eps|, still valid
because V only decreases), and |eps| alone below terminal (not 1 + max(eta(v), 0) + |eps|,
which holds too but is looser). Since a(t) only shrinks (in the usual case) the
lower-bound steps take a(t_k) at each iterate: past the top of a fast flight with quadratic drag
a(t) is ~1 + |eps| instead of 1 + k*v**2 + |eps|.

Lower-bound steps (the loop ``lower_bound_steps`` of ``fastpath.elastic.lower_bound``, with the
gap and bounds of ``drag_gap_bounds``, the graze test ``may_be_drag_graze`` and the descent's
jumps, registered below for ``Dissipative`` descriptions): from t_k with d_k > 0
and slope r_k the paper's step with a(t_k), and the local step of
``fastpath.elastic.lower_bound.certified_step`` with
c_k = min(p(t_k), 0) + eps*cos(phi + t_k) (the particle's part frozen at its lower bound, the
plate's part with its Taylor remainder), all lowered by their rounding bounds
(``fastpath.dissipative.drag.gap_state``); the same stop, polish, graze test and statuses. In the
graze test the largest curvature after t is b = |eps| + max(p(t), 0) (p <= 0 and increasing, or
p > 0 and decreasing; |eps| - 1 without drag: the law's ``acceleration_sup``) and the third
derivative is bounded by |eps| + |p'|, with the law's bound on |p'| = eta'(V)*|p| (``jerk_rate``
of ``fastpath.dissipative.laws``: V stays between V(t) and the terminal velocity).

Concave flights (Halley in a bracket, as ``fastpath.elastic.concave``). If 1 + eta(v) >= 0 then p is
increasing, so on [0, t] d'' <= p(t) + |eps| = -m(t). A point t with m(t) > 0 certifies the gap
concave on [0, t]: with d(0) = 0 < d'(0) there is at most one root in (0, t], so d(t) > E puts t
before the first root and d(t) < -E after it (E the gap's rounding bound). Halley steps in the
bracket [lo, hi] start, as in ``fastpath.elastic.concave``, for long flights (2*w0 >= 1 + |eps|) at
the particle's own landing time to first order in the drag, 2*v*(1 - D/3) with D/3 the law's
relative shortening (``landing_drop``: k*v/3 linear, k*v**2/4 quadratic), when that correction
is below a half; else at the root of w0*t - (1 + eta(v) -
eps*cos(phi))*t**2/2 (the departure curvature frozen); while hi is not yet known (no point after
the root), a step that would go backwards is replaced by the root of the local quadratic model d
+ d'*s + d''*s**2/2 (forward, d'' < 0). The first point where m(t) <= 0 (drag so strong or a
fall so long that the particle nears its terminal velocity: even |eps| < 1 then allows a convex
gap and several roots) hands the flight to the lower-bound steps, which go on from the bracket's
lower end with the iterations left.

Linear drag near the root of a long descent (``tight_gap_errors`` and ``tight_particle_errors`` of
``fastpath.dissipative.laws.linear``; the other laws return the bounds they are given). The rounding
bounds of ``fastpath.dissipative.drag.particle`` charge the rounding of the argument z = -k*t (a
relative change of a few u of the time) with the largest |V'| and |V| of the whole flight, those at
the departure (1 + k*v and v). After a fall of k*t >> 1 at the terminal velocity they are many
orders of magnitude above the local ones: at k = 1000, v = 1e5 the bound on d' is 0.09 where |d'| =
0.03 at the root, and the steps, which lower d' by its bound, creep towards the point where d equals
its bound with ratio R/(|d'| + R) and ran out of evaluations (MAX_ITERATIONS for
k*v >= 1e8). With linear drag the local values are exact: V' = -(1 + k*v)*exp(-k*t) is monotone,
so over the perturbed times t*(1 + theta), |theta| <= 16u, |V'| <= |1 + k*v|*e*exp(2*|z|*u)
with e = fl(exp(z)) (exp's rounding and z's included), and |Y'| = |V| <= |vel| + the velocity's
own bound. The lower-bound steps and the descent's jumps use the smaller of the two bounds (both
are valid); the concave solver keeps ``particle``'s.

The long descent (``descent_jump``). Near the terminal velocity the lower-bound steps would crawl:
their curvature bound is the plate's |eps| while the particle sinks by ~1/k per unit of time
(linear drag k = 3 from v = 1000 falls 330 units for 1000 units of time). But the plate rises at
most c = |eps| - eps*cos(phi) above its departure position, so d(t) >= Y(t) - c: no collision
while the particle is higher than c. Where its height Y is concave for the whole flight (it
starts at or above its terminal velocity: ``falls_concave``), the time it sinks to c is
bracketed by the motion alone, as the elastic concave gap is: the tangent at a point above c
crosses c beyond that time, the chord to a point below it crosses c before it. The steps jump to
the chord's crossing and go on from there. The end is as in ``fastpath.elastic.concave``: a Newton
correction clamped into the bracket; UNCERTAIN at a flat zero.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rotation import sin_cos_of_sum
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.arithmetic.sincos import sin_cos
from fastpath.dissipative.drag import gap_state, particle
from fastpath.dissipative.laws import (
    acceleration_sup,
    eta,
    jerk_rate,
    landing_drop,
    tight_gap_errors,
    tight_particle_errors,
)
from fastpath.elastic.concave import AFTER, AT_ROOT, BEFORE, halley
from fastpath.elastic.flight import AUTO, departure_phase
from fastpath.elastic.gap import departure, departure_verdict
from fastpath.elastic.lower_bound import (
    GapBounds,
    LowerBoundModel,
    lower_bound_model,
    lower_bound_step,
    lower_bound_steps,
)
from fastpath.physics import Dissipative
from fastpath.status import (
    CONVERGED,
    ITERATION_LIMIT,
    MAX_ITERATIONS,
    OVERFLOW,
    UNCERTAIN,
)

_U = UNIT_ROUNDOFF
_DESCENT_EVALUATIONS = 12  # particle evaluations one descent jump may spend
_DESCENT_CLOSE = 0.25  # a jump stops once the particle is within this share of |eps| above c


@jit
def drag_flight(phi, sin_phi, cos_phi, v, physics, w0_error, method=AUTO):
    """(tau, sin(phi + tau), cos(phi + tau), iterations, status) with drag (module docstring).

    physics: the description (``fastpath.physics``) with drag > 0. phi in [-pi, pi) with its
    sine and cosine; w0_error bounds the rounding error of w0 = v + eps*sin_phi
    (``fastpath.elastic.gap.departure``). Statuses as ``fastpath.elastic.flight.flight_from``.
    method: AUTO (Halley where the gap is provably concave) or LOWER_BOUND (lower-bound steps
    only).
    """
    eps, drag, law = physics.eps, physics.drag, physics.drag_law
    w0 = v + eps * sin_phi
    verdict = departure_verdict(w0, w0_error)
    if verdict != CONVERGED:
        return math.nan, math.nan, math.nan, 0, verdict
    a = curvature_bound(v, 0.0, eps, drag, law)
    lo = 2.0 * (w0 - w0_error) / a * (1.0 - 4.0 * _U)
    used = 0
    if method == AUTO and abs(eps) < 1.0 and 1.0 + eta(v, drag, law) >= 0.0:
        tau, iterations, status = concave_drag_flight(phi, cos_phi, v, physics, w0, lo)
        if status != MAX_ITERATIONS or iterations == ITERATION_LIMIT:
            sin1, cos1 = sin_cos_of_sum(phi, tau)
            return tau, sin1, cos1, iterations, status
        used, lo = iterations, tau  # not certified concave: lower-bound steps from its lo
    tau, iterations, status = lower_bound_steps(phi, v, physics, lo, used)
    sin1, cos1 = sin_cos_of_sum(phi, tau)
    return tau, sin1, cos1, iterations, status


@jit
def curvature_bound(vel, v_err, eps, drag, law):
    """a >= -d'' for the rest of the flight from a point with velocity vel (+- v_err), rounded up:
    max(1 + eta(vel + v_err), 0) + |eps| (module docstring)."""
    particle = 1.0 + eta(vel + v_err, drag, law)
    return (max(particle, 0.0) * (1.0 + 4.0 * _U) + abs(eps)) * (1.0 + 2.0 * _U)


@jit
def concave_drag_flight(phi, cos_phi, v, physics, w0, lo):
    """(tau, evaluations, status) by Halley in a certified bracket (module docstring).

    MAX_ITERATIONS with fewer than ITERATION_LIMIT evaluations means: the gap could not be
    certified concave at an iterate; tau is then the bracket's certified lower end (the gap is
    positive on (0, tau]), where the caller goes on with lower-bound steps.
    """
    eps, drag, law = physics.eps, physics.drag, physics.drag_law
    hi = math.inf
    t = 2.0 * w0 / (1.0 + eta(v, drag, law) - eps * cos_phi)
    drop = landing_drop(v, drag, law)  # 3*(relative shortening)
    if 2.0 * w0 >= 1.0 + abs(eps) and drop < 1.5:
        t = 2.0 * v * (1.0 - drop / 3.0)
    if not lo < t:
        t = 2.0 * lo
    for evaluations in range(1, ITERATION_LIMIT + 1):
        d, d1, d2, d_err, d1_err, vel, v_err = gap_state(phi, v, eps, drag, law, t)
        if not (abs(d) < math.inf and abs(d1) < math.inf):
            return math.nan, evaluations, OVERFLOW
        p_high = -1.0 - eta(vel - v_err, drag, law) + 4.0 * _U * (1.0 + abs(eta(vel, drag, law)))
        if not p_high + abs(eps) * (1.0 + 2.0 * _U) < 0.0:
            return lo, evaluations, MAX_ITERATIONS  # not certified concave up to t
        if d > d_err:
            where = BEFORE
        elif d < -d_err:
            where = AFTER
        elif d1 < -d1_err:
            where = AT_ROOT
        elif d1 > d1_err:
            where = BEFORE
        else:
            return t, evaluations, UNCERTAIN  # a flat zero: float64 cannot place the root
        if where == AT_ROOT:
            return min(max(t - d / d1, lo), hi), evaluations, CONVERGED
        if where == BEFORE and hi == math.inf:
            lo = t
            t_next = t - 2.0 * d * d1 / (2.0 * d1 * d1 - d * d2)
            if not t_next > lo:  # backwards before the top: the local model's root instead
                t_next = t + lower_bound_step(max(d, 0.0), d1, max(-d2, _U))
        else:
            t_next, lo, hi = halley(t, d, d1, d2, where, lo, hi)
        if t_next == lo or t_next == hi or t_next == t:
            return lo, evaluations, CONVERGED  # the bracket closed to adjacent floats
        t = t_next
    return t, ITERATION_LIMIT, MAX_ITERATIONS


@jit
def drag_gap_bounds(phi, v, physics, t):
    """(bounds, V(t), its error): the gap with drag at t and what the lower-bound step needs, a
    ``fastpath.elastic.lower_bound.GapBounds`` as ``elastic_gap_bounds``'s: d, d1, their
    rounding bounds, a lower bound on d2 with the particle's part at its bound min(p, 0) (module
    docstring), the jerk -eps*sin(phi + t), eps and the curvature bound a(t); the particle's
    velocity for the graze test."""
    eps, drag, law = physics.eps, physics.drag, physics.drag_law
    d, d1, _, d_err, d1_err, vel, v_err = gap_state(phi, v, eps, drag, law, t)
    d_err, d1_err, v_err = tight_gap_errors(phi, v, eps, drag, law, t, d, d1, vel, d_err,
                                            d1_err, v_err)
    theta = phi + t
    p_low = min(-1.0 - eta(vel + v_err, drag, law), 0.0) * (1.0 + 4.0 * _U)
    curvature = p_low + eps * math.cos(theta) - 4.0 * _U * abs(eps) * (1.0 + t)
    a = curvature_bound(vel, v_err, eps, drag, law)
    return GapBounds(d, d1, d_err, d1_err, curvature, -eps * math.sin(theta), eps, a), vel, v_err


def drag_bounds_at(phi, v, physics, t):
    """``bounds_at`` of ``fastpath.elastic.lower_bound`` with drag: ``drag_gap_bounds`` and
    ``may_be_drag_graze``."""
    bounds, vel, v_err = drag_gap_bounds(phi, v, physics, t)
    grazes = bounds.gap <= bounds.gap_error and may_be_drag_graze(
        phi, physics, vel, v_err, t, bounds.rate, bounds.gap_error)
    return bounds, grazes


def descent_of(phi, v, physics):
    """``jumps_of`` with drag: (the plate's reach c, whether the height falls concave), what
    ``descent_jump`` needs."""
    return plate_reach(math.cos(phi), physics.eps), falls_concave(v, physics)


def drag_jump(v, physics, t, jumps, budget):
    """``jump`` with drag: the descent's jump (``descent_jump``) where the height falls
    concave, else none."""
    reach, concave = jumps
    if concave:
        return descent_jump(v, physics, t, reach, budget)
    return t, 0


lower_bound_model(Dissipative, LowerBoundModel(drag_bounds_at, descent_of, drag_jump))


@jit
def plate_reach(cos_phi, eps):
    """c = |eps| - eps*cos(phi), rounded up: the most the plate rises above its position at the
    departure, so that d(t) >= Y(t) - c (module docstring)."""
    return (abs(eps) - eps * cos_phi) * (1.0 + 4.0 * _U) + 4.0 * _U * abs(eps)


@jit
def falls_concave(v, physics):
    """Whether the particle's height Y is concave for the whole flight: its acceleration
    -1 - eta(V) <= 0 at the departure, beyond the rounding of eta(v). V then moves towards the
    terminal velocity from above and never crosses it (linear: V(t) = -1/k + (v + 1/k)*exp(-kt);
    quadratic: V' = -1 + k*V**2 < 0 while |V| < 1/sqrt(k)), so -1 - eta(V(t)) <= 0 throughout."""
    e = eta(v, physics.drag, physics.drag_law)
    return 1.0 + e > 4.0 * _U * (1.0 + abs(e))


@jit
def descent_jump(v, physics, t, reach, budget):
    """(t', evaluations): a later start for the lower-bound steps, or (t, evaluations) with
    t' = t where the descent's argument does not apply.

    From a point t before the first root, while the particle falls (V(t) < 0) with a concave
    height (``falls_concave``) above the plate's reach c, the gap d >= Y - c stays positive
    until Y falls to c: no collision in between. The time Y reaches c is bracketed by the concave
    motion alone: the tangent from the last point below (Y concave lies under it) overshoots it, and
    the chord through two points above and below, with the heights lowered by their rounding bounds,
    undershoots it (Y concave lies over it), so the chord's crossing is a certified later start. At
    most ``budget`` particle evaluations, each counted.
    """
    y, vel, y_err, v_err = descent_particle(v, physics, t)
    evaluations = 1
    if not (vel + v_err < 0.0 and y - y_err > reach):
        return t, evaluations
    lo, y_lo, vel_lo = t, y - y_err, vel
    while evaluations + 2 <= min(budget, _DESCENT_EVALUATIONS):
        beyond = lo + (reach - y_lo) / vel_lo  # the tangent's crossing of the reach
        y_b, _, e_b, _ = descent_particle(v, physics, beyond)
        evaluations += 1
        if y_b - e_b > reach:  # above the reach there too: Y > c on [lo, beyond] (concave)
            lo = beyond
        else:  # the chord's crossing: Y >= chord >= c up to it
            lo = lo + (y_lo - reach) / (y_lo - (y_b - e_b)) * (beyond - lo) * (1.0 - 4.0 * _U)
        y, vel_lo, y_err, _ = descent_particle(v, physics, lo)
        evaluations += 1
        y_lo = y - y_err
        if not y_lo - reach > _DESCENT_CLOSE * abs(physics.eps) + 4.0 * y_err:
            break  # near the reach: the lower-bound steps go on from here
    return lo, evaluations


@jit
def descent_particle(v, physics, t):
    """``particle`` at t for the descent's jumps, with the law's ``tight_particle_errors``."""
    drag, law = physics.drag, physics.drag_law
    y, vel, y_err, v_err = particle(v, drag, law, t)
    y_err, v_err = tight_particle_errors(v, drag, law, t, vel, y_err, v_err)
    return y, vel, y_err, v_err


@jit
def may_be_drag_graze(phi, physics, vel, v_err, t, r, d_err):
    """Whether a gap within rounding of zero at t may be a near-tangent dip (module docstring;
    the argument of ``fastpath.elastic.lower_bound.may_be_graze`` with the drag's curvature and
    jerk bounds); vel: V(t) with its error bound v_err."""
    eps, drag, law = physics.eps, physics.drag, physics.drag_law
    p = -1.0 - eta(vel, drag, law)
    p_err = abs(eta(vel + v_err, drag, law) - eta(vel - v_err, drag, law)) + 4.0 * _U * abs(p)
    # sup of p after t: 0 (approached, p increasing) or p(t) (p > 0 decreasing); -1 without drag
    convex_bound = abs(eps) + acceleration_sup(p, p_err, drag, law)
    if convex_bound <= 0.0:
        return False  # concave for the rest of the flight: no dip
    curvature = p + p_err + eps * math.cos(phi + t) + 4.0 * _U * abs(eps) * (1.0 + t)
    p_size = abs(p) + p_err
    jerk = abs(eps) + jerk_rate(vel, v_err, drag, law, p_size)
    if curvature < 0.0 and r < 0.0 and 2.0 * d_err * jerk < -r * -curvature:
        return False
    return r > -2.0 * math.sqrt(4.0 * convex_bound * d_err)


@jit
def solve_drag_flight(phi, v, physics, method=AUTO):
    """(tau, iterations, status) for a departure at any real phase phi (as
    ``fastpath.elastic.flight.solve_flight``), with the drag of ``physics``."""
    centred, phase_error = departure_phase(phi)
    sin_phi, cos_phi = sin_cos(centred)  # as dissipative_collide: flight and step agree
    _, w0_error = departure(centred, sin_phi, v, physics.eps, phase_error)
    tau, _, _, iterations, status = drag_flight(
        centred, sin_phi, cos_phi, v, physics, w0_error, method
    )
    return tau, iterations, status
