"""Escape and transport ensembles: many starts through the map, recording only histograms.

Escape and transport (the paper's Sections 3 and 4). Each particle runs from its start (n = 0,
t = 0 is never tested against the holes) until

* collision n = 1, 2, ... lands at a phase phi_n (mod 2*pi) inside a hole j: it escapes through
  hole j with escape index N = n and escape time T = t_n = tau_0 + ... + tau_{n-1};
* the horizon: the next collision would have index n > ``max_collisions`` or time
  t > ``max_time``: it is censored, and we know only N > n and T > t (the last known bound);
* with restitution r < 1: its impacts accumulate where it can never leave the plate (stuck for
  good, ``fastpath.dissipative.sticking``): counted in ``stuck_n`` / ``stuck_t`` by the index n
  of the impact after which the tail was summed and by the accumulation time t_acc (censored
  at (n, t_acc) if t_acc > max_time). Escapes + censored + stuck + flagged = particles;
* a flight that float64 cannot decide (status UNCERTAIN or MAX_ITERATIONS, or NOT_DEPARTING at
  a graze): the particle is flagged with its departure (phi, v, t, n) and stops; the driver
  settles that collision with ``verify`` and resumes it here.

Holes, bins and blocks: ``fastpath.kernels.histogram``, ``fastpath.kernels.arrays``. With r < 1
the collisions are the impacts: riding the plate through a hole's phases during a sticking
episode is not a collision and does not escape; the impacts of a summed tail are collisions, so
a tail whose phases would cross into a hole is not summed (``fastpath.dissipative.carried``).
After a detachment the next collision is the first impact of the flight from the detachment
state; flags and samples then refer to that departure (theta*, u(theta*)).

One particle loop for every description (``fastpath.physics``), compiled per model. Each
group of blocks keeps LANES particles in flight together; for the elastic map the flights of
all lanes are computed first in one vectorised loop (``lane_collide``, ``fastpath.elastic.
lockstep``), then the bookkeeping runs lane by lane, a finished particle's lane taking the next
one. A lane the lockstep flight does not answer gets ``collide``, whose answer is the same
function of the departure: every particle's collisions are those of ``fastpath.step`` whatever
the lanes, blocks or threads. With dissipation each lane's collision is
``fastpath.dissipative.carried.advance`` on its carried state (no vectorised part).

Verification sample (``arrays.Sample``): the pre-collision state and fast result (n, phi, v,
phi1, v1, tau) of the picked collision, and with r < 1 the departure's carried entries
(``fastpath.dissipative.carried.CARRIED``), from which ``fastpath.carried_step`` repeats it.
"""

import math

import numpy as np

from fastpath.arithmetic.jit import inline_jit, jit, typed_overload
from fastpath.arithmetic.phase import MODERATE_LIMIT, centre_moderate
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, select
from fastpath.arithmetic.sincos import sin_cos, sin_cos_error
from fastpath.dissipative.carried import CARRIED, PHI, STATE_SIZE, STUCK, T, V, copy_carried
from fastpath.elastic.collision import collide
from fastpath.elastic.flight import AUTO, GENERAL, departure_phase
from fastpath.elastic.holmes import holmes_collide
from fastpath.elastic.landing import landing_phase_moderate, refine_long_flight
from fastpath.elastic.lockstep import lockstep_collide
from fastpath.kernels.arrays import keeps_carried
from fastpath.kernels.histogram import censor, escape, exit_hole, in_hole, stuck
from fastpath.kernels.particle import advance, departure_point, detachment_of
from fastpath.kernels.records import flag, start_particle, store_carried, store_sample
from fastpath.kernels.threads import over_threads
from fastpath.physics import DISSIPATIVE, Dissipative, Elastic, model_of
from fastpath.status import CONVERGED, UNCERTAIN

LANES = 64  # particles in flight together in a group (a multiple of the vector width)


@inline_jit
def lane_collide(centred, v, eps, phase_error):
    """``collide`` from a centred phase in straight-line code, for the common flight:
    (tau, phi1, v1, centred phi1, its phase error for the next flight, answered).

    The same arithmetic as ``collide`` -> ``collide_from`` -> ``flight_from`` ->
    ``lockstep_flight``, ``refine_long_flight`` -> ``landing_phase`` / centre_phase (their
    moderate ranges); answered False
    where collide would do anything else (then the caller calls it).
    """
    s, c = sin_cos(centred)
    tau, sin1, cos1, _, answered = lockstep_collide(centred, s, c, v, eps, phase_error)
    tau, tau_lo, sin1, _ = refine_long_flight(c, v, eps, tau, sin1, cos1)
    x = centred + tau
    phi1 = landing_phase_moderate(centred, tau, tau_lo)
    centred1 = centre_moderate(phi1)
    phase_error1 = select(centred1 == phi1, 0.0, 2.0 * UNIT_ROUNDOFF * abs(centred1))
    v1 = tau - v - 2.0 * eps * sin1
    return (tau, phi1, v1, centred1, phase_error1 + sin_cos_error(centred1),
            answered and abs(x) < MODERATE_LIMIT)


