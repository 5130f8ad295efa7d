"""fastpath.kernels.moments: block sums of velocity moments, against fastpath.orbit, for any
thread count."""

import math

import numba
import numpy as np
import pytest

import fastpath
from fastpath import moments

N_GRID = np.array([0, 1, 2, 7, 50, 300])
T_GRID = np.array([0.0, 0.5, 3.0, 40.0, 700.0])


def _starts(m, seed=11, eps=0.6, v=(2.0, 4.0)):
    rng = np.random.default_rng(seed)
    return rng.uniform(3.85, 4.15, m), rng.uniform(*v, m)


def _loop(phi0, v0, eps, model):
    """The same sums by a plain loop over fastpath.orbit."""
    sv, sv2, sdv2 = (np.zeros(len(N_GRID)) for _ in range(3))
    st = np.zeros(len(T_GRID))
    for p, v in zip(phi0, v0, strict=True):
        orb = fastpath.orbit(p, v, eps, 5000, model=model)
        assert orb.t[-1] > T_GRID[-1]
        vn = orb.v[N_GRID]
        sv += vn
        sv2 += vn**2
        sdv2 += (vn - v) ** 2
        st += orb.v[np.searchsorted(orb.t, T_GRID, side="right") - 1]
    m = len(phi0)
    return sv / m, sv2 / m, sdv2 / m, st / m


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_matches_a_loop_over_orbit(model):
    phi0, v0 = _starts(7)
    mom = moments(phi0, v0, 0.6, N_GRID, t_grid=T_GRID, model=model, blocks=3)
    mean_v, mean_v2, mean_dv2, mean_vt = _loop(phi0, v0, 0.6, model)
    rtol = 8 * np.finfo(float).eps
    np.testing.assert_allclose(mom.mean_v_n, mean_v, rtol=rtol)
    np.testing.assert_allclose(mom.mean_v2_n, mean_v2, rtol=rtol)
    np.testing.assert_allclose(mom.mean_dv2_n, mean_dv2, rtol=rtol, atol=1e-300)
    np.testing.assert_allclose(mom.mean_v_t, mean_vt, rtol=rtol)
    assert (mom.particles_n == 7).all() and (mom.particles_t == 7).all()
    assert mom.flagged == 0
    assert mom.mean_dv2_n[0] == 0.0


def _all(mom):
    return [mom.count_n, mom.sum_v_n, mom.sum_v2_n, mom.sum_dv2_n, mom.count_t, mom.sum_v_t]


@pytest.mark.parametrize(("model", "eps", "v"), [("exact", 0.6, (2.0, 4.0)),
                                                 ("exact", 3.0, (100.0, 110.0)),
                                                 ("holmes", 3.0, (100.0, 110.0))])
def test_identical_for_one_and_two_threads(model, eps, v):
    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("numba has one thread only: 1 vs 2 threads cannot be compared")
    phi0, v0 = _starts(301, seed=5, v=v)
    saved = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = moments(phi0, v0, eps, N_GRID, t_grid=T_GRID, model=model, blocks=16)
        numba.set_num_threads(2)  # exactly 2: min(2, available) compared 1 with 1 on one core
        two = moments(phi0, v0, eps, N_GRID, t_grid=T_GRID, model=model, blocks=16)
    finally:
        numba.set_num_threads(saved)
    for a, b in zip(_all(one), _all(two), strict=True):
        np.testing.assert_array_equal(a, b)
    assert one.collisions == two.collisions


def test_blocks_partition_the_particles():
    phi0, v0 = _starts(100)
    mom = moments(phi0, v0, 0.6, [0, 10], blocks=64)  # 2 per block: 50 blocks, none empty
    assert mom.count_n.shape == (50, 2)
    assert (mom.count_n == 2).all()
    whole = moments(phi0, v0, 0.6, [0, 10], blocks=1)
    np.testing.assert_allclose(mom.mean_v_n, whole.mean_v_n, rtol=1e-14)


def test_time_points_past_the_cap_are_missing_not_wrong():
    phi0, v0 = _starts(5)
    mom = moments(phi0, v0, 0.6, [0, 3], t_grid=[0.0, 1e9], max_collisions=20)
    assert (mom.particles_t == [5, 0]).all()
    assert math.isnan(mom.mean_v_t[1])
    assert mom.collisions == 5 * 20


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"phi0": [0.0], "v0": [math.nan]}, "v0 must be finite"),
    ({"phi0": [-math.pi / 2], "v0": [0.5]}, "does not depart"),
    ({"n_grid": [5, 1]}, "sorted"),
    ({"n_grid": [], "t_grid": []}, "n_grid and/or t_grid"),
    ({"model": "nope"}, "model"),
])
def test_bad_input_raises(kwargs, match):
    args = {"phi0": [1.0], "v0": [3.0], "eps": 0.6, "n_grid": [0, 1]} | kwargs
    with pytest.raises(ValueError, match=match):
        moments(**args)
