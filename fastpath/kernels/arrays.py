"""The named groups of arrays that the ensemble kernels take and fill.

A kernel call passes a handful of these instead of two dozen arrays in a fixed order: each group
is built by keyword (``Starts(phi=..., v=..., t=..., n=...)``), so two arrays of the same type
cannot change places unnoticed. Counts are kept per block of particles (rows b = 0 .. blocks-1:
fixed sets of consecutive particles, each filled in particle order), which makes every result
the same for any number of threads; the caller sums the rows.
"""

from typing import NamedTuple

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.dissipative.carried import CARRIED
from fastpath.status import STATUS_DTYPE

NO_LIMIT = np.int64(2**62)  # max_collisions when the horizon is a time only
SAMPLE_FIELDS = ("n", "phi", "v", "phi1", "v1", "tau")  # a sample row; then CARRIED (r < 1)
FLAG_FIELDS = ("phi", "v", "t", "n")


class Starts(NamedTuple):
    """The particles: departure phase, velocity and time, and collisions made before (int64)."""

    phi: np.ndarray
    v: np.ndarray
    t: np.ndarray
    n: np.ndarray


class Holes(NamedTuple):
    """Hole j is the arc [lo[j], lo[j] + width[j]) mod 2*pi, lo in [0, 2*pi)."""

    lo: np.ndarray
    width: np.ndarray


class Horizon(NamedTuple):
    """A particle is censored before a collision of index > max_collisions or time > max_time."""

    max_collisions: int
    max_time: float


class Bins(NamedTuple):
    """Lower bin edges of the collision index and of the time (``histogram.bin_index``); which of
    the two clocks are recorded."""

    n_edges: np.ndarray
    t_edges: np.ndarray
    record_n: bool
    record_t: bool


class EscapeCounts(NamedTuple):
    """Histograms per block b: escapes through hole j with index / time in bin k
    (``esc_n[b, j, k]``, ``esc_t[b, j, k]``), censoring bounds (``cens_n[b, k]``,
    ``cens_t[b, k]``), particles stuck on the plate for good (``stuck_n``, ``stuck_t``: by the
    index of the impact after which the tail was summed, and by the accumulation time), and the
    collisions simulated (``collisions[b]``)."""

    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    stuck_n: np.ndarray
    stuck_t: np.ndarray
    collisions: np.ndarray

    @classmethod
    def zeros(cls, blocks, holes, n_bins, t_bins):
        def counts(*shape):
            return np.zeros(shape, np.int64)

        return cls(counts(blocks, holes, n_bins), counts(blocks, holes, t_bins),
                   counts(blocks, n_bins), counts(blocks, t_bins), counts(blocks, n_bins),
                   counts(blocks, t_bins), counts(blocks))


class JointCounts(NamedTuple):
    """``EscapeCounts`` (the same fields, filled the same way) and the joint record of (n, t):
    every particle of block b that ends (escapes, is censored or sticks) appends the code

        (outcome * n_bins + k_n) * t_bins + k_t

    to row b of ``ends`` (``ended[b]`` entries so far; a row holds the block's particles),
    outcome j < holes for an escape through hole j, holes for censored, holes + 1 for stuck,
    k_n and k_t its bins of the two clocks (``histogram.record_end``). The caller counts the
    codes (``joint_histogram``): a histogram does not depend on the order within a row, so the
    result is the same for any threads. A separate class, so that a kernel called with
    ``EscapeCounts`` compiles without the record (``histogram.record_end`` is then ``record``)."""

    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    stuck_n: np.ndarray
    stuck_t: np.ndarray
    collisions: np.ndarray
    ends: np.ndarray
    ended: np.ndarray

    @classmethod
    def zeros(cls, blocks, per_block, holes, n_bins, t_bins):
        """Zero counts of ``blocks`` blocks of at most ``per_block`` particles."""
        return cls(*EscapeCounts.zeros(blocks, holes, n_bins, t_bins),
                   np.zeros((blocks, per_block), np.int64), np.zeros(blocks, np.int64))


