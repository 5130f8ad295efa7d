"""Orbits of the exact collision map at a given precision."""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import mpmath
from mpmath import mp

from ._inputs import check_state
from ._precision import working_dps
from .collision import step


@dataclass(frozen=True)
class Orbit:
    """Collision phases ``phi``, velocities ``v`` after each collision, cumulative times ``t``
    (``t[0] = 0``); tuples of ``mpf`` of length ``n + 1``. ``phi[0]`` is the input phase as
    given (unreduced); later phases lie in ``[0, 2*pi)``."""

    phi: tuple[mpmath.mpf, ...]
    v: tuple[mpmath.mpf, ...]
    t: tuple[mpmath.mpf, ...]


def orbit(phi0, v0, eps, n: int, dps: int = 50) -> Orbit:
    """Iterate :func:`verify.step` ``n`` times from ``(phi0, v0)``.

    ``t[k] = tau_0 + ... + tau_{k-1}``.

    Each step is certified for its (rounded to ``dps`` digits) input state.
    """
    phi, v, _, _, dps = check_state(phi0, v0, eps, dps=dps, names=("phi0", "v0", "eps"))
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 0:
        raise ValueError(f"n must be a non-negative integer, got n={n!r}")
    phis, vs, ts = [phi], [v], [mp.zero]
    t = mp.zero
    for _ in range(int(n)):
        phi, v, tau = step(phi, v, eps, dps)
        with working_dps(dps + 10):
            t = t + tau
        phis.append(phi)
        vs.append(v)
        ts.append(t)
    return Orbit(tuple(phis), tuple(vs), tuple(ts))
