"""One flight: the smallest positive root of the gap.

For |eps| <= 1 (exactly 1 included) the gap is concave and ``fastpath.concave`` finds its single
root in a certified bracket. For |eps| > 1, where several roots can exist, lower-bound steps
approach the first root from below, never overstepping it (up to rounding).

Global step (the seed's, DESIGN fact 3). Gravity and the plate's acceleration give
d2(t) >= -(1 + |eps|) =: -a (d1, d2, d3: the first three derivatives of d), so from a time t_k
with d_k = d(t_k) > 0 and slope r_k = d1(t_k),

    d(t_k + s) >= d_k + r_k*s - a*s**2/2,

and the larger root s_a of the right-hand side is a rigorous lower bound on the time left before
the next collision.

Local step (fast near a double root). The derivatives of the plate term are bounded by |eps|, so
with c_k = d2(t_k) = -1 + eps*cos(phi + t_k) and j_k = d3(t_k) = -eps*sin(phi + t_k),

    d2(t_k + s) >= c_k + j_k*s - |eps|*s**2/2 >= min(c_k, c_k + j_k*H - |eps|*H**2/2) =: c_H

for 0 <= s <= H (a concave quadratic in s has its minimum at an end), and c_H >= -a too. Hence
d(t_k + s) >= q_H(s) := d_k + r_k*s + c_H*s**2/2 on [0, H]. If the first positive root s_H of
q_H is <= H, d > 0 on [t_k, t_k + s_H): a step of s_H never oversteps; if q_H has no root in
[0, H], a step of H does not. H starts at s_a and grows towards s_H for a few rounds; the step is
the largest certified one. Near a double root t* (d ~ m*(t - t*)**2/2) the model's error is
O(|eps|*h**4) at a distance h, so h shrinks quadratically instead of the global step's crawl
(eps just above 1: the global bound a ~ 2 dwarfs the dip's curvature <= eps - 1, and steps of
~sqrt(2*d/a) took up to 20,000 iterations).

Rounding: the models use d_k, r_k and c_k lowered by their error bounds (``gap_error``,
``rate_error``), so they bound the exact gap from below; a discriminant within its rounding of zero
counts as a root. Root formulas are chosen by the sign of r_k so that they never subtract nearly
equal numbers (``first_root``). The iteration stops when the gap is within its rounding error of
zero; a final Newton correction (``polish``) then moves onto the crossing: the stop can be up to
~12 kappa*u early, the polish leaves only the gap's actual rounding. It is taken only where the
slope d1 < 0 beyond its error; where d is convex over the step the tangent lies below d and its
root is not beyond the crossing, where it is concave the overshoot is at most s**2*a/(2|d1|) for a
step s itself at rounding level (|d| <= E). No second root lies that close (``may_be_graze``).

For |eps| > 1 the gap can be convex (d2 <= |eps| - 1 =: b), and a zero gap with a small slope may
be the bottom of a near-tangent dip whose sign float64 cannot tell: that flight is UNCERTAIN. At
most ITERATION_LIMIT evaluations for any input (then MAX_ITERATIONS, as UNCERTAIN). A non-finite
intermediate (v**2, t*v overflowing) gives OVERFLOW.
"""

import math

from fastpath._jit import jit
from fastpath.concave import concave_flight
from fastpath.gap import UNIT_ROUNDOFF, departure, gap, gap_error, gap_rate, rate_error
from fastpath.lockstep import lockstep_flight_one
from fastpath.phase import CODY_WAITE_LIMIT, PAYNE_HANEK_ERROR, centre_phase
from fastpath.rotation import sin_cos_of_sum
from fastpath.sincos import sin_cos, sin_cos_error
from fastpath.status import FlightStatus

CONVERGED = int(FlightStatus.CONVERGED)
UNCERTAIN = int(FlightStatus.UNCERTAIN)
NOT_DEPARTING = int(FlightStatus.NOT_DEPARTING)
MAX_ITERATIONS = int(FlightStatus.MAX_ITERATIONS)
OVERFLOW = int(FlightStatus.OVERFLOW)

AUTO = 0  # bracketed Halley for |eps| <= 1 (fastpath.concave), lower-bound steps otherwise
SEED = 1  # lower-bound steps for every eps (kept for comparison)
GENERAL = 2  # AUTO without the lockstep attempt: for a flight the lockstep did not answer
METHODS = {"auto": AUTO, "seed": SEED}

