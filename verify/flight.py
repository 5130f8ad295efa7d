"""The certified flight time: the public entry point for every physics.

:func:`certify_flight` validates the inputs, picks the certificate for the physics (the elastic
gap of :mod:`verify.elastic.certificate`, or the drag gap of :mod:`verify.dissipative.drag_gap`)
and runs it with :func:`verify.numerics.precision.escalate`, which raises the working precision
until the proof succeeds or :class:`verify.UndecidableCollision` is raised.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from .dissipative.drag_gap import drag_attempt
from .dissipative.physics import check_physics
from .elastic.certificate import elastic_attempt
from .errors import UndecidableCollision
from .numerics.inputs import check_dps, check_state, w0_is_zero
from .numerics.precision import default_max_dps, escalate, working_dps


@dataclass(frozen=True)
class FlightCertificate:
    """Proof data for one flight.

    ``tau``: midpoint of the enclosure, rounded to ``dps`` digits. ``enclosure``: ``(lo, hi)``
    exact ``mpf`` with ``d(lo) > 0 > d(hi)`` proved in interval arithmetic, so the smallest
    positive root lies in ``(lo, hi)``. ``free_until``: ``d > 0`` is proved on
    ``(0, free_until]`` (equal to ``lo``). ``dps_used``: working digits of the successful attempt.
    ``boxes``: interval evaluations (points and boxes) the proof examined.
    """

    tau: mpmath.mpf
    enclosure: tuple[mpmath.mpf, mpmath.mpf]
    free_until: mpmath.mpf
    dps_used: int
    boxes: int


def certify_flight(phi, v, eps, dps: int = 50, max_dps: int | None = None, *, drag=0.0,
                   drag_law: str = "linear", restitution=1.0) -> FlightCertificate:
    """Certify the smallest positive root of the gap ``d`` (see the module docstrings of
    :mod:`verify.elastic.certificate` and :mod:`verify.dissipative.drag_gap`).

    Inputs are taken as exact binary values and checked by
    :func:`verify.numerics.inputs.check_state`: ``ValueError`` for NaN/inf/non-real inputs, a
    bad ``dps`` or ``max_dps``, or ``w0 = v + eps*sin(phi) <= 0``; :class:`UndecidableCollision`
    when the first root cannot be decided at ``max_dps`` digits (default ``max(4*dps, 400)``).

    Physics (keyword-only, :func:`verify.dissipative.physics.check_physics`): ``drag`` k >= 0
    with ``drag_law`` "linear" or "quadratic" (:mod:`verify.dissipative.drag`); ``restitution``
    does not change a flight and is only validated. Without drag the elastic certificate runs,
    except for a departure at rest, ``w0 = 0`` exactly, which it rejects and which goes to the
    drag certificate with ``k = 0``.
    """
    phys = check_physics(drag, drag_law, restitution)
    state = check_state(phi, v, eps, dps=dps, w0_zero_ok=True)
    phi, v, eps, dps = state.phi, state.v, state.eps, state.dps
    max_dps = default_max_dps(dps) if max_dps is None else check_dps(max_dps, "max_dps")
    if max_dps < dps:
        raise ValueError(f"max_dps must be >= dps, got max_dps={max_dps}, dps={dps}")
    elastic = phys.drag == 0 and not w0_is_zero(phi, v, eps)

    def attempt(wdps):
        if elastic:
            lo_, hi_, free, boxes = elastic_attempt(phi, v, eps, dps, wdps)
        else:
            lo_, hi_, free, boxes = drag_attempt(phi, v, eps, phys, dps, wdps)
        return lo_, hi_, free, boxes, wdps, (lo_ + hi_) / 2

    def undecidable(wdps, why):
        return UndecidableCollision(phi, v, eps, wdps, str(why))

    lo_, hi_, free, boxes, wdps, mid = escalate(attempt, dps, max_dps, undecidable)
    with working_dps(dps):
        tau = +mid
    return FlightCertificate(tau, (lo_, hi_), free, wdps, boxes)


def flight_time(phi, v, eps, dps: int = 50, *, drag=0.0, drag_law: str = "linear",
                restitution=1.0) -> mpmath.mpf:
    """Certified smallest positive root of ``d`` at ``dps`` digits: ``certify_flight(...).tau``."""
    return certify_flight(phi, v, eps, dps, drag=drag, drag_law=drag_law,
                          restitution=restitution).tau
