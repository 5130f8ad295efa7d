"""Linearisation of the exact collision map by implicit differentiation of the gap."""

from __future__ import annotations

import mpmath

from .collision import from_certified_flight
from .dissipative.physics import check_physics
from .numerics.inputs import check_state
from .numerics.phase import reduce_phase
from .numerics.precision import (
    DEFAULT_DPS,
    NotDecided,
    hi,
    iv,
    lo,
    mid,
    mp,
    to_user,
    working_dps,
)


def jacobian(phi, v, eps, *, dps: int = DEFAULT_DPS) -> mpmath.matrix:
    """2x2 Jacobian of the elastic map ``(phi, v) -> (phi1, v1)``.

    ``d(tau; phi, v) = 0`` defines ``tau``; with ``d' = v - tau + eps*sin(phi+tau)`` and
    ``d_phi = eps*(sin(phi+tau) - sin(phi))``, ``d_v = tau``::

        tau_phi = -d_phi/d',  tau_v = -tau/d'
        phi1_phi = 1 + tau_phi,  phi1_v = tau_v
        v1_phi = tau_phi - 2*eps*cos(phi+tau)*(1 + tau_phi)
        v1_v   = -1 + tau_v - 2*eps*cos(phi+tau)*tau_v

    At the fixed point ``(0, pi*m)`` this is ``[[1, 2], [-2*eps, 1 - 4*eps]]``.

    Parameters: the departure ``phi``, ``v``, ``eps`` (exact binary values); ``dps`` the digits
    of the entries. Accuracy (proved: each entry is the midpoint of an interval enclosure,
    computed from the certified flight time with as many digits as needed, rounded to ``dps``
    digits): every entry ``J`` within ``10**-dps * max(|J|, 1)`` of the exact one.
    Undefined at a graze (``d'(tau) = 0``): ``ZeroDivisionError`` when ``d'(tau)`` is proved 0;
    :class:`verify.UndecidableCollision` when it cannot be separated from 0 or the accuracy
    cannot be reached at the largest precision tried. Safe to call from any thread.
    """
    phi, v, eps, _, dps = check_state(phi, v, eps, dps=dps)

    def compute(cert, prec):
        left, right = cert.enclosure
        itau = iv.mpf([left, right])
        iphi = reduce_phase(phi, prec).enclosure
        ieps = iv.mpf(eps)
        arg = iphi + itau
        slope = iv.mpf(v) - itau + ieps * iv.sin(arg)
        if lo(slope) == 0 == hi(slope):
            raise ZeroDivisionError("the Jacobian is undefined at a graze: d'(tau) = 0")
        if not (lo(slope) > 0 or hi(slope) < 0):
            raise NotDecided("d'(tau) is not separated from 0 (a graze?)")
        tau_phi = -ieps * (iv.sin(arg) - iv.sin(iphi)) / slope
        tau_v = -itau / slope
        c2 = 2 * ieps * iv.cos(arg)
        rows = [[1 + tau_phi, tau_v], [tau_phi - c2 * (1 + tau_phi), -1 + tau_v - c2 * tau_v]]
        tol = mp.mpf(10) ** -(dps + 1)
        for entry in (x for row in rows for x in row):
            if hi(entry) - lo(entry) > tol * max(abs(mid(entry)), 1):
                raise NotDecided("a Jacobian entry is not known to the digits asked")
        mids = [[mid(x) for x in row] for row in rows]
        with working_dps(dps):
            return [[+x for x in row] for row in mids]

    rows = from_certified_flight(phi, v, eps, check_physics(), dps, compute)
    return mpmath.mp.matrix(to_user(rows))
