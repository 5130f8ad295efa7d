"""Velocity moments with dissipation: drag, or restitution r < 1 with sticking.

The sums of ``fastpath.moments.moments_kernel`` (read its module docstring), each collision made
by ``fastpath.advance.advance`` (any drag with any restitution), plus

* ``stuck_n[b, j]``: particles stuck for good (the impacts accumulate where the particle can
  never leave, |eps| <= 1) after fewer than n_grid[j] recorded impacts; they are not in
  ``count_n[b, j]``, so count_n + stuck_n + (particles flagged or capped before n_grid[j]) =
  particles. The index at which a particle sticks is that of the impact after which the tail is
  summed (``fastpath.sticking.TAIL_Q``).
* ``stuck_t[b, j]``: particles stuck for good at t_acc <= t_grid[j]; not in ``count_t``.

v(t) between collisions is the velocity of the last departure at or before t: an impact's
outgoing velocity, or after a sticking episode the detachment velocity u(theta*) from t_detach
on; during an episode (t_acc <= t < t_detach) it stays the last impact's (~ the plate's
velocity at t_acc, where the relative velocity has gone to 0). An undecidable flight flags the
particle, as in ``moments_kernel``.
"""

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import jit, parallel_jit
from fastpath.dissipative.carried import (
    EPISODE,
    STATE_SIZE,
    STUCK,
    VK,
    T,
    V,
    advance,
    begin,
    detachment,
)
from fastpath.elastic.flight import AUTO
from fastpath.status import CONVERGED


@jit
def _add_n(b, jn, n, v, start, n_grid, count_n, sum_v_n, sum_v2_n, sum_dv2_n):
    """Add v = v_n to the grid points n_grid[jn], ... equal to n; return the next jn."""
    while jn < len(n_grid) and n_grid[jn] == n:
        count_n[b, jn] += 1
        sum_v_n[b, jn] += v
        sum_v2_n[b, jn] += v * v
        sum_dv2_n[b, jn] += (v - start) * (v - start)
        jn += 1
    return jn


@jit
def _add_t(b, jt, until, v, t_grid, count_t, sum_v_t):
    """Add v to the time points t_grid[jt], ... below ``until``; return the next jt."""
    while jt < len(t_grid) and t_grid[jt] < until:
        count_t[b, jt] += 1
        sum_v_t[b, jt] += v
        jt += 1
    return jt


@jit
def run_block(b, first, last, phi0, v0, eps, drag, law, restitution, detach, n_grid, t_grid,
              max_collisions, count_n, sum_v_n, sum_v2_n, sum_dv2_n, count_t, sum_v_t,
              stuck_n, stuck_t, flags):
    """Run particles first .. last-1 into the rows of block b; return the collisions made."""
    state = np.empty(STATE_SIZE)
    no_holes = np.empty(0)
    kn, kt = len(n_grid), len(t_grid)
    n_last = n_grid[kn - 1] if kn > 0 else 0
    t_last = t_grid[kt - 1] if kt > 0 else -1.0
    done = 0
    for i in range(first, last):
        v = v0[i]
        start = v
        t = 0.0
        n = 0
        jt = 0
        flags[i] = 0
        status = begin(state, phi0[i], v, 0.0, eps, drag, restitution)
        if status != CONVERGED:
            flags[i] = status
            continue
        jn = _add_n(b, 0, n, v, start, n_grid, count_n, sum_v_n, sum_v2_n, sum_dv2_n)
        while not ((n >= n_last and t > t_last) or n >= max_collisions):
            status, _, _, kind, t_start, t_end = advance(
                state, eps, drag, law, restitution, AUTO, detach, no_holes
            )
            if status != CONVERGED:
                flags[i] = status
                break
            jt = _add_t(b, jt, state[T], v, t_grid, count_t, sum_v_t)  # t <= t_grid < t1
            v, t = state[V], state[T]
            n += 1
            done += 1
            jn = _add_n(b, jn, n, v, start, n_grid, count_n, sum_v_n, sum_v2_n, sum_dv2_n)
            if kind == STUCK:
                jt = _add_t(b, jt, t_start, v, t_grid, count_t, sum_v_t)
                for j in range(jn, kn):
                    stuck_n[b, j] += 1
                for j in range(jt, kt):
                    stuck_t[b, j] += 1
                break
            if kind == EPISODE:  # riding: the last impact's velocity; then the detachment
                jt = _add_t(b, jt, t_end, v, t_grid, count_t, sum_v_t)
                v, t = state[VK], t_end
    return done


@parallel_jit
def dissipative_moments_kernel(phi0, v0, eps, drag, law, restitution, n_grid, t_grid,
                               max_collisions, count_n, sum_v_n, sum_v2_n, sum_dv2_n, count_t,
                               sum_v_t, stuck_n, stuck_t, collisions, flags):
    """The block sums of ``moments_kernel`` plus ``stuck_n`` (blocks, len(n_grid)) and
    ``stuck_t`` (blocks, len(t_grid)); see the module docstring. Outputs are added to."""
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    detach = detachment(eps, drag, law, restitution)
    for b in prange(blocks):
        collisions[b] += run_block(
            b, b * per_block, min(m, (b + 1) * per_block), phi0, v0, eps, drag, law,
            restitution, detach, n_grid, t_grid, max_collisions, count_n, sum_v_n, sum_v2_n,
            sum_dv2_n, count_t, sum_v_t, stuck_n, stuck_t, flags,
        )


__all__ = ["dissipative_moments_kernel", "run_block"]
