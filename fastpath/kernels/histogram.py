"""Histogram bins and the holes of the escape kernels.

Only counts are kept: bin k holds values x with edges[k] <= x < edges[k+1], the last bin is
open above, values below edges[0] go to bin 0. A hole is the arc [lo, lo + width) mod 2*pi with
lo in [0, 2*pi), so holes centred at 0 wrap: phi is inside iff ((phi - lo) mod 2*pi) < width.

``escape``, ``censor`` and ``stuck`` also append the particle's joint (n, t) bin to the joint
record (``record_end``) when the kernel is given ``arrays.JointCounts``; with
``arrays.EscapeCounts`` they compile to ``record`` alone, as before.
"""

import decimal

import numpy as np
from numba.extending import overload

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.phase import TWO_PI
from fastpath.arithmetic.rounding import select, two_sum
from fastpath.kernels.arrays import JointCounts


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
    """Lower bin edges lo*10**(k/per_decade), k = 0..decades*per_decade (rounded to integers and
    deduplicated when ``integer``), as float64.

    Each edge is the float64 nearest the exact value, from 50-digit decimal arithmetic, so the
    edges are the same on every machine (a vectorised ``10.0 ** x`` differs between CPUs in the
    last bit, and a run's counts are audited against the edges they were binned with).
    """
    with decimal.localcontext() as context:
        context.prec = 50
        scale = decimal.Decimal(lo)  # the float's exact value
        edges = np.array([float(scale * decimal.Decimal(10) ** (decimal.Decimal(k) / per_decade))
                          for k in range(decades * per_decade + 1)], dtype=np.float64)
    if integer:
        edges = np.unique(np.round(edges))
    return edges


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
def joint_code(bins, outcome, k_n, k_t):
    """The code of the joint bin (outcome, k_n, k_t) of a particle's end (``JointCounts``)."""
    return (outcome * len(bins.n_edges) + k_n) * len(bins.t_edges) + k_t


@jit
def append_joint(counts, b, code):
    """Append a particle's joint bin ``code`` to row b of the joint record
    (``arrays.JointCounts``). A row holds as many entries as its block has particles: a further
    one is not stored but counted (``ended``), so that the caller sees it
    (``arrays.joint_histogram`` refuses it)."""
    k = counts.ended[b]
    if k < counts.ends.shape[1]:
        counts.ends[b, k] = code
    counts.ended[b] = k + 1


def record_end(counts, bins, b, row_n, row_t, outcome, n, t):
    """A particle of block b ended with ``outcome`` (hole j, censored = holes, stuck =
    holes + 1) at index n and time t: counted into the rows row_n, row_t (``record``) and, if
    ``counts`` is ``arrays.JointCounts`` (a scene that records the joint histogram), appended
    to the joint record with the same two bins."""
    if isinstance(counts, JointCounts):
        record_with_joint(counts, bins, b, row_n, row_t, outcome, n, t)
    else:
        record(bins, row_n, row_t, n, t)


def record_with_joint(counts, bins, b, row_n, row_t, outcome, n, t):
    """``record_end`` with ``arrays.JointCounts``: each bin index found once for the rows and
    the joint record (Python, and the compiled implementation of ``record_end``)."""
    k_n, k_t = bin_index(bins.n_edges, n), bin_index(bins.t_edges, t)
    if bins.record_n:
        row_n[k_n] += 1
    if bins.record_t:
        row_t[k_t] += 1
    append_joint(counts, b, joint_code(bins, outcome, k_n, k_t))


@overload(record_end)
def _record_end_compiled(counts, bins, b, row_n, row_t, outcome, n, t):
    """The compiled ``record_end``, chosen by the class of ``counts`` when the kernel is
    compiled: with ``EscapeCounts`` it is ``record`` alone, so such a kernel carries no trace of
    the joint record; with ``JointCounts`` each bin index is found once for both."""
    if counts.instance_class is not JointCounts:
        return lambda counts, bins, b, row_n, row_t, outcome, n, t: record(bins, row_n, row_t,
                                                                           n, t)
    return record_with_joint


@jit
def censor(counts, bins, b, n, t):
    """A particle censored with index bound n and time bound t, into block b's row."""
    record_end(counts, bins, b, counts.cens_n[b], counts.cens_t[b], counts.esc_n.shape[1], n, t)


@jit
def escape(counts, bins, b, j, n, t):
    """A particle escaped through hole j at collision n, time t, into block b's row."""
    record_end(counts, bins, b, counts.esc_n[b, j], counts.esc_t[b, j], j, n, t)


@jit
def stuck(counts, bins, b, n, t):
    """A particle stuck on the plate for good after collision n, from time t."""
    record_end(counts, bins, b, counts.stuck_n[b], counts.stuck_t[b], counts.esc_n.shape[1] + 1,
               n, t)
