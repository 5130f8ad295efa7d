"""Reversibility, the eps -> -eps symmetry (a shift by pi in phase) and eps = 0 (tau = 2v).

Reversal: from (-phi1, tau - v) the gap is d_rev(s) = d(tau - s), so the flight time is tau
again and the landing phase is -phi. The float reversed state carries the fast tau's error and
the roundings of tau - v and phi1; to first order they move the reversed root by
(tau*|dv'| + 2|eps|*|dphi'|)/w0 (d_rev'(tau) = -w0). With both flights' own K*kappa*u:

    |tau_rev - tau| <= K*u*tau*(kappa + kappa_rev) + (tau*dv' + 2|eps|*dphi') / w0.

eps -> -eps: d(t; phi + pi, v, -eps) = d(t; phi, v, eps); fl(phi + pi) is off by
ulp(|phi| + pi) + |pi - fl(pi)|, which moves tau by 2|eps|*dphi/|d'(tau)|.
"""

import math

from fastpath_reference import assert_flight_ok
from fastpath_tolerances import (
    FLOAT_PI_ERROR,
    K,
    U,
    exact_w0,
    kappa,
    phase_distance,
    phase_rounding,
    phi1_tolerance,
    tau_tolerance,
)
from hypothesis import assume, example, given
from hypothesis import strategies as st

import fastpath

TWO_PI = 2.0 * math.pi
phases = st.floats(min_value=0.0, max_value=TWO_PI, exclude_max=True)
speeds = st.floats(min_value=1e-4, max_value=50.0)


@given(phi=phases, w0=speeds, eps=st.floats(min_value=-3.0, max_value=3.0))
@example(phi=4.0, w0=3.0 + 0.6 * math.sin(4.0), eps=0.6)
def test_reversibility(phi, w0, eps):
    v = w0 - eps * math.sin(phi)
    assume(exact_w0(phi, v, eps) > 0)
    res = fastpath.flight(phi, v, eps)
    assume(res.status == fastpath.FlightStatus.CONVERGED)  # UNCERTAIN is judged elsewhere
    phi1, _, tau = fastpath.step(phi, v, eps)
    phi_r, v_r = -phi1, tau - v
    rev = fastpath.flight(phi_r, v_r, eps)
    if rev.status != fastpath.FlightStatus.CONVERGED:
        assert_flight_ok(phi_r, v_r, eps)  # UNCERTAIN must be a justified near-graze
    else:
        _check_reversed(phi, v, eps, phi1, tau, phi_r, v_r, rev)


def _check_reversed(phi, v, eps, phi1, tau, phi_r, v_r, rev):
    w0_exact = float(exact_w0(phi, v, eps))
    dv = float(tau_tolerance(phi, v, eps, tau)) + math.ulp(abs(tau - v))
    dphi = phi1_tolerance(phi, v, eps, tau)
    tolerance = (
        K * U * tau * float(kappa(phi, v, eps, tau) + kappa(phi_r, v_r, eps, tau))
        + (tau * dv + 2.0 * abs(eps) * dphi) / w0_exact
    )
    assert abs(rev.tau - tau) <= tolerance
    landing, _, _ = fastpath.step(phi_r, v_r, eps)
    assert float(phase_distance(landing, -phi)) <= tolerance + dphi + phase_rounding(phi_r, tau)


@given(phi=phases, w0=speeds, eps=st.floats(min_value=0.0, max_value=0.99))
def test_eps_sign_symmetry(phi, w0, eps):
    v = w0 - eps * math.sin(phi)
    assume(exact_w0(phi, v, eps) > 0 and exact_w0(phi + math.pi, v, -eps) > 0)
    tau = fastpath.flight_time(phi, v, eps)
    tau_shifted = fastpath.flight_time(phi + math.pi, v, -eps)
    rate = abs(v - tau + eps * math.sin(phi + tau))
    dphi = math.ulp(abs(phi) + math.pi) + FLOAT_PI_ERROR
    tolerance = 2.0 * float(tau_tolerance(phi, v, eps, tau)) + 2.0 * eps * dphi / rate
    assert abs(tau_shifted - tau) <= tolerance


@given(phi=st.floats(min_value=-1e6, max_value=1e6), v=st.floats(min_value=1e-300, max_value=1e6))
@example(phi=0.0, v=3.0)
@example(phi=0.0, v=1e-300)  # v**2 underflows: the bracket's bound must not
def test_eps_zero_gives_2v_bitwise(phi, v):
    assert fastpath.flight_time(phi, v, 0.0) == 2.0 * v
    assert fastpath.flight_time(phi, v, -0.0) == 2.0 * v
