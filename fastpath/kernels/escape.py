"""Ensemble kernels: many starts through the exact map, recording only histograms.

Escape and transport (the seed's Sections 3 and 4). Each particle runs ``collide`` from its
start (n = 0, t = 0 is never tested against the holes) until

* collision n = 1, 2, ... lands at a phase phi_n (mod 2*pi) inside a hole j: it escapes through
  hole j with escape index N = n and escape time T = t_n = tau_0 + ... + tau_{n-1};
* the horizon: the next collision would have index n > ``max_collisions`` or time
  t > ``max_time``: it is censored, and we know only N > n and T > t (the last known bound);
* a flight that float64 cannot decide (status UNCERTAIN or MAX_ITERATIONS, only for |eps| > 1,
  or NOT_DEPARTING at a graze): the particle is flagged with its state (phi, v, t, n) and
  stops; the driver settles that collision with ``verify`` and resumes it here.

A hole is the arc [lo, lo + width) mod 2*pi with lo in [0, 2*pi), so holes centred at 0 wrap:
phi is inside iff ((phi - lo) mod 2*pi) < width.

Only counts are kept: for each hole the histograms of N and T in the caller's fixed bins
(bin k holds values x with edges[k] <= x < edges[k+1], the last bin is open, values below
edges[0] go to bin 0), and the histograms of the censoring bounds. The particles of a chunk are
split into a fixed number of blocks, each with its own histogram rows; the caller sums them.
Integer counts make the sum, hence the result, identical for any number of threads, and the
memory is set by the chunk and the bins, not by the number of particles.

Verification sample: particle i with ``sample_slot[i] = s >= 0`` stores, in ``samples[s]``, the
pre-collision state and fast result (n, phi, v, phi1, v1, tau) of its collision
n = min(``sample_target[i]``, last collision it made in this kernel).
"""


import numpy as np
from numba import get_num_threads, prange

from fastpath.arithmetic.jit import inline_jit, jit, parallel_jit
from fastpath.arithmetic.phase import MODERATE_LIMIT, TWO_PI, centre_moderate, reduce_moderate
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, select, two_sum
from fastpath.arithmetic.sincos import sin_cos, sin_cos_error
from fastpath.elastic.collision import collide
from fastpath.elastic.flight import GENERAL, departure_phase
from fastpath.elastic.holmes import holmes_collide
from fastpath.elastic.lockstep import lockstep_collide
from fastpath.status import CONVERGED

NO_LIMIT = np.int64(2**62)  # max_collisions when the horizon is a time only
LANES = 64  # particles in flight together in a group (a multiple of the vector width)
SAMPLE_FIELDS = ("n", "phi", "v", "phi1", "v1", "tau")
FLAG_FIELDS = ("phi", "v", "t", "n")


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
def bin_index(edges, x):
    """k with edges[k] <= x < edges[k+1] (last bin open above, values below edges[0] -> 0)."""
    k = np.searchsorted(edges, x, side="right") - 1
    return max(k, 0)


@jit
def _store_sample(samples, s, n, phi, v, phi1, v1, tau):
    samples[s, 0] = n
    samples[s, 1] = phi
    samples[s, 2] = v
    samples[s, 3] = phi1
    samples[s, 4] = v1
    samples[s, 5] = tau


@jit
def _flag(flags, flag_state, i, status, phi, v, t, n):
    flags[i] = status
    flag_state[i, 0] = phi
    flag_state[i, 1] = v
    flag_state[i, 2] = t
    flag_state[i, 3] = n


@jit
def _load(i, lane, phi0, v0, t0, n0, sample_slot, sample_target, flags, idx, phi, centred,
          phase_error, v, t, n, slot, target):
    """Put particle i into a lane: its state and where its flight starts."""
    idx[lane] = i
    phi[lane], v[lane], t[lane], n[lane] = phi0[i], v0[i], t0[i], n0[i]
    slot[lane], target[lane] = sample_slot[i], sample_target[i]
    flags[i] = 0
    centred[lane], phase_error[lane] = departure_phase(phi[lane])