def joint_histogram(counts, n_bins, t_bins):
    """The joint record of ``counts`` (``JointCounts``) as counts[outcome, k_n, k_t], outcomes
    0 .. holes + 1 (``JointCounts``). ValueError if a block recorded more ends than it holds
    particles (``histogram.append_joint`` drops those: a particle ended twice)."""
    holes = counts.esc_n.shape[1]
    capacity = counts.ends.shape[1]
    if np.any(counts.ended > capacity):
        raise ValueError(f"a block of at most {capacity} particles recorded"
                         f" {int(counts.ended.max())} ends")
    codes = np.concatenate([row[:k] for row, k in zip(counts.ends, counts.ended, strict=True)])
    size = (holes + 2) * n_bins * t_bins
    counts = np.bincount(codes, minlength=size).astype(np.int64, copy=False)
    return counts.reshape(holes + 2, n_bins, t_bins)


class Sample(NamedTuple):
    """The verification sample: particle i with ``slot[i] = s >= 0`` stores in ``rows[s]`` the
    departure and result (``SAMPLE_FIELDS``, then the carried state if rows has the columns and
    r < 1) of its collision n = min(``target[i]``, the last collision it made)."""

    slot: np.ndarray
    target: np.ndarray
    rows: np.ndarray

    @classmethod
    def none(cls, particles):
        """No particle sampled."""
        return cls(np.full(particles, -1, np.int64), np.zeros(particles, np.int64),
                   np.zeros((0, len(SAMPLE_FIELDS))))


class Flags(NamedTuple):
    """``status[i]``: the FlightStatus of the flight that stopped particle i undecided (0 if
    none), ``state[i]`` its departure (``FLAG_FIELDS``), for the caller to settle and resume."""

    status: np.ndarray
    state: np.ndarray

    @classmethod
    def zeros(cls, particles):
        return cls(np.zeros(particles, STATUS_DTYPE), np.zeros((particles, len(FLAG_FIELDS))))


class Portrait(NamedTuple):
    """``counts[b, p, q]``: collision states with phi in bin p of [0, 2*pi) and v in bin q of
    [v_lo, v_hi) (uniform bins; states outside are not counted); ``collisions[b]``."""

    v_lo: float
    v_hi: float
    counts: np.ndarray
    collisions: np.ndarray


class MomentGrid(NamedTuple):
    """Collision indices ``n`` and times ``t`` (sorted int64, float64) where moments are taken;
    a particle runs until it has passed both grids, at most ``max_collisions`` collisions."""

    n: np.ndarray
    t: np.ndarray
    max_collisions: int


class MomentSums(NamedTuple):
    """Block sums at the grid points (rows = blocks): particles that reached collision n_j
    (``count_n``) and their sums of v_n, v_n**2, (v_n - v_0)**2; particles that reached time
    t_j (``count_t``) and their sum of v(t); particles stuck for good before n_j / t_j
    (``stuck_n``, ``stuck_t``, not in the counts); ``collisions[b]``."""

    count_n: np.ndarray
    sum_v_n: np.ndarray
    sum_v2_n: np.ndarray
    sum_dv2_n: np.ndarray
    count_t: np.ndarray
    sum_v_t: np.ndarray
    stuck_n: np.ndarray
    stuck_t: np.ndarray
    collisions: np.ndarray

    @classmethod
    def zeros(cls, blocks, n_points, t_points):
        return cls(np.zeros((blocks, n_points), np.int64), np.zeros((blocks, n_points)),
                   np.zeros((blocks, n_points)), np.zeros((blocks, n_points)),
                   np.zeros((blocks, t_points), np.int64), np.zeros((blocks, t_points)),
                   np.zeros((blocks, n_points), np.int64), np.zeros((blocks, t_points), np.int64),
                   np.zeros(blocks, np.int64))


class OrbitArrays(NamedTuple):
    """An orbit's arrays: phi, v, t (length n + 1), iterations (length n), sticking rows
    (t_start, t_end) (at most n + 1)."""

    phi: np.ndarray
    v: np.ndarray
    t: np.ndarray
    iterations: np.ndarray
    sticking: np.ndarray

    @classmethod
    def empty(cls, n):
        return cls(np.empty(n + 1), np.empty(n + 1), np.empty(n + 1), np.zeros(n, np.int32),
                   np.empty((n + 1, 2)))


@jit
def keeps_carried(rows, restitution):
    """Whether sample rows get the carried state after the six fields (r < 1 and the columns)."""
    return rows.shape[1] >= len(SAMPLE_FIELDS) + len(CARRIED) and restitution < 1.0
