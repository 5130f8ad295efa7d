"""Relative condition number of the flight time, used to scale float64 tolerances."""

from __future__ import annotations

import mpmath
from mpmath.libmp import dps_to_prec

from ..numerics.inputs import check_state
from ..numerics.phase import reduce_phase
from ..numerics.precision import hi, iv, lo, mid, mp, to_user, working_prec

KAPPA_DPS = 20  # digits of the condition number unless asked
_KAPPA_ROUNDS = 11  # precision doublings before d'(tau) counts as 0 (x2048)


def kappa(phi, v, eps, tau, reduced: bool = True, dps: int = KAPPA_DPS,
          max_bits: int | None = None):
    """:func:`condition_number` on validated exact values (this thread's context), without
    the validation. ``max_bits``: stop raising the precision there (a cheap estimate)."""
    target = dps_to_prec(dps)
    bits = target
    for _ in range(_KAPPA_ROUNDS):
        with working_prec(bits + 16):
            red = reduce_phase(phi, mp.prec)
            it = iv.mpf(tau)
            den = abs(iv.mpf(v) - it + iv.mpf(eps) * iv.sin(red.enclosure + it))
            size = abs(red.value) if reduced else abs(phi)
            num = abs(iv.mpf(v)) + it + abs(iv.mpf(eps)) * (1 + iv.mpf(size) + it)
            if hi(den) == 0:
                return mp.inf
            if lo(den) > 0:
                k = num / den
                if hi(k) - lo(k) <= lo(k) * mp.ldexp(1, -target - 4):
                    with working_prec(target):
                        return +mid(k)
        if max_bits is not None and bits >= max_bits:
            break
        bits *= 2
    return mp.inf


def condition_number(phi, v, eps, tau, *, reduced: bool = True,
                     dps: int = KAPPA_DPS) -> mpmath.mpf:
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
    ``dps`` the digits of the result (default 20).

    Accuracy: the exact formula's value rounded to ``dps`` digits (an interval enclosure
    refined to a relative width below ``2**-(bits + 4)`` first). Safe to call from any thread.
    """
    phi, v, eps, tau, dps = check_state(phi, v, eps, tau=tau, dps=dps)
    return to_user(kappa(phi, v, eps, tau, reduced=bool(reduced), dps=dps))
