"""Enclosures of p collisions of a box, and of the Jacobian of F^p over it.

One collision of a box B = Phi x V (``box_step``): the flight over B is certified in
:mod:`verify.dynamics.box_flight` on a bracket T proposed from the point flight of a nearby state
(its tau plus the first-order change across the box; widened and retried where the certificate
fails). With T, for every departure in B (phases unreduced, F(phi, v) = (phi + tau, v1)):

    phi1 in Phi + T,     v1 in T - V - 2*eps*sin(Phi + T),
    DF in [[1 + a, b], [a - c*(1 + a), -1 + b - c*b]],
    a = eps*(sin(Phi + T) - sin(Phi))/W1,  b = T/W1,  c = 2*eps*cos(Phi + T),
    W1 = -d'(T) > 0 (proved by the certificate).

p collisions of a box X around a point x (``enclose``): with B_0 = X and J_0 = I,
J_k = DF(B_(k-1)) J_(k-1) encloses DF^k over X, and B_k is the intersection of the naive image
above with the mean-value form P_k + J_k (X - x), where P_k encloses F^k(x) (the same
propagation run on the point box x, ``enclose_point``). Interval widths still grow like the
product of the entrywise absolute Jacobians; the driver pays for that with precision.
"""

from __future__ import annotations

from typing import NamedTuple

from verify.dynamics.box_flight import Undecided, box_flight, gap_prime, point_flight
from verify.dynamics.numbers import mat_mul, mat_vec

_RETRIES = 4  # widenings of a bracket whose ends were not proved
_WIDEN = 16


class BoxStep(NamedTuple):
    """One collision of a box: the flight bracket T, the image box, the Jacobian enclosure."""

    tau: object
    phi: object
    v: object
    jacobian: tuple


def point_orbit(ctx, phi, v, eps, period) -> list:
    """The candidate orbit of ``period`` collisions from (phi, v) in the point context: a list
    of :class:`verify.dynamics.box_flight.PointFlight` (phases unreduced)."""
    flights = []
    for _ in range(period):
        flight = point_flight(ctx, phi, v, eps)
        flights.append(flight)
        phi, v = flight.phi1, flight.v1
    return flights


def box_step(ctx, phi_box, v_box, eps, centre, flight) -> BoxStep:
    """One certified collision of the box; ``flight`` is the point flight from ``centre``."""
    iv, mp = ctx.iv, ctx.mp
    ga, gb = flight.gradient
    mid_phi, mid_v = phi_box.mid, v_box.mid
    off_phi = abs(mp.make_mpf(mid_phi._mpi_[0]) - centre[0]) + mp.make_mpf(
        phi_box.delta._mpi_[1]) / 2
    off_v = abs(mp.make_mpf(mid_v._mpi_[0]) - centre[1]) + mp.make_mpf(v_box.delta._mpi_[1]) / 2
    guess = (flight.tau + ga * (mp.make_mpf(mid_phi._mpi_[0]) - centre[0])
             + gb * (mp.make_mpf(mid_v._mpi_[0]) - centre[1]))
    delta = 2 * (abs(ga) * off_phi + abs(gb) * off_v) + mp.mpf(2) ** (-mp.prec + 16) * (
        1 + flight.tau)
    for attempt in range(_RETRIES + 1):
        try:
            tau, _ = box_flight(ctx, phi_box, v_box, eps, guess - delta, guess + delta)
            break
        except Undecided as und:
            if attempt == _RETRIES or "departure" in und.what:
                raise
            delta *= _WIDEN
    eps_iv = iv.mpf(eps)
    arrival = phi_box + tau
    s0, s1, c1 = iv.sin(phi_box), iv.sin(arrival), iv.cos(arrival)
    w1 = -gap_prime(iv, phi_box, v_box, eps_iv, tau)
    ta = eps_iv * (s1 - s0) / w1
    tb = tau / w1
    c = 2 * eps_iv * c1
    jac = (1 + ta, tb, ta - c * (1 + ta), -1 + tb - c * tb)
    v1 = tau - v_box - 2 * eps_iv * s1
    return BoxStep(tau, arrival, v1, jac)


class OrbitEnclosure(NamedTuple):
    """Boxes B_0..B_p (B_k contains F^k of the start box) and J_p (contains DF^p over it)."""

    boxes: list
    jacobian: tuple


def _intersect(ctx, a, b):
    """The intersection of two intervals that both contain the same (non-empty) set."""
    mp = ctx.mp
    low = max(mp.make_mpf(a._mpi_[0]), mp.make_mpf(b._mpi_[0]))
    high = min(mp.make_mpf(a._mpi_[1]), mp.make_mpf(b._mpi_[1]))
    if low > high:
        raise Undecided("two enclosures of the same image do not meet (internal error)")
    return ctx.iv.mpf([low, high])


def enclose_point(ctx, phi, v, eps, flights) -> list:
    """Boxes P_0..P_p containing F^k of the point (phi, v) (exact point values)."""
    iv = ctx.iv
    box = (iv.mpf(phi), iv.mpf(v))
    boxes = [box]
    centre = (phi, v)
    for flight in flights:
        step = box_step(ctx, box[0], box[1], eps, centre, flight)
        box = (step.phi, step.v)
        boxes.append(box)
        centre = (flight.phi1, flight.v1)
    return boxes


def enclose(ctx, box, x, eps, flights, point_boxes) -> OrbitEnclosure:
    """B_0..B_p and J_p for the start box ``box`` around the point ``x`` (see module doc)."""
    iv = ctx.iv
    one, zero = iv.mpf(1), iv.mpf(0)
    jac = (one, zero, zero, one)
    offset = (box[0] - iv.mpf(x[0]), box[1] - iv.mpf(x[1]))
    boxes = [box]
    centre = x
    for k, flight in enumerate(flights):
        step = box_step(ctx, box[0], box[1], eps, centre, flight)
        jac = mat_mul(step.jacobian, jac)
        spread = mat_vec(jac, offset)
        mean_value = (point_boxes[k + 1][0] + spread[0], point_boxes[k + 1][1] + spread[1])
        box = (_intersect(ctx, step.phi, mean_value[0]), _intersect(ctx, step.v, mean_value[1]))
        boxes.append(box)
        centre = (flight.phi1, flight.v1)
    return OrbitEnclosure(boxes, jac)
