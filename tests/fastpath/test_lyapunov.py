"""fastpath.lyapunov: the tangent map against verify.jacobian, known exponents, the separation
method, running values, ensembles and bad input."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import fastpath
import verify
from fastpath.dynamics import lyapunov, separation, step_jacobian

U = 2.0**-53


@given(phi=st.floats(0, 2 * math.pi), v=st.floats(0.5, 50), eps=st.floats(-0.95, 0.95))
def test_tangent_map_agrees_with_verify_jacobian(phi, v, eps):
    if not v + eps * math.sin(phi) > 0.05:
        return
    ours = step_jacobian(phi, v, eps)
    ref = verify.jacobian(phi, v, eps, dps=30)
    ref = np.array([[float(ref[i, j]) for j in range(2)] for i in range(2)])
    _, v1, tau = fastpath.step(phi, v, eps)
    w1 = v1 + eps * math.sin(phi + tau)
    # entries are ratios over w1 = -d'(tau): their rounding is ~u*(1 + tau)/w1 relative to DF
    scale = np.max(np.abs(ref)) * (1 + (1 + tau + v) / w1)
    assert np.max(np.abs(ours - ref)) <= 256 * U * scale * (1 + tau)


def test_jacobian_at_the_fixed_point_is_the_papers_matrix():
    assert np.allclose(step_jacobian(0.0, math.pi, 0.25), [[1, 2], [-0.5, 0.0]], atol=1e-13)


def test_elliptic_fixed_point_has_zero_exponent():
    # the tangent vector rotates: |DF^n u| stays bounded, so lambda_n <= log(max growth)/n
    lyap = lyapunov(0.0, math.pi, 0.3, 10_000)
    assert 0 <= lyap.per_collision < 1e-3


def test_hyperbolic_fixed_point_gives_its_eigenvalue():
    # trace 2 - 4*eps = -4 at eps = 1.5: |mu| = 2 + sqrt(3); the float orbit leaves the fixed
    # point only after ~25 collisions (rounding 1e-16 grown by 3.73**n)
    lyap = lyapunov(0.0, 2 * math.pi, 1.5, 20)
    assert abs(lyap.per_collision - math.log(2 + math.sqrt(3))) < 0.1


def test_standard_map_exponent_at_large_k_is_log_k_over_two():
    # Chirikov: lambda ~ log(K/2) for K >> 1 (K = 4*eps = 40: corrections below 1e-3); v starts
    # high enough that its diffusion (~sqrt(2*eps**2*n) = 3000) never reaches v - 2*eps < 0
    rng = np.random.default_rng(3)
    lyap = lyapunov(rng.uniform(0, 2 * math.pi, 4), 1e5 + rng.uniform(0, 3, 4), 10.0, 50_000,
                    model="holmes")
    assert abs(lyap.per_collision.mean() - math.log(20.0)) < 0.02


def test_separation_of_nearby_orbits_gives_the_same_exponent():
    rng = np.random.default_rng(4)
    for phi, v in zip(rng.uniform(3.85, 4.15, 3), rng.uniform(2, 4, 3), strict=True):
        tangent = lyapunov(phi, v, 0.6, 20_000).per_collision
        assert abs(separation(phi, v, 0.6, 20_000) - tangent) < 0.01


def test_running_values_end_at_the_final_values():
    lyap = lyapunov(4.0, 3.0, 0.6, 5_000, checkpoints=20)
    assert lyap.collisions[-1] == 5_000
    assert lyap.running_per_collision[-1] == lyap.per_collision
    assert lyap.running_per_time[-1] == lyap.per_time
    assert np.all(np.diff(lyap.collisions) > 0)
    assert np.all(np.diff(lyap.time) > 0)
    orbit = fastpath.orbit(4.0, 3.0, 0.6, 5_000)
    assert abs(lyap.time[-1] - orbit.t[-1]) < 1e-9 * orbit.t[-1]


def test_ensemble_rows_equal_single_runs():
    phi, v = np.array([3.9, 4.1]), np.array([2.5, 3.5])
    both = lyapunov(phi, v, 0.6, 3_000)
    for i in range(2):
        one = lyapunov(float(phi[i]), float(v[i]), 0.6, 3_000)
        assert both.per_collision[i] == one.per_collision
        assert both.per_time[i] == one.per_time


def test_per_time_is_per_collision_scaled_by_mean_flight():
    lyap = lyapunov(4.0, 3.0, 0.6, 10_000)
    ratio = lyap.per_collision / lyap.per_time
    assert abs(ratio - lyap.time[-1] / 10_000) < 1e-9 * ratio


@pytest.mark.parametrize("bad", [
    dict(n=0), dict(eps=math.nan), dict(phi=[1.0, 2.0], v=[3.0, 3.0, 3.0]), dict(checkpoints=0),
    dict(v=-1.0), dict(model="x"), dict(phi=np.zeros((2, 2)), v=np.ones((2, 2)))])
def test_bad_input_raises_value_error(bad):
    args = dict(phi=4.0, v=3.0, eps=0.6, n=10) | bad
    with pytest.raises(ValueError):
        lyapunov(**args)


def test_separation_refuses_a_large_distance():
    with pytest.raises(ValueError):
        separation(4.0, 3.0, 0.6, 10, distance=0.1)


def test_band_exponents_pool_to_the_running_exponent():
    """The log-stretches pooled by band add up to the orbit's S_n: sum over bands of
    mean*count equals lambda_n*n (the same tangent vector, the same collisions)."""
    from fastpath.dynamics import lyapunov_by_band

    phi, v = np.array([4.0, 3.9]), np.array([3.0, 2.5])
    edges = [0.0, 4.0, 8.0, 16.0, 1e9]
    bands = lyapunov_by_band(phi, v, 0.6, 20_000, edges)
    whole = fastpath.lyapunov(phi, v, 0.6, 20_000)
    total = np.nansum(bands.per_collision * bands.collisions)
    assert bands.collisions.sum() == 2 * 20_000
    assert abs(total - np.sum(whole.per_collision * 20_000)) < 1e-8 * 20_000
    assert np.all(bands.orbits[bands.collisions > 0] >= 1)


def test_band_exponents_refuse_bad_edges():
    from fastpath.dynamics import lyapunov_by_band

    with pytest.raises(ValueError, match="edges"):
        lyapunov_by_band(4.0, 3.0, 0.6, 10, [1.0])
    with pytest.raises(ValueError, match="edges"):
        lyapunov_by_band(4.0, 3.0, 0.6, 10, [1.0, 0.5])
