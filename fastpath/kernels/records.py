"""What a kernel records of one particle besides its counts: the flag of an undecided flight and
the verification sample (``fastpath.kernels.arrays``: ``Flags``, ``Sample``).

``start_particle`` and ``sampled_collision`` are the first and every further step of a particle
in the loops that take no time horizon (velocity moments, the portrait); the escape lanes write
the same records with ``flag``, ``store_sample`` and ``store_carried``.
"""

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.dissipative.carried import CARRIED, PHI, STATE_SIZE, V, copy_carried
from fastpath.elastic.flight import AUTO as AUTO_METHOD
from fastpath.kernels.arrays import SAMPLE_FIELDS, keeps_carried
from fastpath.kernels.particle import advance, begin, departure_point
from fastpath.status import CONVERGED


@jit
def flag(flags, i, status, phi, v, t, n):
    """Particle i stopped at an undecided flight from (phi, v) at time t after n collisions."""
    flags.status[i] = status
    flags.state[i, 0] = phi
    flags.state[i, 1] = v
    flags.state[i, 2] = t
    flags.state[i, 3] = n


@jit
def store_sample(rows, s, n, departure, result):
    """Row s of the sample: n, the departure (phi, v) and the result (phi1, v1, tau)."""
    rows[s, 0] = n
    rows[s, 1], rows[s, 2] = departure
    rows[s, 3], rows[s, 4], rows[s, 5] = result


@jit
def store_carried(rows, s, carried):
    """``carried`` into the columns after the six sample fields of row s."""
    for j in range(len(carried)):
        rows[s, len(SAMPLE_FIELDS) + j] = carried[j]


@jit
def particle_buffers():
    """(state, carried): a particle's state array and a buffer for its carried entries."""
    return np.empty(STATE_SIZE), np.empty(len(CARRIED))


@jit
def start_particle(state, physics, i, starts, flags, as_step):
    """Fill ``state`` with particle i's start (``particle.begin``) and clear its flag; flag it
    instead if it does not depart for certain. Whether it departs."""
    flags.status[i] = 0
    status = begin(state, starts.phi[i], starts.v[i], starts.t[i], physics, as_step)
    if status != CONVERGED:
        flag(flags, i, status, starts.phi[i], starts.v[i], starts.t[i], starts.n[i])
        return False
    return True


@jit
def sampled_collision(state, physics, i, n, sample, flags, carried, motion):
    """Particle i's collision n + 1 (``particle.advance``), flagged if undecided, into its sample
    row if picked: (status, tau, sticking, t_start, t_end). ``carried``: a buffer for the
    departure's carried entries; motion = (as_step, detach, hole_lo) of ``advance``."""
    as_step, detach, hole_lo = motion
    slot, target = sample.slot[i], sample.target[i]
    keep = keeps_carried(sample.rows, physics.restitution) and slot >= 0 and n < target
    phi, v, t = departure_point(state)
    if keep:
        copy_carried(state, carried)
    status, _, tau, kind, t_start, t_end = advance(state, physics, AUTO_METHOD, as_step, detach,
                                                   hole_lo)
    if status != CONVERGED:
        flag(flags, i, status, phi, v, t, n)
    elif slot >= 0 and n < target:
        store_sample(sample.rows, slot, n + 1, (phi, v), (state[PHI], state[V], tau))
        if keep:
            store_carried(sample.rows, slot, carried)
    return status, tau, kind, t_start, t_end