def escape_chunk(physics, starts, holes, horizon, bins, sample, counts, flags):
    """Run the particles ``starts`` (``arrays.Starts``) to their exit (module docstring).

    physics: an Elastic or Dissipative description (``fastpath.physics``; a Holmes description
    is refused: its ensemble is ``holmes_escape_chunk``). Outputs are added to (the caller zeroes
    them): ``counts`` (``arrays.EscapeCounts``, one row per block: len(counts.collisions)
    blocks of consecutive particles), ``flags`` (``arrays.Flags``), ``sample.rows``.

    Groups of whole blocks share lanes, one group per thread (``fastpath.kernels.threads``): a
    group ends with its last long-lived particles in half-empty lanes, so the fewer groups the
    less of that (16 groups of the 2^16 starts of a paper chunk cost 7% more per collision than
    one, on one thread). A particle counts into its own block's row, so the grouping, like the
    threads, changes no number: it only spreads the work.
    """
    if type(physics) not in (Elastic, Dissipative):
        raise ValueError(f"escape_chunk takes an Elastic or Dissipative description, got"
                         f" {physics!r}; the Holmes map's ensemble is holmes_escape_chunk")
    m = len(starts.phi)
    per_block = (m + len(counts.collisions) - 1) // len(counts.collisions)
    detach = detachment_of(physics)

    def run_group(first_block, end_block):
        span = (per_block, min(m, first_block * per_block), min(m, end_block * per_block))
        _escape_lanes(physics, span, starts, holes, horizon, bins, sample, counts, flags, detach)

    over_threads(run_group, len(counts.collisions))


# The lanes' entries, rows of two arrays (real, integer) of LANES columns: each row is a
# contiguous array for the vectorised loop, and a particle is loaded through three arrays (its
# state row too) rather than a tuple of eleven (which cost 5% of the elastic ensemble's time).
PHI_L, V_L, T_L, CENTRED_L, PHASE_ERROR_L = range(5)  # real
IDX_L, BLOCK_L, N_L, SLOT_L, TARGET_L = range(5)  # integer


@inline_jit
def _load(physics, real, integer, states, lane, i, per_block, starts, sample, flags):
    """Put particle i into a lane; False (the particle flagged) if it does not depart."""
    integer[IDX_L, lane], integer[BLOCK_L, lane] = i, i // per_block
    integer[N_L, lane], integer[SLOT_L, lane] = starts.n[i], sample.slot[i]
    integer[TARGET_L, lane] = sample.target[i]
    real[PHI_L, lane], real[V_L, lane], real[T_L, lane] = starts.phi[i], starts.v[i], starts.t[i]
    flags.status[i] = 0
    return _depart(physics, real, states, lane, i, starts, flags)


def _depart(physics, real, states, lane, i, starts, flags):
    """The departure of particle i in a lane: its centred phase (elastic) or its state
    (``start_particle``: False if it does not depart), compiled for the model only."""


@typed_overload(_depart)
def _depart_of_model(physics, real, states, lane, i, starts, flags):
    if physics.instance_class is Elastic:
        def elastic_departure(physics, real, states, lane, i, starts, flags):
            real[CENTRED_L, lane], real[PHASE_ERROR_L, lane] = departure_phase(starts.phi[i])
            return True
        return elastic_departure

    def dissipative_departure(physics, real, states, lane, i, starts, flags):
        state = states[lane]
        if not start_particle(state, physics, i, starts, flags, True):
            return False
        real[PHI_L, lane], real[V_L, lane], real[T_L, lane] = departure_point(state)
        return True
    return dissipative_departure


def _dissipative_collision(physics, states, carried, lane, keep, detach, hole_lo):
    """The collision of a dissipative lane (``fastpath.dissipative.carried.advance`` on its
    state; its carried entries first copied if ``keep``): (status, tau, sticking kind,
    t_start, phi1, v1, t1). Compiled for dissipative descriptions only: an elastic loop never
    calls it (its lanes take the vectorised flight), so it compiles no dissipative code."""


