"""The tolerance model: errors in units of ``kappa*u`` (``u = 2**-53``, ``kappa`` =
:func:`verify.condition_number` of the phase as given, ``reduced=False``: a user's integrator
may add ``phi + t`` in floating point), the tolerances of a float64 step's ``(tau, phi1, v1)``,
the rounding of an exactly reduced float phase, and the central-difference Jacobian's step and
tolerance."""

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


def phase_rounding(k) -> float:
    """Rounding of a float phase ``phi1 = (phi + tau) mod 2*pi`` beside the flight time's error:
    ``k/2`` ulps of ``4*pi``. An integrator that reduces ``phi`` and ``tau`` modulo 2*pi exactly
    (as verify and fastpath do) adds two reduced phases (< 4*pi together) and reduces once:
    a few ulps of 4*pi, at any ``|phi|`` and any ``tau`` (8 ulps = 1.4e-14 at k = 16). It is
    not ulps of ``|phi| + tau``: those grow with the flight and pass, unnoticed, the loss of
    the departure phase in a rounded sum ``phi + tau`` (at ``tau ~ 2**51`` they exceed 2*pi)."""
    return k / 2 * math.ulp(2 * TWO_PI)


def map_tolerances(k, phi, v, eps, tau, kappa, tau_error=None):
    """(tau, phi1, v1) tolerances of a float64 step (the fastpath suite's derivation, with k).

    ``tau``: ``k*kappa*u*tau``. ``phi1``: the flight time's error plus :func:`phase_rounding`;
    where the integrator's step has returned its ``tau``, pass ``tau_error = tau_step -
    tau_exact`` (the error it made): then ``phi1`` is held to that error plus the rounding of
    the exact reduced phase, so a phase that lost more than its own flight time's error (a
    rounded sum ``phi + tau``) fails even where ``k*kappa*u*tau`` exceeds 2*pi; without it,
    ``k*kappa*u*tau`` stands for the error. ``v1 = tau - v - 2*eps*sin(phi1)`` carries the tau
    tolerance with weight ``1 + 2|eps|``, the phase rounding with weight ``2|eps|`` and ``k/4``
    ulps of its terms."""
    tau_tol = float(k * kappa * U * tau) if mp.isfinite(kappa) else math.inf
    phase = phase_rounding(k)
    e2 = 2.0 * abs(float(eps))
    phi1_tol = (tau_tol if tau_error is None else abs(float(tau_error))) + phase
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
