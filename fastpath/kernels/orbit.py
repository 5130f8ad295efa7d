"""The orbit loop: n successive collisions of one particle, for any description.

The driver fills preallocated arrays (``arrays.OrbitArrays``); t is the time since the start
(t[0] = 0), accumulated from the flight times (the Holmes flight time is 2*v). Each collision is
``fastpath.kernels.particle.advance`` without ``as_step``: the sine and cosine of the phase are
carried from collision to collision (one libm sine and cosine per collision).

With restitution r < 1 the loop also records sticking episodes
(``fastpath.dissipative.sticking``): phi, v, t hold the impacts actually computed, a chattering
sequence's ones included up to the impact after which its tail is summed; the summed tail is not
an entry. An episode (t_acc, t_detach) goes into ``sticking``; the entry after it is the first
impact of the flight from the detachment state (theta*, v = u(theta*)).
"""

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.dissipative.carried import NO_STICKING, PHI, STATE_SIZE, STUCK, T, V
from fastpath.kernels.particle import advance, begin, detachment_of
from fastpath.status import CONVERGED


@jit
def orbit_loop(phi0, v0, physics, method, out):
    """Fill ``out`` (phi, v, t of length n+1, iterations of length n, sticking rows) from
    (phi0, v0); return (collisions done, sticking episodes, status, stuck for good).

    method: a ``fastpath.elastic.flight`` code (AUTO or LOWER_BOUND). Stops early at the first
    flight that is not CONVERGED (its status is returned), and when the particle sticks for good.
    """
    state = np.empty(STATE_SIZE)
    status = begin(state, phi0, v0, 0.0, physics, False)
    out.phi[0], out.v[0], out.t[0] = state[PHI], v0, 0.0
    if status != CONVERGED:
        return 0, 0, status, False
    detach = detachment_of(physics)
    no_holes = np.empty(0)
    episodes = 0
    for k in range(len(out.iterations)):
        status, its, _, kind, t_start, t_end = advance(state, physics, method, False, detach,
                                                       no_holes)
        if status != CONVERGED:
            return k, episodes, status, False
        out.iterations[k] = its
        out.phi[k + 1], out.v[k + 1], out.t[k + 1] = state[PHI], state[V], state[T]
        if kind != NO_STICKING:
            out.sticking[episodes, 0], out.sticking[episodes, 1] = t_start, t_end
            episodes += 1
            if kind == STUCK:
                return k + 1, episodes, CONVERGED, True
    return len(out.iterations), episodes, CONVERGED, False