ITERATION_LIMIT = 60
_GROWTH_ROUNDS = 4  # rounds of growing H in the local step


@jit
def lower_bound_step(d, r, a):
    """Larger root s of d + r*s - a*s**2/2 = 0 (d >= 0, a > 0), cancellation-free."""
    root = math.sqrt(r * r + 2.0 * a * d)
    if r >= 0.0:
        return (r + root) / a
    return 2.0 * d / (root - r)


@jit
def first_root(d, r, k):
    """Smallest positive root of d + r*s + k*s**2/2 (d > 0), inf if none; cancellation-free.

    A discriminant within its rounding error of zero counts as zero (a root: the shorter step).
    """
    disc = r * r - 2.0 * k * d
    if disc < -4.0 * UNIT_ROUNDOFF * (r * r + 2.0 * abs(k) * d) or (r >= 0.0 and k >= 0.0):
        return math.inf
    disc = max(disc, 0.0)
    if r < 0.0:
        return 2.0 * d / (math.sqrt(disc) - r)
    return (r + math.sqrt(disc)) / -k


@jit
def certified_step(d, r, c, j, eps, a):
    """Largest step from a point with d > 0 that the module docstring's lower models certify.

    a > 0 bounds -d2 from above for the rest of the flight (1 + |eps| here; with drag
    ``fastpath.drag_flight`` passes its own bound), c is a lower bound on d2 at the point where
    only the plate's part still varies (third derivative j, Taylor remainder |eps|*s**2/2).
    """
    best = lower_bound_step(d, r, a)
    h = best
    for _ in range(_GROWTH_ROUNDS):
        c_h = max(min(c, c + j * h - 0.5 * abs(eps) * h * h), -a)
        s_h = first_root(d, r, c_h)
        if s_h <= h:
            return max(best, s_h)
        best = h  # q_H > 0 on [0, H]
        h = min(s_h, 4.0 * h)
    return best


@jit
def phase_error_of(phi_given, phi_centred):
    """Bound on the error of the centred phase: 0 if unchanged, else one ulp (``phase``), and
    for |phi| >= 2**20 (Payne-Hanek) the absolute PAYNE_HANEK_ERROR besides."""
    if phi_centred == phi_given:
        return 0.0
    error = 2.0 * UNIT_ROUNDOFF * abs(phi_centred)
    return error + PAYNE_HANEK_ERROR if abs(phi_given) >= CODY_WAITE_LIMIT else error


@jit
def departure_phase(phi):
    """(centred phase, bound on its error) of a departure at any real phi, with its sine taken
    from ``fastpath.sincos``: the centring's error plus what ``sin_cos`` adds beyond libm."""
    centred = centre_phase(phi)
    return centred, phase_error_of(phi, centred) + sin_cos_error(centred)


@jit
def departure_of(phi, v, eps):
    """(w0, bound): w0 = v + eps*sin(phi) as the flight kernels compute it, with its error bound."""
    centred, phase_error = departure_phase(phi)
    return departure(centred, sin_cos(centred)[0], v, eps, phase_error)


@jit
def solve_flight(phi, v, eps, method=AUTO):
    """Return (tau, iterations, status) for a departure at phase phi (any real) with velocity v.

    tau is the smallest positive root of the gap; ``status`` is a FlightStatus code.
    """
    centred, phase_error = departure_phase(phi)
    sin_phi, cos_phi = sin_cos(centred)  # as collide: flight and step give the same tau
    tau, _, _, iterations, status = flight_from(
        centred, sin_phi, cos_phi, v, eps, method, phase_error
    )
    return tau, iterations, status


