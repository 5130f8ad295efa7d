"""Relative condition number of the flight time, used to scale float64 tolerances."""

from __future__ import annotations

import mpmath
from mpmath.libmp import dps_to_prec

from ..numerics.inputs import check_dps, check_state
from ..numerics.phase import reduce_phase
from ..numerics.precision import hi, iv, lo, mid, mp, to_user, working_prec

KAPPA_BITS = 64  # bits of the condition number unless digits are asked for
_KAPPA_ROUNDS = 11  # precision doublings before d'(tau) counts as 0 (x2048)


def kappa(phi, v, eps, tau, reduced: bool = True, dps: int | None = None,
          max_bits: int | None = None):
    """:func:`condition_number` on validated exact values (this thread's context), without
    the validation. ``max_bits``: stop raising the precision there (a cheap estimate)."""
    target = KAPPA_BITS if dps is None else dps_to_prec(dps)
    enclosure = _enclosure(phi, v, eps, tau, reduced, target, max_bits)
    if enclosure is None or not mp.isfinite(hi(enclosure)):
        return mp.inf
    with working_prec(target + 16):
        centre = mid(enclosure)
        if dps is None:
            # the formula in 64-bit arithmetic (what kappa always was), kept where the
            # enclosure proves it within 2**-58 (a few of its last bits): figures recorded
            # with it stand
            point = _point_value(phi, v, eps, tau, reduced)
            if mp.isfinite(point) and abs(point - centre) <= mp.ldexp(point, 6 - KAPPA_BITS):
                return point
    with working_prec(target):
        return +centre


def _point_value(phi, v, eps, tau, reduced):
    with working_prec(KAPPA_BITS):
        red = reduce_phase(phi, mp.prec).value
        num = abs(v) + tau + abs(eps) * (1 + abs(red if reduced else phi) + tau)
        den = abs(v - tau + eps * mp.sin(red + tau))
        return mp.inf if den == 0 else num / den


def _enclosure(phi, v, eps, tau, reduced, target, max_bits):
    """An interval of relative width below ``2**-(target + 4)`` holding kappa, ``[inf, inf]``
    where ``d'(tau) = 0`` exactly, None where ``d'(tau)`` stays unseparated from 0."""
    bits = target
    for _ in range(_KAPPA_ROUNDS):
        with working_prec(bits + 16):
            red = reduce_phase(phi, mp.prec)
            it = iv.mpf(tau)
            den = abs(iv.mpf(v) - it + iv.mpf(eps) * iv.sin(red.enclosure + it))
            size = abs(red.value) if reduced else abs(phi)
            num = abs(iv.mpf(v)) + it + abs(iv.mpf(eps)) * (1 + iv.mpf(size) + it)
            if hi(den) == 0:
                return iv.mpf([mp.inf, mp.inf])
            if lo(den) > 0:
                k = num / den
                if hi(k) - lo(k) <= lo(k) * mp.ldexp(1, -target - 4):
                    return k
        if max_bits is not None and bits >= max_bits:
            break
        bits *= 2
    return None


def condition_number(phi, v, eps, tau, *, reduced: bool = True,
                     dps: int | None = None) -> mpmath.mpf:
    """``kappa = (|v| + tau + |eps|*(1 + |phi_r| + tau)) / |v - tau + eps*sin(phi+tau)|``.

    A float64 method's relative error in ``tau`` is expected to be ``<= k*kappa*2**-53`` for a
    small ``k``. The numerator is the scale of the rounding error made when ``d`` is evaluated in
    floating point, divided by ``tau``: the terms ``tau*v`` and ``tau**2`` of ``tau*(v - tau/2)``
    and ``eps*tau*(1 + argument error)``, the argument ``phi_r + tau`` carrying an absolute
    error of order ``|phi_r| + tau`` ulps. The denominator is ``|d'(tau)|``, the relative
    impact speed: an error ``e`` in ``d`` moves the root by ``e/|d'(tau)|``. For small ``w0`` (a
    short flight, ``tau ~ 2*w0/(1 - eps*cos(phi))``, ``|d'(tau)| ~ w0``) it reduces to
    ``~ (|v| + |eps|*(1 + |phi_r|)) / w0``. Infinite at a graze (``d'(tau) = 0``, or not
    separated from 0 at 2048 times the working precision).

    Parameters: the departure ``phi``, ``v``, ``eps`` and a time ``tau > 0`` (exact binary
    values, validated by :func:`verify.numerics.inputs.check_state`: a departure);
    ``reduced``: ``phi_r`` is the phase reduced exactly modulo 2*pi (``|phi| >= 8``; smaller
    phases are used as given), as by an integrator that reduces its phases exactly (verify,
    fastpath), so that a huge ``phi`` does not inflate kappa; ``reduced=False`` takes
    ``phi_r = phi`` as given, for an integrator that adds ``phi + t`` in floating point;
    ``dps`` the digits of the result (default: a 64-bit value).

    Accuracy: an interval enclosure of the exact formula's value is refined to a relative
    width below ``2**-(bits + 4)``. With ``dps``, its midpoint rounded to ``dps`` digits. By
    default, the formula evaluated in 64-bit arithmetic where the enclosure proves that value
    within ``2**-58`` of the exact one (so figures recorded with it stand), else the enclosure's
    midpoint at 64 bits: a relative error below ``2**-58`` either way. Safe to call from any
    thread.
    """
    phi, v, eps, tau, _ = check_state(phi, v, eps, tau=tau)
    if dps is not None:
        dps = check_dps(dps)
    return to_user(kappa(phi, v, eps, tau, reduced=bool(reduced), dps=dps))
