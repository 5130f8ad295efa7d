"""The ensemble kernels: hole membership, bins, conservation of particles, thread independence."""

import math
import re

import numba
import numpy as np
import pytest

import fastpath
from fastpath.kernels.arrays import (
    NO_LIMIT,
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    Sample,
    Starts,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import bin_index, exit_hole, log_edges
from fastpath.physics import dissipative, elastic, holmes

TWO_PI = 2 * math.pi
EPS = 0.6
N_EDGES = log_edges(1.0, 8, 10, integer=True)
T_EDGES = np.concatenate([[0.0], log_edges(0.1, 9, 10)])


def run_kernel(
    phi0, v0, hole_lo, hole_width, max_n=NO_LIMIT, max_t=np.inf, blocks=8, sample_target=None,
    physics=None,
):
    m = len(phi0)
    holes = len(hole_lo)
    nb, tb = len(N_EDGES), len(T_EDGES)
    out = {
        "esc_n": np.zeros((blocks, holes, nb), np.int64),
        "esc_t": np.zeros((blocks, holes, tb), np.int64),
        "cens_n": np.zeros((blocks, nb), np.int64),
        "cens_t": np.zeros((blocks, tb), np.int64),
        "collisions": np.zeros(blocks, np.int64),
        "flags": np.zeros(m, np.int8),
        "flag_state": np.zeros((m, 4)),
    }
    slot = np.full(m, -1, np.int64)
    target = np.zeros(m, np.int64)
    samples = np.zeros((0, 6))
    if sample_target is not None:
        slot[:] = np.arange(m)
        target[:] = sample_target
        samples = np.zeros((m, 6))
    escape_chunk(
        elastic(EPS) if physics is None else physics,
        Starts(phi=np.asarray(phi0, float), v=np.asarray(v0, float), t=np.zeros(m),
               n=np.zeros(m, np.int64)),
        Holes(lo=np.asarray(hole_lo, float), width=np.asarray(hole_width, float)),
        Horizon(max_collisions=max_n, max_time=max_t),
        Bins(n_edges=N_EDGES, t_edges=T_EDGES, record_n=True, record_t=True),
        Sample(slot=slot, target=target, rows=samples),
        EscapeCounts(esc_n=out["esc_n"], esc_t=out["esc_t"], cens_n=out["cens_n"],
                     cens_t=out["cens_t"], stuck_n=np.zeros((blocks, nb), np.int64),
                     stuck_t=np.zeros((blocks, tb), np.int64), collisions=out["collisions"]),
        Flags(status=out["flags"], state=out["flag_state"]),
    )
    out["samples"] = samples
    return out


@pytest.mark.parametrize("physics", [holmes(EPS), (EPS, 0.0, 0, 1.0), "elastic"],
                         ids=["Holmes", "plain tuple", "string"])
def test_escape_chunk_refuses_what_is_not_an_elastic_or_dissipative_description(physics):
    """The lanes run the exact map: a Holmes description (or anything else) is refused by name
    rather than run through the exact loop with its lanes' phases unset."""
    phi, v = starts(20)
    with pytest.raises(ValueError, match=re.escape(repr(physics))):
        run_kernel(phi, v, [0.0], [0.3], max_n=50, physics=physics)


def test_escape_chunk_runs_a_dissipative_description_with_restitution_one():
    """A Dissipative description that is the elastic map (drag 0, r = 1) is run, not refused,
    and gives the elastic description's counts."""
    phi, v = starts(200)
    want = run_kernel(phi, v, [(2.5 - 0.15) % TWO_PI], [0.3], max_n=300)
    got = run_kernel(phi, v, [(2.5 - 0.15) % TWO_PI], [0.3], max_n=300,
                     physics=dissipative(EPS, 0.0, 0, 1.0))
    for key in ("esc_n", "esc_t", "cens_n", "cens_t", "collisions"):
        np.testing.assert_array_equal(got[key], want[key], err_msg=key)


def starts(m, seed=1):
    rng = np.random.default_rng(seed)
    return rng.uniform(3.85, 4.15, m), rng.uniform(2, 4, m)


@pytest.mark.parametrize(
    ("phi", "inside"),
    [
        (0.0, True),
        (0.1, True),
        (TWO_PI - 0.1, True),
        (0.2, False),
        (TWO_PI - 0.2, False),
        (math.pi, False),
    ],
)
def test_hole_centred_at_zero_wraps(phi, inside):
    lo = np.array([(0.0 - 0.15) % TWO_PI])
    assert (exit_hole(phi, lo, np.array([0.3])) == 0) == inside


def test_second_hole_is_found():
    lo = np.array([(0.0 - 0.5) % TWO_PI, math.pi - 0.5])
    assert exit_hole(math.pi, lo, np.array([1.0, 1.0])) == 1


def test_bins_put_values_in_half_open_intervals():
    assert bin_index(N_EDGES, 1.0) == 0
    assert bin_index(N_EDGES, 2.0) == 1
    assert bin_index(T_EDGES, 0.0) == 0
    assert bin_index(T_EDGES, 0.05) == 0
    assert bin_index(T_EDGES, 0.1) == 1
    assert bin_index(T_EDGES, 1e12) == len(T_EDGES) - 1
    assert len(N_EDGES) > 8 * 5 and N_EDGES[-1] == 1e8  # eight decades, integer edges


@pytest.mark.parametrize("edges", [N_EDGES, T_EDGES, np.array([2.0]), np.array([0.0, 0.0, 1.0])],
                         ids=["collisions", "times", "one edge", "repeated edge"])
def test_bin_index_is_numpys_right_searchsorted_less_one(edges):
    """The bin of every kind of value (edges themselves and their neighbours, below the first,
    far above the last, integers, infinities, NaN) is np.searchsorted(side="right") - 1,
    clipped at 0."""
    rng = np.random.default_rng(4)
    values = [*edges, *np.nextafter(edges, -np.inf), *np.nextafter(edges, np.inf),
              *rng.uniform(-1.0, 1.2 * edges[-1], 200), -np.inf, np.inf, np.nan, -1e300, 1e300]
    for x in values:
        assert bin_index(edges, x) == max(np.searchsorted(edges, x, side="right") - 1, 0), x
    for n in (0, 1, 2, 7, 10**6, 10**8, 2**62):
        want = max(np.searchsorted(edges, float(n), side="right") - 1, 0)
        assert bin_index(edges, n) == want, n


def test_every_particle_escapes_or_is_censored():
    phi, v = starts(3000)
    out = run_kernel(phi, v, [(2.5 - 0.15) % TWO_PI], [0.3], max_n=200)
    escaped, censored = out["esc_n"].sum(), out["cens_n"].sum()
    assert escaped + censored == 3000
    assert out["esc_t"].sum() == escaped and out["cens_t"].sum() == censored
    assert censored > 0 and not out["flags"].any()


def test_escape_matches_a_plain_orbit():
    """The kernel's escape index and time agree with fastpath.orbit for each particle."""
    phi, v = starts(40, seed=5)
    lo, width = (1.0 - 0.5) % TWO_PI, 1.0
    for p, w in zip(phi, v, strict=True):
        out = run_kernel([p], [w], [lo], [width], max_n=500, blocks=1)
        orb = fastpath.orbit(p, w, EPS, 500)
        hits = np.flatnonzero(((orb.phi[1:] - lo) % TWO_PI) < width)
        if len(hits) == 0:
            assert out["cens_n"].sum() == 1
            continue
        n = hits[0] + 1
        assert out["esc_n"][0, 0, bin_index(N_EDGES, n)] == 1
        assert out["esc_t"][0, 0, bin_index(T_EDGES, orb.t[n])] == 1
        assert out["collisions"].sum() == n


def test_time_horizon_censors_before_the_late_collision():
    phi, v = starts(500)
    out = run_kernel(phi, v, [(2.5 - 0.15) % TWO_PI], [0.3], max_t=50.0)
    censored_times = np.flatnonzero(out["cens_t"].sum(axis=0))
    assert T_EDGES[censored_times[0] + 1] > 50.0  # bounds are > 50: beyond the horizon


def test_sample_holds_the_state_before_the_target_collision():
    phi, v = starts(50, seed=3)
    out = run_kernel(phi, v, [(2.5 - 0.15) % TWO_PI], [0.3], max_n=10, sample_target=3)
    for row in out["samples"]:
        n, p, w, p1, w1, tau = row
        assert 1 <= n <= 3
        assert fastpath.step(p, w, EPS) == (p1, w1, tau)


def test_counts_do_not_depend_on_the_number_of_threads():
    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("numba has one thread only: 1 vs 2 threads cannot be compared")
    phi, v = starts(20_000, seed=7)
    before = numba.get_num_threads()
    try:
        results = []
        for threads in (1, 2):
            numba.set_num_threads(threads)
            results.append(
                run_kernel(phi, v, [(2.0 - 0.15) % TWO_PI], [0.3], max_n=2000, blocks=16)
            )
    finally:
        numba.set_num_threads(before)
    for key in ("esc_n", "esc_t", "cens_n", "cens_t", "collisions"):
        np.testing.assert_array_equal(results[0][key], results[1][key])


def test_escape_chunk_counts_each_particle_into_its_own_block():
    """Particles are split into ``len(collisions)`` blocks of ceil(m/blocks) consecutive ones,
    and a particle's collisions count into its block's row: 7 particles in 4 blocks (of 2, 2,
    2, 1), no hole (width 0), each censored at exactly 5 collisions, give 10, 10, 10, 5 (a block
    size (m + blocks + 1)//blocks = 3 would give 15, 15, 5, 0; a first lane's block
    (first - lane)//per_block, wrapped as a negative index, 5, 10, 10, 10)."""
    from fastpath.kernels.escape import escape_chunk
    from fastpath.kernels.histogram import log_edges

    m, blocks, max_n = 7, 4, 5
    rng = np.random.default_rng(3)
    n_edges = log_edges(1.0, 8, 10, integer=True)
    t_edges = np.concatenate([[0.0], log_edges(0.1, 9, 10)])
    nb, tb = len(n_edges), len(t_edges)
    collisions = np.zeros(blocks, np.int64)
    cens_n = np.zeros((blocks, nb), np.int64)
    counts = EscapeCounts.zeros(blocks, 1, nb, tb)._replace(cens_n=cens_n, collisions=collisions)
    escape_chunk(elastic(0.6), Starts(phi=rng.uniform(-np.pi, np.pi, m),
                                      v=rng.uniform(1.0, 5.0, m), t=np.zeros(m),
                                      n=np.zeros(m, np.int64)),
                 Holes(lo=np.array([1.0]), width=np.array([0.0])),
                 Horizon(max_collisions=max_n, max_time=np.inf),
                 Bins(n_edges=n_edges, t_edges=t_edges, record_n=True, record_t=True),
                 Sample.none(m), counts, Flags.zeros(m))
    assert cens_n.sum(axis=1).tolist() == [2, 2, 2, 1]  # every particle censored, none flagged
    assert collisions.tolist() == [2 * max_n, 2 * max_n, 2 * max_n, max_n]


def test_overlapping_holes_count_into_the_first_listed():
    """Where holes overlap, a landing in both escapes through the first listed (``exit_hole``
    returns the first j): with two identical holes every escape is in hole 0, in the lanes'
    vectorised hole test too (``hole[lane] < 0`` keeps the first; ``<= 0`` would let hole 1
    overwrite hole 0)."""
    from fastpath.kernels.escape import escape_chunk
    from fastpath.kernels.histogram import log_edges

    m, blocks, max_n = 50, 2, 2000
    rng = np.random.default_rng(4)
    n_edges = log_edges(1.0, 8, 10, integer=True)
    t_edges = np.concatenate([[0.0], log_edges(0.1, 9, 10)])
    nb, tb = len(n_edges), len(t_edges)
    esc_n = np.zeros((blocks, 2, nb), np.int64)
    cens_n = np.zeros((blocks, nb), np.int64)
    flags = np.zeros(m, np.int8)
    counts = EscapeCounts.zeros(blocks, 2, nb, tb)._replace(esc_n=esc_n, cens_n=cens_n)
    escape_chunk(elastic(0.6), Starts(phi=rng.uniform(-np.pi, np.pi, m),
                                      v=rng.uniform(1.0, 5.0, m), t=np.zeros(m),
                                      n=np.zeros(m, np.int64)),
                 Holes(lo=np.array([1.0, 1.0]), width=np.array([0.5, 0.5])),
                 Horizon(max_collisions=max_n, max_time=np.inf),
                 Bins(n_edges=n_edges, t_edges=t_edges, record_n=True, record_t=True),
                 Sample.none(m), counts, Flags(status=flags, state=np.zeros((m, 4))))
    assert not flags.any()
    assert esc_n[:, 0].sum() > m // 2  # most escape (hole 0.5 wide, 2000 collisions)
    assert esc_n[:, 1].sum() == 0
    assert esc_n.sum() + cens_n.sum() == m


def _escape_one(phi, v, eps, hole_lo, hole_width, max_time, max_n=NO_LIMIT, target=None):
    """One particle through ``escape_chunk``, one block, unit bins: (esc_t, cens_t, collisions),
    and with a sample ``target`` also the sample row."""
    t_edges = np.arange(0.0, 10.0)
    esc_n, esc_t = np.zeros((1, 1, 10), np.int64), np.zeros((1, 1, 10), np.int64)
    cens_n, cens_t = np.zeros((1, 10), np.int64), np.zeros((1, 10), np.int64)
    collisions, samples = np.zeros(1, np.int64), np.zeros((1, 6))
    escape_chunk(elastic(eps), Starts(phi=np.array([phi]), v=np.array([v]), t=np.zeros(1),
                                      n=np.zeros(1, np.int64)),
                 Holes(lo=np.array([hole_lo]), width=np.array([hole_width])),
                 Horizon(max_collisions=max_n, max_time=max_time),
                 Bins(n_edges=t_edges, t_edges=t_edges, record_n=True, record_t=True),
                 Sample(slot=np.full(1, -1 if target is None else 0, np.int64),
                        target=np.full(1, target or 0, np.int64), rows=samples),
                 EscapeCounts(esc_n, esc_t, cens_n, cens_t, np.zeros((1, 10), np.int64),
                              np.zeros((1, 10), np.int64), collisions),
                 Flags.zeros(1))
    return esc_t[0, 0], cens_t[0], collisions[0], samples[0]


def test_collision_exactly_at_the_time_horizon_is_made():
    """Censoring needs t > max_time (module docstring): with eps = 0 the first flight is exactly
    tau = 2*v = 2, so a horizon of 2 still makes that collision and the particle escapes."""
    esc_t, cens_t, collisions, _ = _escape_one(0.0, 1.0, 0.0, 1.9, 0.2, max_time=2.0)
    assert collisions == 1
    assert esc_t[2] == 1 and esc_t.sum() == 1 and cens_t.sum() == 0
    esc_t, cens_t, collisions, _ = _escape_one(0.0, 1.0, 0.0, 1.9, 0.2, max_time=np.nextafter(2, 0))
    assert collisions == 0 and esc_t.sum() == 0 and cens_t[2] == 1  # the bound t1 = 2 is kept


def test_sample_is_the_target_collision_when_the_particle_gets_there():
    """eps = 0: every flight is tau = 2, phi advances by 2; the hole [5, 5.1) is never hit in 5
    collisions (phases 2, 4, 6, 8 - 2*pi, 10 - 2*pi). The sample of target 3 is collision 3,
    from (phi, v) = (4, 1) to (6, 1)."""
    _, _, collisions, row = _escape_one(0.0, 1.0, 0.0, 5.0, 0.1, np.inf, max_n=5, target=3)
    assert collisions == 5
    assert tuple(row) == (3.0, 4.0, 1.0, 6.0, 1.0, 2.0)