@jit
def flight_from(phi, sin_phi, cos_phi, v, eps, method=AUTO, phase_error=0.0):
    """(tau, sin(phi + tau), cos(phi + tau), iterations, status) for phi in [-pi, pi).

    The caller supplies sin and cos of the departure phase, which the previous collision has
    already computed: an orbit needs one libm sine and cosine per collision. phase_error bounds
    the error of phi itself (its reduction). NOT_DEPARTING only where w0 <= 0 is certain; a w0
    within its rounding bound of zero is UNCERTAIN.
    """
    w0, w0_error = departure(phi, sin_phi, v, eps, phase_error)
    if not abs(w0) < math.inf:
        return math.nan, math.nan, math.nan, 0, OVERFLOW
    if not w0 > -w0_error:
        return math.nan, math.nan, math.nan, 0, NOT_DEPARTING
    if not w0 > w0_error:
        return math.nan, math.nan, math.nan, 0, UNCERTAIN
    if abs(eps) <= 1.0 and method != SEED:
        if method == AUTO:
            tau, sin1, cos1, evaluations, done = lockstep_flight_one(phi, sin_phi, cos_phi, v,
                                                                     eps, w0_error)
            if done:  # the common flight, as the ensembles compute it (fastpath.lockstep)
                return tau, sin1, cos1, evaluations, CONVERGED
        return concave_flight(phi, sin_phi, cos_phi, v, eps, w0_error)
    tau, iterations, status = lower_bound_flight(phi, v, eps, w0)
    sin1, cos1 = sin_cos_of_sum(phi, tau)
    return tau, sin1, cos1, iterations, status


@jit
def may_be_graze(phi, eps, t, r, d_err):
    """Whether a gap within rounding of zero at t (|d| <= d_err) may be a near-tangent dip.

    The exact gap is then <= 2*d_err at t. Where it is locally concave, d2 = d''(t) < 0, it
    stays concave for a time R = -d2/|eps| (the third derivative is bounded by |eps|), so with
    slope r < 0 it surely crosses zero within 2*d_err/|r| if that is shorter than R: a collision
    at t up to rounding. Otherwise a dip of depth <= 2*d_err can follow only if
    r > -sqrt(4*b*d_err), with b = |eps| - 1 the largest possible curvature (safety factor 2).
    """
    convex_bound = abs(eps) - 1.0
    if convex_bound <= 0.0:
        return False  # the gap is concave everywhere: no dip
    # raised by its rounding bound, the argument's rounding u*(|phi| + t) included (as in
    # lower_bound_flight): the shortcut needs d'' < 0 for certain
    curvature = -1.0 + eps * math.cos(phi + t) + 4.0 * UNIT_ROUNDOFF * abs(eps) * (1.0 + t)
    if curvature < 0.0 and r < 0.0 and 2.0 * d_err < -r * (-curvature / abs(eps)):
        return False
    return r > -2.0 * math.sqrt(4.0 * convex_bound * d_err)


@jit
def lower_bound_flight(phi, v, eps, w0, start=0.0):
    """(tau, iterations, status) by certified lower-bound steps; phi reduced, w0 > 0.

    start > 0: the steps begin at t = start instead, a point the caller has certified to lie
    before the first root (d > 0 on (0, start]; e.g. a departure with w0 = 0 from a convex gap,
    ``fastpath.sticking``). w0 is then not used.
    """
    a = 1.0 + abs(eps)
    t = start if start > 0.0 else 2.0 * w0 / a  # else the step from d(0) = 0, d'(0) = w0
    for k in range(1, ITERATION_LIMIT + 1):
        d = gap(phi, v, eps, t)
        r = gap_rate(phi, v, eps, t)
        if not (abs(d) < math.inf and abs(r) < math.inf):
            return math.nan, k, OVERFLOW
        d_err = gap_error(phi, v, eps, t)
        if d <= d_err:
            if may_be_graze(phi, eps, t, r, d_err):
                return t, k, UNCERTAIN
            return polish(phi, v, eps, t, d, r), k, CONVERGED
        # the models take the worst values within rounding: d, d' and d'' lowered by their bounds
        theta = phi + t
        curvature = -1.0 + eps * math.cos(theta) - 4.0 * UNIT_ROUNDOFF * abs(eps) * (1.0 + t)
        r_low = r - rate_error(phi, v, eps, t)
        t_next = t + certified_step(d - d_err, r_low, curvature, -eps * math.sin(theta), eps, a)
        if t_next == t:  # the root is within rounding of t: d <= d_err + |r|*ulp(t)
            return polish(phi, v, eps, t, d, r), k, CONVERGED
        t = t_next
    return t, ITERATION_LIMIT, MAX_ITERATIONS


@jit
def polish(phi, v, eps, t, d, r):
    """One certified Newton correction t - d/r at a stop with |d| within rounding of zero."""
    if not r < -rate_error(phi, v, eps, t):
        return t
    return t - d / r
