"""The landing phase phi1 = (phi + tau) mod 2*pi keeps the departure phase at every speed.

A float flight time has an absolute error of at least half an ulp of tau (the whole circle at
v = 1e16), so ``fastpath`` carries a long flight's root as an unevaluated sum 2*v + delta and
reduces phi + tau exactly (``fastpath.elastic.landing``). The reference is ``verify``'s
certified flight time at enough digits for its absolute error to be far below ulp(2*pi)
(log10(v) + 40 digits), reduced in mpmath.

Tolerances (module docstring of ``fastpath.elastic.landing``):

* where the root is refined (|eps| <= 1 or v >= 2|eps| + 4, tau >= 8): LANDING_ULPS ulps of
  2*pi for the reductions (the TwoSum is exact; the reduction of the rounded sum, the addition of
  the two remainders and the final reduction round a few times at the size of 2*pi), plus the
  root's own error, the rounding of the gap in its Holmes form over the slope:
  16u*(|eps| + |delta|*(v + |delta|))/|d'(tau)|, delta = tau - 2*v;
* elsewhere (short flights, |eps| > 1 below 2|eps| + 4): the certified flight time's error
  K*kappa*u*tau plus the rounding of a float tau (half an ulp of tau) and the same reductions.
"""

import math

import numpy as np
import pytest
from fastpath_figures import record
from fastpath_tolerances import ULP_2PI, K, U, kappa
from mpmath import mp

import fastpath
import verify
from fastpath.elastic.landing import LONG_FLIGHT

LANDING_ULPS = 4


def reference_landing(phi, v, eps):
    """(phi1, tau) from verify's certified root, reduced at log10(v) + 40 digits."""
    digits = int(max(0.0, math.log10(max(v, 1.0)))) + 40
    cert = verify.certify_flight(phi, v, eps, dps=digits)
    with mp.workdps(digits + 20):
        x = mp.mpf(phi) + cert.tau
        two_pi = 2 * mp.pi
        return float(x - two_pi * mp.floor(x / two_pi)), cert.tau


def distance(a, b):
    d = abs(a - b) % (2.0 * math.pi)
    return min(d, 2.0 * math.pi - d)


def refined(v, eps, tau):
    return (abs(eps) <= 1.0 or v >= 2.0 * abs(eps) + 4.0) and tau >= LONG_FLIGHT


def landing_tolerance(phi, v, eps, tau):
    """Absolute tolerance on phi1 (module docstring); tau the reference (an mpf)."""
    with mp.workdps(60):
        slope = abs(mp.mpf(v) - tau + eps * mp.sin(mp.mpf(phi) + tau))
        if refined(v, eps, float(tau)):
            delta = abs(tau - 2 * mp.mpf(v))
            root = 16 * U * (abs(eps) + delta * (v + delta)) / slope
        else:
            root = K * kappa(phi, v, eps, tau) * U * tau + math.ulp(float(tau)) / 2
        return LANDING_ULPS * ULP_2PI + float(root)


@pytest.mark.parametrize(("phi", "truth"), [(1.0, 5.4949), (-0.5, 3.9949), (1.9, 0.1117)])
def test_the_departure_phase_survives_a_flight_at_v_1e16(phi, truth):
    """Three departures at v = 1e16, eps = 0.6 land at three different phases (a float tau
    there is a multiple of 4, and phi + tau rounded to it loses phi entirely)."""
    phi1, _, _ = fastpath.step(phi, 1e16, 0.6)
    ref, tau = reference_landing(phi, 1e16, 0.6)
    assert abs(ref - truth) < 1e-4
    assert distance(phi1, ref) <= landing_tolerance(phi, 1e16, 0.6, tau)


def _departures(seed, m, eps_choices, log_v):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(m):
        eps = float(rng.choice(eps_choices))
        v = 10.0 ** rng.uniform(*log_v)
        if abs(eps) > 1.0:
            v = max(v, 2.0 * abs(eps) + 4.0)
        out.append((float(rng.uniform(-math.pi, math.pi)), v, eps))
    return out


