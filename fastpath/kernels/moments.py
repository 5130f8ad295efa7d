"""Velocity moments of many particles (Fermi acceleration, velocity diffusion), any description.

Each particle i runs from (phi0[i], v0[i]) through the map of the description (``fastpath.physics``:
the exact map, the Holmes map with flight time 2*v, or drag and restitution with sticking). Only
sums are kept, never the orbits:

* at the collision indices ``n_grid`` (sorted, >= 0): sum of v_n, of v_n**2 and of
  (v_n - v_0)**2 over the particles that reached collision n;
* at the times ``t_grid`` (sorted, >= 0): sum of v(t) = v_N with t_N <= t < t_{N+1}, the velocity
  just after the last collision at or before t, over the particles that reached time t.

A particle runs until it has passed both n_grid[-1] and t_grid[-1], or until ``max_collisions``
(then the later time points miss it: ``count_t`` says how many particles each point holds). An
exact flight float64 cannot decide (status UNCERTAIN or MAX_ITERATIONS, only for |eps| >= 1)
stops the particle: it is flagged (``arrays.Flags``) and contributes only to the grid points it
reached before; ``count_n`` records that.

With restitution r < 1 a particle stuck for good (the impacts accumulate where it can never
leave, ``fastpath.dissipative.sticking``) after collision n is counted in ``stuck_n`` at every
n_j > n and in ``stuck_t`` at every t_j >= t_acc, and not in ``count_n`` / ``count_t`` there: its
velocity is the plate's. v(t) between collisions is the velocity of the last departure at or
before t: an impact's outgoing velocity, or after a sticking episode the detachment velocity
u(theta*) from t_detach on; during an episode (t_acc <= t < t_detach) it stays the last
impact's (~ the plate's velocity at t_acc, where the relative velocity has gone to 0).

Given a ``record`` array, each particle's v_n at the grid points of n_grid it reached is also
written into its row: the velocities of many orbits at collision counts
(``fastpath.dynamics.velocities``) are this loop's, with the sums left aside.

The particles are split into ``len(count_n)`` fixed blocks of consecutive indices, each with its
own row of sums, filled in particle order: the result is identical for any number of threads,
and the spread over blocks gives the statistical uncertainty.
"""

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.dissipative.carried import EPISODE, STUCK, VK, T, V
from fastpath.kernels.arrays import MomentSums
from fastpath.kernels.particle import detachment_of
from fastpath.kernels.records import particle_buffers, sampled_collision, start_particle
from fastpath.kernels.threads import over_threads
from fastpath.status import CONVERGED

NO_RECORD = np.empty((0, 0))  # moments_chunk keeps the sums only


def moments_chunk(physics, starts, grid, as_step, sample, sums, flags, record=NO_RECORD):
    """Fill the block sums ``sums`` (``arrays.MomentSums``, added to; the caller zeroes them)
    for the particles ``starts`` (module docstring). as_step: each collision is
    ``fastpath.step``'s (the runs' velocity scenes, audited by ``step``) or, False, an orbit's
    (``fastpath.kernels.particle``). Flags and sample as ``fastpath.kernels.escape``; a resumed
    particle (n > 0) starts at the grid point of its n, which is filled here. ``record``: an
    array (particles, len(grid.n)) that gets particle i's v_n in row i at the grid points it
    reaches (the others are left as they are), or ``NO_RECORD``."""
    m = len(starts.phi)
    per_block = (m + len(sums.collisions) - 1) // len(sums.collisions)
    detach = detachment_of(physics)

    def run_group(first_block, end_block):
        _moments_blocks(physics, (first_block, end_block, per_block, as_step), starts, grid,
                        sample, sums, flags, detach, record)

    over_threads(run_group, len(sums.collisions))


@jit
def _moments_blocks(physics, span, starts, grid, sample, sums, flags, detach, record):
    """Blocks first .. end-1 of ``moments_chunk``, span = (first, end, per_block, as_step)."""
    first, end, per_block, as_step = span
    m = len(starts.phi)
    for b in range(first, end):
        _moments_block(physics, (b, min(m, b * per_block), min(m, (b + 1) * per_block), as_step),
                       starts, grid, sample, sums, flags, detach, record)


@jit
def _add_n(sums, b, jn, n, v, start, n_grid, record, i):
    """Add v = v_n to the grid points n_grid[jn], ... equal to n (and to particle i's row of
    ``record``, if any); return the next jn."""
    while jn < len(n_grid) and n_grid[jn] == n:
        if len(record):
            record[i, jn] = v
        sums.count_n[b, jn] += 1
        sums.sum_v_n[b, jn] += v
        sums.sum_v2_n[b, jn] += v * v
        sums.sum_dv2_n[b, jn] += (v - start) * (v - start)
        jn += 1
    return jn


