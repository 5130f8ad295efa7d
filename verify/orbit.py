"""Orbits of the exact collision map at a given precision: one loop for every physics."""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import mpmath

from .collision import impact
from .dissipative.physics import check_physics
from .dissipative.sticking_model import sticking_model
from .numerics.inputs import check_state
from .numerics.precision import DEFAULT_DPS, GUARD_DPS, mp, to_user, working_dps


@dataclass(frozen=True)
class Orbit:
    """Successive collisions of the exact map: the same fields as ``fastpath.Orbit`` where they
    mean the same (``phi``, ``v``, ``t``, ``model``, ``eps``, ``sticking``, ``stopped``), as
    tuples of ``mpf`` (``mpmath.mp`` numbers).

    ``phi``: collision phases, ``phi[0]`` the input phase as given (unreduced), later ones in
    ``[0, 2*pi)``; ``v``: velocities after each collision; ``t``: cumulative times
    (``t[0] = 0``); length ``n + 1`` unless the orbit ended early. ``model``: ``"exact"`` (the
    exact map; fastpath also has ``"holmes"``). ``eps``: the amplitude (exact). ``sticking``:
    ``(t_start, t_end)`` pairs of sticking episodes (:mod:`verify.dissipative.sticking`): the
    particle rides the plate from the accumulation time ``t_start`` and leaves at ``t_end``
    (``mp.inf``: never, stuck for good). ``stopped``: ``"collisions"`` (made the ``n``
    collisions) or ``"stuck"`` (stuck for good before that). ``phi``/``v``/``t`` record the
    impacts computed; a summed tail is not an entry, and the entry after an episode is the
    impact ending the flight from detachment. ``dps``: the digits of every entry. (fastpath's
    ``iterations`` and ``status`` have no counterpart: verify raises where it cannot decide.)
    """

    phi: tuple[mpmath.mpf, ...]
    v: tuple[mpmath.mpf, ...]
    t: tuple[mpmath.mpf, ...]
    model: str
    eps: mpmath.mpf
    sticking: tuple[tuple[mpmath.mpf, mpmath.mpf], ...] = ()
    stopped: str = "collisions"
    dps: int = DEFAULT_DPS


def orbit(phi0, v0, eps, n: int, *, dps: int = DEFAULT_DPS, drag=0.0, drag_law: str = "linear",
          restitution=1.0) -> Orbit:
    """Iterate the map of :func:`verify.step` ``n`` times from ``(phi0, v0)``.

    Parameters: the start ``phi0``, ``v0`` and ``eps`` (exact binary values; a departure),
    ``n`` the number of collisions, ``dps`` the digits of every entry, and the physics
    keywords of :func:`verify.step` (``drag``, ``drag_law``, ``restitution``).

    ``t[k] = tau_0 + ... + tau_{k-1}`` (summed from the flight times' enclosures). Each entry
    is within ``10**-dps`` of the exact impact of the exact state carried from the previous
    one (as :func:`verify.step`); the state carried to the next flight is not the rounded
    entry but the exact midpoint of the impact's enclosure, with the relative velocity
    ``w = v + eps*sin(phi)`` kept to ``dps`` digits of itself
    (:func:`verify.dissipative.impact.carried_state`), so a tiny ``w`` (a restitution of
    ``1e-40``, a chattering run) stays a departure.

    Restitution ``r < 1`` (the sticking models of :mod:`verify.dissipative.sticking_model`):
    after each impact, when the impacts from it accumulate (relative velocity ``w`` down to
    ~``10**(-dps/3)``, the tail's second-order term ``q*T0 <= 10**-dps`` and its enclosure
    proved), the tail is summed: ``t_acc = t + T``. Then the particle rides the plate; if it
    never leaves (no drag: ``|eps| <= 1``; with drag: decided exactly,
    :mod:`verify.dissipative.drag_sticking`) ``sticking`` ends with ``(t_acc, inf)``,
    ``stopped = "stuck"`` and the orbit ends early; otherwise it leaves at the next detachment
    phase ``theta*`` (no drag: ``2*pi - arccos(1/eps)``, or ``pi - arccos(1/|eps|)`` for
    ``eps < -1``; with drag: the proved root of the riding force) at ``t_detach``, the episode
    ``(t_acc, t_detach)`` is recorded and the next entry is the impact of the certified flight
    from ``theta*`` (``w0 = 0``). The number of chattering impacts recorded depends on this
    threshold: compare implementations by their episodes and the impacts after them.

    With drag, should ``w`` fall below ``w_min = 10**(-dps//2) * (1 + |v| + |eps|)`` (far below
    where the tail is summed) with no tail summed and ``d''(0) < 0`` proved,
    :class:`verify.ChatteringDetected`. Undecidable steps raise
    :class:`verify.UndecidableCollision`. Safe to call from any thread.
    """
    phys = check_physics(drag, drag_law, restitution)
    phi, v, eps_, _, dps = check_state(phi0, v0, eps, dps=dps, names=("phi0", "v0", "eps"),
                                       w0_zero_ok=not phys.is_default)
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 0:
        raise ValueError(f"n must be a non-negative integer, got n={n!r}")
    model = sticking_model(eps_, phys, dps)
    phis, vs, ts, episodes = [phi], [v], [mp.zero], []
    t = mp.zero
    state = (phi, v)
    detached = False
    stopped = "collisions"
    for k in range(int(n)):
        if detached:
            hit = model.detachment_step()
            detached = False
        else:
            hit = impact(*state, eps_, phys, dps)
        state = hit.state
        with working_dps(dps + GUARD_DPS):
            t = t + hit.elapsed
        phis.append(hit.phi1)
        vs.append(hit.v1)
        ts.append(t)
        if model is None:
            continue
        acc = model.accumulation(*state)
        if acc is None:
            model.check_chattering(k + 1, t, *state)
            continue
        with working_dps(dps + GUARD_DPS):
            t_acc = t + acc.tail
            if not model.leaves_plate():
                episodes.append((t_acc, mp.inf))
                stopped = "stuck"
                break
            t = t_acc + model.riding_time(acc.phase)
        episodes.append((t_acc, t))
        detached = True
    return Orbit(to_user(tuple(phis)), to_user(tuple(vs)), to_user(tuple(ts)), "exact",
                 to_user(eps_), to_user(tuple(tuple(e) for e in episodes)), stopped, dps)
