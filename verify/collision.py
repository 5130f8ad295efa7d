"""One step of the exact collision map (the seed's equations (1)-(2))."""

from __future__ import annotations

import mpmath
from mpmath import mp

from ._inputs import check_state
from ._precision import working_dps
from .certify import certify_flight
from .phase import reduce_phase


def step(phi, v, eps, dps: int = 50) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``(phi, v) -> (phi1, v1, tau)`` with the certified flight time ``tau``::

        phi1 = (phi + tau) mod 2*pi  in [0, 2*pi)     (mpmath's pi at working precision)
        v_in = v - tau,  u = -eps*sin(phi + tau),  v1 = 2*u - v_in

    Computed from the enclosure midpoint at the certificate's working precision, rounded to
    ``dps`` digits. A huge phase is reduced exactly first (:mod:`verify.phase`).
    """
    phi, v, eps, _, dps = check_state(phi, v, eps, dps=dps)
    cert = certify_flight(phi, v, eps, dps)
    with working_dps(cert.dps_used) as prec:
        tau = (cert.enclosure[0] + cert.enclosure[1]) / 2
        arg = reduce_phase(phi, prec).value + tau
        v1 = -2 * eps * mp.sin(arg) - (v - tau)
        phi1 = _reduce(arg)
    with working_dps(dps):
        phi1, v1 = +phi1, +v1
        if phi1 >= 2 * mp.pi:
            phi1 = mp.zero
    return phi1, v1, cert.tau


def _reduce(x):
    two_pi = 2 * mp.pi
    r = x - two_pi * mp.floor(x / two_pi)
    if r < 0:
        r += two_pi
    if r >= two_pi:
        r -= two_pi
    return r
