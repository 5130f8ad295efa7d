"""Relative condition number of the flight time, used to scale float64 tolerances."""

from __future__ import annotations

import mpmath
from mpmath import mp

from ..numerics.inputs import check_state
from ..numerics.phase import reduce_phase


def condition_number(phi, v, eps, tau) -> mpmath.mpf:
    """``kappa = (|v| + tau + |eps|*(1 + |phi| + tau)) / |v - tau + eps*sin(phi+tau)|``.

    A float64 method's relative error in ``tau`` is expected to be ``<= k*kappa*2**-53`` for a
    small ``k``. The numerator is the scale of the rounding error made when ``d`` is evaluated in
    floating point, divided by ``tau``: the terms ``tau*v`` and ``tau**2`` of ``tau*(v - tau/2)``
    and ``eps*tau*(1 + argument error)``, the argument ``phi + tau`` carrying an absolute error of
    order ``|phi| + tau`` ulps. The denominator is ``|d'(tau)|``, the relative impact speed:
    an error ``e`` in ``d`` moves the root by ``e/|d'(tau)|``. For small ``w0`` (a short flight,
    ``tau ~ 2*w0/(1 - eps*cos(phi))``, ``|d'(tau)| ~ w0``) it reduces to
    ``~ (|v| + |eps|*(1 + |phi|)) / w0``. Infinite at a graze (``d'(tau) = 0``).

    Inputs are validated by :func:`verify.numerics.inputs.check_state` (a departure, ``tau > 0``).
    """
    phi, v, eps, tau, _ = check_state(phi, v, eps, tau=tau)
    with mp.workprec(max(mp.prec, 64)):
        num = abs(v) + tau + abs(eps) * (1 + abs(phi) + tau)
        reduced = reduce_phase(phi, mp.prec).value
        den = abs(v - tau + eps * mp.sin(reduced + tau))
        if den == 0:
            return mp.inf
        return num / den
