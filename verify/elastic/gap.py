"""The gap between particle and plate during one flight, its derivatives, point and interval.

For a departure at phase ``phi`` with velocity ``v`` from the plate ``y0(t) = eps*cos(t)``::

    d(tau)   = eps*(cos(phi) - cos(phi+tau)) + tau*(v - tau/2)
             = 2*eps*sin(phi + tau/2)*sin(tau/2) + tau*(v - tau/2)
    d'(tau)  = v - tau + eps*sin(phi+tau)
    d''(tau) = -1 + eps*cos(phi+tau)

The product form has no cancellation for small ``tau``. Functions prefixed ``iv_`` take and
return ``mpmath.iv`` intervals in the current ``iv`` precision and enclose the exact values.
"""

from __future__ import annotations

import mpmath
from mpmath import iv, mp

from ..numerics.inputs import check_state
from ..numerics.phase import reduce_phase
from ..numerics.precision import working_dps


def mp_gap(phi, v, eps, t):
    """``d(t)`` in the current ``mp`` precision (product form)."""
    half = t / 2
    return 2 * eps * mp.sin(phi + half) * mp.sin(half) + t * (v - half)


def mp_gap_prime(phi, v, eps, t):
    """``d'(t) = v - t + eps*sin(phi+t)`` in the current ``mp`` precision."""
    return v - t + eps * mp.sin(phi + t)


def iv_gap(phi, v, eps, t):
    """Interval enclosure of ``d(t)``; all arguments are ``iv`` intervals."""
    half = t / 2
    return 2 * eps * iv.sin(phi + half) * iv.sin(half) + t * (v - half)


def iv_gap_prime(phi, v, eps, t):
    """Interval enclosure of ``d'(t)``."""
    return v - t + eps * iv.sin(phi + t)


def iv_gap_second(phi, eps, t):
    """Interval enclosure of ``d''`` over the interval ``t``: ``-1 + eps*cos(phi+t)``."""
    return eps * iv.cos(phi + t) - 1


def gap(phi, v, eps, tau, dps: int = 50) -> mpmath.mpf:
    """The gap ``d(tau)`` at ``dps`` digits (inputs taken as exact binary values, validated by
    :func:`verify.numerics.inputs.check_state`: a departure ``w0 > 0`` and ``tau > 0``)."""
    phi, v, eps, tau, dps = check_state(phi, v, eps, tau=tau, dps=dps)
    with working_dps(dps + 10) as prec:
        val = mp_gap(reduce_phase(phi, prec).value, v, eps, tau)
    with working_dps(dps):
        return +val
