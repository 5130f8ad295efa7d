"""The ensemble kernels give the same counts on 1 and on 2 threads.

Each block of particles has its own histogram rows and the caller sums integer counts, so the
result must not depend on the number of threads. The comparison means something only if the
second run really has two threads working: numba's thread count (the setting the kernels
follow, ``fastpath.kernels.threads``) must read back as 2, and the kernel's groups of blocks
must have run in two distinct threads. On a machine where numba offers one thread the tests are
skipped, never passed.
"""

import math
import threading

import numba
import numpy as np
import pytest

from fastpath.kernels import escape, portrait
from fastpath.kernels.arrays import (
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    Portrait,
    Sample,
    Starts,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import log_edges
from fastpath.kernels.portrait import portrait_chunk
from fastpath.kernels.threads import groups_of, over_threads
from fastpath.physics import elastic

TWO_PI = 2 * math.pi
N_EDGES = log_edges(1.0, 8, 20, integer=True)
T_EDGES = np.concatenate([[0.0], log_edges(0.1, 9, 20)])
BLOCKS = 16

pytestmark = pytest.mark.skipif(
    numba.config.NUMBA_NUM_THREADS < 2,
    reason=f"numba offers {numba.config.NUMBA_NUM_THREADS} thread (NUMBA_NUM_THREADS): "
    "1 and 2 threads cannot be compared here",
)


def on_threads(threads, run, monkeypatch):
    """``run()`` with numba set to ``threads`` threads, checked to be in force and in use: the
    kernels' groups of blocks ran in ``threads`` distinct threads."""
    idents = set()

    def recorded(run_group, blocks):
        def run_and_record(first, end):
            idents.add(threading.get_ident())
            run_group(first, end)

        over_threads(run_and_record, blocks)

    for module in (escape, portrait):
        monkeypatch.setattr(module, "over_threads", recorded)
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(threads)
        assert numba.get_num_threads() == threads
        result = run()
    finally:
        numba.set_num_threads(before)
    assert len(idents) == threads
    return result


def escape_run(eps, max_n, max_t, m=6000, seed=7):
    rng = np.random.default_rng(seed)
    phi0, v0 = rng.uniform(3.85, 4.15, m), rng.uniform(2.0, 4.0, m)
    hole_lo = np.array([(0.0 - 0.15) % TWO_PI, 2.0 - 0.15])
    hole_width = np.array([0.3, 0.3])
    nb, tb = len(N_EDGES), len(T_EDGES)
    out = {"esc_n": np.zeros((BLOCKS, 2, nb), np.int64),
           "esc_t": np.zeros((BLOCKS, 2, tb), np.int64),
           "cens_n": np.zeros((BLOCKS, nb), np.int64), "cens_t": np.zeros((BLOCKS, tb), np.int64),
           "collisions": np.zeros(BLOCKS, np.int64), "flags": np.zeros(m, np.int8),
           "flag_state": np.zeros((m, 4)), "samples": np.zeros((m // 10, 6))}
    slot = np.full(m, -1, np.int64)
    slot[::10] = np.arange(m // 10)
    target = rng.integers(1, 50, m)

    def run():
        escape_chunk(elastic(eps),
                     Starts(phi=phi0, v=v0, t=np.zeros(m), n=np.zeros(m, np.int64)),
                     Holes(lo=hole_lo, width=hole_width),
                     Horizon(max_collisions=max_n, max_time=max_t),
                     Bins(n_edges=N_EDGES, t_edges=T_EDGES, record_n=True, record_t=True),
                     Sample(slot=slot, target=target, rows=out["samples"]),
                     EscapeCounts(esc_n=out["esc_n"], esc_t=out["esc_t"], cens_n=out["cens_n"],
                                  cens_t=out["cens_t"], stuck_n=np.zeros((BLOCKS, nb), np.int64),
                                  stuck_t=np.zeros((BLOCKS, tb), np.int64),
                                  collisions=out["collisions"]),
                     Flags(status=out["flags"], state=out["flag_state"]))
        return out

    return run


@pytest.mark.slow
@pytest.mark.parametrize(("eps", "max_n", "max_t"), [(0.6, 60, np.inf), (0.6, 2**62, 300.0),
                                                      (1.5, 500, 2000.0)])
def test_escape_counts_are_the_same_on_one_and_two_threads(eps, max_n, max_t, monkeypatch):
    """Every output array, block by block (not only the sums), bit for bit."""
    one = on_threads(1, escape_run(eps, max_n, max_t), monkeypatch)
    two = on_threads(2, escape_run(eps, max_n, max_t), monkeypatch)
    assert one["esc_n"].sum() > 0 and one["cens_n"].sum() > 0
    assert len(np.flatnonzero(one["collisions"])) == BLOCKS  # every block has work
    for key in one:
        np.testing.assert_array_equal(one[key], two[key], err_msg=key)


def test_portrait_counts_are_the_same_on_one_and_two_threads(monkeypatch):
    m = 3000
    rng = np.random.default_rng(3)
    phi0, v0 = rng.uniform(0.0, TWO_PI, m), rng.uniform(2.0, 6.0, m)

    def run():
        counts = np.zeros((8, 90, 60), np.int64)
        collisions = np.zeros(8, np.int64)
        flags, flag_state = np.zeros(m, np.int8), np.zeros((m, 4))
        portrait_chunk(elastic(0.6),
                       Starts(phi=phi0, v=v0, t=np.zeros(m), n=np.zeros(m, np.int64)), 200,
                       Sample.none(m), Portrait(v_lo=0.0, v_hi=12.0, counts=counts,
                                                collisions=collisions),
                       Flags(status=flags, state=flag_state))
        return counts, collisions, flags

    one, two = on_threads(1, run, monkeypatch), on_threads(2, run, monkeypatch)
    assert one[0].sum() > 0
    for a, b in zip(one, two, strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize(("blocks", "groups", "spans"), [
    (64, 2, [(0, 32), (32, 64)]), (3, 2, [(0, 2), (2, 3)]), (1, 4, [(0, 1)]),
    (5, 3, [(0, 2), (2, 4), (4, 5)]), (4, 3, [(0, 2), (2, 4)]), (7, 0, [(0, 7)])])
def test_groups_of_blocks_cover_every_block_once_in_order(blocks, groups, spans):
    """Consecutive groups, none empty, at most ``groups`` of them, every block in one."""
    assert groups_of(blocks, groups) == spans
