"""One chunk of a run, computed and verified: ``run_chunk``.

Escape and transport scenes run ``fastpath.kernels.escape.escape_chunk`` with the scene's physics
description (``fastpath.physics``: elastic without ``[physics]``; with restitution < 1 it also
counts the particles stuck on the plate for good); velocity scenes run
``simulate_velocity_chunk`` (``fastpath.kernels.moments``, the same settling and sample). Flagged
and sampled collisions are recomputed by ``verify.step`` with the same physics. With
restitution < 1 a sample row also records the departure's carried state (``CARRIED_COLUMNS``),
from which ``fastpath.carried_step`` repeats the kernel's step in ``bouncer verify``.
"""

from __future__ import annotations

import hashlib
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import mpmath
import numpy as np

import verify
from fastpath.arithmetic.phase import TWO_PI
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.kernels.arrays import (
    NO_LIMIT,
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    JointCounts,
    MomentGrid,
    MomentSums,
    Portrait,
    Sample,
    Starts,
    joint_histogram,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import bin_index, exit_hole
from fastpath.kernels.moments import moments_chunk
from fastpath.kernels.portrait import portrait_chunk
from fastpath.physics import LAWS, describe
from reports.runs.counts import Counts, exact_block_sums
from reports.runs.plan import BLOCKS, PORTRAIT_BLOCKS, chunk_starts, make_plan
from reports.runs.rundir import CARRIED_COLUMNS, RunFailed

OVERSTEP_TOLERANCE = 16.0  # in units of kappa*u


VERIFY_DPS = 30


@dataclass
class ChunkResult:
    """What ``run_chunk`` returns (small and picklable: it travels back from a Dask worker).

    ``rows`` are the chunk's verified sample rows (``rundir.SAMPLE_COLUMNS``), ``bad`` those of
    them that overstepped; ``failure`` is the message of a collision verify could not settle
    (the run fails with it) or None; ``code`` a digest of the sources that computed it.
    """

    curve: int
    chunk: int
    counts: Counts
    rows: list
    bad: list
    failure: str | None = None
    seconds: float = 0.0
    code: str = ""


# numba's workqueue threading layer must not be entered by two threads at once (a Dask worker
# with several threads would); one kernel at a time per process, each parallel inside
_KERNEL_LOCK = threading.Lock()
# verify is thread-safe, but check_sample's own arithmetic (the error's quotient, and
# dissipative_kappa's mpmath.mp.workdps) uses mpmath's process-wide precision: one sample
# check at a time
_SAMPLE_LOCK = threading.Lock()


def _physics(scene, physics=None):
    """The description (``fastpath.physics``) of a scene's physics, or of one curve's
    (``physics``: the keywords of ``Scene.curve_physics``)."""
    if physics is None:
        physics = scene.physics()
    return describe(scene.eps, physics.get("drag", 0.0), LAWS[physics.get("drag_law", "linear")],
                    physics.get("restitution", 1.0))


def kernel(plan, exp, state, slot, target, samples, out):
    """One pass of the fast kernel over the particles in ``state`` = (phi, v, t, n)."""
    sc = plan.scene
    phi, v, t, n = state
    m = len(phi)
    starts = Starts(phi=phi, v=v, t=t, n=n)
    sample = Sample(slot=slot, target=target, rows=samples)
    flags = Flags.zeros(m)
    if sc.kind == "phase-space":
        blocks = min(PORTRAIT_BLOCKS, m)
        portrait = Portrait(v_lo=sc.v_range[0], v_hi=sc.v_range[1],
                            counts=np.zeros((blocks, sc.phi_bins, sc.v_bins), np.int64),
                            collisions=np.zeros(blocks, np.int64))
        with _KERNEL_LOCK:
            portrait_chunk(_physics(sc), starts, sc.max_collisions, sample, portrait, flags)
        out.portrait += portrait.counts.sum(axis=0)
        collisions = portrait.collisions
    else:
        blocks = min(BLOCKS, m)
        holes = len(exp.hole_lo)
        counts = escape_counts(plan, blocks, m, holes)
        with _KERNEL_LOCK:
            escape_chunk(_physics(sc), starts,
                         Holes(lo=np.array(exp.hole_lo), width=np.array(exp.hole_width)),
                         Horizon(max_collisions=sc.max_collisions or NO_LIMIT,
                                 max_time=sc.max_time or np.inf),
                         Bins(n_edges=plan.n_edges, t_edges=plan.t_edges,
                              record_n="collisions" in sc.clocks, record_t="time" in sc.clocks),
                         sample, counts, flags)
        if sc.joint:
            add_joint(out, counts, plan)
        if not sc.elastic:
            out.stuck_n += counts.stuck_n.sum(axis=0)
            out.stuck_t += counts.stuck_t.sum(axis=0)
        out.esc_n[:holes] += counts.esc_n.sum(axis=0)
        out.esc_t[:holes] += counts.esc_t.sum(axis=0)
        out.cens_n += counts.cens_n.sum(axis=0)
        out.cens_t += counts.cens_t.sum(axis=0)
        collisions = counts.collisions
    out.collisions += int(collisions.sum())
    return flags.status, flags.state


def escape_counts(plan, blocks, m, holes):
    """The kernel's counts for m particles in ``blocks`` blocks: ``JointCounts`` for a scene
    that records the joint histogram (the kernel is then compiled with the record),
    ``EscapeCounts`` otherwise."""
    nb, tb = len(plan.n_edges), len(plan.t_edges)
    if plan.scene.joint:
        return JointCounts.zeros(blocks, -(-m // blocks), holes, nb, tb)
    return EscapeCounts.zeros(blocks, holes, nb, tb)


def add_joint(out, counts, plan):
    """The kernel's joint record (``JointCounts``) into ``out.joint`` (outcomes: the holes,
    censored, stuck). A block that recorded more ends than particles fails the run."""
    try:
        joint = joint_histogram(counts, len(plan.n_edges), len(plan.t_edges))
    except ValueError as err:
        raise RunFailed(f"the joint record is inconsistent: {err}") from None
    if joint.shape == out.joint.shape:
        out.joint += joint
    else:  # fewer holes than the run's widest curve set
        holes = len(joint) - 2
        out.joint[:holes] += joint[:holes]
        out.joint[-2:] += joint[-2:]


def add_joint_end(out, plan, outcome, n, t):
    """One particle's end, settled here rather than in the kernel, into ``out.joint`` (outcome
    as in ``add_joint``: hole j, or -2 censored); the same bins as the kernel's."""
    if out.joint is not None:
        out.joint[outcome, bin_index(plan.n_edges, n), bin_index(plan.t_edges, t)] += 1


def settle(phi, v, eps, physics=None):
    """The collision float64 could not decide, by ``verify.step`` (with the scene's ``physics``
    keywords, none for the elastic model): floats (phi1, v1, tau)."""
    phi, v = float(phi), float(v)  # plain numbers in verify's messages, not np.float64(...)
    try:
        phi1, v1, tau = verify.step(phi, v, eps, dps=VERIFY_DPS, **(physics or {}))
    except (verify.UndecidableCollision, ValueError) as err:
        raise RunFailed(f"verify could not settle the flagged collision from phi={phi!r},"
                        f" v={v!r}: {err}") from None
    return float(phi1), float(v1), float(tau)


def _resumed(resume, slot, target):
    """The kernel's next pass over the settled particles ``resume`` = [(i, phi, v, t, n)]:
    (state, their sample slots, their sample targets)."""
    idx = np.array([r[0] for r in resume], np.int64)
    state = tuple(np.array([r[c] for r in resume], dtype)
                  for c, dtype in ((1, float), (2, float), (3, float), (4, np.int64)))
    return state, slot[idx], target[idx]


def _sample_rows(e, k, picks, samples):
    """The chunk's sample rows [e, k, particle, n, phi, v, ...] of the picks that were reached."""
    return [[e, k, int(picks[s]), *map(float, samples[s])] for s in range(len(picks))
            if samples[s, 0] > 0]


def simulate_chunk(plan, e, k):
    """Simulate chunk k of experiment e, settling flagged collisions by verify:
    (Counts, sample rows not yet verified)."""
    sc, exp = plan.scene, plan.experiments[e]
    phi, v, slot, target, picks = chunk_starts(plan, e, k)
    m = len(phi)
    holes = max(len(exp.hole_lo), 1)
    out = Counts.zeros(plan, holes)
    # (n, phi, v, phi1, v1, tau), then the carried state (``rundir.sample_columns``)
    samples = np.zeros((len(picks), 6 + (len(CARRIED_COLUMNS) if sc.carries else 0)))
    state = (phi, v, np.zeros(m), np.zeros(m, np.int64))
    max_n = sc.max_collisions or NO_LIMIT
    max_t = sc.max_time or np.inf
    hole_lo, hole_w = np.array(exp.hole_lo), np.array(exp.hole_width)
    while len(state[0]):
        flags, flag_state = kernel(plan, exp, state, slot, target, samples, out)
        resume = []
        for i in np.flatnonzero(flags):
            phi_i, v_i, t_i, n_i = flag_state[i]
            phi1, v1, tau = (settle(phi_i, v_i, sc.eps, sc.physics()) if not sc.elastic
                             else settle(phi_i, v_i, sc.eps))
            out.settled += 1
            t1, n1 = t_i + tau, int(n_i) + 1
            if t1 > max_t:  # as the kernel: censored before this collision
                out.cens_n[bin_index(plan.n_edges, float(n_i))] += 1
                out.cens_t[bin_index(plan.t_edges, t1)] += 1
                add_joint_end(out, plan, -2, float(n_i), t1)
                continue
            out.collisions += 1
            if sc.kind == "phase-space":
                lo, hi = sc.v_range
                if lo <= v1 < hi:
                    p = min(int(phi1 / TWO_PI * sc.phi_bins), sc.phi_bins - 1)
                    q = min(int((v1 - lo) / (hi - lo) * sc.v_bins), sc.v_bins - 1)
                    out.portrait[p, q] += 1
                if n1 >= max_n:
                    continue
            else:
                j = exit_hole(phi1, hole_lo, hole_w)
                if j >= 0:
                    out.esc_n[j, bin_index(plan.n_edges, float(n1))] += 1
                    out.esc_t[j, bin_index(plan.t_edges, t1)] += 1
                    add_joint_end(out, plan, j, float(n1), t1)
                    continue
            resume.append((i, phi1, v1, t1, n1))
        state, slot, target = _resumed(resume, slot, target)
    return out, _sample_rows(e, k, picks, samples)


def velocity_kernel(plan, e, state, slot, target, samples, out):
    """``kernel`` for a velocity scene: one pass of ``fastpath.kernels.moments`` over the
    particles in ``state`` = (phi, v, t, n) with curve e's physics, into ``out`` (exact block
    sums, ``reports.runs.counts``); returns (flags, flag_state)."""
    sc = plan.scene
    phi, v, t, n = state
    m, grid = len(phi), plan.n_grid
    sums = MomentSums.zeros(min(BLOCKS, m), len(grid), 0)
    flags = Flags.zeros(m)
    grid = MomentGrid(n=grid, t=np.zeros(0), max_collisions=sc.max_collisions or NO_LIMIT)
    with _KERNEL_LOCK:
        moments_chunk(_physics(sc, sc.curve_physics(e)), Starts(phi=phi, v=v, t=t, n=n), grid,
                      True, Sample(slot=slot, target=target, rows=samples), sums, flags)
    out.moving += sums.count_n.sum(axis=0)
    out.stuck_at += sums.stuck_n.sum(axis=0)
    out.sum_v += exact_block_sums(sums.sum_v_n)
    out.sum_v2 += exact_block_sums(sums.sum_v2_n)
    out.collisions += int(sums.collisions.sum())
    return flags.status, flags.state


def simulate_velocity_chunk(plan, e, k):
    """``simulate_chunk`` for a velocity scene (``reports.runs.velocity``): chunk k of curve e
    through ``fastpath.kernels.moments``, flagged collisions settled by verify, the particle
    resuming from the state after it (the kernel fills its grid point)."""
    sc = plan.scene
    phi, v, slot, target, picks = chunk_starts(plan, e, k)
    m = len(phi)
    out = Counts.zeros(plan, 1)
    samples = np.zeros((len(picks), 6 + (len(CARRIED_COLUMNS) if sc.carries else 0)))
    state = (phi, v, np.zeros(m), np.zeros(m, np.int64))
    physics = sc.curve_physics(e)
    while len(state[0]):
        flags, flag_state = velocity_kernel(plan, e, state, slot, target, samples, out)
        resume = []
        for i in np.flatnonzero(flags):
            phi_i, v_i, t_i, n_i = flag_state[i]
            phi1, v1, tau = (settle(phi_i, v_i, sc.eps, physics) if physics
                             else settle(phi_i, v_i, sc.eps))
            out.settled += 1
            out.collisions += 1
            resume.append((i, phi1, v1, t_i + tau, int(n_i) + 1))  # its grid point: the kernel
        state, slot, target = _resumed(resume, slot, target)
    return out, _sample_rows(e, k, picks, samples)


def run_chunk(scene, seed, curve, chunk, particles=None, threads=None):
    """Chunk ``chunk`` of curve (experiment) ``curve`` of the run of ``scene`` with ``seed`` and
    ``particles`` per curve (default: the scene's): simulated, flagged collisions settled and
    the sample verified, all here (in the worker, on a cluster). A pure function of its
    arguments; ``threads`` (numba threads of this call) does not change the result.

    A collision verify cannot settle is returned as ``failure`` (data, not an exception), so
    that Dask's retries are spent only on lost workers and unexpected errors.
    """
    t0 = time.perf_counter()
    plan = make_plan(scene, particles, seed)
    if not (0 <= curve < len(plan.experiments) and 0 <= chunk < plan.chunks_per_experiment):
        raise ValueError(f"no chunk ({curve}, {chunk}) in a run of {len(plan.experiments)}"
                         f" curves x {plan.chunks_per_experiment} chunks")
    if threads is not None:
        import numba

        numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    empty = Counts(*(np.zeros(0, np.int64) for _ in range(5)))
    try:
        simulate = simulate_velocity_chunk if scene.kind == "velocity" else simulate_chunk
        counts, rows = simulate(plan, curve, chunk)
        bad = verify_rows(rows, scene.eps, scene.curve_physics(curve))
    except RunFailed as err:
        return ChunkResult(curve, chunk, empty, [], [], str(err),
                           time.perf_counter() - t0, CODE_DIGEST)
    return ChunkResult(curve, chunk, counts, rows, bad, None, time.perf_counter() - t0,
                       CODE_DIGEST)


# the verify modules behind verify.step and verify.condition_number (what a chunk calls)
_VERIFY_SOURCES = ("collision.py", "errors.py", "flight.py", "numerics", "elastic", "dissipative")


def _code_digest():
    """Digest of the sources a chunk's result depends on (all of fastpath, verify's step and
    condition number, and the run engine ``reports/runs``), as imported: the client refuses
    results from workers that run other sources."""
    root = Path(__file__).resolve().parents[2]
    digest = hashlib.sha256()
    files = [*sorted((root / "fastpath").rglob("*.py")),
             *(path for name in _VERIFY_SOURCES
               for path in sorted((root / "verify").glob(name if name.endswith(".py")
                                                         else f"{name}/*.py"))),
             *sorted((root / "reports" / "runs").glob("*.py"))]
    for path in files:
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


CODE_DIGEST = _code_digest()


def dissipative_kappa(phi, v, eps, tau_ref, phi1_ref, v1_ref, restitution):
    """The elastic condition number's scale with the dissipative impact speed:

        kappa = (|v| + tau + |eps|*(1 + |phi| + tau)) / |d'(tau)|,
        |d'(tau)| = |v_in - u| = |v1 - u| / r,   u = -eps*sin(phi1)

    (``verify.condition_number`` with ``d'(tau) = V(tau) + eps*sin(phi + tau)`` the relative
    impact speed of the drag flight, read off the certified impact ``v1 - u = -r*(v_in - u)``).
    The numerator is the size of the gap's terms as in the elastic case (with drag the
    particle's part ``Y(t)`` is no larger than ``v*t``, ``t**2``)."""
    with mpmath.mp.workdps(VERIFY_DPS):
        u = -eps * mpmath.sin(phi1_ref)
        rate = abs(v1_ref - u) / restitution
        num = abs(v) + tau_ref + abs(eps) * (1 + abs(phi) + tau_ref)
        return mpmath.inf if rate == 0 else num / rate


def check_sample(phi, v, tau, eps, physics=None):
    """verify's flight time from the same float64 state: (tau_ref, error in kappa*u, overstep).
    ``physics``: the scene's keywords (``Scene.physics()``), none for the elastic model."""
    if physics:
        phi1_ref, v1_ref, tau_ref = verify.step(phi, v, eps, dps=VERIFY_DPS, **physics)
        kappa = dissipative_kappa(phi, v, eps, tau_ref, phi1_ref, v1_ref,
                                  physics["restitution"])
    else:  # the flight time of verify.step (its cert.tau), without the step's phi1 and v1
        tau_ref = verify.certify_flight(phi, v, eps, dps=VERIFY_DPS).tau
        kappa = verify.condition_number(phi, v, eps, tau_ref)
    rel = (tau - tau_ref) / tau_ref
    error = float(abs(rel) / (kappa * UNIT_ROUNDOFF))
    return float(tau_ref), error, bool(rel > OVERSTEP_TOLERANCE * kappa * UNIT_ROUNDOFF)


def verify_rows(rows, eps, physics=None):
    """Recompute the chunk's sample; rows gain tau_ref and error (after tau, before a carried
    state: ``rundir.sample_columns``). Returns overstepped rows."""
    bad = []
    for row in rows:
        _, _, _, n, phi, v, phi1, v1, tau = row[:9]
        try:
            # the elastic call is the one it always was (no physics argument)
            with _SAMPLE_LOCK:
                tau_ref, error, overstep = (check_sample(phi, v, tau, eps, physics) if physics
                                            else check_sample(phi, v, tau, eps))
        except (verify.UndecidableCollision, ValueError) as err:
            raise RunFailed(f"verify could not decide sampled collision {int(n)} from "
                            f"phi={phi!r}, v={v!r} that fastpath converged: {err}") from None
        row[3] = int(n)
        row[9:9] = [tau_ref, error]
        if overstep:
            bad.append(row)
    return bad


def check_result(result):
    """RunFailed for a chunk that failed (data from ``run_chunk``) or that other sources
    computed (a worker with another bouncer-verify: not bit-identical)."""
    if result.failure:
        raise RunFailed(result.failure)
    if result.code != CODE_DIGEST:
        raise RunFailed(f"chunk ({result.curve}, {result.chunk}) was computed by other sources"
                        f" (digest {result.code}, here {CODE_DIGEST}): install the same"
                        " bouncer-verify on the client and every worker")
