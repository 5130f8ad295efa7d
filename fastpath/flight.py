"""One flight: the smallest positive root of the gap.

For |eps| < 1 the gap is concave and ``fastpath.concave`` finds its single root by bracketed
Halley steps (about two gap evaluations a flight). For |eps| >= 1, where several roots can exist,
the seed's lower-bound steps are used, which approach the first root from below:

Gravity and the plate's acceleration give d''(t) >= -(1 + |eps|) =: -a, so from a time t_k with
d_k = d(t_k) > 0 and slope r_k = d'(t_k),

    d(t_k + s) >= d_k + r_k*s - a*s**2/2,

and the larger root s_k of the right-hand side is a rigorous lower bound on the time left before
the next collision (DESIGN fact 3). Iterating t_{k+1} = t_k + s_k never oversteps (up to
rounding) and converges quadratically at a transversal root. The root formula is chosen by the
sign of r_k so that it never subtracts nearly equal numbers:

    s = (r + sqrt(r**2 + 2*a*d)) / a          if r >= 0
    s = 2*d / (sqrt(r**2 + 2*a*d) - r)        if r <  0

The iteration stops when the gap is within its rounding error of zero. For |eps| > 1 the gap can
be convex (d'' <= |eps| - 1 =: b), and a zero gap with a small slope may be the bottom of a
near-tangent dip whose sign float64 cannot tell: that flight is returned as UNCERTAIN.
"""

import math

from fastpath._jit import jit
from fastpath.concave import ITERATION_LIMIT as CONCAVE_LIMIT
from fastpath.concave import concave_flight
from fastpath.gap import UNIT_ROUNDOFF, gap, gap_error, gap_rate
from fastpath.phase import centre_phase
from fastpath.status import FlightStatus

CONVERGED = int(FlightStatus.CONVERGED)
UNCERTAIN = int(FlightStatus.UNCERTAIN)
NOT_DEPARTING = int(FlightStatus.NOT_DEPARTING)
MAX_ITERATIONS = int(FlightStatus.MAX_ITERATIONS)

AUTO = 0  # bracketed Halley for |eps| < 1 (fastpath.concave), lower-bound steps otherwise
SEED = 1  # the seed's lower-bound steps for every eps (kept for comparison)
METHODS = {"auto": AUTO, "seed": SEED}

ITERATION_LIMIT = 100_000  # crawling past a near-tangency at eps slightly above 1 is slow


@jit
def lower_bound_step(d, r, a):
    """Larger root s of d + r*s - a*s**2/2 = 0 (d >= 0, a > 0), cancellation-free."""
    root = math.sqrt(r * r + 2.0 * a * d)
    if r >= 0.0:
        return (r + root) / a
    return 2.0 * d / (root - r)


@jit
def solve_flight(phi, v, eps, method=AUTO):
    """Return (tau, iterations, status) for a departure at phase phi (any real) with velocity v.

    tau is the smallest positive root of the gap; ``status`` is a FlightStatus code.
    """
    phi = centre_phase(phi)
    tau, _, _, iterations, status = flight_from(
        phi, math.sin(phi), math.cos(phi), v, eps, method
    )
    return tau, iterations, status


@jit
def flight_from(phi, sin_phi, cos_phi, v, eps, method=AUTO):
    """(tau, sin(phi + tau), cos(phi + tau), iterations, status) for phi in [-pi, pi).

    The caller supplies sin and cos of the departure phase, which the previous collision has
    already computed: an orbit needs one libm sine and cosine per collision.
    """
    w0 = v + eps * sin_phi
    if not w0 > 0.0:
        return math.nan, math.nan, math.nan, 0, NOT_DEPARTING
    if abs(eps) < 1.0 and method == AUTO:
        tau, sin_end, cos_end, evaluations = concave_flight(phi, sin_phi, cos_phi, v, eps)
        status = CONVERGED if evaluations < CONCAVE_LIMIT else MAX_ITERATIONS
        return tau, sin_end, cos_end, evaluations, status
    tau, iterations, status = lower_bound_flight(phi, v, eps, w0)
    return tau, math.sin(phi + tau), math.cos(phi + tau), iterations, status


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
    curvature = -1.0 + eps * math.cos(phi + t) + 4.0 * UNIT_ROUNDOFF * abs(eps)
    if curvature < 0.0 and r < 0.0 and 2.0 * d_err < -r * (-curvature / abs(eps)):
        return False
    return r > -2.0 * math.sqrt(4.0 * convex_bound * d_err)


@jit
def lower_bound_flight(phi, v, eps, w0):
    """(tau, iterations, status) by the seed's lower-bound steps; phi reduced, w0 > 0."""
    a = 1.0 + abs(eps)
    t = 2.0 * w0 / a  # the step from d(0) = 0, d'(0) = w0
    for k in range(1, ITERATION_LIMIT + 1):
        d = gap(phi, v, eps, t)
        r = gap_rate(phi, v, eps, t)
        d_err = gap_error(phi, v, eps, t)
        if d <= d_err:
            if may_be_graze(phi, eps, t, r, d_err):
                return t, k, UNCERTAIN
            return t, k, CONVERGED
        t_next = t + lower_bound_step(d, r, a)
        if t_next == t:  # the root is within one ulp of t
            return t, k, CONVERGED
        t = t_next
    return t, ITERATION_LIMIT, MAX_ITERATIONS
