"""Linearisation of the exact collision map by implicit differentiation of the gap."""

from __future__ import annotations

import mpmath
from mpmath import mp

from .flight import certify_flight
from .numerics.inputs import check_state
from .numerics.phase import reduce_phase
from .numerics.precision import working_dps


def jacobian(phi, v, eps, dps: int = 50) -> mpmath.matrix:
    """2x2 Jacobian of ``(phi, v) -> (phi1, v1)``.

    ``d(tau; phi, v) = 0`` defines ``tau``; with ``d' = v - tau + eps*sin(phi+tau)`` and
    ``d_phi = eps*(sin(phi+tau) - sin(phi))``, ``d_v = tau``::

        tau_phi = -d_phi/d',  tau_v = -tau/d'
        phi1_phi = 1 + tau_phi,  phi1_v = tau_v
        v1_phi = tau_phi - 2*eps*cos(phi+tau)*(1 + tau_phi)
        v1_v   = -1 + tau_v - 2*eps*cos(phi+tau)*tau_v

    At the fixed point ``(0, pi*m)`` this is ``[[1, 2], [-2*eps, 1 - 4*eps]]``.
    Undefined at a graze (``d' = 0``): raises ``ZeroDivisionError``.
    """
    phi, v, eps, _, dps = check_state(phi, v, eps, dps=dps)
    cert = certify_flight(phi, v, eps, dps)
    with working_dps(cert.dps_used) as prec:
        phi = reduce_phase(phi, prec).value
        tau = (cert.enclosure[0] + cert.enclosure[1]) / 2
        arg = phi + tau
        slope = v - tau + eps * mp.sin(arg)
        tau_phi = -eps * (mp.sin(arg) - mp.sin(phi)) / slope
        tau_v = -tau / slope
        c2 = 2 * eps * mp.cos(arg)
        rows = [
            [1 + tau_phi, tau_v],
            [tau_phi - c2 * (1 + tau_phi), -1 + tau_v - c2 * tau_v],
        ]
    with working_dps(dps):
        return mp.matrix([[+x for x in row] for row in rows])
