"""Departures built to (nearly) graze the plate: test cases for the ``|eps| >= 1`` regime.

A tangency at time ``T`` after departure, at plate phase ``psi = phi + T``, needs
``d'(T) = 0`` and ``d(T) = clearance``:

    d'(T) = v - T + eps*sin(psi) = 0                 =>  v = T - eps*sin(psi)
    d(T)  = eps*(cos(psi - T) - cos(psi)) + T*(v - T/2)
          = eps*(cos(psi - T) - cos(psi) - T*sin(psi)) + T**2/2  =: D(T)

With ``psi`` fixed, ``D`` is solved for ``T`` by Newton's method starting from the given ``T``;
its derivative is ``D'(T) = T - eps*sin(psi) + eps*sin(psi - T) = v + eps*sin(phi) = w0``, the
departure velocity relative to the plate, so a solution with ``w0 > 0`` is where ``D`` increases.
The contact is a local minimum of ``d`` (a graze from above, not a crossing) iff
``d''(T) = -1 + eps*cos(psi) > 0``, i.e. ``eps*cos(psi) > 1``: this is required.

Positive clearance: the particle passes above the plate at ``T`` and lands later (provided no
earlier root, which :func:`verify.certify_flight` checks). Negative clearance: ``d`` crosses 0
just before ``T``. Zero: an exact tangency (to ``dps`` digits), undecidable at lower precision.
The returned ``phi, v`` are rounded to ``dps`` digits, which moves the clearance by about
``T*10**-dps``; rounding them to float64 moves it by about ``T*1e-16``.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from ..numerics.inputs import check_dps, exact_real
from ..numerics.precision import DEFAULT_DPS, mp, to_user, working_dps


@dataclass(frozen=True)
class GrazingContact:
    """Departure ``(phi, v)`` with ``d(T) = clearance``, ``d'(T) = 0`` at plate phase ``psi``."""

    phi: mpmath.mpf
    v: mpmath.mpf
    T: mpmath.mpf
    psi: mpmath.mpf
    clearance: mpmath.mpf
    w0: mpmath.mpf


def grazing_contact(eps, psi, T, clearance, *, dps: int = DEFAULT_DPS) -> GrazingContact:
    """Solve ``D(T) = clearance`` for ``T`` near the given guess (see module docstring).

    Parameters: ``eps`` the amplitude (``eps*cos(psi) > 1`` required), ``psi`` the plate phase
    of the contact, ``T`` a guess of the contact time (> 0), ``clearance`` the minimum gap
    wanted there (0: an exact tangency), ``dps`` the digits of the results. Newton's method at
    ``dps + 20`` digits; ``ValueError`` when it does not converge to a departure. The returned
    values are rounded to ``dps`` digits (so the clearance of the returned ``phi, v`` is met up
    to ``~T*10**-dps``). Safe to call from any thread.
    """
    dps = check_dps(dps)
    eps, psi = exact_real("eps", eps), exact_real("psi", psi)
    t, c = exact_real("T", T), exact_real("clearance", clearance)
    if t <= 0:
        raise ValueError(f"T (the contact time guess) must be > 0, got T={T!r}")
    with working_dps(dps + 20):
        if not eps * mp.cos(psi) > 1:
            raise ValueError(f"a graze from above needs eps*cos(psi) > 1, got eps={eps}, psi={psi}")
        tol = mp.mpf(10) ** (-(dps + 15))
        for _ in range(200):
            w0 = t - eps * mp.sin(psi) + eps * mp.sin(psi - t)
            if w0 <= 0:
                raise ValueError(f"no departure (w0={mp.nstr(w0, 5)} <= 0) near T={mp.nstr(t, 8)}")
            big_d = eps * (mp.cos(psi - t) - mp.cos(psi) - t * mp.sin(psi)) + t * t / 2
            dt = (big_d - c) / w0
            t -= dt
            if abs(dt) <= tol * (1 + abs(t)):
                break
        else:
            raise ValueError(f"Newton for the contact time did not converge from T={T}")
        if t <= 0:
            raise ValueError(f"contact time solution T={mp.nstr(t, 8)} is not positive")
        phi = psi - t
        v = t - eps * mp.sin(psi)
        w0 = v + eps * mp.sin(phi)
    with working_dps(dps):
        return GrazingContact(*to_user((+phi, +v, +t, +psi, +c, +w0)))


def grazing_departure(eps, psi, T, clearance, *,
                      dps: int = DEFAULT_DPS) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(phi, v)`` of :func:`grazing_contact` (the same parameters; the solved contact time
    is its ``.T``)."""
    g = grazing_contact(eps, psi, T, clearance, dps=dps)
    return g.phi, g.v
