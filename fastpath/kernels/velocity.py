"""Velocity ensembles: <v_n> and <v_n**2> on a grid of collision indices, for trusted runs.

Each particle runs from (phi0[i], v0[i]) at time t0[i] after n0[i] collisions, each collision
made by ``fastpath.advance.advance`` (the elastic, drag-free step is ``fastpath.step``'s
``collide``, bit for bit; drag; restitution r < 1 with sticking), until it has made
``max_collisions`` collisions or sticks to the plate for good. At every grid point
n_grid[j] it passes (its start included) it adds, in block b (the blocks of
``fastpath.moments``: consecutive particles, serial inside),

    moving[b, j] += 1,   sum_v[b, j] += v_n,   sum_v2[b, j] += v_n**2,

v_n the velocity just after collision n. A particle stuck for good after collision n (the
impact after which the tail is summed, ``fastpath.sticking.TAIL_Q``; |eps| <= 1 and r < 1)
is counted in ``stuck[b, j]`` for every grid point n_grid[j] > n and is not in ``moving``
there: its velocity is the plate's, reported apart, as ``fastpath.dissipative_moments`` does.

Flags and samples as ``fastpath.dissipative_ensemble`` (the departure of the flight concerned,
the carried state after the six sample fields when ``samples`` has the columns and r < 1,
with or without drag): a flagged particle stops with (phi, v, t, n) of that departure; the
caller settles the collision with ``verify`` and resumes the particle here from its state after
it. The grid
point of a start, resumed or not, is filled here: the caller adds nothing.
"""

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import jit, parallel_jit
from fastpath.dissipative.carried import (
    CARRIED,
    PHI,
    STATE_SIZE,
    STUCK,
    V,
    advance,
    begin,
    copy_carried,
    departure_point,
    detachment,
    store_carried,
)
from fastpath.elastic.flight import AUTO
from fastpath.kernels.escape import _flag, _store_sample
from fastpath.status import CONVERGED


@jit
def _add(b, jn, n, v, n_grid, moving, sum_v, sum_v2):
    """Add v = v_n at the grid points n_grid[jn], ... equal to n; return the next jn."""
    while jn < len(n_grid) and n_grid[jn] == n:
        moving[b, jn] += 1
        sum_v[b, jn] += v
        sum_v2[b, jn] += v * v
        jn += 1
    return jn


@jit
def run_block(b, first, last, phi0, v0, t0, n0, eps, drag, law, restitution, detach, n_grid,
              max_collisions, sample_slot, sample_target, moving, sum_v, sum_v2, stuck,
              flags, flag_state, samples):
    """Run particles first .. last-1 into the rows of block b; return the collisions made."""
    state = np.empty(STATE_SIZE)
    no_holes = np.empty(0)
    keep_carried = samples.shape[1] >= 6 + len(CARRIED) and restitution < 1.0
    carried = np.empty(len(CARRIED))
    done = 0
    for i in range(first, last):
        n = n0[i]
        slot, target = sample_slot[i], sample_target[i]
        flags[i] = 0
        status = begin(state, phi0[i], v0[i], t0[i], eps, drag, restitution)
        if status != CONVERGED:
            _flag(flags, flag_state, i, status, phi0[i], v0[i], t0[i], n)
            continue
        jn = np.searchsorted(n_grid, n)
        jn = _add(b, jn, n, v0[i], n_grid, moving, sum_v, sum_v2)
        while n < max_collisions:
            phi, v, t = departure_point(state)
            if keep_carried and slot >= 0 and n < target:
                copy_carried(state, carried)
            status, _, tau, kind, _, _ = advance(
                state, eps, drag, law, restitution, AUTO, detach, no_holes
            )
            if status != CONVERGED:
                _flag(flags, flag_state, i, status, phi, v, t, n)
                break
            n += 1
            done += 1
            if slot >= 0 and n <= target:
                _store_sample(samples, slot, n, phi, v, state[PHI], state[V], tau)
                if keep_carried:
                    store_carried(samples, slot, carried)
            jn = _add(b, jn, n, state[V], n_grid, moving, sum_v, sum_v2)
            if kind == STUCK:
                for j in range(jn, len(n_grid)):
                    stuck[b, j] += 1
                break
    return done


@parallel_jit
def velocity_chunk(phi0, v0, t0, n0, eps, drag, law, restitution, n_grid, max_collisions,
                   sample_slot, sample_target, moving, sum_v, sum_v2, stuck, collisions, flags,
                   flag_state, samples):
    """Fill the block rows (added to; the caller zeroes them); see the module docstring.

    Shapes: ``moving``, ``sum_v``, ``sum_v2``, ``stuck`` (blocks, len(n_grid)), n_grid sorted
    int64; ``collisions`` (blocks,); ``flags`` (particles,), ``flag_state`` (particles, 4);
    ``samples`` (picks, 6 or 6 + len(CARRIED)). drag: law code of ``fastpath.drag``.
    """
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    detach = detachment(eps, drag, law, restitution)
    for b in prange(blocks):
        collisions[b] += run_block(
            b, b * per_block, min(m, (b + 1) * per_block), phi0, v0, t0, n0, eps, drag, law,
            restitution, detach, n_grid, max_collisions, sample_slot, sample_target, moving,
            sum_v, sum_v2, stuck, flags, flag_state, samples,
        )


__all__ = ["run_block", "velocity_chunk"]
