"""Orbit kernels: n successive collisions from one start, exact or Holmes.

The driver fills preallocated arrays; t is the time since the start (t[0] = 0), accumulated
from the flight times (the Holmes flight time is 2*v).
"""

import math

from fastpath._jit import jit
from fastpath.collision import collide_from
from fastpath.flight import CONVERGED
from fastpath.holmes import holmes_collide
from fastpath.phase import reduce_phase


@jit
def exact_orbit(phi0, v0, eps, phi, v, t, iterations, method):
    """Fill phi, v, t (length n+1) and iterations (length n); return (collisions done, status).

    method: a ``fastpath.flight`` method code (AUTO or SEED).

    Stops early at the first flight that is not CONVERGED; its status is returned.
    """
    phi[0] = reduce_phase(phi0)
    v[0] = v0
    t[0] = 0.0
    sin_phi, cos_phi = math.sin(phi[0]), math.cos(phi[0])
    for k in range(len(iterations)):
        phi1, sin_phi, cos_phi, v1, tau, its, status = collide_from(
            phi[k], sin_phi, cos_phi, v[k], eps, method
        )
        iterations[k] = its
        if status != CONVERGED:
            return k, status
        phi[k + 1] = phi1
        v[k + 1] = v1
        t[k + 1] = t[k] + tau
    return len(iterations), CONVERGED


@jit
def holmes_orbit(phi0, v0, eps, phi, v, t):
    """Fill phi, v, t (length n+1) with the Holmes map; flight time 2*v."""
    phi[0] = reduce_phase(phi0)
    v[0] = v0
    t[0] = 0.0
    for k in range(len(phi) - 1):
        phi[k + 1], v[k + 1] = holmes_collide(phi[k], v[k], eps)
        t[k + 1] = t[k] + 2.0 * v[k]
