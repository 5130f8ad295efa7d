"""The collision map, orbits, reversibility and the impact energy balance."""

from __future__ import annotations

import pytest
from mpmath import mp

import verify

DPS = 50
TOL = mp.mpf(10) ** -40


@pytest.mark.parametrize(("phi", "v", "eps"), [(0.3, 2.0, 0.6), (4.0, 3.0, 0.6), (0.3, 2.0, 3.0)])
def test_reversibility(phi, v, eps):
    phi1, _, tau = verify.step(phi, v, eps, DPS)
    with mp.workdps(DPS):
        back_phi, back_v = -phi1, tau - mp.mpf(v)
    phi2, _, tau2 = verify.step(back_phi, back_v, eps, DPS)
    assert abs(tau2 - tau) < TOL * tau
    with mp.workdps(DPS):
        target = (-mp.mpf(phi)) % (2 * mp.pi)
        diff = abs(phi2 - target)
        assert min(diff, 2 * mp.pi - diff) < TOL


@pytest.mark.parametrize(("phi", "v", "eps"), [(0.3, 2.0, 0.6), (1e6 + 0.3, 5.0, 3.0)])
def test_impact_energy_balance(phi, v, eps):
    phi1, v1, tau = verify.step(phi, v, eps, DPS)
    with mp.workdps(DPS):
        phi, v, eps = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        v_in, u = v - tau, -eps * mp.sin(phi + tau)
        e0 = v**2 / 2 + eps * mp.cos(phi)
        e1 = v1**2 / 2 + eps * mp.cos(phi1)
        assert abs((e1 - e0) - 2 * u * (u - v_in)) < TOL * (1 + abs(e0))
        assert 0 <= phi1 < 2 * mp.pi


def test_orbit_matches_steps():
    orb = verify.orbit(0.3, 2.0, 0.6, 6, DPS)
    assert len(orb.phi) == len(orb.v) == len(orb.t) == 7
    assert orb.t[0] == 0
    phi, v, t = mp.mpf(0.3), mp.mpf(2.0), mp.zero
    with mp.workdps(DPS):
        for k in range(6):
            phi, v, tau = verify.step(phi, v, 0.6, DPS)
            t += tau
            # the orbit carries the exact impact state, the steps the rounded one
            assert abs(orb.phi[k + 1] - phi) < TOL and abs(orb.v[k + 1] - v) < TOL
            assert abs(orb.t[k + 1] - t) < TOL * t


def test_orbit_fixed_point_times():
    with mp.workdps(DPS + 10):
        v = +mp.pi
    orb = verify.orbit(0, v, 0.6, 3, DPS)
    with mp.workdps(DPS):
        for k, t in enumerate(orb.t):
            assert abs(t - 2 * mp.pi * k) < TOL * (k + 1)
