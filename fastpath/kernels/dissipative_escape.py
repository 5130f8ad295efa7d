"""Escape ensembles with dissipation: drag, or restitution r < 1 with sticking.

The contract of ``fastpath.ensemble.escape_chunk`` (blocks, histograms, flags, samples: read its
module docstring), with each collision made by ``fastpath.advance.advance`` (any drag with any
restitution), plus one more outcome:

* stuck for good: the impacts accumulate where the particle can never leave the plate
  (|eps| <= 1 without drag, ``fastpath.sticking``; with drag ``fastpath.drag_sticking``).
  It is counted in ``stuck_n[b, k]`` / ``stuck_t[b, k]``,
  binned by the collision index n of the impact after which the tail was summed (the
  implementation's threshold, ``fastpath.sticking.TAIL_Q``) and by the accumulation time
  t_acc; neither an escape nor censored. It counts as stuck when t_acc <= max_time, else it is
  censored at (n, t_acc). Escapes + censored + stuck + flagged = particles.

Collisions are the impacts: riding the plate through a hole's phases during a sticking episode
is not a collision and does not escape. The impacts of a summed tail are collisions, so a tail
whose phases would cross into a hole is not summed (``fastpath.advance``): those impacts are
computed and tested one by one. After a detachment the next collision is the first impact of
the flight from the detachment state; a horizon max_time inside an episode censors at the next
impact's time, as for a long flight.

Flags and samples refer to the departure of the flight concerned (``advance.departure_point``):
the last impact, or after an episode the detachment state (theta*, u(theta*)) with w0 = 0.
A ``samples`` array of 6 + len(CARRIED) columns gets, after the six of
``fastpath.ensemble``, the departure's carried entries (``fastpath.advance.CARRIED``), from
which ``fastpath.carried_step`` repeats the sampled step bit for bit (r < 1: the step depends
on them, not on (phi, v) alone).
The particles are split into ``len(collisions)`` fixed blocks; ``prange`` runs the blocks,
each by the serial ``run_block``, so the counts do not depend on the number of threads.
"""

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import jit, parallel_jit
from fastpath.dissipative.carried import (
    CARRIED,
    PHI,
    STATE_SIZE,
    STUCK,
    T,
    V,
    advance,
    begin,
    copy_carried,
    departure_point,
    detachment,
    store_carried,
)
from fastpath.elastic.flight import AUTO
from fastpath.kernels.escape import _flag, _store_sample, bin_index, exit_hole
from fastpath.status import CONVERGED


@jit
def _censor(cens_n, cens_t, b, n, t, n_edges, t_edges, record_n, record_t):
    if record_n:
        cens_n[b, bin_index(n_edges, n)] += 1
    if record_t:
        cens_t[b, bin_index(t_edges, t)] += 1


@jit
def run_block(b, first, last, phi0, v0, t0, n0, eps, drag, law, restitution, detach, hole_lo,
              hole_width, max_collisions, max_time, n_edges, t_edges, record_n, record_t,
              sample_slot, sample_target, esc_n, esc_t, cens_n, cens_t, stuck_n, stuck_t,
              flags, flag_state, samples):
    """Run particles first .. last-1 into the rows of block b; return the collisions made."""
    state = np.empty(STATE_SIZE)
    carried = np.empty(len(CARRIED))
    keep_carried = samples.shape[1] >= 6 + len(CARRIED)
    done = 0
    for i in range(first, last):
        n = n0[i]
        slot, target = sample_slot[i], sample_target[i]
        flags[i] = 0
        status = begin(state, phi0[i], v0[i], t0[i], eps, drag, restitution)
        if status != CONVERGED:
            _flag(flags, flag_state, i, status, phi0[i], v0[i], t0[i], n)
            continue
        while True:
            if n >= max_collisions:
                _censor(cens_n, cens_t, b, n, departure_point(state)[2], n_edges, t_edges,
                        record_n, record_t)
                break
            phi, v, t = departure_point(state)
            if keep_carried and slot >= 0 and n < target:
                copy_carried(state, carried)
            status, _, tau, kind, t_start, _ = advance(
                state, eps, drag, law, restitution, AUTO, detach, hole_lo
            )
            if status != CONVERGED:
                _flag(flags, flag_state, i, status, phi, v, t, n)
                break
            if state[T] > max_time:
                _censor(cens_n, cens_t, b, n, state[T], n_edges, t_edges, record_n, record_t)
                break
            n += 1
            done += 1
            if slot >= 0 and n <= target:
                _store_sample(samples, slot, n, phi, v, state[PHI], state[V], tau)
                if keep_carried:
                    store_carried(samples, slot, carried)
            j = exit_hole(state[PHI], hole_lo, hole_width)
            if j >= 0:
                if record_n:
                    esc_n[b, j, bin_index(n_edges, n)] += 1
                if record_t:
                    esc_t[b, j, bin_index(t_edges, state[T])] += 1
                break
            if kind == STUCK:
                if t_start <= max_time:
                    if record_n:
                        stuck_n[b, bin_index(n_edges, n)] += 1
                    if record_t:
                        stuck_t[b, bin_index(t_edges, t_start)] += 1
                else:
                    _censor(cens_n, cens_t, b, n, t_start, n_edges, t_edges, record_n,
                            record_t)
                break
    return done


@parallel_jit
def dissipative_escape_chunk(phi0, v0, t0, n0, eps, drag, law, restitution, hole_lo,
                             hole_width, max_collisions, max_time, n_edges, t_edges, record_n,
                             record_t, sample_slot, sample_target, esc_n, esc_t, cens_n,
                             cens_t, stuck_n, stuck_t, collisions, flags, flag_state,
                             samples):
    """``fastpath.ensemble.escape_chunk`` with drag (law code ``fastpath.drag``), restitution,
    and ``stuck_n[b, k]`` / ``stuck_t[b, k]`` (module docstring). Outputs are added to."""
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    detach = detachment(eps, drag, law, restitution)
    for b in prange(blocks):
        collisions[b] += run_block(
            b, b * per_block, min(m, (b + 1) * per_block), phi0, v0, t0, n0, eps, drag, law,
            restitution, detach, hole_lo, hole_width, max_collisions, max_time, n_edges,
            t_edges, record_n, record_t, sample_slot, sample_target, esc_n, esc_t, cens_n,
            cens_t, stuck_n, stuck_t, flags, flag_state, samples,
        )


__all__ = ["dissipative_escape_chunk", "run_block"]