@pytest.mark.parametrize(("eps_choices", "log_v"), [
    ((0.6, -0.9, 1.0, 0.3, 0.05, -1.0), (0.0, 20.0)),
    ((0.6, -0.9, 1.0, 0.3, 0.05, -1.0), (20.0, 300.0)),
    ((1.5, 2.5, -3.0, 10.0), (0.0, 150.0)),
], ids=["eps<=1,v<1e20", "eps<=1,v<1e300", "eps>1,v<1e150"])
def test_landing_phase_is_a_few_ulps_of_2pi_at_every_speed(eps_choices, log_v):
    """Random departures, v log-uniform: phi1 of ``step`` within the module docstring's
    tolerance of verify's, and the refined ones (every long flight here) within LANDING_ULPS
    ulps of 2*pi plus a root error far below an ulp."""
    worst = 0.0
    for phi, v, eps in _departures(7, 60, eps_choices, log_v):
        phi1, _, _ = fastpath.step(phi, v, eps)
        ref, tau = reference_landing(phi, v, eps)
        tolerance = landing_tolerance(phi, v, eps, tau)
        assert distance(phi1, ref) <= tolerance, (phi, v, eps, phi1, ref)
        worst = max(worst, distance(phi1, ref) / ULP_2PI)
    assert worst <= LANDING_ULPS + 1


def test_orbit_and_moments_collisions_land_as_step_does():
    """An orbit at v ~ 1e12 (sines carried from collision to collision): each collision's
    phase within the tolerance of verify's landing from the orbit's own previous state."""
    orb = fastpath.orbit(1.0, 1e12, 0.6, 6)
    for k in range(6):
        ref, tau = reference_landing(orb.phi[k], orb.v[k], 0.6)
        assert distance(orb.phi[k + 1], ref) <= landing_tolerance(orb.phi[k], orb.v[k], 0.6, tau)


@pytest.mark.parametrize("v", [3.0, 1e8, 1e16, 1e100, 1e300])
def test_holmes_phase_reduces_phi_plus_2v_exactly(v):
    """holmes_step's phi1 = (phi + 2v) mod 2*pi within LANDING_ULPS ulps of 2*pi of the exact
    reduction (a float phi + 2v alone is off by up to half an ulp of 2v)."""
    for phi in (1.0, -0.5, 1.9, 3.0):
        phi1, _ = fastpath.holmes_step(phi, v, 0.6)
        with mp.workdps(400):
            x = mp.mpf(phi) + 2 * mp.mpf(v)
            ref = float(x - 2 * mp.pi * mp.floor(x / (2 * mp.pi)))
        assert distance(phi1, ref) <= LANDING_ULPS * ULP_2PI, (phi, v)


@pytest.mark.parametrize(("phi", "v", "eps"), [
    (math.pi, 1.886041815035182e64, 1e-300),   # 1.72 ulps, the largest measured
    (math.pi, 1.178397871306019e175, 0.05),    # 1.70 ulps
])
def test_the_worst_measured_landings_stay_within_the_bound(phi, v, eps):
    phi1, _, _ = fastpath.step(phi, v, eps)
    ref, tau = reference_landing(phi, v, eps)
    assert distance(phi1, ref) <= landing_tolerance(phi, v, eps, tau)
    with mp.workdps(int(math.log10(v)) + 60):  # the error itself, without rounding ref
        x = mp.mpf(phi) + tau
        exact = x - 2 * mp.pi * mp.floor(x / (2 * mp.pi))
        error = abs(mp.mpf(phi1) - exact)
        error = float(min(error, 2 * mp.pi - error))
    record(f"landing phase at phi={phi}, v={v:.4g}, eps={eps:g} (ulps of 2*pi)",
           f"{error / ULP_2PI:.2f}")