def _store_carried(physics, rows, s, carried):
    """``fastpath.kernels.records.store_carried`` for a dissipative loop (not compiled for an
    elastic one, which never calls it)."""


def _departure_point(state, physics):
    """``fastpath.kernels.particle.departure_point`` for a dissipative loop (not compiled for an
    elastic one, which never calls it)."""


@typed_overload(_dissipative_collision)
def _dissipative_collision_of_model(physics, states, carried, lane, keep, detach, hole_lo):
    if physics.instance_class is Elastic:
        def not_called(physics, states, carried, lane, keep, detach, hole_lo):
            return UNCERTAIN, math.nan, 0, math.nan, math.nan, math.nan, math.nan
        return not_called

    def dissipative_collision(physics, states, carried, lane, keep, detach, hole_lo):
        state = states[lane]
        if keep:
            copy_carried(state, carried[lane])
        status, _, tau, kind, t_start, _ = advance(state, physics, AUTO, True, detach, hole_lo)
        return status, tau, kind, t_start, state[PHI], state[V], state[T]
    return dissipative_collision


@typed_overload(_store_carried)
def _store_carried_of_model(physics, rows, s, carried):
    if physics.instance_class is Elastic:
        return lambda physics, rows, s, carried: None
    return lambda physics, rows, s, carried: store_carried(rows, s, carried)


@typed_overload(_departure_point)
def _departure_point_of_model(state, physics):
    if physics.instance_class is Elastic:
        return lambda state, physics: (math.nan, math.nan, math.nan)
    return lambda state, physics: departure_point(state)


@inline_jit
def _load_next(physics, lanes, lane, following, end, per_block, starts, sample, flags):
    """Fill the lane with the next particle that departs: (loaded, the next index);
    lanes = (real, integer, states)."""
    real, integer, states = lanes
    while following < end:
        loaded = _load(physics, real, integer, states, lane, following, per_block, starts,
                       sample, flags)
        following += 1
        if loaded:
            return True, following
    return False, following


@jit
def _escape_lanes(physics, span, starts, holes, horizon, bins, sample, counts, flags, detach):
    """Particles first .. end-1 of ``escape_chunk`` (whole blocks of per_block) in lanes;
    span = (per_block, first, end)."""
    per_block, first, end = span
    real, integer = np.empty((5, LANES)), np.empty((5, LANES), np.int64)
    phi, v, t = real[PHI_L], real[V_L], real[T_L]
    centred, phase_error = real[CENTRED_L], real[PHASE_ERROR_L]
    idx, block, n = integer[IDX_L], integer[BLOCK_L], integer[N_L]
    slot, target = integer[SLOT_L], integer[TARGET_L]
    tau, phi1, v1 = np.empty(LANES), np.empty(LANES), np.empty(LANES)
    centred1, phase_error1 = np.empty(LANES), np.empty(LANES)
    answered, hole = np.empty(LANES, np.bool_), np.empty(LANES, np.int64)
    states, carried = np.empty((LANES, STATE_SIZE)), np.empty((LANES, len(CARRIED)))
    lanes = (real, integer, states)
    eps = physics.eps
    hole_lo, hole_width = holes.lo, holes.width
    max_collisions, max_time = horizon.max_collisions, horizon.max_time
    dissipative = model_of(physics) == DISSIPATIVE
    keep_carried = keeps_carried(sample.rows, physics.restitution)
    active, following = 0, first
    while active < LANES:
        loaded, following = _load_next(physics, lanes, active, following, end, per_block,
                                       starts, sample, flags)
        if not loaded:
            break
        active += 1
    while active > 0:
        if not dissipative:
            for lane in range(active):  # vectorised: no calls, no branches but selects
                (tau[lane], phi1[lane], v1[lane], centred1[lane], phase_error1[lane],
                 answered[lane]) = lane_collide(centred[lane], v[lane], eps, phase_error[lane])
            for lane in range(active):
                hole[lane] = -1
            for h in range(len(hole_lo)):  # exit_hole of every lane, vectorised over the lanes
                lo_h, width_h = hole_lo[h], hole_width[h]
                for lane in range(active):
                    hole[lane] = select(hole[lane] < 0 and in_hole(phi1[lane], lo_h, width_h),
                                        h, hole[lane])
        idle = False
        for lane in range(active):
            i = idx[lane]
            b = block[lane]
            finished = False
            if n[lane] >= max_collisions:
                censor(counts, bins, b, n[lane], t[lane])
                finished = True
            else:
                kind, t_start = 0, 0.0
                if dissipative:
                    keep = keep_carried and slot[lane] >= 0 and n[lane] < target[lane]
                    status, tau_l, kind, t_start, phi1_l, v1_l, t1 = _dissipative_collision(
                        physics, states, carried, lane, keep, detach, hole_lo)
                    answered[lane] = False
                elif answered[lane]:
                    phi1_l, v1_l, tau_l, status = phi1[lane], v1[lane], tau[lane], CONVERGED
                    t1 = t[lane] + tau_l
                else:  # what the lanes do not answer: collide's general path, the same function
                    phi1_l, v1_l, tau_l, _, status = collide(phi[lane], v[lane], eps, GENERAL)
                    centred1[lane], phase_error1[lane] = departure_phase(phi1_l)
                    t1 = t[lane] + tau_l
                if status != CONVERGED:
                    flag(flags, i, status, phi[lane], v[lane], t[lane], n[lane])
                    finished = True
                elif t1 > max_time:
                    censor(counts, bins, b, n[lane], t1)
                    finished = True
                else:
                    n[lane] += 1
                    counts.collisions[b] += 1
                    if slot[lane] >= 0 and n[lane] <= target[lane]:
                        store_sample(sample.rows, slot[lane], n[lane], (phi[lane], v[lane]),
                                     (phi1_l, v1_l, tau_l))
                        if dissipative and keep_carried:
                            _store_carried(physics, sample.rows, slot[lane], carried[lane])
                    if dissipative:
                        phi[lane], v[lane], t[lane] = _departure_point(states[lane], physics)
                    else:
                        phi[lane], v[lane], t[lane] = phi1_l, v1_l, t1
                    j = hole[lane] if answered[lane] else exit_hole(phi1_l, hole_lo, hole_width)
                    if j >= 0:
                        escape(counts, bins, b, j, n[lane], t1)
                        finished = True
                    elif kind == STUCK:
                        if t_start <= max_time:
                            stuck(counts, bins, b, n[lane], t_start)
                        else:
                            censor(counts, bins, b, n[lane], t_start)
                        finished = True
                    else:
                        centred[lane], phase_error[lane] = centred1[lane], phase_error1[lane]
            if finished:
                loaded, following = _load_next(physics, lanes, lane, following, end, per_block,
                                               starts, sample, flags)
                if not loaded:
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
                    if dissipative:  # entry by entry: a slice copy compiles its shape check
                        for j in range(STATE_SIZE):
                            states[busy, j] = states[lane, j]
                        for j in range(len(CARRIED)):
                            carried[busy, j] = carried[lane, j]
                    busy += 1
            active = busy


