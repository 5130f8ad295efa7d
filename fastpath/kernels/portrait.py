"""Phase-space portrait: a histogram of the collision states (phi_n, v_n), n = 1 .. max_collisions.

Each particle runs from its start for ``max_collisions`` collisions (or until it sticks to the
plate for good, or a flight float64 cannot decide: then it is flagged as in
``fastpath.kernels.escape``, and resumed by the caller after settling it). Every state
(phi_n, v_n) after a collision with v_n in [v_lo, v_hi) is counted in its bin of
``arrays.Portrait``. Each collision is ``fastpath.step``'s (``particle.advance`` with
``as_step``), so a sampled collision is audited by ``step``. The particles are split into
len(portrait.collisions) fixed blocks, one row of counts each, filled in particle order.
"""

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import TWO_PI
from fastpath.dissipative.carried import PHI, STUCK, V
from fastpath.kernels.particle import detachment_of
from fastpath.kernels.records import particle_buffers, sampled_collision, start_particle
from fastpath.kernels.threads import over_threads
from fastpath.status import CONVERGED


def portrait_chunk(physics, starts, max_collisions, sample, portrait, flags):
    """Fill ``portrait.counts`` (added to) with the collision states of ``starts`` (module
    docstring); flags and sample as ``fastpath.kernels.escape.escape_chunk``."""
    m = len(starts.phi)
    per_block = (m + len(portrait.collisions) - 1) // len(portrait.collisions)
    detach = detachment_of(physics)

    def run_group(first_block, end_block):
        _portrait_blocks(physics, (first_block, end_block, per_block), starts, max_collisions,
                         sample, portrait, flags, detach)

    over_threads(run_group, len(portrait.collisions))


@jit
def _portrait_blocks(physics, span, starts, max_collisions, sample, portrait, flags, detach):
    """Blocks first .. end-1 of ``portrait_chunk``, span = (first, end, per_block)."""
    first, end, per_block = span
    m = len(starts.phi)
    for b in range(first, end):
        _portrait_block(physics, (b, min(m, b * per_block), min(m, (b + 1) * per_block)), starts,
                        max_collisions, sample, portrait, flags, detach)


@jit
def _portrait_block(physics, span, starts, max_collisions, sample, portrait, flags, detach):
    """Particles first .. last-1 into block b's row, span = (b, first, last)."""
    b, first, last = span
    done = 0
    state, carried = particle_buffers()
    motion = (True, detach, np.empty(0))
    counts = portrait.counts
    n_phi, n_v = counts.shape[1], counts.shape[2]
    for i in range(first, last):
        if not start_particle(state, physics, i, starts, flags, True):
            continue
        n = starts.n[i]
        while n < max_collisions:
            status, _, kind, _, _ = sampled_collision(state, physics, i, n, sample, flags,
                                                      carried, motion)
            if status != CONVERGED:
                break
            n += 1
            done += 1
            phi1, v1 = state[PHI], state[V]
            if portrait.v_lo <= v1 < portrait.v_hi:
                p = min(int(phi1 / TWO_PI * n_phi), n_phi - 1)
                q = min(int((v1 - portrait.v_lo) / (portrait.v_hi - portrait.v_lo) * n_v),
                        n_v - 1)
                counts[b, p, q] += 1
            if kind == STUCK:
                break
    portrait.collisions[b] += done
