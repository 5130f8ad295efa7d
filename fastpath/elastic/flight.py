"""One flight: the smallest positive root of the gap, by the method that suits it.

For |eps| <= 1 (exactly 1 included) the gap is concave and ``fastpath.elastic.concave`` finds its
single root in a certified bracket (the common flight first in straight-line code,
``fastpath.elastic.lockstep``). For |eps| > 1, where several roots can exist, the paper's
lower-bound steps (``fastpath.elastic.lower_bound``) approach the first root from below, never
overstepping it (up to rounding).

Departure. The flight kernels take a phase centred in [-pi, pi) with its sine and cosine and a
bound on the error of the phase (its reduction) and of the sine; w0 = v + eps*sin(phi) decides
whether the particle leaves the plate (``fastpath.elastic.gap.departure``): NOT_DEPARTING only
where w0 <= 0 is certain, UNCERTAIN where w0 is within its rounding of 0.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import MODERATE_LIMIT, PAYNE_HANEK_ERROR, centre_phase
from fastpath.arithmetic.rotation import sin_cos_of_sum
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.arithmetic.sincos import sin_cos, sin_cos_error
from fastpath.elastic.concave import concave_flight
from fastpath.elastic.gap import departure, departure_verdict
from fastpath.elastic.landing import refine_long_flight
from fastpath.elastic.lockstep import lockstep_flight_one
from fastpath.elastic.lower_bound import lower_bound_flight
from fastpath.status import CONVERGED

AUTO = 0  # bracketed Halley for |eps| <= 1 (fastpath.elastic.concave), lower-bound steps otherwise
LOWER_BOUND = 1  # the paper's lower-bound steps for every eps
GENERAL = 2  # AUTO without the lockstep attempt: for a flight the lockstep did not answer
METHODS = {"auto": AUTO, "lower_bound": LOWER_BOUND}  # the public names of the methods


@jit
def phase_error_of(phi_given, phi_centred):
    """Bound on the error of the centred phase: 0 if unchanged, else one ulp
    (``fastpath.arithmetic.phase``), and for |phi| >= 2**20 (Payne-Hanek) the absolute
    PAYNE_HANEK_ERROR besides."""
    if phi_centred == phi_given:
        return 0.0
    error = 2.0 * UNIT_ROUNDOFF * abs(phi_centred)
    return error + PAYNE_HANEK_ERROR if abs(phi_given) >= MODERATE_LIMIT else error


@jit
def departure_phase(phi):
    """(centred phase, bound on its error) of a departure at any real phi, with its sine taken
    from ``fastpath.arithmetic.sincos``: the centring's error plus what ``sin_cos`` adds beyond
    libm."""
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
    tau, _, _, _, iterations, status = flight_from(
        centred, sin_phi, cos_phi, v, eps, method, phase_error
    )
    return tau, iterations, status


@jit
def flight_from(phi, sin_phi, cos_phi, v, eps, method=AUTO, phase_error=0.0):
    """(tau, tau_lo, sin(phi + tau), cos(phi + tau), iterations, status) for phi in [-pi, pi).

    The caller supplies sin and cos of the departure phase, which the previous collision has
    already computed: an orbit needs one libm sine and cosine per collision. phase_error bounds
    the error of phi itself (its reduction). NOT_DEPARTING only where w0 <= 0 is certain; a w0
    within its rounding bound of zero is UNCERTAIN. A long flight's root is tau + tau_lo, an
    unevaluated sum (``fastpath.elastic.landing``; tau_lo = 0 otherwise), and the sine and
    cosine are of phi + tau + tau_lo.
    """
    tau, sin1, cos1, iterations, status = certified_flight(phi, sin_phi, cos_phi, v, eps,
                                                           method, phase_error)
    if status != CONVERGED:
        return tau, 0.0, sin1, cos1, iterations, status
    tau, tau_lo, sin1, cos1 = refine_long_flight(cos_phi, v, eps, tau, sin1, cos1)
    return tau, tau_lo, sin1, cos1, iterations, status


@jit
def certified_flight(phi, sin_phi, cos_phi, v, eps, method=AUTO, phase_error=0.0):
    """(tau, sin(phi + tau), cos(phi + tau), iterations, status): ``flight_from``'s certified
    flight time as one float, by the method that suits the flight (module docstring)."""
    w0, w0_error = departure(phi, sin_phi, v, eps, phase_error)
    verdict = departure_verdict(w0, w0_error)
    if verdict != CONVERGED:
        return math.nan, math.nan, math.nan, 0, verdict
    if abs(eps) <= 1.0 and method != LOWER_BOUND:
        if method == AUTO:
            tau, sin1, cos1, evaluations, done = lockstep_flight_one(phi, sin_phi, cos_phi, v,
                                                                     eps, w0_error)
            if done:  # the common flight, as the ensembles compute it (fastpath.elastic.lockstep)
                return tau, sin1, cos1, evaluations, CONVERGED
        return concave_flight(phi, sin_phi, cos_phi, v, eps, w0_error)
    # the first step from d(0) = 0, d1(0) = w0 with d2 >= -(1 + |eps|)
    tau, iterations, status = lower_bound_flight(phi, v, eps, 2.0 * w0 / (1.0 + abs(eps)))
    sin1, cos1 = sin_cos_of_sum(phi, tau)
    return tau, sin1, cos1, iterations, status
