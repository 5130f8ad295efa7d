"""Censoring at the horizon, checked against the horizon itself.

A particle that has not escaped when the horizon is reached is censored (``escape_chunk``):

* collision horizon N: it made collisions 1..N without landing in a hole; recorded with the
  bounds n = N and t = t_N (the time of collision N);
* time horizon T: its next collision would come at t_{n+1} > T; recorded with the bounds n
  (collisions made, t_n <= T) and t_{n+1}: the escape time is at least t_{n+1}.

Escapes are never beyond the horizon: escape index <= N and escape time <= T. With 200
collision bins per decade every index up to 86 has its own bin, so "the bin contains exactly N"
is a statement about N itself. The expected histograms are rebuilt here particle by particle,
from ``fastpath.step`` (the kernel's arithmetic, bit for bit) for whole chunks and from
``fastpath.orbit`` (an independent loop; it adds tau to the uncentred phase, so its phases can
differ from the kernel's in the last bit) for single particles over short horizons.
"""

import numpy as np
import pytest

import fastpath
from fastpath.arithmetic.phase import TWO_PI
from fastpath.kernels.arrays import Bins, EscapeCounts, Flags, Holes, Horizon, Sample, Starts
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import bin_index
from fastpath.physics import elastic
from reports.runs import chunk
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.scenes import parse_scene

EPS = 0.6
CENTRE, WIDTH = 1.0, 0.3
LO = (CENTRE - WIDTH / 2) % TWO_PI

SCENE = """
name = "censoring"
kind = "escape"
eps = 0.6
particles = 600
seed = 21
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [1.0]
widths = [0.3]
[horizon]
{horizon}
[record]
bins_per_decade = 200
"""

HORIZONS = {"collisions": (60, None), "time": (None, 300.0), "both": (60, 300.0)}


def horizon_toml(max_n, max_t):
    lines = [f"collisions = {max_n}"] if max_n else []
    return "\n".join(lines + ([f"time = {max_t}"] if max_t else []))


def outcomes(phi, v, max_n, max_t):
    """[(escaped, n, t)] of the particles by hand, all stepped together with fastpath.step:
    escape index and time, or the censoring bounds."""
    phi, v = phi.copy(), v.copy()
    m = len(phi)
    t, n = np.zeros(m), np.zeros(m, np.int64)
    escaped, bound = np.zeros(m, bool), np.zeros(m)
    running = np.ones(m, bool)
    while running.any():
        if max_n is not None:
            at_n = running & (n >= max_n)
            bound[at_n] = t[at_n]
            running &= ~at_n
        i = np.flatnonzero(running)
        phi[i], v[i], tau = fastpath.step(phi[i], v[i], EPS)
        if max_t is not None:
            late = t[i] + tau > max_t
            bound[i[late]] = t[i[late]] + tau[late]
            running[i[late]] = False
            i, tau = i[~late], tau[~late]
        t[i] += tau
        n[i] += 1
        hit = i[(phi[i] - LO) % TWO_PI < WIDTH]
        escaped[hit] = True
        bound[hit] = t[hit]
        running[hit] = False
    return [(bool(e), int(k), float(b)) for e, k, b in zip(escaped, n, bound, strict=True)]


@pytest.mark.parametrize("horizon", list(HORIZONS))
def test_chunk_censoring_bins_hold_the_horizon(horizon):
    max_n, max_t = HORIZONS[horizon]
    plan = make_plan(parse_scene(SCENE.format(horizon=horizon_toml(max_n, max_t))))
    counts, _ = chunk.simulate_chunk(plan, 0, 0)
    phi0, v0, *_ = chunk_starts(plan, 0, 0)
    outs = outcomes(phi0, v0, max_n, max_t)
    cens = [(n, t) for escaped, n, t in outs if not escaped]
    esc = [(n, t) for escaped, n, t in outs if escaped]
    assert len(cens) >= 20 and len(esc) >= 20  # both kinds occur

    for n, t in cens:  # the bounds are the horizon itself
        if max_n is not None and n == max_n:
            assert max_t is None or t <= max_t
        else:
            assert max_t is not None and t > max_t
            assert max_n is None or n < max_n
    for n, t in esc:  # never beyond the horizon
        assert (max_n is None or n <= max_n) and (max_t is None or t <= max_t)

    want_cens_n = np.bincount([bin_index(plan.n_edges, float(n)) for n, _ in cens],
                              minlength=len(plan.n_edges))
    want_cens_t = np.bincount([bin_index(plan.t_edges, t) for _, t in cens],
                              minlength=len(plan.t_edges))
    want_esc_n = np.bincount([bin_index(plan.n_edges, float(n)) for n, _ in esc],
                             minlength=len(plan.n_edges))
    want_esc_t = np.bincount([bin_index(plan.t_edges, t) for _, t in esc],
                             minlength=len(plan.t_edges))
    np.testing.assert_array_equal(counts.cens_n, want_cens_n)
    np.testing.assert_array_equal(counts.cens_t, want_cens_t)
    np.testing.assert_array_equal(counts.esc_n[0], want_esc_n)
    np.testing.assert_array_equal(counts.esc_t[0], want_esc_t)

    if max_n is not None:
        k = bin_index(plan.n_edges, float(max_n))
        assert plan.n_edges[k] == max_n and plan.n_edges[k + 1] == max_n + 1  # N alone
        assert counts.cens_n[k] == sum(n == max_n for n, _ in cens) > 0
        assert counts.esc_n[0, k + 1:].sum() == 0
    if max_t is not None:
        k = bin_index(plan.t_edges, max_t)
        assert counts.esc_t[0, k + 1:].sum() == 0
        if max_n is None:
            assert counts.cens_t[:k].sum() == 0  # every bound is > T
    if horizon == "both":  # each horizon censors some
        assert 0 < sum(n == max_n for n, _ in cens) < len(cens)


