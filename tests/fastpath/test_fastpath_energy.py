"""Energy bookkeeping: E = v**2/2 + eps*cos(phase) at the plate.

Flight conserves E: (v - tau)**2/2 + eps*cos(phi1) - v**2/2 - eps*cos(phi) = -d(tau), so with
the fast tau the residual is |d'(tau)|*(tau error) + |eps|*(phase rounding) to first order:

    flight tolerance = K*u*tau*(|v| + tau + |eps|*(1 + |phi| + tau)) + |eps|*phase_rounding
                     (+ |d'(tau)|*ulp(t) when tau comes from the differences of an orbit's t).

The impact changes E by 2*u*(u - v_in) (u = -eps*sin(phi1), v_in = v - tau) exactly when
v1 = 2*u - v_in; the fast v1 is that to delta = 2|eps|*phase_rounding + 4 ulp(|tau|+|v|+2|eps|)
(fastpath_tolerances), so the impact residual is <= |v1|*delta + delta**2. All energies are
evaluated exactly (mpmath) from the float outputs.
"""

import math

import pytest
from fastpath_tolerances import DPS, K, U, phase_rounding
from hypothesis import assume, given
from hypothesis import strategies as st
from mpmath import mp

import fastpath

TWO_PI = 2.0 * math.pi


def _energy(v, phase, eps):
    return mp.mpf(v) ** 2 / 2 + mp.mpf(eps) * mp.cos(mp.mpf(phase))


def _flight_tolerance(phi, v, eps, tau, t_rounding=0.0):
    e = abs(eps)
    rate = abs(v - tau) + e  # >= |d'(tau)|
    return (
        K * U * tau * (abs(v) + tau + e * (1.0 + abs(phi) + tau))
        + e * phase_rounding(phi, tau)
        + rate * t_rounding
    )


def _impact_tolerance(phi, v, eps, tau, v1):
    delta = 2.0 * abs(eps) * phase_rounding(phi, tau)
    delta += 4.0 * math.ulp(abs(tau) + abs(v) + 2 * abs(eps))
    return abs(v1) * delta + delta * delta


def _one_collision(phi, v, eps, phi1, v1, tau):
    """(flight residual, impact residual, impact change) as mpf."""
    with mp.workdps(DPS):
        v_in = mp.mpf(v) - mp.mpf(tau)
        u = -mp.mpf(eps) * mp.sin(mp.mpf(phi1))
        e0 = _energy(v, phi, eps)
        e_in = v_in**2 / 2 + mp.mpf(eps) * mp.cos(mp.mpf(phi1))
        e1 = _energy(v1, phi1, eps)
        change = 2 * u * (u - v_in)
        return e_in - e0, (e1 - e_in) - change, change


@given(
    phi=st.floats(min_value=0.0, max_value=TWO_PI, exclude_max=True),
    w0=st.floats(min_value=1e-6, max_value=50.0),
    eps=st.floats(min_value=-0.99, max_value=5.0),
)
def test_energy_in_one_collision(phi, w0, eps):
    v = w0 - eps * math.sin(phi)
    res = fastpath.flight(phi, v, eps)
    assume(res.status == fastpath.FlightStatus.CONVERGED)  # UNCERTAIN: judged elsewhere
    phi1, v1, tau = fastpath.step(phi, v, eps)
    flight, impact, _ = _one_collision(phi, v, eps, phi1, v1, tau)
    assert abs(flight) <= _flight_tolerance(phi, v, eps, tau), (flight, tau)
    assert abs(impact) <= _impact_tolerance(phi, v, eps, tau, v1), (impact, v1)


@pytest.mark.slow
def test_energy_over_an_orbit():
    """E_n - E_0 equals the sum of the impact changes over 10^4 collisions (eps = 0.6)."""
    eps, n = 0.6, 10_000
    orb = fastpath.orbit(4.0, 3.0, eps, n)
    total_change = mp.mpf(0)
    tolerance = 0.0
    with mp.workdps(DPS):
        for k in range(n):
            phi, v, phi1, v1 = orb.phi[k], orb.v[k], orb.phi[k + 1], orb.v[k + 1]
            tau = float(mp.mpf(orb.t[k + 1]) - mp.mpf(orb.t[k]))  # exact difference
            t_rounding = math.ulp(orb.t[k + 1])  # |this tau - the orbit's tau| <= ulp/2
            _, _, change = _one_collision(phi, v, eps, phi1, v1, tau)
            total_change += change
            tolerance += _flight_tolerance(phi, v, eps, tau, t_rounding)
            tolerance += _impact_tolerance(phi, v, eps, tau, v1) + abs(v1) * t_rounding
        drift = _energy(orb.v[n], orb.phi[n], eps) - _energy(orb.v[0], orb.phi[0], eps)
        assert abs(drift - total_change) <= tolerance, (drift, total_change, tolerance)