@inline_jit
def lane_collide(centred, v, eps, phase_error):
    """``collide`` from a centred phase in straight-line code, for the common flight:
    (tau, phi1, v1, centred phi1, its phase error for the next flight, answered).

    The same arithmetic as ``collide`` -> ``collide_from`` -> ``flight_from`` ->
    ``lockstep_flight`` -> reduce_phase / centre_phase (their moderate ranges); answered False
    where collide would do anything else (then the caller calls it).
    """
    s, c = sin_cos(centred)
    tau, sin1, _, _, answered = lockstep_collide(centred, s, c, v, eps, phase_error)
    x = centred + tau
    phi1 = reduce_moderate(x)
    centred1 = centre_moderate(phi1)
    phase_error1 = select(centred1 == phi1, 0.0, 2.0 * UNIT_ROUNDOFF * abs(centred1))
    v1 = tau - v - 2.0 * eps * sin1
    return (tau, phi1, v1, centred1, phase_error1 + sin_cos_error(centred1),
            answered and abs(x) < MODERATE_LIMIT)


def escape_chunk(phi0, v0, t0, n0, eps, hole_lo, hole_width, max_collisions, max_time,
                 n_edges, t_edges, record_n, record_t, sample_slot, sample_target,
                 esc_n, esc_t, cens_n, cens_t, collisions, flags, flag_state, samples):
    """Run the particles (phi0[i], v0[i]) at time t0[i] after n0[i] collisions to their exit.

    Outputs (added to; the caller zeroes them): ``esc_n[b, j, k]`` / ``esc_t[b, j, k]`` escapes
    through hole j with N / T in bin k, ``cens_n[b, k]`` / ``cens_t[b, k]`` censoring bounds,
    ``collisions[b]`` collisions simulated, for block b = 0 .. len(collisions)-1;
    ``flags[i]`` the status of an undecided flight (0 if none) with ``flag_state[i]`` =
    (phi, v, t, n) before it; ``samples`` as in the module docstring.

    Each block keeps LANES particles in flight together: the flights of all lanes in one
    vectorised loop (``fastpath.lockstep``), then the bookkeeping lane by lane, a finished
    particle's lane taking the block's next one. A lane the lockstep flight does not answer
    gets ``collide``, whose answer is the same function of the departure: every particle's
    collisions are those of ``fastpath.step`` whatever the lanes, blocks or threads.

    Groups of whole blocks share lanes, one group per thread: a group ends with its last
    long-lived particles in half-empty lanes, so the fewer groups the less of that (16 groups
    of the 2^16 starts of a seed's chunk cost 7% more per collision than one, on one thread).
    A particle counts into its own block's row, so the grouping, like the threads, changes no
    number: it only spreads the work.
    """
    _escape_groups(phi0, v0, t0, n0, eps, hole_lo, hole_width, max_collisions, max_time,
                   n_edges, t_edges, record_n, record_t, sample_slot, sample_target, esc_n,
                   esc_t, cens_n, cens_t, collisions, flags, flag_state, samples,
                   get_num_threads())


@parallel_jit
def _escape_groups(phi0, v0, t0, n0, eps, hole_lo, hole_width, max_collisions, max_time,
                   n_edges, t_edges, record_n, record_t, sample_slot, sample_target, esc_n,
                   esc_t, cens_n, cens_t, collisions, flags, flag_state, samples, groups):
    """``escape_chunk`` in ``groups`` groups of blocks (at least 1, at most one per block)."""
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    groups = max(1, min(blocks, groups))
    per_group = (blocks + groups - 1) // groups
    for g in prange(groups):
        _escape_lanes(
            per_block, min(m, g * per_group * per_block), min(m, (g + 1) * per_group * per_block),
            phi0, v0, t0, n0, eps, hole_lo, hole_width, max_collisions, max_time, n_edges,
            t_edges, record_n, record_t, sample_slot, sample_target, esc_n, esc_t, cens_n,
            cens_t, collisions, flags, flag_state, samples)


