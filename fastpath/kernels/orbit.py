"""Orbit kernels: n successive collisions from one start, exact or Holmes.

The driver fills preallocated arrays; t is the time since the start (t[0] = 0), accumulated
from the flight times (the Holmes flight time is 2*v).

``dissipative_orbit`` (drag, or restitution r < 1; ``fastpath.advance``) also records
sticking episodes (``fastpath.sticking``): phi, v, t hold the impacts actually computed, a
chattering sequence's ones included up to the impact after which its tail is summed; the
summed tail is not an entry. An episode (t_acc, t_detach) goes into ``sticking``; the entry
after it is the first impact of the flight from the detachment state (theta*, v = u(theta*)).
"""

import math

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import reduce_phase
from fastpath.dissipative.carried import (
    NO_STICKING,
    PHI,
    STATE_SIZE,
    STUCK,
    T,
    V,
    advance,
    begin,
    detachment,
)
from fastpath.elastic.collision import collide_from
from fastpath.elastic.flight import AUTO, GENERAL
from fastpath.elastic.holmes import holmes_collide
from fastpath.physics import NONE
from fastpath.status import CONVERGED


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
    # An orbit carries its sines from collision to collision (its collisions are not step's
    # bit for bit anyway), so it skips the lockstep flight, which pays for its straight-line
    # code when it runs one flight at a time, and takes the concave solver's early exits.
    method = GENERAL if method == AUTO else method
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


@jit
def dissipative_orbit(phi0, v0, eps, drag, law, r, phi, v, t, iterations, sticking, method):
    """Fill phi, v, t (length n+1), iterations (length n), sticking rows: drag and/or r < 1.

    Returns (collisions done, sticking episodes, status, stuck for good). One call of
    ``fastpath.advance.advance`` per impact (physics covered: see there).
    Stops early at a flight that is not CONVERGED, and when the particle sticks for good.
    """
    state = np.empty(STATE_SIZE)
    phi[0], v[0], t[0] = reduce_phase(phi0), v0, 0.0
    status = begin(state, phi0, v0, 0.0, eps, drag, r)
    if status != CONVERGED:
        return 0, 0, status, False
    detach = detachment(eps, drag, law, r)
    no_holes = np.empty(0)
    episodes = 0
    for k in range(len(iterations)):
        status, its, _, kind, t_start, t_end = advance(
            state, eps, drag, law, r, method, detach, no_holes
        )
        if status != CONVERGED:
            return k, episodes, status, False
        iterations[k] = its
        phi[k + 1], v[k + 1], t[k + 1] = state[PHI], state[V], state[T]
        if kind != NO_STICKING:
            sticking[episodes, 0], sticking[episodes, 1] = t_start, t_end
            episodes += 1
            if kind == STUCK:
                return k + 1, episodes, CONVERGED, True
    return len(iterations), episodes, CONVERGED, False


@jit
def inelastic_orbit(phi0, v0, eps, r, phi, v, t, iterations, sticking, method):
    """Fill phi, v, t (length n+1), iterations (length n), sticking rows; restitution r < 1.

    Returns (collisions done, sticking episodes, status, stuck for good): ``dissipative_orbit``
    without drag. Each flight is a short flight in relative coordinates where ``short_window``
    certifies one (chattering), the flight from detachment after a sticking episode, or an
    ordinary flight (``fastpath.advance``).
    """
    return dissipative_orbit(phi0, v0, eps, 0.0, NONE, r, phi, v, t, iterations, sticking,
                             method)
