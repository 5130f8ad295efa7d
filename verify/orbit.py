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
from .drag_sticking import drag_accumulation, drag_detachment_step, riding, riding_time
from .errors import ChatteringDetected
from .sticking import accumulation, can_detach, detachment_step, stay


@dataclass(frozen=True)
class Orbit:
    """Collision phases ``phi``, velocities ``v`` after each collision, cumulative times ``t``
    (``t[0] = 0``); tuples of ``mpf`` of length ``n + 1``. ``phi[0]`` is the input phase as
    given (unreduced); later phases lie in ``[0, 2*pi)``.

    ``sticking``: ``(t_start, t_end)`` pairs of sticking episodes (the dissipation spec,
    :mod:`verify.sticking`): the particle rides the plate from the accumulation time
    ``t_start`` and leaves at ``t_end`` (``mp.inf``: never, stuck for good). ``stopped``:
    ``"collisions"`` (made the ``n`` collisions) or ``"stuck"`` (stuck for good before that).
    ``phi``/``v``/``t`` record the impacts computed; a summed tail is not an entry, and the entry
    after an episode is the impact ending the flight from detachment.
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

    Each step is certified for its (rounded to ``dps`` digits) input state.

    Restitution ``r < 1`` without drag (:mod:`verify.sticking`): after each impact, when the
    impacts from it accumulate (relative velocity ``w`` down to ~``10**(-dps/3)``, the tail's
    second-order term ``q*T0 <= 10**-dps`` and its enclosure proved), the tail is summed:
    ``t_acc = t + T``. Then the particle rides the plate; for ``|eps| <= 1`` it never leaves
    (``sticking`` ends with ``(t_acc, inf)``, ``stopped = "stuck"``, the orbit ends early);
    otherwise it leaves at the next phase ``theta*`` (``2*pi - arccos(1/eps)``, or
    ``pi - arccos(1/|eps|)`` for ``eps < -1``) at ``t_detach``, the episode ``(t_acc,
    t_detach)`` is recorded and the next entry is the impact of the certified flight from
    ``(theta*, u(theta*))`` (``w0 = 0``). The number of chattering impacts recorded depends on
    this threshold: compare implementations by their episodes and the impacts after them.

    Drag with ``r < 1`` (:mod:`verify.drag_sticking`): the same with the drag's tail
    ``T = T0 + J*T0**2/(3a) - c*T0**2/6`` (its enclosure proved, ``a = 1 + eta(u) -
    eps*cos(theta)`` the riding force), the exact decision "ever leaves" (linear drag iff
    ``eps**2*(1 + drag**2) > 1``), the proved detachment phase (linear: ``atan(drag) -
    arccos(1/E)``, ``E = |eps|*sqrt(1 + drag**2)``, ``+ pi`` for ``eps < 0``, mod 2*pi; quadratic:
    the isolated root of ``a``) and the certified flight from it. Should ``w`` fall below
    ``w_min = 10**(-dps//2) * (1 + |v| + |eps|)`` (far below where the tail is summed) with no
    tail summed and ``d''(0) < 0`` proved, :class:`verify.errors.ChatteringDetected`.
    Undecidable steps raise :class:`verify.errors.UndecidableCollision`.
    """
    phys = check_physics(drag, drag_law, restitution)
    phi, v, eps_, _, dps = check_state(phi0, v0, eps, dps=dps, names=("phi0", "v0", "eps"),
                                       w0_zero_ok=not phys.is_default)
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 0:
        raise ValueError(f"n must be a non-negative integer, got n={n!r}")
    kwargs = {} if phys.is_default else {"drag": phys.drag, "drag_law": phys.drag_law,
                                         "restitution": phys.restitution}
    sticks = phys.restitution < 1 and phys.drag == 0
    drag_sticks = phys.restitution < 1 and phys.drag > 0
    phis, vs, ts, episodes = [phi], [v], [mp.zero], []
    t = mp.zero
    detached = False
    for k in range(int(n)):
        if detached and drag_sticks:
            phi, v, tau = drag_detachment_step(eps_, phys.drag, phys.drag_law,
                                               phys.restitution, dps)
            detached = False
        elif detached:
            phi, v, tau = detachment_step(eps_, phys.restitution, dps)
            detached = False
        else:
            phi, v, tau = step(phi, v, eps, dps, **kwargs)
        with working_dps(dps + 10):
            t = t + tau
        phis.append(phi)
        vs.append(v)
        ts.append(t)
        if drag_sticks:
            acc = drag_accumulation(phi, v, eps_, phys.drag, phys.drag_law, phys.restitution,
                                    dps)
            if acc is None:
                _check_chattering(k + 1, t, phi, v, eps_, phys, dps)
                continue
            ride = riding(eps_, phys.drag, phys.drag_law, dps)
            with working_dps(dps + 10):
                t_acc = t + acc.tail
                if ride is None:
                    episodes.append((t_acc, mp.inf))
                    return Orbit(tuple(phis), tuple(vs), tuple(ts), tuple(episodes), "stuck")
                t = t_acc + riding_time(acc.phase, ride)
            episodes.append((t_acc, t))
            detached = True
        elif sticks:
            acc = accumulation(phi, v, eps_, phys.restitution, dps)
            if acc is None:
                continue
            with working_dps(dps + 10):
                t_acc = t + acc.tail
                if not can_detach(eps_):
                    episodes.append((t_acc, mp.inf))
                    return Orbit(tuple(phis), tuple(vs), tuple(ts), tuple(episodes), "stuck")
                t = t_acc + stay(acc.phase, eps_)
            episodes.append((t_acc, t))
            detached = True
    return Orbit(tuple(phis), tuple(vs), tuple(ts), tuple(episodes))


def _check_chattering(n, t, phi, v, eps, phys, dps):
    with working_dps(dps + 10):
        w_min = mp.mpf(10) ** (-(dps // 2)) * (1 + abs(v) + abs(eps))
        w = iv.mpf(v) + iv.mpf(eps) * iv.sin(iv.mpf(phi))
        if hi(w) >= w_min:
            return
        flight = DragFlight(v, phys.drag, phys.drag_law)
        curvature = -1 - flight.eta(iv.mpf(v)) + iv.mpf(eps) * iv.cos(iv.mpf(phi))
        if hi(curvature) < 0:
            raise ChatteringDetected(n, t, phi, v, mp.mpf(hi(w)), w_min)
