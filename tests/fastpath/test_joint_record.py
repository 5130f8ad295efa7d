"""The joint record of (n, t) in the escape kernel (``arrays.JointCounts``): each particle's
end in one bin whose n and t are that particle's, marginals equal to the clocks' histograms,
histograms unchanged by the record, the same for any number of threads."""

import math

import numba
import numpy as np
import pytest

import fastpath
from fastpath.kernels.arrays import (
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    JointCounts,
    Sample,
    Starts,
    joint_histogram,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import bin_index, exit_hole, log_edges
from fastpath.physics import describe

N_EDGES = log_edges(1.0, 8, 10, integer=True)
T_EDGES = np.concatenate([[0.0], log_edges(0.1, 9, 10)])
BINS = Bins(n_edges=N_EDGES, t_edges=T_EDGES, record_n=True, record_t=True)
EPS = 0.6
BLOCKS = 8


def holes_at(*centres, width=0.3):
    return Holes(lo=np.array([(c - width / 2) % (2 * math.pi) for c in centres]),
                 width=np.full(len(centres), width))


def starts(m, seed=1):
    rng = np.random.default_rng(seed)
    return Starts(phi=rng.uniform(3.85, 4.15, m), v=rng.uniform(2, 4, m), t=np.zeros(m),
                  n=np.zeros(m, np.int64))


def run(counts, start, holes, horizon, physics=None):
    m = len(start.phi)
    flags = Flags.zeros(m)
    escape_chunk(physics or describe(EPS), start, holes, horizon, BINS, Sample.none(m),
                 counts, flags)
    assert not flags.status.any()
    return counts


def joint_run(start, holes, horizon, physics=None):
    m, h = len(start.phi), len(holes.lo)
    counts = run(JointCounts.zeros(BLOCKS, -(-m // BLOCKS), h, len(N_EDGES), len(T_EDGES)),
                 start, holes, horizon, physics)
    return counts, joint_histogram(counts, len(N_EDGES), len(T_EDGES))


def reference_ends(start, holes, horizon):
    """(outcome, n, t) of every particle, stepped one collision at a time by ``fastpath.step``
    (the kernel's collisions bit for bit) with the kernel's rules for holes and the horizon."""
    out = []
    for phi, v in zip(start.phi, start.v, strict=True):
        n, t = 0, 0.0
        while True:
            if n >= horizon.max_collisions:
                out.append((len(holes.lo), n, t))
                break
            phi, v, tau = (float(x) for x in fastpath.step(phi, v, EPS))
            if t + tau > horizon.max_time:
                out.append((len(holes.lo), n, t + tau))
                break
            n, t = n + 1, t + tau
            j = exit_hole(phi, holes.lo, holes.width)
            if j >= 0:
                out.append((j, n, t))
                break
    return out


def test_each_particle_is_counted_in_the_bin_of_its_own_n_and_t():
    """Against an independent per-particle reference: the pairing of n with t, which the
    marginals alone cannot show, is each particle's own."""
    start, holes = starts(400, seed=2), holes_at(1.0, 2.5)
    horizon = Horizon(max_collisions=60, max_time=150.0)  # both kinds of censoring occur
    _, joint = joint_run(start, holes, horizon)
    ends = reference_ends(start, holes, horizon)
    expected = np.zeros_like(joint)
    for o, n, t in ends:
        expected[o, bin_index(N_EDGES, n), bin_index(T_EDGES, t)] += 1
    assert sum(o == 2 for o, _, _ in ends) > 20  # the horizon matters here
    np.testing.assert_array_equal(joint, expected)


@pytest.mark.parametrize("physics", [describe(EPS), describe(EPS, restitution=0.5)],
                         ids=["elastic", "restitution 0.5"])
def test_marginals_are_the_histograms_of_the_clocks(physics):
    start, holes = starts(3000, seed=3), holes_at(2.0)
    counts, joint = joint_run(start, holes, Horizon(max_collisions=2000, max_time=1e4), physics)
    esc_n, esc_t = counts.esc_n.sum(0), counts.esc_t.sum(0)
    sides = [(esc_n[0], esc_t[0]), (counts.cens_n.sum(0), counts.cens_t.sum(0)),
             (counts.stuck_n.sum(0), counts.stuck_t.sum(0))]
    for o, (by_n, by_t) in enumerate(sides):
        np.testing.assert_array_equal(joint[o].sum(axis=1), by_n)
        np.testing.assert_array_equal(joint[o].sum(axis=0), by_t)
    assert joint.sum() == 3000
    if physics.restitution < 1:
        assert joint[2].sum() > 100  # particles at rest on the plate: their own outcome


def test_the_record_leaves_the_histograms_alone():
    start, holes = starts(2000, seed=4), holes_at(0.0, 2.5)
    horizon = Horizon(max_collisions=500, max_time=3e3)
    m, nb, tb = 2000, len(N_EDGES), len(T_EDGES)
    plain = run(EscapeCounts.zeros(BLOCKS, 2, nb, tb), start, holes, horizon)
    joint, _ = joint_run(start, holes, horizon)
    for name in EscapeCounts._fields:
        np.testing.assert_array_equal(getattr(joint, name), getattr(plain, name), err_msg=name)
    assert m == joint.ended.sum()


def test_the_joint_histogram_does_not_depend_on_threads():
    start, holes = starts(3000, seed=5), holes_at(2.0)
    horizon = Horizon(max_collisions=3000, max_time=1e5)
    saved = numba.get_num_threads()
    try:
        out = []
        for k in sorted({1, numba.config.NUMBA_NUM_THREADS}):
            numba.set_num_threads(k)
            out.append(joint_run(start, holes, horizon)[1])
    finally:
        numba.set_num_threads(saved)
    for other in out[1:]:
        np.testing.assert_array_equal(other, out[0])


def test_a_block_that_records_more_ends_than_particles_is_refused():
    counts = JointCounts.zeros(2, 3, 1, len(N_EDGES), len(T_EDGES))
    counts.ended[1] = 4
    with pytest.raises(ValueError, match="at most 3 particles recorded 4 ends"):
        joint_histogram(counts, len(N_EDGES), len(T_EDGES))
