"""The impact at the end of a flight, in interval arithmetic: the paper's map and its
dissipative form.

A flight that left at phase ``phi`` and lasted ``tau`` lands at phase ``theta = phi + tau``,
where the plate moves with ``u = -eps*sin(theta)`` and the particle arrives with ``v_in``
(``v - tau`` without drag, ``V(tau)`` of :mod:`verify.dissipative.drag` with drag). The impact
law with restitution ``r``::

    w1 = v1 - u = -r*(v_in - u) = r*(u - v_in)        v1 = u + w1
    phi1 = theta mod 2*pi

For ``r = 1`` this is the paper's map, ``v1 = 2*u - v_in = -2*eps*sin(phi + tau) - (v - tau)``
(equations (1)-(2)). Every quantity is enclosed from enclosures of ``phi`` (reduced exactly,
:mod:`verify.numerics.phase`), ``tau`` and ``v_in``, so the widths say how accurate the point
values are: the phase in absolute terms, which is what a phase needs (a flight of length
``1e15`` known to 15 significant digits leaves the phase unknown), the velocity relative to
``max(|v1|, |eps|)``. :func:`rounded` gives the values to ``dps`` digits, or
:class:`verify.numerics.precision.NotDecided` when the enclosures are too wide for that.

``w1`` is the relative velocity the next flight departs with (``w0`` of that flight), known to
the relative accuracy of ``u - v_in``; :func:`carried_state` builds from it the exact state the
orbit loop continues from, so that a small ``w1`` (a restitution ``r = 1e-40``, a chattering
run) is not lost when ``v1`` is rounded.
"""

from __future__ import annotations

from typing import NamedTuple

from ..numerics.precision import (
    NotDecided,
    hi,
    iv,
    lo,
    mid,
    mp,
    working_dps,
    working_prec,
)


class Landing(NamedTuple):
    """Interval enclosures of the state after the impact: the phase ``phi1`` (of a point of
    ``[0, 2*pi)`` up to the enclosure's width), the velocity ``v1`` and ``w1 = v1 - u``."""

    phi1: object
    v1: object
    w1: object


def landing(iphi, itau, v_in, eps, r) -> Landing:
    """The impact after a flight (module docstring) from the enclosures ``iphi`` of the
    departure phase, ``itau`` of the flight time and ``v_in`` of the arrival velocity (``iv``
    intervals), the exact ``eps`` and restitution ``r``, at the current precision."""
    theta = iphi + itau
    turns = mp.floor(mid(theta) / (2 * mp.pi))
    phi1 = theta - 2 * iv.pi * int(turns)
    u = -iv.mpf(eps) * iv.sin(theta)
    w1 = iv.mpf(r) * (u - v_in)
    return Landing(phi1, u + w1, w1)


def excess_digits(land: Landing, eps, dps: int) -> int:
    """0 when the enclosures are narrow enough for :func:`rounded` (phase width at most
    ``10**-(dps+1)``, velocity width at most ``10**-(dps+1)*max(|v1|, |eps|)``), else by how
    many digits (rounded up, plus one) they are too wide: the digits to add to the flight
    time's enclosure, whose width they follow."""
    tol = mp.mpf(10) ** -(dps + 1)
    scale = max(abs(mid(land.v1)), abs(eps))
    ratio = max((hi(land.phi1) - lo(land.phi1)) / tol, (hi(land.v1) - lo(land.v1)) / (tol * scale))
    return 0 if ratio <= 1 else int(mp.ceil(mp.log10(ratio))) + 1


def rounded(land: Landing, eps, dps: int):
    """``(phi1, v1)`` rounded to ``dps`` digits, ``phi1`` in ``[0, 2*pi)``; both within
    ``10**-dps`` of the exact values, ``phi1`` absolutely and ``v1`` relative to
    ``max(|v1|, |eps|)``: the enclosures' widths must be at most a tenth of that
    (:class:`NotDecided` otherwise, so that the caller works at a higher precision)."""
    if excess_digits(land, eps, dps):
        raise NotDecided("the impact's phase or velocity is not known to the digits asked")
    phi1, v1 = mid(land.phi1), mid(land.v1)
    two_pi = 2 * mp.pi
    if phi1 < 0:
        phi1 += two_pi
    elif phi1 >= two_pi:
        phi1 -= two_pi
    with working_dps(dps):
        phi1, v1 = +phi1, +v1
        if phi1 >= 2 * mp.pi:
            phi1 = mp.zero
    return phi1, v1


def carried_state(land: Landing, eps):
    """The exact state ``(phi, v)`` an orbit continues from: ``phi`` the midpoint of the phase
    enclosure and ``v = w - eps*sin(phi)`` with ``w`` the midpoint of ``w1``, computed with
    enough bits that ``v + eps*sin(phi)`` equals ``w`` to the relative accuracy ``w1`` has
    (so a departure with a tiny ``w`` stays a departure). At the current precision plus the
    bits ``|v1|`` and ``|eps|`` have above ``w``."""
    phi = mid(land.phi1)
    w = mid(land.w1)
    extra = max(0, int(mp.mag(abs(mid(land.v1)) + abs(eps))) - int(mp.mag(w))) if w else 0
    with working_prec(mp.prec + extra + 10):
        v = w - eps * mp.sin(phi)
    return phi, v


class Impact(NamedTuple):
    """One impact for the map and the orbit loop: ``phi1``, ``v1``, ``tau`` rounded to ``dps``
    digits (each within ``10**-dps`` of the exact value: ``phi1`` absolutely, ``v1`` relative to
    ``max(|v1|, |eps|)``, ``tau`` relatively); ``state`` the exact ``(phi, v)`` to continue from
    (:func:`carried_state`); ``elapsed`` the midpoint of the flight time's enclosure (exact,
    at the working precision, for summing times without rounding each to ``dps`` digits)."""

    phi1: object
    v1: object
    tau: object
    state: tuple
    elapsed: object


def detachment_impact(search, landing_of, eps, digits, dps: int):
    """``(Impact, digits)`` of a flight from detachment: ``search(digits)`` encloses the flight
    time to ``digits`` relative digits (``(left, right)``), ``landing_of(left, right)`` is its
    :class:`Landing`; where the impact is too wide for ``dps`` digits the flight time is
    enclosed once more with the digits :func:`excess_digits` asks for (the enclosure's digits
    are not tied to the working precision: deciding signs ``10**-digits`` from the root needs
    the working precision to exceed them by the digits of the root's condition number). The
    digits used are returned, to start from there at a higher precision; :class:`NotDecided`
    when the second try is still too wide."""
    for _ in range(2):
        left, right = search(digits)
        land = landing_of(left, right)
        extra = excess_digits(land, eps, dps)
        if not extra:
            return impact_of(land, eps, left, right, dps), digits
        digits += extra
    raise NotDecided("the impact's phase or velocity is not known to the digits asked")


def impact_of(land: Landing, eps, left, right, dps: int) -> Impact:
    """The :class:`Impact` of a flight with time in ``[left, right]`` (relative half-width at
    most ``10**-(dps+1)``) ending in ``land``; :class:`NotDecided` when the enclosures are
    too wide for ``dps`` digits (:func:`rounded`)."""
    phi1, v1 = rounded(land, eps, dps)
    elapsed = (left + right) / 2
    with working_dps(dps):
        tau = +elapsed
    return Impact(phi1, v1, tau, carried_state(land, eps), elapsed)
