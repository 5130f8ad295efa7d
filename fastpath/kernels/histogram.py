"""Histogram bins and the holes of the escape kernels.

Only counts are kept: bin k holds values x with edges[k] <= x < edges[k+1], the last bin is
open above, values below edges[0] go to bin 0. A hole is the arc [lo, lo + width) mod 2*pi with
lo in [0, 2*pi), so holes centred at 0 wrap: phi is inside iff ((phi - lo) mod 2*pi) < width.
"""

import numpy as np

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.phase import TWO_PI
from fastpath.arithmetic.rounding import select, two_sum


@jit
def bin_index(edges, x):
    """k with edges[k] <= x < edges[k+1] (last bin open above, values below edges[0] -> 0; NaN
    in the last bin). ``np.searchsorted(edges, x, side="right") - 1`` as a plain bisection:
    numba's searchsorted compiles comparisons for every dtype, seconds on first use."""
    lo, hi = 0, len(edges)
    while lo < hi:
        mid = (lo + hi) // 2
        if edges[mid] > x:
            hi = mid
        else:  # edges[mid] <= x, or x is NaN (sorted last, as numpy does)
            lo = mid + 1
    return max(lo - 1, 0)


def log_edges(lo, decades, per_decade, integer=False):
    """Lower bin edges lo*10**(k/per_decade), k = 0..decades*per_decade (rounded and
    deduplicated when ``integer``), as float64."""
    k = np.arange(decades * per_decade + 1)
    edges = lo * 10.0 ** (k / per_decade)
    if integer:
        edges = np.unique(np.round(edges))
    return edges.astype(np.float64)


@jit
def exit_hole(phi, hole_lo, hole_width):
    """Index of the hole containing the reduced phase phi in [0, 2*pi), or -1.

    Hole j is the arc [hole_lo[j], hole_lo[j] + hole_width[j]) mod 2*pi: phi is in it when
    d = (phi - lo) mod 2*pi < width. d is carried as an unevaluated sum d_hi + d_lo (two_sum),
    so the comparison is exact to O(u**2) even where the hole wraps through 2*pi; rounding
    (phi - lo) + 2*pi first misplaces phases up to ~14 ulps from the wrapped upper edge.
    """
    for j in range(len(hole_lo)):
        if in_hole(phi, hole_lo[j], hole_width[j]):
            return j
    return -1


@inline_jit
def in_hole(phi, lo, width):
    """phi in [0, 2*pi) lies in the arc [lo, lo + width) mod 2*pi (``exit_hole``), with selects
    instead of branches (also used in the vectorised loop of the lanes)."""
    d_hi, d_lo = two_sum(phi, -lo)
    wrapped, carry = two_sum(d_hi, TWO_PI)
    wraps = d_hi < 0.0
    d_hi = select(wraps, wrapped, d_hi)
    d_lo = select(wraps, d_lo + carry, d_lo)
    return (d_hi - width) + d_lo < 0.0


@jit
def record(bins, row_n, row_t, n, t):
    """Count one particle with index n and time t into the histogram rows row_n, row_t (those
    of its block, and hole), on the clocks that ``bins`` records."""
    if bins.record_n:
        row_n[bin_index(bins.n_edges, n)] += 1
    if bins.record_t:
        row_t[bin_index(bins.t_edges, t)] += 1


@jit
def censor(counts, bins, b, n, t):
    """A particle censored with index bound n and time bound t, into block b's row."""
    record(bins, counts.cens_n[b], counts.cens_t[b], n, t)


@jit
def escape(counts, bins, b, j, n, t):
    """A particle escaped through hole j at collision n, time t, into block b's row."""
    record(bins, counts.esc_n[b, j], counts.esc_t[b, j], n, t)


@jit
def stuck(counts, bins, b, n, t):
    """A particle stuck on the plate for good after collision n, from time t."""
    record(bins, counts.stuck_n[b], counts.stuck_t[b], n, t)
