"""The certified flight time: the public entry point for every physics.

:func:`certify_flight` validates the inputs, picks the certificate for the physics (the elastic
gap of :mod:`verify.elastic.certificate`, or the drag gap of :mod:`verify.dissipative.drag_gap`)
and runs it with :func:`verify.numerics.precision.escalate`, which raises the working precision
until the proof succeeds or :class:`verify.UndecidableCollision` is raised. :func:`certify` is
the same on validated values, for verify's own use (the map, the Jacobian, the orbit loop).
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from .dissipative.drag_gap import drag_attempt
from .dissipative.physics import Physics, check_physics
from .elastic.certificate import elastic_attempt
from .errors import UndecidableCollision
from .numerics.inputs import check_dps, check_state, w0_is_zero
from .numerics.precision import DEFAULT_DPS, default_max_dps, escalate, to_user, working_dps


@dataclass(frozen=True)
class FlightCertificate:
    """Proof data for one flight.

    ``tau``: midpoint of the enclosure, rounded to ``dps`` digits. ``enclosure``: ``(lo, hi)``
    exact ``mpf`` with ``d(lo) > 0 > d(hi)`` proved in interval arithmetic, so the smallest
    positive root lies in ``(lo, hi)``; its relative half-width is at most ``10**-dps``, so
    ``tau`` is within ``1.2*10**-dps*tau`` of the root (with the rounding to ``dps`` digits).
    ``free_until``: ``d > 0`` is proved on ``(0, free_until]`` (equal to ``lo``). ``dps_used``:
    working digits of the successful attempt. ``boxes``: interval evaluations (points and
    boxes) the proof examined.
    """

    tau: mpmath.mpf
    enclosure: tuple[mpmath.mpf, mpmath.mpf]
    free_until: mpmath.mpf
    dps_used: int
    boxes: int

    def for_user(self) -> FlightCertificate:
        """The same certificate with its numbers as ``mpmath.mp`` numbers (for a caller)."""
        return FlightCertificate(to_user(self.tau), to_user(self.enclosure),
                                 to_user(self.free_until), self.dps_used, self.boxes)


def certify(phi, v, eps, phys: Physics, dps: int, max_dps: int | None = None,
            digits: int | None = None) -> FlightCertificate:
    """Certify the flight from the validated exact departure ``(phi, v, eps)`` (values of this
    thread's context). ``digits`` (default ``dps``): the enclosure's relative half-width is at
    most ``10**-digits``; ``tau`` is its midpoint rounded to ``dps`` digits. The values of the
    certificate are this thread's (see :meth:`FlightCertificate.for_user`)."""
    digits = dps if digits is None else digits
    max_dps = default_max_dps(digits) if max_dps is None else max_dps
    elastic = phys.drag == 0 and not w0_is_zero(phi, v, eps)

    def attempt(wdps):
        if elastic:
            lo_, hi_, free, boxes = elastic_attempt(phi, v, eps, digits, wdps)
        else:
            lo_, hi_, free, boxes = drag_attempt(phi, v, eps, phys, digits, wdps)
        return lo_, hi_, free, boxes, wdps, (lo_ + hi_) / 2

    def undecidable(wdps, why):
        return UndecidableCollision(phi, v, eps, wdps, str(why))

    lo_, hi_, free, boxes, wdps, mid = escalate(attempt, digits, max_dps, undecidable)
    with working_dps(dps):
        tau = +mid
    return FlightCertificate(tau, (lo_, hi_), free, wdps, boxes)


def certify_flight(phi, v, eps, *, dps: int = DEFAULT_DPS, max_dps: int | None = None, drag=0.0,
                   drag_law: str = "linear", restitution=1.0) -> FlightCertificate:
    """Certify the smallest positive root of the gap ``d`` (see the module docstrings of
    :mod:`verify.elastic.certificate` and :mod:`verify.dissipative.drag_gap`).

    Parameters: ``phi``, ``v``, ``eps`` the departure (phase, velocity, plate amplitude), each
    taken as its exact binary value (:func:`verify.numerics.inputs.exact_real`); ``dps`` the
    digits of ``tau`` (relative error below ``1.2*10**-dps``: the enclosure's half-width plus
    the rounding); ``max_dps`` the largest working
    precision tried (default ``max(4*dps, 400)``); ``drag`` k >= 0 and ``drag_law`` "linear" or
    "quadratic" (:mod:`verify.dissipative.drag`); ``restitution`` only 1 (the default): it acts
    at the impact, not on a flight (:func:`verify.step` and :func:`verify.orbit` take it).
    Everything after ``eps`` is keyword-only.

    ``ValueError`` for NaN/inf/non-real inputs, a bad ``dps`` or ``max_dps``, a restitution
    other than 1, or
    ``w0 = v + eps*sin(phi) <= 0`` (no departure); :class:`verify.UndecidableCollision` when
    the first root cannot be decided at ``max_dps`` digits. Without drag the elastic
    certificate runs, except for a departure at rest, ``w0 = 0`` exactly, which goes to the
    drag certificate with ``k = 0``. Safe to call from any thread.
    """
    phys = check_physics(drag, drag_law, restitution)
    if phys.restitution != 1:
        raise ValueError(f"restitution={restitution!r} does not act on a flight (only at its"
                         " impact): certify_flight and flight_time take restitution 1; step and"
                         " orbit apply it")
    state = check_state(phi, v, eps, dps=dps, w0_zero_ok=True)
    dps = state.dps
    max_dps = default_max_dps(dps) if max_dps is None else check_dps(max_dps, "max_dps")
    if max_dps < dps:
        raise ValueError(f"max_dps must be >= dps, got max_dps={max_dps}, dps={dps}")
    return certify(state.phi, state.v, state.eps, phys, dps, max_dps).for_user()


def flight_time(phi, v, eps, *, dps: int = DEFAULT_DPS, drag=0.0, drag_law: str = "linear",
                restitution=1.0) -> mpmath.mpf:
    """Certified smallest positive root of ``d`` at ``dps`` digits: ``certify_flight(...).tau``.

    Parameters as for :func:`certify_flight`: the departure ``phi``, ``v``, ``eps``, the digits
    ``dps`` (relative error of the result below ``1.2*10**-dps``), ``drag``, ``drag_law`` and
    ``restitution`` (only 1), all keyword-only.
    """
    return certify_flight(phi, v, eps, dps=dps, drag=drag, drag_law=drag_law,
                          restitution=restitution).tau
