"""The tolerance model: errors in units of ``kappa*u`` (``u = 2**-53``, ``kappa`` =
:func:`verify.condition_number`), the tolerances of a float64 step's ``(tau, phi1, v1)``, the
rounding of a float phase, and the central-difference Jacobian's step and tolerance."""

from __future__ import annotations

import math

from mpmath import mp

from ..numerics.float64 import TWO_PI
from ..numerics.float64 import UNIT_ROUNDOFF as U

WORK_DPS = 60  # digits of the checker's own arithmetic on exact float inputs


def mpf(x):
    return mp.mpf(x)


def kappa_numerator(phi, v, eps, tau):
    """Numerator of kappa: the rounding scale of d divided by tau (verify.condition_number)."""
    return abs(mpf(v)) + tau + abs(mpf(eps)) * (1 + abs(mpf(phi)) + tau)


def phase_rounding(k, phi, tau) -> float:
    """Rounding of a float phase (phi + tau) mod 2*pi beside the tau error: k/2 ulps of
    |phi| + tau + 2*pi (a sum and up to two reductions, each a few ulps; 8 ulps at k = 16)."""
    return k / 2 * math.ulp(abs(float(phi)) + abs(float(tau)) + TWO_PI)


def map_tolerances(k, phi, v, eps, tau, kappa):
    """(tau, phi1, v1) tolerances of a float64 step (the fastpath suite's derivation, with k):
    phi1 carries the tau error and the phase rounding; v1 = tau - v - 2*eps*sin(phi1) carries
    the tau error with weight 1 + 2|eps|, the phase rounding with weight 2|eps| and k/4 ulps of
    its terms."""
    tau_tol = float(k * kappa * U * tau) if mp.isfinite(kappa) else math.inf
    phase = phase_rounding(k, phi, tau)
    e2 = 2.0 * abs(float(eps))
    phi1_tol = tau_tol + phase
    v1_tol = (1.0 + e2) * tau_tol + e2 * phase + k / 4 * math.ulp(
        abs(float(tau)) + abs(float(v)) + e2
    )
    return tau_tol, phi1_tol, v1_tol


def phase_distance(a, b):
    """|a - b| mod 2*pi folded into [0, pi] (mpf)."""
    two_pi = 2 * mp.pi
    d = (mpf(a) - mpf(b)) % two_pi
    return min(d, two_pi - d)


def jacobian_tolerance(eps: float, step_tol: float) -> tuple[float, float]:
    """(h, tolerance) of the central-difference Jacobian at a fixed point.

    Central differences make an error ``<= step_tol/h`` from the step's own errors (at most
    ``step_tol`` at each of the two points) plus the truncation ``C*h**2`` with ``C`` a bound on
    a third derivative of the map over 6: ``C = (1 + |eps|)**3``, since each derivative of
    ``-2*eps*sin(phi + tau)`` brings a factor of order ``1 + |eps|`` (checked against verify's
    40-digit map for m = 1..10, eps = 0.1..10: the ratio is at most 0.55). ``h`` minimises
    ``step_tol/h + C*h**2``; the tolerance is twice that sum.
    """
    c = (1.0 + abs(eps)) ** 3
    h = (step_tol / (2.0 * c)) ** (1.0 / 3.0)
    return h, 2.0 * (step_tol / h + c * h * h)
