"""The collision map, orbits, reversibility and the impact energy balance."""

from __future__ import annotations

import pytest
from mpmath import mp

import verify

DPS = 50
TOL = mp.mpf(10) ** -40


@pytest.mark.parametrize(("phi", "v", "eps"), [(0.3, 2.0, 0.6), (4.0, 3.0, 0.6), (0.3, 2.0, 3.0)])
def test_reversibility(phi, v, eps):
    phi1, _, tau = verify.step(phi, v, eps, dps=DPS)
    with mp.workdps(DPS):
        back_phi, back_v = -phi1, tau - mp.mpf(v)
    phi2, _, tau2 = verify.step(back_phi, back_v, eps, dps=DPS)
    assert abs(tau2 - tau) < TOL * tau
    with mp.workdps(DPS):
        target = (-mp.mpf(phi)) % (2 * mp.pi)
        diff = abs(phi2 - target)
        assert min(diff, 2 * mp.pi - diff) < TOL


@pytest.mark.parametrize(("phi", "v", "eps"), [(0.3, 2.0, 0.6), (1e6 + 0.3, 5.0, 3.0)])
def test_impact_energy_balance(phi, v, eps):
    phi1, v1, tau = verify.step(phi, v, eps, dps=DPS)
    with mp.workdps(DPS):
        phi, v, eps = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        v_in, u = v - tau, -eps * mp.sin(phi + tau)
        e0 = v**2 / 2 + eps * mp.cos(phi)
        e1 = v1**2 / 2 + eps * mp.cos(phi1)
        assert abs((e1 - e0) - 2 * u * (u - v_in)) < TOL * (1 + abs(e0))
        assert 0 <= phi1 < 2 * mp.pi


def test_orbit_matches_steps():
    orb = verify.orbit(0.3, 2.0, 0.6, 6, dps=DPS)
    assert len(orb.phi) == len(orb.v) == len(orb.t) == 7
    assert orb.t[0] == 0
    phi, v, t = mp.mpf(0.3), mp.mpf(2.0), mp.zero
    with mp.workdps(DPS):
        for k in range(6):
            phi, v, tau = verify.step(phi, v, 0.6, dps=DPS)
            t += tau
            # the orbit carries the exact impact state, the steps the rounded one
            assert abs(orb.phi[k + 1] - phi) < TOL and abs(orb.v[k + 1] - v) < TOL
            assert abs(orb.t[k + 1] - t) < TOL * t


def test_orbit_fixed_point_times():
    with mp.workdps(DPS + 10):
        v = +mp.pi
    orb = verify.orbit(0, v, 0.6, 3, dps=DPS)
    with mp.workdps(DPS):
        for k, t in enumerate(orb.t):
            assert abs(t - 2 * mp.pi * k) < TOL * (k + 1)


# --- every returned value to what it promises, at any v and phase -----------------------------

def _exact_map(phi, v, eps, digits):
    """An independent reference at ``digits`` digits: Newton's method for the root of d from
    2*w0 (these are fast flights, d' ~ -w0 near the only root there), the phase reduced by
    mpmath at that precision, the map's formulas."""
    with mp.workdps(digits):
        phi, v, eps = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        tau = 2 * (v + eps * mp.sin(phi))
        for _ in range(100):
            gap = 2 * eps * mp.sin(phi + tau / 2) * mp.sin(tau / 2) + tau * (v - tau / 2)
            step = gap / (v - tau + eps * mp.sin(phi + tau))
            tau -= step
            if abs(step) < mp.mpf(10) ** (20 - digits) * tau:
                break
        arg = phi + tau
        phi1 = arg % (2 * mp.pi)
        v1 = -2 * eps * mp.sin(arg) - (v - tau)
        slope = v - tau + eps * mp.sin(arg)
        tau_phi = -eps * (mp.sin(arg) - mp.sin(phi)) / slope
        tau_v = -tau / slope
        c2 = 2 * eps * mp.cos(arg)
        jac = [[1 + tau_phi, tau_v], [tau_phi - c2 * (1 + tau_phi), -1 + tau_v - c2 * tau_v]]
        return phi1, v1, tau, jac


FAST = [(1.0, 1e15, 3.0, 15), (1.0, 1e50, 3.0, 50), (-0.5, 1e16, 0.6, 20), (1.9, 1e16, 0.6, 20),
        (1.0, 1e100, 0.6, 30), (2.0, 1e100, -5.0, 30), (1e300, 1e150, 0.6, 30),
        (0.3, 1e300, 3.0, 15)]


@pytest.mark.parametrize(("phi", "v", "eps", "dps"), FAST)
def test_step_phase_is_accurate_in_absolute_terms_at_any_velocity(phi, v, eps, dps):
    """(phi1, v1, tau) of verify.step within 10**-dps of the exact map: phi1 absolutely (mod
    2*pi), tau relatively, v1 relative to max(|v1|, |eps|); a flight of length 2e15 known only
    to 15 significant digits would leave the phase unknown."""
    phi1, v1, tau = verify.step(phi, v, eps, dps=dps)
    digits = 2 * int(mp.log10(v)) + dps + 40
    phi1_x, v1_x, tau_x, _ = _exact_map(phi, v, eps, digits)
    with mp.workdps(digits):
        turn = 2 * mp.pi
        off = (phi1 - phi1_x) % turn
        assert min(off, turn - off) <= mp.mpf(10) ** -dps
        assert abs(tau - tau_x) <= mp.mpf(10) ** -dps * tau_x
        assert abs(v1 - v1_x) <= mp.mpf(10) ** -dps * max(abs(v1_x), abs(eps))
        assert 0 <= phi1 < turn


def test_three_phases_at_v_1e16_stay_apart():
    """phi = 1.0, -0.5, 1.9 at v = 1e16, eps = 0.6: three different landing phases (a sum
    phi + tau rounded to the flight's ulp would give one), each as the exact map."""
    phases = [verify.step(phi, 1e16, 0.6, dps=20)[0] for phi in (1.0, -0.5, 1.9)]
    assert len({float(p) for p in phases}) == 3
    assert [round(float(p), 4) for p in phases] == [5.4949, 3.9949, 0.1117]


@pytest.mark.parametrize(("phi", "v", "eps", "dps"), FAST[:5] + [(0.3, 2.0, 0.6, 30)])
def test_jacobian_entries_are_accurate_at_any_velocity(phi, v, eps, dps):
    jac = verify.jacobian(phi, v, eps, dps=dps)
    digits = 2 * int(mp.log10(v) if v > 1 else 0) + dps + 40
    *_, exact = _exact_map(phi, v, eps, digits)
    with mp.workdps(digits):
        for i in range(2):
            for j in range(2):
                tol = mp.mpf(10) ** -dps * max(abs(exact[i][j]), 1)
                assert abs(jac[i, j] - exact[i][j]) <= tol


def test_condition_number_of_a_huge_phase_uses_the_reduced_phase():
    """At phi = 1e300 the unreduced |phi| would inflate kappa by ~1e300 (so that '16 kappa*u'
    accepted anything); the reduced phase gives the kappa of the same flight at phi mod 2*pi."""
    tau = verify.flight_time(1e300, 3.0, 0.6)
    with mp.workdps(1000):
        reduced = float(mp.mpf(1e300) % (2 * mp.pi))
    kappa = verify.condition_number(1e300, 3.0, 0.6, tau)
    same = verify.condition_number(reduced, 3.0, 0.6, tau)
    assert abs(kappa - same) <= 1e-12 * same and kappa < 100
    assert verify.condition_number(1e300, 3.0, 0.6, tau, reduced=False) > 1e299
