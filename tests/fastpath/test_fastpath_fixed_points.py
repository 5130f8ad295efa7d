"""Fixed points (0, pi*m): map to themselves, linearisation, stability."""

import math

import mpmath
import numpy as np
import pytest
from fastpath_figures import record
from fastpath_tolerances import DPS, phase_distance, phi1_tolerance, v1_tolerance
from mpmath import mp

import fastpath

EPS_VALUES = (-0.5, 0.2, 0.6, 0.99, 1.01, 3.0)


@pytest.mark.parametrize("m", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("eps", [-0.5, 0.2, 0.6, 0.99, 1.01, 3.0])
def test_fixed_point_maps_to_itself_fast(m, eps):
    """From the float state (0, fl(pi*m)) one step returns to it within rounding.

    The float start is off the exact fixed point by |pi*m - fl(pi*m)| <= ulp(pi*m)/2; the
    linearisation [[1, 2], [-2eps, 1-4eps]] moves that by at most a factor 3 + 4|eps|.
    """
    v = math.pi * m
    start_error = abs(float(mp.mpf(v) - mp.pi * m))
    phi1, v1, tau = fastpath.step(0.0, v, eps)
    spread = (3.0 + 4.0 * abs(eps)) * start_error
    assert abs(tau - 2.0 * math.pi * m) <= (2.0 * spread + float(phi1_tolerance(0.0, v, eps, tau)))
    assert float(phase_distance(phi1, 0.0)) <= spread + phi1_tolerance(0.0, v, eps, tau)
    assert abs(v1 - v) <= spread + v1_tolerance(0.0, v, eps, tau)


@pytest.mark.parametrize("m", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("eps", [0.2, 0.6, 3.0])
def test_fixed_point_maps_to_itself_verify(m, eps):
    """verify from the exact (mpf) fixed point returns to it to ~50 digits."""
    import verify

    with mp.workdps(DPS + 10):
        v = mp.pi * m
    phi1, v1, tau = verify.step(mp.mpf(0), v, eps, dps=DPS)
    with mp.workdps(DPS + 10):  # compare at full precision (mp's default is 15 digits)
        assert phase_distance(phi1, 0) <= mpmath.mpf(10) ** -40
        assert abs(v1 - v) <= mpmath.mpf(10) ** -40
        assert abs(tau - 2 * v) <= mpmath.mpf(10) ** -40


@pytest.mark.parametrize("m", [1, 3])
@pytest.mark.parametrize("eps", EPS_VALUES)
def test_jacobian_at_fixed_point(m, eps):
    import verify

    with mp.workdps(DPS + 10):
        v = mp.pi * m
    jac = verify.jacobian(mp.mpf(0), v, eps, dps=DPS)
    mp.dps, saved = DPS + 10, mp.dps
    try:
        _check_jacobian(jac, eps)
    finally:
        mp.dps = saved


def _check_jacobian(jac, eps):
    expected = [[1, 2], [-2 * mp.mpf(eps), 1 - 4 * mp.mpf(eps)]]
    for i in range(2):
        for j in range(2):
            assert abs(jac[i, j] - expected[i][j]) <= mpmath.mpf(10) ** -40, (i, j, jac)


@pytest.mark.parametrize("eps", EPS_VALUES)
def test_fixed_point_eigenvalues_elliptic_iff_0_lt_eps_lt_1(eps):
    import verify

    with mp.workdps(DPS + 10):
        jac = verify.jacobian(mp.mpf(0), +mp.pi, eps, dps=DPS)
        eigenvalues = mpmath.eig(jac, left=False, right=False)
        tiny = mpmath.mpf(10) ** -30
        assert abs(mpmath.det(jac) - 1) <= tiny
        if 0 < eps < 1:
            for lam in eigenvalues:
                assert abs(mpmath.im(lam)) > tiny, eigenvalues  # complex
                assert abs(abs(lam) - 1) <= tiny, eigenvalues  # on the unit circle
        else:
            for lam in eigenvalues:
                assert abs(mpmath.im(lam)) <= tiny, eigenvalues  # real
            assert max(abs(lam) for lam in eigenvalues) > 1 + tiny  # hyperbolic


def _max_distance(orb, v_fixed):
    dphi = np.abs((orb.phi + math.pi) % (2.0 * math.pi) - math.pi)
    return float(np.max(np.maximum(dphi, np.abs(orb.v - v_fixed))))


@pytest.mark.parametrize("eps", [0.1, 0.3, 0.6])
def test_elliptic_fixed_point_is_stable(eps):
    """Rotation angle cos(theta) = 1 - 2*eps away from theta/2pi = 1/3, 1/4 (eps = 0.75, 0.5)."""
    orb = fastpath.orbit(1e-4, math.pi, eps, 10_000)
    assert len(orb.phi) == 10_001
    distance = _max_distance(orb, math.pi)
    record(f"fixed point (0, pi): max distance over 1e4 collisions at eps={eps}", f"{distance:.3g}")
    assert distance <= 1e-2


@pytest.mark.parametrize("eps", [1.5, -0.3])
def test_hyperbolic_fixed_point_is_left(eps):
    orb = fastpath.orbit(1e-4, math.pi, eps, 10_000, on_uncertain="stop")
    assert _max_distance(orb, math.pi) > 0.1
