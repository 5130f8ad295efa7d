"""Velocities of many orbits: the values at given collision counts (velocity diffusion) and the
first passage above a velocity (transport across a band).

``velocities`` is the loop of the velocity moments (``fastpath.kernels.moments``, the orbits of
``fastpath.orbit``) with each orbit's v_n recorded instead of summed: use it for per-orbit
values, ``fastpath.moments`` for ensemble means over many particles (sums only, any
description, time grids). ``first_passage`` runs the same orbits (``fastpath.kernels.particle``)
until v >= v_top. Their Holmes map is the map itself, v1 = |v - 2*eps*sin(phi1)|, not the
standard-map form of the Jacobians (``kernels.step_tangent``).
"""

import numpy as np

from fastpath.inputs import departing, integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.kernels.arrays import Flags, MomentGrid, MomentSums, Sample, Starts
from fastpath.kernels.moments import moments_chunk
from fastpath.status import STATUS_DTYPE

THREAD_BLOCKS = 64  # blocks of orbits run in parallel by velocities (its results do not
#                     depend on them)


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
    """v of each orbit after each count in ``collisions`` (ascending positive integers), the
    orbits of ``fastpath.orbit`` (module docstring).

    Returns (velocities (starts, len(collisions)), status per start): NaN after a flight that
    stopped an orbit (status its FlightStatus code, 0 for an orbit that got to the end).
    """
    eps = real("eps", eps)
    physics = model_physics(model, eps)
    phi, v = _starts(phi, v, eps)
    points = np.asarray(collisions, dtype=np.int64)
    if points.ndim != 1 or len(points) == 0 or points[0] < 1 or np.any(np.diff(points) <= 0):
        raise ValueError("collisions must be ascending positive integers")
    m = len(phi)
    out = np.full((m, len(points)), np.nan)
    flags = Flags.zeros(m)
    moments_chunk(physics, Starts(phi=phi, v=v, t=np.zeros(m), n=np.zeros(m, np.int64)),
                  MomentGrid(n=points, t=np.zeros(0), max_collisions=int(points[-1])), False,
                  Sample.none(m), MomentSums.zeros(min(m, THREAD_BLOCKS), len(points), 0), flags,
                  out)
    return out, flags.status


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