@jit
def _escape_lanes(per_block, first, end, phi0, v0, t0, n0, eps, hole_lo, hole_width,
                  max_collisions, max_time, n_edges, t_edges, record_n, record_t, sample_slot,
                  sample_target, esc_n, esc_t, cens_n, cens_t, collisions, flags, flag_state,
                  samples):
    """Particles first .. end-1 of ``escape_chunk`` (whole blocks of per_block) in lanes."""
    idx = np.empty(LANES, np.int64)
    phi, centred, phase_error = np.empty(LANES), np.empty(LANES), np.empty(LANES)
    v, t, n = np.empty(LANES), np.empty(LANES), np.empty(LANES, np.int64)
    slot, target = np.empty(LANES, np.int64), np.empty(LANES, np.int64)
    tau, phi1, v1 = np.empty(LANES), np.empty(LANES), np.empty(LANES)
    centred1, phase_error1 = np.empty(LANES), np.empty(LANES)
    answered = np.empty(LANES, np.bool_)
    hole, block = np.empty(LANES, np.int64), np.empty(LANES, np.int64)
    active = max(min(LANES, end - first), 0)
    for lane in range(active):
        _load(first + lane, lane, phi0, v0, t0, n0, sample_slot, sample_target, flags, idx, phi,
              centred, phase_error, v, t, n, slot, target)
        block[lane] = (first + lane) // per_block
    following = first + active
    while active > 0:
        for lane in range(active):  # vectorised: no calls, no branches but selects
            tau[lane], phi1[lane], v1[lane], centred1[lane], phase_error1[lane], answered[lane] = (
                lane_collide(centred[lane], v[lane], eps, phase_error[lane]))
        for lane in range(active):
            hole[lane] = -1
        for h in range(len(hole_lo)):  # exit_hole of every lane, vectorised over the lanes
            lo_h, width_h = hole_lo[h], hole_width[h]
            for lane in range(active):
                hole[lane] = select(hole[lane] < 0 and in_hole(phi1[lane], lo_h, width_h), h,
                                     hole[lane])
        idle = False
        for lane in range(active):
            i = idx[lane]
            b = block[lane]
            finished = False
            if n[lane] >= max_collisions:
                if record_n:
                    cens_n[b, bin_index(n_edges, n[lane])] += 1
                if record_t:
                    cens_t[b, bin_index(t_edges, t[lane])] += 1
                finished = True
            else:
                if answered[lane]:
                    phi1_l, v1_l, tau_l, status = phi1[lane], v1[lane], tau[lane], CONVERGED
                else:  # what the lanes do not answer: collide's general path, the same function
                    phi1_l, v1_l, tau_l, _, status = collide(phi[lane], v[lane], eps, GENERAL)
                    centred1[lane], phase_error1[lane] = departure_phase(phi1_l)
                t1 = t[lane] + tau_l
                if status != CONVERGED:
                    _flag(flags, flag_state, i, status, phi[lane], v[lane], t[lane], n[lane])
                    finished = True
                elif t1 > max_time:
                    if record_n:
                        cens_n[b, bin_index(n_edges, n[lane])] += 1
                    if record_t:
                        cens_t[b, bin_index(t_edges, t1)] += 1
                    finished = True
                else:
                    n[lane] += 1
                    collisions[b] += 1
                    if slot[lane] >= 0 and n[lane] <= target[lane]:
                        _store_sample(samples, slot[lane], n[lane], phi[lane], v[lane], phi1_l,
                                      v1_l, tau_l)
                    phi[lane], v[lane], t[lane] = phi1_l, v1_l, t1
                    j = hole[lane] if answered[lane] else exit_hole(phi1_l, hole_lo, hole_width)
                    if j >= 0:
                        if record_n:
                            esc_n[b, j, bin_index(n_edges, n[lane])] += 1
                        if record_t:
                            esc_t[b, j, bin_index(t_edges, t1)] += 1
                        finished = True
                    else:
                        centred[lane], phase_error[lane] = centred1[lane], phase_error1[lane]
            if finished:
                if following < end:
                    _load(following, lane, phi0, v0, t0, n0, sample_slot, sample_target,
                          flags, idx, phi, centred, phase_error, v, t, n, slot, target)
                    block[lane] = following // per_block
                    following += 1
                else:
                    idx[lane] = -1
                    idle = True
        if idle:  # the block's last particles: move the lanes still in flight to the front
            busy = 0
            for lane in range(active):
                if idx[lane] >= 0:
                    idx[busy], phi[busy], centred[busy] = idx[lane], phi[lane], centred[lane]
                    phase_error[busy], v[busy], t[busy] = phase_error[lane], v[lane], t[lane]
                    n[busy], slot[busy], target[busy] = n[lane], slot[lane], target[lane]
                    block[busy] = block[lane]
                    busy += 1
            active = busy


