"""Velocity moments of many orbits (Fermi acceleration, velocity diffusion), exact or Holmes.

Each particle i runs from (phi0[i], v0[i]) through the exact map (``model`` EXACT) or the Holmes
map (HOLMES, flight time 2*v). Only sums are kept, never the orbits:

* at the collision indices ``n_grid`` (sorted, >= 0): sum of v_n, of v_n**2 and of
  (v_n - v_0)**2 over the particles that reached collision n;
* at the times ``t_grid`` (sorted, >= 0): sum of v(t) = v_N with t_N <= t < t_{N+1}, the velocity
  just after the last collision at or before t, over the particles that reached time t.

A particle runs until it has passed both n_grid[-1] and t_grid[-1], or until ``max_collisions``
(then the later time points miss it: ``count_t`` says how many particles each point holds). An
exact flight float64 cannot decide (status UNCERTAIN or MAX_ITERATIONS, only for |eps| >= 1)
stops the particle: it is flagged (``flags[i]`` = the status) and contributes only to the grid
points it reached before; ``count_n`` records that.

The particles are split into ``len(count_n)`` fixed blocks of consecutive indices, each with its
own row of sums, filled in particle order: the result is identical for any number of threads,
and the spread over blocks gives the statistical uncertainty.
"""

import math

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import parallel_jit
from fastpath.arithmetic.phase import reduce_phase
from fastpath.elastic.collision import collide_from
from fastpath.elastic.flight import GENERAL
from fastpath.elastic.holmes import holmes_collide
from fastpath.inputs import count, float_inputs, physics
from fastpath.kernels.dissipative_moments import dissipative_moments_kernel
from fastpath.status import CONVERGED

EXACT = 0
HOLMES = 1
MODELS = {"exact": EXACT, "holmes": HOLMES}


@parallel_jit
def moments_kernel(phi0, v0, eps, model, n_grid, t_grid, max_collisions, count_n, sum_v_n,
                   sum_v2_n, sum_dv2_n, count_t, sum_v_t, collisions, flags):
    """Fill the block sums (added to; the caller zeroes them); see the module docstring.

    Shapes: ``count_n``, ``sum_*_n`` (blocks, len(n_grid)); ``count_t``, ``sum_v_t``
    (blocks, len(t_grid)); ``collisions`` (blocks,); ``flags`` (particles,).
    """
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    kn, kt = len(n_grid), len(t_grid)
    n_last = n_grid[kn - 1] if kn > 0 else 0
    t_last = t_grid[kt - 1] if kt > 0 else -1.0
    for b in prange(blocks):
        done = 0
        for i in range(b * per_block, min(m, (b + 1) * per_block)):
            phi = reduce_phase(phi0[i])
            v = v0[i]
            start = v
            sin_phi, cos_phi = math.sin(phi), math.cos(phi)
            t = 0.0
            n = 0
            jn = 0
            jt = 0
            flags[i] = 0
            while True:
                while jn < kn and n_grid[jn] == n:
                    count_n[b, jn] += 1
                    sum_v_n[b, jn] += v
                    sum_v2_n[b, jn] += v * v
                    sum_dv2_n[b, jn] += (v - start) * (v - start)
                    jn += 1
                if (n >= n_last and t > t_last) or n >= max_collisions:
                    break
                if model == HOLMES:
                    phi1, v1 = holmes_collide(phi, v, eps)
                    tau = 2.0 * v
                else:
                    # GENERAL as fastpath.orbit: the same collisions, bit for bit
                    phi1, sin_phi, cos_phi, v1, tau, _, status = collide_from(
                        phi, sin_phi, cos_phi, v, eps, GENERAL)
                    if status != CONVERGED:
                        flags[i] = status
                        break
                t1 = t + tau
                while jt < kt and t_grid[jt] < t1:  # t <= t_grid[jt] < t1: v(t) = v
                    count_t[b, jt] += 1
                    sum_v_t[b, jt] += v
                    jt += 1
                phi, v, t = phi1, v1, t1
                n += 1
                done += 1
        collisions[b] += done


class Moments:
    """Block sums of ``moments`` with the grids; means and block-level views.

    Attributes: ``n_grid``, ``t_grid``; block arrays ``count_n``, ``sum_v_n``, ``sum_v2_n``,
    ``sum_dv2_n``, ``count_t``, ``sum_v_t`` (rows = blocks); ``collisions`` (total) and
    ``flagged`` (particles stopped at an undecidable flight); ``stuck_n``, ``stuck_t`` (rows =
    blocks): particles stuck for good before grid point n resp. time t, not in count_n/count_t
    (``fastpath.dissipative_moments``; zeros for the elastic, drag-free physics).
    """

    def __init__(self, n_grid, t_grid, count_n, sum_v_n, sum_v2_n, sum_dv2_n, count_t,
                 sum_v_t, collisions, flagged, model, eps, stuck_n=None, stuck_t=None):
        self.n_grid, self.t_grid = n_grid, t_grid
        self.count_n, self.sum_v_n, self.sum_v2_n = count_n, sum_v_n, sum_v2_n
        self.sum_dv2_n, self.count_t, self.sum_v_t = sum_dv2_n, count_t, sum_v_t
        self.collisions, self.flagged, self.model, self.eps = collisions, flagged, model, eps
        self.stuck_n = np.zeros_like(count_n) if stuck_n is None else stuck_n
        self.stuck_t = np.zeros_like(count_t) if stuck_t is None else stuck_t

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


