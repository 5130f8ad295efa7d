"""Orbits of the exact collision map at a given precision."""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import mpmath
from mpmath import iv, mp

from ._inputs import check_physics, check_state
from ._precision import hi, working_dps
from .collision import step
from .drag import DragFlight
from .errors import ChatteringDetected


@dataclass(frozen=True)
class Orbit:
    """Collision phases ``phi``, velocities ``v`` after each collision, cumulative times ``t``
    (``t[0] = 0``); tuples of ``mpf`` of length ``n + 1``. ``phi[0]`` is the input phase as
    given (unreduced); later phases lie in ``[0, 2*pi)``.

    ``sticking``: ``(t_start, t_end)`` pairs of sticking episodes (the dissipation spec);
    ``stopped``: ``"collisions"`` (made the ``n`` collisions) or ``"stuck"``. verify does not
    compute sticking yet: it raises :class:`verify.errors.ChatteringDetected` when impacts
    accumulate, so ``sticking`` is always empty and ``stopped`` is ``"collisions"``.
    """

    phi: tuple[mpmath.mpf, ...]
    v: tuple[mpmath.mpf, ...]
    t: tuple[mpmath.mpf, ...]
    sticking: tuple[tuple[mpmath.mpf, mpmath.mpf], ...] = ()
    stopped: str = "collisions"


def orbit(phi0, v0, eps, n: int, dps: int = 50, *, drag=0.0, drag_law: str = "linear",
          restitution=1.0) -> Orbit:
    """Iterate :func:`verify.step` ``n`` times from ``(phi0, v0)``.

    ``t[k] = tau_0 + ... + tau_{k-1}``.

    Each step is certified for its (rounded to ``dps`` digits) input state. With
    ``restitution < 1``, chattering is detected after each collision: the relative velocity
    ``w = v + eps*sin(phi)`` below ``w_min = 10**(-dps//3) * (1 + |v| + |eps|)`` with
    ``d''(0) = -1 - eta(v) + eps*cos(phi) < 0`` proved raises
    :class:`verify.errors.ChatteringDetected` (a geometric run of impacts, ratio ~ r, reaches
    it after about ``dps/3 / log10(1/r)`` collisions; ``w_min`` stays far above the rounding of
    the state to ``dps`` digits, so the next flight could still be certified).
    """
    phys = check_physics(drag, drag_law, restitution)
    phi, v, eps_, _, dps = check_state(phi0, v0, eps, dps=dps, names=("phi0", "v0", "eps"),
                                       w0_zero_ok=not phys.is_default)
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 0:
        raise ValueError(f"n must be a non-negative integer, got n={n!r}")
    kwargs = {} if phys.is_default else {"drag": phys.drag, "drag_law": phys.drag_law,
                                         "restitution": phys.restitution}
    phis, vs, ts = [phi], [v], [mp.zero]
    t = mp.zero
    for k in range(int(n)):
        phi, v, tau = step(phi, v, eps, dps, **kwargs)
        with working_dps(dps + 10):
            t = t + tau
        phis.append(phi)
        vs.append(v)
        ts.append(t)
        if phys.restitution < 1:
            _check_chattering(k + 1, t, phi, v, eps_, phys, dps)
    return Orbit(tuple(phis), tuple(vs), tuple(ts))


def _check_chattering(n, t, phi, v, eps, phys, dps):
    with working_dps(dps + 10):
        w_min = mp.mpf(10) ** (-(dps // 3)) * (1 + abs(v) + abs(eps))
        w = iv.mpf(v) + iv.mpf(eps) * iv.sin(iv.mpf(phi))
        if hi(w) >= w_min:
            return
        flight = DragFlight(v, phys.drag, phys.drag_law)
        curvature = -1 - flight.eta(iv.mpf(v)) + iv.mpf(eps) * iv.cos(iv.mpf(phi))
        if hi(curvature) < 0:
            raise ChatteringDetected(n, t, phi, v, mp.mpf(hi(w)), w_min)
