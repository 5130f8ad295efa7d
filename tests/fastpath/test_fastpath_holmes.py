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


def _holmes_reference(phi, v, eps):
    """(phi + 2v) mod 2*pi and |v - 2*eps*sin(phi1)| at enough digits for any double v."""
    import mpmath

    with mpmath.workdps(360):
        x = mpmath.mpf(phi) + 2 * mpmath.mpf(v)
        turn = 2 * mpmath.pi
        phi1 = x - turn * mpmath.floor(x / turn)
        return phi1, abs(mpmath.mpf(v) - 2 * mpmath.mpf(eps) * mpmath.sin(phi1))


def _ulps_of_two_pi(a, b):
    import mpmath

    with mpmath.workdps(40):
        d = abs(mpmath.mpf(a) - b)
        d = min(d, 2 * mpmath.pi - d)
        return float(d) / math.ulp(TWO_PI)


HOLMES_PHASE_ULPS = 5.0  # the phase's reduction (its rounding) + the landing's few ulps of 2*pi


@given(phi=st.floats(-20.0, 20.0), log_v=st.floats(-1.0, 300.0), eps=st.floats(0.0, 2.0))
def test_holmes_step_reduces_any_phase_at_any_speed(phi, log_v, eps):
    v = 10.0**log_v
    if not v + eps * math.sin(phi) > 1e-9:
        return
    phi1, v1 = fastpath.holmes_step(phi, v, eps)
    ref_phi, ref_v = _holmes_reference(phi, v, eps)
    assert 0.0 <= phi1 < TWO_PI
    assert _ulps_of_two_pi(phi1, ref_phi) <= HOLMES_PHASE_ULPS
    assert abs(v1 - float(ref_v)) <= 8 * 2.0**-53 * (v + 2 * eps) + 2 * eps * 1e-15


def test_holmes_step_array_path_reduces_like_the_scalar_path():
    rng = np.random.default_rng(3)
    phi = np.concatenate([[100.0, -100.0, 1e10, -1e15], rng.uniform(-20, 20, 200)])
    v = np.concatenate([[1e20, 1e20, 3.0, 1e200], 10.0 ** rng.uniform(17, 300, 200)])
    phi1, v1 = fastpath.holmes_step(phi, v, 0.6)
    for i in range(len(phi)):
        assert (phi1[i], v1[i]) == fastpath.holmes_step(float(phi[i]), float(v[i]), 0.6)
        ref_phi, _ = _holmes_reference(float(phi[i]), float(v[i]), 0.6)
        assert _ulps_of_two_pi(phi1[i], ref_phi) <= HOLMES_PHASE_ULPS