def holmes_escape_chunk(physics, starts, holes, horizon, bins, counts):
    """``escape_chunk`` with the Holmes map (flight time 2*v) instead of the exact map: the
    project's Holmes-map ensemble on the same starts, holes, horizon, bins and blocks (no
    verification sample, no flags: the Holmes map has no undecidable flight; starts at t = 0,
    n = 0), its phase reduced exactly (``fastpath.elastic.holmes``). Blocks over threads as
    ``escape_chunk``."""
    m = len(starts.phi)
    per_block = (m + len(counts.collisions) - 1) // len(counts.collisions)

    def run_group(first_block, end_block):
        _holmes_blocks(physics.eps, (first_block, end_block, per_block), starts, holes, horizon,
                       bins, counts)

    over_threads(run_group, len(counts.collisions))


@jit
def _holmes_blocks(eps, span, starts, holes, horizon, bins, counts):
    """Blocks first .. end-1 of ``holmes_escape_chunk``, span = (first, end, per_block)."""
    first, end, per_block = span
    m = len(starts.phi)
    for b in range(first, end):
        _holmes_block(eps, (b, min(m, b * per_block), min(m, (b + 1) * per_block)), starts,
                      holes, horizon, bins, counts)


@jit
def _holmes_block(eps, span, starts, holes, horizon, bins, counts):
    """Particles first .. last-1 of ``holmes_escape_chunk`` into block b's row,
    span = (b, first, last)."""
    b, first, last = span
    done = 0
    for i in range(first, last):
        phi, v, t, n = starts.phi[i], starts.v[i], 0.0, 0
        while True:
            if n >= horizon.max_collisions:
                censor(counts, bins, b, n, t)
                break
            t1 = t + 2.0 * v
            if t1 > horizon.max_time:
                censor(counts, bins, b, n, t1)
                break
            phi, v = holmes_collide(phi, v, eps)
            t = t1
            n += 1
            done += 1
            j = exit_hole(phi, holes.lo, holes.width)
            if j >= 0:
                escape(counts, bins, b, j, n, t)
                break
    counts.collisions[b] += done
