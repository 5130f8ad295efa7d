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

from ..errors import UndecidableCollision
from ..numerics.inputs import check_state
from ..numerics.phase import reduce_phase
from ..numerics.precision import (
    DEFAULT_DPS,
    NotDecided,
    default_max_dps,
    escalate,
    hi,
    iv,
    lo,
    mp,
    to_user,
    working_dps,
    working_prec,
)

_W0_ROUNDS = 6  # precision doublings while the sign of w0 is undecided


def mp_gap(phi, v, eps, t):
    """``d(t)`` (product form) in the context and precision of the ``mpf`` ``t`` (verify's
    own thread context inside verify, mpmath's ``mp`` for a caller's ``mpf``)."""
    ctx = _context_of(t)
    half = t / 2
    return 2 * eps * ctx.sin(phi + half) * ctx.sin(half) + t * (v - half)


def mp_gap_prime(phi, v, eps, t):
    """``d'(t) = v - t + eps*sin(phi+t)`` in the context and precision of the ``mpf`` ``t``."""
    return v - t + eps * _context_of(t).sin(phi + t)


def _context_of(t):
    return getattr(t, "context", None) or mp


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


def departure_speed(phi, v, eps, prec: int):
    """``iv`` enclosure of ``w0 = d'(0) = v + eps*sin(phi)`` for the exact departure, with
    about ``prec`` bits relative to ``w0`` itself: the sum cancels the bits that ``|v|`` and
    ``|eps|`` have above ``w0``, so those are added to the working precision (doubled, up to
    ``_W0_ROUNDS`` times, while the sign of ``w0`` is undecided). The interval's ends are exact
    ``mpf``; it contains 0 only where ``w0`` is 0 or too close to 0 to decide."""
    scale = int(mp.mag(abs(v) + abs(eps) + 1))
    bits = prec
    for _ in range(_W0_ROUNDS):
        with working_prec(bits):
            iw = iv.mpf(v) + iv.mpf(eps) * iv.sin(reduce_phase(phi, bits).enclosure)
        size = max(abs(lo(iw)), abs(hi(iw)))
        if size == 0:
            return iw
        decided = lo(iw) > 0 or hi(iw) < 0
        missing = scale - int(mp.mag(size))  # bits of |v| + |eps| above w0 (or the rounding)
        if decided and bits >= prec + missing:
            return iw
        bits = prec + max(missing, 0) if decided else 2 * bits
    return iw


def gap(phi, v, eps, tau, *, dps: int = DEFAULT_DPS) -> mpmath.mpf:
    """The gap ``d(tau)`` of the elastic flight from ``(phi, v)``, to ``dps`` digits.

    Parameters: the departure ``phi``, ``v``, ``eps`` and the time ``tau > 0`` (exact binary
    values, validated by :func:`verify.numerics.inputs.check_state`: a departure ``w0 > 0``);
    ``dps`` the digits of the result. Accuracy: relative error below ``10**-dps`` (an interval
    enclosure, the working precision raised until its relative width allows it, the phase
    reduced exactly); 0 where ``d(tau)`` is exactly 0; :class:`verify.UndecidableCollision`
    where ``d(tau)`` cannot be separated from 0 at ``max(4*dps, 400)`` digits. Safe to call
    from any thread.
    """
    phi, v, eps, tau, dps = check_state(phi, v, eps, tau=tau, dps=dps)

    def attempt(wdps):
        d = iv_gap(reduce_phase(phi, mp.prec).enclosure, iv.mpf(v), iv.mpf(eps), iv.mpf(tau))
        if lo(d) == 0 == hi(d):
            return mp.zero
        if not hi(d) - lo(d) <= mp.mpf(10) ** -(dps + 1) * min(abs(lo(d)), abs(hi(d))):
            raise NotDecided(f"d(tau) is not separated from 0 (within {mp.nstr(hi(d) - lo(d), 3)})")
        with working_dps(dps):
            return +((lo(d) + hi(d)) / 2)

    def undecidable(wdps, why):
        return UndecidableCollision(phi, v, eps, wdps, str(why))

    return to_user(escalate(attempt, dps, default_max_dps(dps), undecidable))