@jit
def _add_t(sums, b, jt, until, v, t_grid):
    """Add v to the time points t_grid[jt], ... below ``until``; return the next jt."""
    while jt < len(t_grid) and t_grid[jt] < until:
        sums.count_t[b, jt] += 1
        sums.sum_v_t[b, jt] += v
        jt += 1
    return jt


@jit
def _moments_block(physics, span, starts, grid, sample, sums, flags, detach, record):
    """Particles first .. last-1 into block b's rows, span = (b, first, last, as_step)."""
    b, first, last, as_step = span
    n_grid, t_grid = grid.n, grid.t
    kn, kt = len(n_grid), len(t_grid)
    n_last = n_grid[kn - 1] if kn > 0 else 0
    t_last = t_grid[kt - 1] if kt > 0 else -1.0
    state, carried = particle_buffers()
    motion = (as_step, detach, np.empty(0))
    done = 0
    for i in range(first, last):
        if not start_particle(state, physics, i, starts, flags, as_step):
            continue
        n, v, t = starts.n[i], starts.v[i], starts.t[i]
        start = v
        jn = _add_n(sums, b, np.searchsorted(n_grid, n), n, v, start, n_grid, record, i)
        jt = np.searchsorted(t_grid, t)
        while not ((n >= n_last and t > t_last) or n >= grid.max_collisions):
            status, _, kind, t_start, t_end = sampled_collision(state, physics, i, n, sample,
                                                                flags, carried, motion)
            if status != CONVERGED:
                break
            jt = _add_t(sums, b, jt, state[T], v, t_grid)  # t <= t_grid < t1: v(t) = v
            v, t = state[V], state[T]
            n += 1
            done += 1
            jn = _add_n(sums, b, jn, n, v, start, n_grid, record, i)
            if kind == STUCK:
                jt = _add_t(sums, b, jt, t_start, v, t_grid)
                for j in range(jn, kn):
                    sums.stuck_n[b, j] += 1
                for j in range(jt, kt):
                    sums.stuck_t[b, j] += 1
                break
            if kind == EPISODE:  # riding: the last impact's velocity; then the detachment's
                jt = _add_t(sums, b, jt, t_end, v, t_grid)
                v, t = state[VK], t_end
    sums.collisions[b] += done


class Moments:
    """Block sums of ``fastpath.moments`` with the grids; means and block-level views.

    Attributes: ``n_grid``, ``t_grid``; ``sums`` (``arrays.MomentSums``) and its block arrays
    ``count_n``, ``sum_v_n``, ``sum_v2_n``, ``sum_dv2_n``, ``count_t``, ``sum_v_t``, ``stuck_n``,
    ``stuck_t`` (rows = blocks; stuck: particles stuck for good before grid point n resp. time
    t, not in count_n/count_t, zeros without restitution < 1); ``collisions`` (total),
    ``flagged`` (particles stopped at an undecidable flight), ``model``, ``eps``.
    """

    def __init__(self, n_grid, t_grid, sums, flagged, model, eps):
        self.n_grid, self.t_grid, self.sums = n_grid, t_grid, sums
        self.collisions = int(sums.collisions.sum())
        self.flagged, self.model, self.eps = flagged, model, eps

    def __getattr__(self, name):
        if name in MomentSums._fields:
            return getattr(self.sums, name)
        raise AttributeError(name)

    @property
    def particles_n(self):
        return self.count_n.sum(axis=0)

    @property
    def particles_t(self):
        return self.count_t.sum(axis=0)

    @property
    def mean_v_n(self):
        """<v_n> at n_grid (NaN where no particle got there)."""
        return _ratio(self.sum_v_n.sum(axis=0), self.particles_n)

    @property
    def mean_v2_n(self):
        return _ratio(self.sum_v2_n.sum(axis=0), self.particles_n)

    @property
    def mean_dv2_n(self):
        """<(v_n - v_0)**2> at n_grid."""
        return _ratio(self.sum_dv2_n.sum(axis=0), self.particles_n)

    @property
    def mean_v_t(self):
        """<v(t)> at t_grid."""
        return _ratio(self.sum_v_t.sum(axis=0), self.particles_t)


def _ratio(num, den):
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, num / np.maximum(den, 1), np.nan)


__all__ = ["Moments", "moments_chunk"]
