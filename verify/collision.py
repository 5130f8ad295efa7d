"""One step of the exact collision map: the paper's equations (1)-(2), and the impact law with
restitution and drag."""

from __future__ import annotations

import mpmath
from mpmath import mp

from .dissipative.drag import DragFlight
from .dissipative.physics import check_physics
from .flight import certify_flight
from .numerics.inputs import check_state
from .numerics.phase import reduce_phase
from .numerics.precision import hi, lo, working_dps


def step(phi, v, eps, dps: int = 50, *, drag=0.0, drag_law: str = "linear",
         restitution=1.0) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``(phi, v) -> (phi1, v1, tau)`` with the certified flight time ``tau``::

        phi1 = (phi + tau) mod 2*pi  in [0, 2*pi)     (mpmath's pi at working precision)
        v_in = v - tau,  u = -eps*sin(phi + tau),  v1 = 2*u - v_in

    With dissipation (keyword-only; the defaults run the lines above unchanged):
    ``v_in = V(tau)`` the velocity of the drag flight (:mod:`verify.dissipative.drag`) and
    ``v1 = (1 + r)*u - r*v_in`` (``v1 - u = -r*(v_in - u)``, ``r = restitution``).

    Computed from the enclosure midpoint at the certificate's working precision, rounded to
    ``dps`` digits. A huge phase is reduced exactly first (:mod:`verify.numerics.phase`).
    """
    phys = check_physics(drag, drag_law, restitution)
    phi, v, eps, _, dps = check_state(phi, v, eps, dps=dps, w0_zero_ok=not phys.is_default)
    cert = certify_flight(phi, v, eps, dps, drag=phys.drag, drag_law=phys.drag_law)
    with working_dps(cert.dps_used) as prec:
        tau = (cert.enclosure[0] + cert.enclosure[1]) / 2
        arg = reduce_phase(phi, prec).value + tau
        if phys.is_default:
            v1 = -2 * eps * mp.sin(arg) - (v - tau)
        else:
            v_in = DragFlight(v, phys.drag, phys.drag_law).velocity(tau)
            u = -eps * mp.sin(arg)
            r = phys.restitution
            v1 = (1 + r) * u - r * (lo(v_in) + hi(v_in)) / 2
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
