"""One step of the exact collision map: the paper's equations (1)-(2), and the impact law with
restitution and drag (:mod:`verify.dissipative.impact`)."""

from __future__ import annotations

import mpmath

from .dissipative.drag import DragFlight
from .dissipative.impact import Impact, impact_of, landing
from .dissipative.physics import Physics, check_physics
from .errors import UndecidableCollision
from .flight import certify
from .numerics.inputs import check_state
from .numerics.phase import reduce_phase
from .numerics.precision import (
    DEFAULT_DPS,
    GUARD_DPS,
    NotDecided,
    default_max_dps,
    iv,
    mp,
    to_user,
    working_dps,
)


def phase_digits(v, eps, dps: int) -> int:
    """Relative digits of the flight time that put its absolute error below ``10**-(dps+2)``:
    ``dps + 2`` plus the decimal exponent of the bound ``tau <= v + sqrt(v**2 + 4|eps|)`` (the
    gap is ``<= 2|eps| + t*v - t**2/2``, negative beyond it; with drag an estimate)."""
    with working_dps(GUARD_DPS):
        bound = abs(v) + mp.sqrt(v * v + 4 * abs(eps))
        return dps + 2 + max(0, int(mp.ceil(mp.log10(bound))))


def from_certified_flight(phi, v, eps, phys: Physics, dps: int, compute,
                          max_dps: int | None = None):
    """``compute(cert, prec)`` on the certified flight from the validated exact departure,
    inside the working precision ``prec``; ``compute`` raises :class:`NotDecided` when its
    enclosures are too wide for ``dps`` digits. The flight is certified to
    :func:`phase_digits` relative digits first, then to ``GUARD_DPS`` more at a time (and the
    working precision with them) until ``compute`` succeeds or ``max_dps`` (default
    ``max(4*digits, 400)``) is passed: :class:`verify.UndecidableCollision`."""
    digits = phase_digits(v, eps, dps)
    max_dps = default_max_dps(digits) if max_dps is None else max_dps
    while True:
        cert = certify(phi, v, eps, phys, dps, max_dps, digits=digits)
        with working_dps(max(cert.dps_used, digits + GUARD_DPS)) as prec:
            try:
                return compute(cert, prec)
            except NotDecided as why:
                if digits >= max_dps:
                    raise UndecidableCollision(phi, v, eps, digits, str(why)) from None
        digits = min(max_dps, digits + GUARD_DPS)


def impact(phi, v, eps, phys: Physics, dps: int, max_dps: int | None = None) -> Impact:
    """The certified flight from the validated exact departure and its impact, every value to
    ``dps`` digits (:class:`verify.dissipative.impact.Impact`: the phase absolutely), computed
    in interval arithmetic (:func:`verify.dissipative.impact.landing`) from the flight time's
    enclosure, whose digits are raised until they suffice (:func:`from_certified_flight`)."""

    def compute(cert, prec):
        left, right = cert.enclosure
        itau = iv.mpf([left, right])
        if phys.drag == 0:
            v_in = iv.mpf(v) - itau
        else:
            v_in = DragFlight(v, phys.drag, phys.drag_law).velocity_box(left, right)
        land = landing(reduce_phase(phi, prec).enclosure, itau, v_in, eps, phys.restitution)
        return impact_of(land, eps, left, right, dps)

    return from_certified_flight(phi, v, eps, phys, dps, compute, max_dps)


def step(phi, v, eps, *, dps: int = DEFAULT_DPS, drag=0.0, drag_law: str = "linear",
         restitution=1.0) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``(phi, v) -> (phi1, v1, tau)`` with the certified flight time ``tau``::

        phi1 = (phi + tau) mod 2*pi  in [0, 2*pi)
        v_in = v - tau,  u = -eps*sin(phi + tau),  v1 = 2*u - v_in

    (the paper's equations (1)-(2)). With dissipation (keyword-only; the defaults are the
    elastic map): ``v_in = V(tau)`` the velocity of the drag flight
    (:mod:`verify.dissipative.drag`) and ``v1 = u - r*(v_in - u)``, ``r = restitution``.

    Parameters: the departure ``phi``, ``v``, ``eps`` (exact binary values); keyword-only:
    ``dps`` the digits of the results; ``drag`` k >= 0, ``drag_law`` "linear" or "quadratic",
    ``restitution`` r in ``(0, 1]``.

    Accuracy (proved: every value is the midpoint of an interval enclosure of the exact one,
    rounded to ``dps`` digits): ``|tau - exact| <= 10**-dps * tau``; ``|phi1 - exact| <=
    10**-dps`` modulo 2*pi, absolutely, at any ``v`` (the flight time is certified to as many
    more digits as its size needs, and a huge ``phi`` is reduced exactly first,
    :mod:`verify.numerics.phase`); ``|v1 - exact| <= 10**-dps * max(|v1|, |eps|)``. Where that
    cannot be reached at the largest precision tried, :class:`verify.UndecidableCollision`.
    ``ValueError`` for invalid inputs or no departure. Safe to call from any thread.
    """
    phys = check_physics(drag, drag_law, restitution)
    phi, v, eps, _, dps = check_state(phi, v, eps, dps=dps, w0_zero_ok=not phys.is_default)
    hit = impact(phi, v, eps, phys, dps)
    return to_user((hit.phi1, hit.v1, hit.tau))
