"""Agreement with the Holmes map at large velocity, |tau - 2v| <= 4|eps|/tau.

tau*(v - tau/2) = eps*(cos(phi + tau) - cos(phi)) gives |tau - 2v| <= 4|eps|/tau exactly; the
fast tau adds at most K*kappa*u*tau, and 2v is exact in float64. One step of the two maps then
differs by |tau - 2v| in phase and by at most (1 + 2|eps|)*|tau - 2v| in velocity, i.e. by
O(eps/v): the scaled differences |diff|*v/eps stay below 2 and 2*(1 + 2*eps) (bound 10 here).
"""

import math

import numpy as np
import pytest
from fastpath_figures import record
from fastpath_tolerances import phase_distance, tau_tolerance
from hypothesis import given
from hypothesis import strategies as st

import fastpath

TWO_PI = 2.0 * math.pi


@given(
    phi=st.floats(min_value=0.0, max_value=TWO_PI, exclude_max=True),
    log_v=st.floats(min_value=1.0, max_value=6.0),
    eps=st.floats(min_value=0.0, max_value=2.0),
)
def test_flight_time_near_2v(phi, log_v, eps):
    v = 10.0**log_v
    res = fastpath.flight(phi, v, eps)
    assert res.status == fastpath.FlightStatus.CONVERGED
    tau = res.tau
    bound = 4.0 * eps / tau + float(tau_tolerance(phi, v, eps, tau))
    assert abs(tau - 2.0 * v) <= bound


@pytest.mark.parametrize("eps", [0.1, 0.6])
def test_exact_and_holmes_steps_differ_by_order_eps_over_v(eps):
    v = np.repeat(10.0 ** np.arange(1, 6), 16)
    phi = np.tile(np.linspace(0.0, TWO_PI, 16, endpoint=False), 5)
    phi1, v1, _ = fastpath.step(phi, v, eps)
    h_phi1, h_v1 = fastpath.holmes_step(phi, v, eps)
    distance = [float(phase_distance(a, b)) for a, b in zip(phi1, h_phi1, strict=True)]
    scaled_phase = np.array(distance) * v / eps
    scaled_velocity = np.abs(v1 - h_v1) * v / eps
    worst = max(scaled_phase.max(), scaled_velocity.max())
    record(f"exact vs Holmes: max |diff|*v/eps at eps={eps}", f"{worst:.3g}")
    assert scaled_phase.max() <= 10.0
    assert scaled_velocity.max() <= 10.0
