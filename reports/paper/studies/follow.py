"""Particles followed collision by collision, keeping what the ensemble runs do not record.

A run (``reports.runs.driver``) stores histograms of the escape collision count n and of the
escape time t separately. Some of the paper's statements are about both at once (the orbits
that escape at time t made n ~ t^(1/2) collisions; the transporting orbits decay with many
fewer collisions and reach large velocities) or about where the late survivors are. For those,
``follow`` steps a sampled set of starts with ``fastpath.step`` on whole arrays (all particles
still inside make their k-th collision together) and records for every particle

    exit     index of the hole it leaves through (-1: still inside at the horizon)
    n, t     its collision count and time at that escape (or at the horizon)
    v_max    the largest velocity after any of its collisions
    v_exit   its velocity after the escaping collision

and, for each collision count s in ``snapshot_at``, the states (phi, v) of up to
``snapshot_size`` particles still inside after collision s during their next
``snapshot_length`` collisions, with their times (NaN after an escape).

Holes are arcs [lo, lo + width) mod 2 pi of the collision phase, as in the runs; membership is
decided in float64 from (phi - lo) mod 2 pi, which can misplace a phase within a few ulps of a
hole edge (irrelevant to these statistical studies; the runs decide it exactly). The time
horizon censors a particle whose next collision would come after ``max_time``.

A flight float64 cannot decide is settled by ``verify.step`` (``reports.runs.chunk.settle``), and
``verify_samples`` collisions spread over the study are recomputed by ``verify`` from the same
float64 state (``reports.runs.chunk.check_sample``): the worst error in kappa*u and the count of
overstepped collisions are returned with the records.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import fastpath
from fastpath.arithmetic.phase import TWO_PI
from reports.runs.chunk import check_sample, settle


@dataclass
class Followed:
    """Records of ``follow`` (module docstring); arrays indexed by particle."""

    eps: float
    exit: np.ndarray
    n: np.ndarray
    t: np.ndarray
    v_max: np.ndarray
    v_exit: np.ndarray
    snapshots: dict = field(default_factory=dict)  # s -> (ids, phi, v, t), each (k, L)
    collisions: int = 0
    settled: int = 0
    verification: dict = field(default_factory=dict)

    @property
    def particles(self):
        return len(self.exit)


def in_holes(phi, hole_lo, hole_width):
    """Index of the hole containing each phase (-1 for none); phases in [0, 2 pi)."""
    phi = np.asarray(phi, dtype=np.float64)
    out = np.full(phi.shape, -1, dtype=np.int8)
    for j in range(len(hole_lo) - 1, -1, -1):
        d = np.mod(phi - hole_lo[j], TWO_PI)
        out[d < hole_width[j]] = j
    return out


def _step_all(phi, v, eps):
    """fastpath.step on arrays; flights float64 cannot decide are settled by verify. Returns
    (phi1, v1, tau, settled count)."""
    try:
        phi1, v1, tau = fastpath.step(phi, v, eps)
        return phi1, v1, tau, 0
    except fastpath.UncertainCollision:
        status = np.asarray(fastpath.flight(phi, v, eps).status)
    bad = status != int(fastpath.FlightStatus.CONVERGED)
    phi1, v1, tau = np.empty_like(phi), np.empty_like(v), np.empty_like(v)
    good = ~bad
    if good.any():
        phi1[good], v1[good], tau[good] = fastpath.step(phi[good], v[good], eps)
    for i in np.flatnonzero(bad):
        phi1[i], v1[i], tau[i] = settle(float(phi[i]), float(v[i]), eps)
    return phi1, v1, tau, int(bad.sum())


def follow(phi0, v0, eps, hole_lo, hole_width, max_collisions, max_time=math.inf, *,
           snapshot_at=(), snapshot_size=2000, snapshot_length=200, verify_samples=200,
           seed=0, progress=None):
    """Follow every start (arrays phi0, v0) until it escapes or reaches the horizon; returns a
    ``Followed``. ``progress(k, inside)`` is called every 1000 collisions."""
    phi = np.asarray(phi0, dtype=np.float64).copy()
    v = np.asarray(v0, dtype=np.float64).copy()
    m = len(phi)
    hole_lo = np.asarray(hole_lo, dtype=np.float64)
    hole_width = np.asarray(hole_width, dtype=np.float64)
    exit_ = np.full(m, -1, dtype=np.int8)
    n_out = np.zeros(m, dtype=np.int64)
    t_out = np.zeros(m)
    v_max = v.copy()
    v_exit = np.full(m, math.nan)
    ids = np.arange(m)
    t = np.zeros(m)
    rng = np.random.default_rng(seed)
    # collision indices of the verification sample: log-uniform over the horizon's first 10^4
    check_at = set(np.unique(np.floor(np.exp(rng.uniform(0, math.log(1e4), verify_samples)))
                             .astype(np.int64)).tolist())
    worst, over, sampled = 0.0, 0, 0
    snapshots, watching = {}, []
    collisions = settled = 0
    k = 0
    while len(ids) and k < max_collisions:
        phi_in, v_in = phi, v
        phi, v, tau, s = _step_all(phi, v, eps)
        settled += s
        if k + 1 in check_at:
            i = int(rng.integers(len(ids)))
            _, err, overstep = check_sample(float(phi_in[i]), float(v_in[i]), float(tau[i]), eps)
            worst, over, sampled = max(worst, err), over + overstep, sampled + 1
        k += 1
        collisions += len(ids)
        t_new = t + tau
        late = t_new > max_time
        hole = in_holes(phi, hole_lo, hole_width)
        v_max[ids] = np.maximum(v_max[ids], v)
        gone = (hole >= 0) & ~late
        exit_[ids[gone]] = hole[gone]
        n_out[ids[gone]] = k
        t_out[ids[gone]] = t_new[gone]
        v_exit[ids[gone]] = v[gone]
        stop = late
        n_out[ids[stop]] = k - 1
        t_out[ids[stop]] = max_time
        keep = ~(gone | stop)
        for snap in watching:
            snap.record(ids, phi, v, t_new, k)
        ids, phi, v, t = ids[keep], phi[keep], v[keep], t_new[keep]
        if k in snapshot_at and len(ids):
            pick = np.sort(rng.choice(len(ids), min(snapshot_size, len(ids)), replace=False))
            watch = _Watch(ids[pick], snapshot_length, k)
            watching.append(watch)
            snapshots[k] = watch
        watching = [w for w in watching if w.until > k]
        if progress is not None and k % 1000 == 0:
            progress(k, len(ids))
    n_out[ids] = k
    t_out[ids] = t
    return Followed(eps, exit_, n_out, t_out, v_max, v_exit,
                    {s: (w.ids, w.phi, w.v, w.t) for s, w in snapshots.items()}, collisions,
                    settled,
                    {"sampled": sampled, "worst_error": worst, "overstepped": over})


class _Watch:
    """States of a fixed set of particles during ``length`` collisions after collision k0."""

    def __init__(self, ids, length, k0):
        self.ids = ids
        self.until = k0 + length
        self.k0 = k0
        self.phi = np.full((len(ids), length), math.nan)
        self.v = np.full((len(ids), length), math.nan)
        self.t = np.full((len(ids), length), math.nan)

    def record(self, ids, phi, v, t, k):
        col = k - self.k0 - 1
        if not 0 <= col < self.phi.shape[1]:
            return
        where = np.searchsorted(ids, self.ids)
        ok = (where < len(ids)) & (ids[np.minimum(where, len(ids) - 1)] == self.ids)
        self.phi[ok, col] = phi[where[ok]]
        self.v[ok, col] = v[where[ok]]
        self.t[ok, col] = t[where[ok]]