def moments(phi0, v0, eps, n_grid, t_grid=(), model="exact", blocks=64, max_collisions=None,
            *, drag=0.0, drag_law="linear", restitution=1.0):
    """Velocity moments of the orbits from (phi0[i], v0[i]) at collision indices ``n_grid`` and
    times ``t_grid``: a ``Moments``. ``blocks`` (at most; fewer if some would be empty) fixes
    the partition of the particles (not the threads: any thread count gives the same numbers).
    ``max_collisions`` caps each orbit (default: 100 * n_grid[-1] + 10**6 when a time grid is
    given, else n_grid[-1]).

    drag, drag_law, restitution: as for ``fastpath.orbit`` (model "exact" only); the defaults
    run ``moments_kernel`` unchanged, any other physics ``fastpath.dissipative_moments`` (with
    ``stuck_n``, ``stuck_t``).

    Raises ValueError for non-finite inputs, non-departing starts (v0 + eps*sin(phi0) <= 0),
    unsorted or negative grids, an unknown model, bad physics keywords.
    """
    drag, law, restitution = physics(drag, drag_law, restitution)
    dissipative = drag != 0.0 or restitution != 1.0
    if dissipative and model != "exact":
        raise ValueError(f"drag or restitution < 1 needs model='exact', got model={model!r}")
    (phi_a, v_a), _, _ = float_inputs(phi0=phi0, v0=v0)
    (eps_a,), _, scalar = float_inputs(eps=eps)
    if not scalar:
        raise ValueError(f"eps must be a scalar, got shape {np.shape(eps)}")
    eps = float(eps_a[0])
    if model not in MODELS:
        raise ValueError(f"model must be 'exact' or 'holmes', got {model!r}")
    bad = np.flatnonzero(~(v_a + eps * np.sin(phi_a) > 0.0))
    if len(bad):
        i = int(bad[0])
        raise ValueError(f"start {i} (phi0={phi_a[i]!r}, v0={v_a[i]!r}) does not depart:"
                         f" v0 + eps*sin(phi0) <= 0 at eps={eps!r}")
    n_grid = np.asarray(n_grid, dtype=np.int64).ravel()
    t_grid = np.asarray(t_grid, dtype=np.float64).ravel()
    for name, grid in (("n_grid", n_grid), ("t_grid", t_grid)):
        if len(grid) and (np.any(np.diff(grid) < 0) or grid[0] < 0
                          or not np.all(np.isfinite(grid))):
            raise ValueError(f"{name} must be finite, >= 0 and sorted, got {grid!r}")
    if not len(n_grid) and not len(t_grid):
        raise ValueError("give n_grid and/or t_grid")
    blocks = max(1, min(count("blocks", blocks, 1), len(phi_a)))
    per_block = -(-len(phi_a) // blocks)
    blocks = -(-len(phi_a) // per_block)  # no empty block
    if max_collisions is None:
        n_last = int(n_grid[-1]) if len(n_grid) else 0
        max_collisions = 100 * n_last + 10**6 if len(t_grid) else n_last
    max_collisions = count("max_collisions", max_collisions)
    kn, kt = len(n_grid), len(t_grid)
    count_n = np.zeros((blocks, kn), np.int64)
    sums_n = [np.zeros((blocks, kn)) for _ in range(3)]
    count_t, sum_v_t = np.zeros((blocks, kt), np.int64), np.zeros((blocks, kt))
    collisions = np.zeros(blocks, np.int64)
    flags = np.zeros(len(phi_a), np.int8)
    if not dissipative:
        moments_kernel(phi_a, v_a, eps, MODELS[model], n_grid, t_grid, max_collisions, count_n,
                       *sums_n, count_t, sum_v_t, collisions, flags)
        return Moments(n_grid, t_grid, count_n, *sums_n, count_t, sum_v_t,
                       int(collisions.sum()), int(np.count_nonzero(flags)), model, eps)
    stuck_n, stuck_t = np.zeros_like(count_n), np.zeros_like(count_t)
    dissipative_moments_kernel(phi_a, v_a, eps, drag, law, restitution, n_grid, t_grid,
                               max_collisions, count_n, *sums_n, count_t, sum_v_t, stuck_n,
                               stuck_t, collisions, flags)
    return Moments(n_grid, t_grid, count_n, *sums_n, count_t, sum_v_t, int(collisions.sum()),
                   int(np.count_nonzero(flags)), model, eps, stuck_n, stuck_t)


__all__ = ["EXACT", "HOLMES", "Moments", "moments", "moments_kernel"]
