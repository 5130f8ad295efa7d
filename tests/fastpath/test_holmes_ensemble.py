"""holmes_escape_chunk (fastpath.kernels.escape): the benchmark's Holmes-map ensemble, replayed by
hand."""

import math

import numpy as np

import fastpath
from fastpath.kernels.arrays import Bins, EscapeCounts, Holes, Horizon, Starts
from fastpath.kernels.escape import holmes_escape_chunk
from fastpath.kernels.histogram import bin_index, exit_hole, log_edges
from fastpath.physics import holmes


def test_holmes_ensemble_matches_a_replay_with_holmes_step():
    rng = np.random.default_rng(8)
    m, eps = 300, 0.6
    phi0, v0 = rng.uniform(3.85, 4.15, m), rng.uniform(2.0, 4.0, m)
    lo, width = np.array([2.0 - 0.15, 6.1]), np.array([0.3, 0.5])
    n_edges = log_edges(1.0, 4, 10, integer=True)
    t_edges = np.concatenate([[0.0], log_edges(0.1, 6, 10)])
    max_n, max_t = 15, 3000.0
    blocks = 5
    esc_n = np.zeros((blocks, 2, len(n_edges)), np.int64)
    esc_t = np.zeros((blocks, 2, len(t_edges)), np.int64)
    cens_n = np.zeros((blocks, len(n_edges)), np.int64)
    cens_t = np.zeros((blocks, len(t_edges)), np.int64)
    collisions = np.zeros(blocks, np.int64)
    holmes_escape_chunk(holmes(eps), Starts(phi=phi0, v=v0, t=np.zeros(m),
                                            n=np.zeros(m, np.int64)),
                        Holes(lo=lo, width=width), Horizon(max_collisions=max_n, max_time=max_t),
                        Bins(n_edges=n_edges, t_edges=t_edges, record_n=True, record_t=True),
                        EscapeCounts(esc_n, esc_t, cens_n, cens_t, np.zeros_like(cens_n),
                                     np.zeros_like(cens_t), collisions))
    want_n, want_cens = np.zeros((2, len(n_edges)), np.int64), np.zeros(len(n_edges), np.int64)
    total = 0
    for p, v in zip(phi0, v0, strict=True):
        t, n = 0.0, 0
        while True:
            if n >= max_n or t + 2 * v > max_t:
                want_cens[bin_index(n_edges, n)] += 1
                break
            t += 2 * v
            p, v = fastpath.holmes_step(p, v, eps)
            n += 1
            total += 1
            j = exit_hole(p, lo, width)
            if j >= 0:
                want_n[j, bin_index(n_edges, n)] += 1
                break
    np.testing.assert_array_equal(esc_n.sum(axis=0), want_n)
    np.testing.assert_array_equal(cens_n.sum(axis=0), want_cens)
    assert collisions.sum() == total
    assert esc_n.sum() + cens_n.sum() == m and esc_t.sum() + cens_t.sum() == m
    assert want_n.sum() > 0 and want_cens.sum() > 0 and not math.isnan(t)
