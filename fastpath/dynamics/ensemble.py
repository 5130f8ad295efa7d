"""Velocities of many orbits: the values at given collision counts (velocity diffusion) and the
first passage above a velocity (transport across a band). Thin wrappers of the parallel kernels
``kernels.velocity_ensemble`` and ``kernels.first_passage``.
"""

import numpy as np

from fastpath.inputs import departing, integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.status import STATUS_DTYPE


def _starts(phi, v, eps):
    phi = np.ascontiguousarray(np.atleast_1d(np.asarray(phi, dtype=np.float64)))
    v = np.ascontiguousarray(np.atleast_1d(np.asarray(v, dtype=np.float64)))
    if phi.ndim != 1 or phi.shape != v.shape:
        raise ValueError(f"phi and v must be 1-D arrays of one length, got shapes {phi.shape}, "
                         f"{v.shape}")
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(v))):
        raise ValueError("phi and v must be finite")
    for p, w in zip(phi, v, strict=True):
        departing(float(p), float(w), eps)
    return phi, v


def velocities(phi, v, eps, collisions, *, model="exact"):
    """v of each orbit after each count in ``collisions`` (ascending positive integers).

    Returns (velocities (starts, len(collisions)), status per start): NaN after a flight that
    stopped an orbit (status its FlightStatus code).
    """
    from fastpath.dynamics.kernels import velocity_ensemble

    eps = real("eps", eps)
    physics = model_physics(model, eps)
    phi, v = _starts(phi, v, eps)
    points = np.asarray(collisions, dtype=np.int64)
    if points.ndim != 1 or len(points) == 0 or points[0] < 1 or np.any(np.diff(points) <= 0):
        raise ValueError("collisions must be ascending positive integers")
    out = np.full((len(phi), len(points)), np.nan)
    done, status = np.zeros(len(phi), np.int64), np.zeros(len(phi), STATUS_DTYPE)
    velocity_ensemble(phi, v, physics, points, out, done, status)
    for i in range(len(phi)):
        out[i, points > done[i]] = np.nan
    return out, status


def first_passage(phi, v, eps, v_top, n, *, model="exact"):
    """Collision count at which each orbit first has v >= v_top (-1: not within n collisions).

    Returns (passage, status per start).
    """
    from fastpath.dynamics.kernels import first_passage as kernel

    eps, v_top = real("eps", eps), real("v_top", v_top)
    n = integer("n", n, minimum=1)
    physics = model_physics(model, eps)
    phi, v = _starts(phi, v, eps)
    passage, status = np.zeros(len(phi), np.int64), np.zeros(len(phi), STATUS_DTYPE)
    kernel(phi, v, physics, v_top, n, passage, status)
    return passage, status
