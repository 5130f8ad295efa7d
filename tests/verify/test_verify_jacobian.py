"""Linearisation of the map and the condition number."""

from __future__ import annotations

import pytest
from mpmath import mp

import verify

DPS = 50


@pytest.mark.parametrize("m", [1, 3])
@pytest.mark.parametrize("eps", [0.2429, 0.6, 3.0, -0.6])
def test_jacobian_at_fixed_points(m, eps):
    with mp.workdps(DPS + 10):
        v = mp.pi * m
    jac = verify.jacobian(0, v, eps, dps=DPS)
    with mp.workdps(DPS):
        expected = mp.matrix([[1, 2], [-2 * mp.mpf(eps), 1 - 4 * mp.mpf(eps)]])
        assert mp.mnorm(jac - expected, 1) < mp.mpf(10) ** -45
        assert abs(mp.det(jac) - 1) < mp.mpf(10) ** -45


@pytest.mark.parametrize(("phi", "v", "eps"), [(0.3, 2.0, 0.6), (1.1, 4.0, 3.0)])
def test_jacobian_matches_central_differences(phi, v, eps):
    jac = verify.jacobian(phi, v, eps, dps=DPS)
    h = mp.mpf(10) ** -15
    with mp.workdps(DPS):
        phi, v = mp.mpf(phi), mp.mpf(v)
        for col, (dphi, dv) in enumerate([(h, 0), (0, h)]):
            plus = verify.step(phi + dphi, v + dv, eps, dps=DPS)
            minus = verify.step(phi - dphi, v - dv, eps, dps=DPS)
            dphi1 = (plus[0] - minus[0]) / (2 * h)
            dphi1 -= 2 * mp.pi * mp.nint(dphi1 * 2 * h / (2 * mp.pi)) / (2 * h)
            dv1 = (plus[1] - minus[1]) / (2 * h)
            assert abs(dphi1 - jac[0, col]) < mp.mpf(10) ** -20
            assert abs(dv1 - jac[1, col]) < mp.mpf(10) ** -20


def test_condition_number_at_fixed_point_and_small_w0():
    with mp.workdps(DPS):
        kappa = verify.condition_number(0, mp.pi, 0.6, 2 * mp.pi, dps=45)
        expected = (3 * mp.pi + mp.mpf(0.6) * (1 + 2 * mp.pi)) / mp.pi
        assert abs(kappa - expected) < mp.mpf(10) ** -40
    v = -0.6 * mp.sin(0.3) + 1e-9
    tau = verify.flight_time(0.3, float(v), 0.6)
    kappa = verify.condition_number(0.3, float(v), 0.6, tau)
    approx = (abs(v) + 0.6 * 1.3) / 1e-9
    assert approx / 3 < kappa < 3 * approx