@parallel_jit
def holmes_escape_chunk(phi0, v0, eps, hole_lo, hole_width, max_collisions, max_time,
                        n_edges, t_edges, esc_n, esc_t, cens_n, cens_t, collisions):
    """``escape_chunk`` with the Holmes map (flight time 2*v) instead of the exact map: the bare
    loop the benchmark compares with (same starts, holes, horizon, bins and blocks; no
    verification sample, no flags: the Holmes map has no undecidable flight)."""
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    for b in prange(blocks):
        done = 0
        for i in range(b * per_block, min(m, (b + 1) * per_block)):
            phi, v, t, n = phi0[i], v0[i], 0.0, 0
            while True:
                if n >= max_collisions:
                    cens_n[b, bin_index(n_edges, n)] += 1
                    cens_t[b, bin_index(t_edges, t)] += 1
                    break
                t1 = t + 2.0 * v
                if t1 > max_time:
                    cens_n[b, bin_index(n_edges, n)] += 1
                    cens_t[b, bin_index(t_edges, t1)] += 1
                    break
                phi, v = holmes_collide(phi, v, eps)
                t = t1
                n += 1
                done += 1
                j = exit_hole(phi, hole_lo, hole_width)
                if j >= 0:
                    esc_n[b, j, bin_index(n_edges, n)] += 1
                    esc_t[b, j, bin_index(t_edges, t)] += 1
                    break
        collisions[b] += done


@parallel_jit
def portrait_chunk(phi0, v0, n0, eps, max_collisions, v_lo, v_hi, sample_slot, sample_target,
                   counts, collisions, flags, flag_state, samples):
    """Phase-space portrait: histogram the collision states (phi_n, v_n), n = 1..max_collisions.

    ``counts[b, p, q]`` counts the states with phi in bin p of [0, 2*pi) and v in bin q of
    [v_lo, v_hi) (uniform bins; states outside are not counted), for block b. Flags and samples
    as for ``escape_chunk`` (flag_state[i, 2], the time, is not tracked and stays 0).
    """
    m = len(phi0)
    blocks = len(collisions)
    per_block = (m + blocks - 1) // blocks
    n_phi, n_v = counts.shape[1], counts.shape[2]
    for b in prange(blocks):
        done = 0
        for i in range(b * per_block, min(m, (b + 1) * per_block)):
            phi, v, n = phi0[i], v0[i], n0[i]
            slot, target = sample_slot[i], sample_target[i]
            flags[i] = 0
            while n < max_collisions:
                phi1, v1, tau, _, status = collide(phi, v, eps)
                if status != CONVERGED:
                    _flag(flags, flag_state, i, status, phi, v, 0.0, n)
                    break
                n += 1
                done += 1
                if slot >= 0 and n <= target:
                    _store_sample(samples, slot, n, phi, v, phi1, v1, tau)
                phi, v = phi1, v1
                if v_lo <= v < v_hi:
                    p = min(int(phi / TWO_PI * n_phi), n_phi - 1)
                    q = min(int((v - v_lo) / (v_hi - v_lo) * n_v), n_v - 1)
                    counts[b, p, q] += 1
        collisions[b] += done


def log_edges(lo, decades, per_decade, integer=False):
    """Lower bin edges lo*10**(k/per_decade), k = 0..decades*per_decade (rounded and
    deduplicated when ``integer``), as float64."""
    k = np.arange(decades * per_decade + 1)
    edges = lo * 10.0 ** (k / per_decade)
    if integer:
        edges = np.unique(np.round(edges))
    return edges.astype(np.float64)


__all__ = [
    "NO_LIMIT",
    "SAMPLE_FIELDS",
    "FLAG_FIELDS",
    "bin_index",
    "escape_chunk",
    "exit_hole",
    "holmes_escape_chunk",
    "log_edges",
    "portrait_chunk",
]