def run_one(phi, v, max_n, max_t, n_edges, t_edges):
    """escape_chunk on one particle: (esc_n, esc_t, cens_n, cens_t) for the hole LO, WIDTH."""
    nb, tb = len(n_edges), len(t_edges)
    out = (np.zeros((1, 1, nb), np.int64), np.zeros((1, 1, tb), np.int64),
           np.zeros((1, nb), np.int64), np.zeros((1, tb), np.int64))
    flags = np.zeros(1, np.int8)
    escape_chunk(elastic(EPS), Starts(phi=np.array([phi]), v=np.array([v]), t=np.zeros(1),
                                      n=np.zeros(1, np.int64)),
                 Holes(lo=np.array([LO]), width=np.array([WIDTH])),
                 Horizon(max_collisions=max_n, max_time=max_t),
                 Bins(n_edges=n_edges, t_edges=t_edges, record_n=True, record_t=True),
                 Sample.none(1),
                 EscapeCounts(*out, stuck_n=np.zeros((1, nb), np.int64),
                              stuck_t=np.zeros((1, tb), np.int64),
                              collisions=np.zeros(1, np.int64)),
                 Flags(status=flags, state=np.zeros((1, 4))))
    assert flags[0] == 0
    return tuple(a.reshape(-1) for a in out)


@pytest.mark.parametrize(("max_n", "max_t"), [(12, np.inf), (2**62, 60.0), (12, 60.0)],
                         ids=["collisions", "time", "both"])
def test_single_particles_are_censored_where_their_orbit_crosses_the_horizon(max_n, max_t):
    """A few particles alone in the kernel against fastpath.orbit (short horizons: the orbit's
    last-bit differences from the kernel stay far below the bin widths)."""
    plan = make_plan(parse_scene(SCENE.format(horizon="collisions = 12")))
    n_edges, t_edges = plan.n_edges, plan.t_edges
    rng = np.random.default_rng(4)
    seen = set()
    for phi, v in zip(rng.uniform(3.85, 4.15, 12), rng.uniform(2.0, 4.0, 12), strict=True):
        orb = fastpath.orbit(phi, v, EPS, 40)
        hits = np.flatnonzero((orb.phi[1:] - LO) % TWO_PI < WIDTH) + 1
        first = int(hits[0]) if len(hits) else len(orb.t)  # first landing in the hole
        beyond = np.flatnonzero(orb.t > max_t)
        crossed = int(beyond[0]) if len(beyond) else len(orb.t)  # first collision beyond T
        assert min(first, crossed, max_n) < len(orb.t)  # decided within the 40 collisions
        esc_n, esc_t, cens_n, cens_t = run_one(phi, v, max_n, max_t, n_edges, t_edges)
        if first < min(crossed, max_n + 1):
            seen.add("escape")
            assert esc_n[bin_index(n_edges, float(first))] == 1 == esc_n.sum()
            assert esc_t[bin_index(t_edges, orb.t[first])] == 1 == esc_t.sum()
            assert cens_n.sum() == 0 == cens_t.sum()
        elif max_n < crossed:  # the collision horizon comes first
            seen.add("collisions")
            assert cens_n[bin_index(n_edges, float(max_n))] == 1 == cens_n.sum()
            assert cens_t[bin_index(t_edges, orb.t[max_n])] == 1 == cens_t.sum()
            assert esc_n.sum() == 0 == esc_t.sum()
        else:  # censored by time: n collisions made, the next at orb.t[n + 1] > T
            seen.add("time")
            assert cens_n[bin_index(n_edges, float(crossed - 1))] == 1 == cens_n.sum()
            assert cens_t[bin_index(t_edges, orb.t[crossed])] == 1 == cens_t.sum()
            assert esc_n.sum() == 0 == esc_t.sum()
    assert "escape" in seen and len(seen) >= 2
