"""fastpath.orbit against verify.orbit through chattering and sticking (r < 1, no drag).

Starts next to chattering (w0 = 1e-3), so that the comparison ends before the orbits' chaos
amplifies float64 rounding (from (4, 3) at eps = 1.5 the episodes differ already between verify
at 40, 50 and 70 digits: see the report). Bounds (u = 2**-53; verify is exact to ~1e-45 here):

- t_start (accumulation): fastpath's documented bound (tests/fastpath/
  test_sticking_accumulation.py): 8u*t_acc/(1 - r) for the impacts' roundings plus the start's
  w0 rounding bound B = 2u*|w0| + 3u*|eps*sin(phi0)| times T0's conditioning 2/(a0*(1 - r)).
- t_end (detachment): fastpath tracks phase and time separately; after k flights they differ by
  <= 2*k*u*(t_end + 8*pi), and its theta* is within 16u (tests/fastpath/test_sticking_orbit.py).
- The impact after detachment: fastpath's flight from its float (theta*, u(theta*)) is within
  K*kappa*u*tau of the exact first root (K = 16, tests/fastpath/fastpath_tolerances.py; kappa
  from verify.condition_number), the phase adds the rounding of theta* + tau and two reductions
  (2 ulp(tau + 2*pi) + 8 ulp(2*pi)) and theta*'s own 16u; v1 = (1 + r)*u - r*v_in weighs them by
  at most (1 + r)*|eps| + r <= 1 + 2|eps| (plus a few ulps of the formula).
- Later impacts: fastpath's impact k+1 against verify.step from fastpath's float state k (the
  same per-collision bounds), so chaos does not enter.
"""

import math

import numpy as np
import pytest
from mpmath import mp

import fastpath
import verify

U = 2.0**-53
K = 16


def _phase_distance(a, b):
    with mp.workdps(50):
        d = (mp.mpf(a) - mp.mpf(b)) % (2 * mp.pi)
        return min(d, 2 * mp.pi - d)


def _step_tolerances(phi, v, eps, tau):
    """(phase, velocity) tolerances of one fastpath collision from (phi, v) (module docstring)."""
    kappa = verify.condition_number(phi, v, eps, tau)
    tau_tol = float(K * kappa * U * mp.mpf(tau))
    phase = tau_tol + 2 * math.ulp(abs(float(tau)) + 2 * math.pi) + 8 * math.ulp(2 * math.pi)
    e2 = 1 + 2 * abs(eps)
    return phase + 16 * U, e2 * (phase + 16 * U) + 4 * math.ulp(float(tau) + abs(v) + e2)


SLOW = pytest.mark.slow


@pytest.mark.parametrize("eps, r, phi0", [
    pytest.param(1.5, 0.8, math.pi, marks=SLOW), pytest.param(3.0, 0.5, math.pi, marks=SLOW),
    pytest.param(-1.5, 0.8, 0.5, marks=SLOW), pytest.param(1.2, 0.3, math.pi, marks=SLOW),
    (0.5, 0.5, 0.0)])
def test_sticking_intervals_and_impacts_after_detachment_agree(eps, r, phi0):
    w0 = 1e-3
    v0 = w0 - eps * math.sin(phi0)
    n = 400
    fast = fastpath.orbit(phi0, v0, eps, n, restitution=r)
    ref = verify.orbit(phi0, v0, eps, n, restitution=r)
    assert fast.stopped == ref.stopped
    assert fast.sticking.shape[0] >= 1 and len(ref.sticking) >= 1
    # the first episode
    t_acc, t_end = ref.sticking[0]
    a0 = 1 - eps * math.cos(phi0)
    bound_w0 = 2 * U * abs(w0) + 3 * U * abs(eps * math.sin(phi0))
    tol = 8 * U * float(t_acc) / (1 - r) + bound_w0 * 2 / (a0 * (1 - r))
    assert abs(fast.sticking[0, 0] - t_acc) <= tol
    if ref.stopped == "stuck":
        assert fast.sticking[0, 1] == math.inf and t_end == mp.inf
        return
    flights = int(np.searchsorted(fast.t, fast.sticking[0, 1])) + 1
    tol = 2 * flights * U * (float(t_end) + 8 * math.pi) + 16 * U
    assert abs(fast.sticking[0, 1] - t_end) <= tol
    # the impact ending the flight from detachment, in both
    jf = int(np.searchsorted(fast.t, fast.sticking[0, 1]))
    jr = next(k for k, t in enumerate(ref.t) if t > t_end)
    with mp.workdps(50):
        theta_star = 2 * mp.pi - mp.acos(1 / mp.mpf(eps)) if eps > 0 else mp.pi - mp.acos(
            1 / mp.mpf(-eps))
        v_star = mp.sqrt(mp.mpf(eps) ** 2 - 1)
    tol_phi, tol_v = _step_tolerances(theta_star, v_star, eps, ref.t[jr] - t_end)
    assert _phase_distance(fast.phi[jf], ref.phi[jr]) <= tol_phi
    assert abs(fast.v[jf] - ref.v[jr]) <= tol_v
    # the next impacts: fastpath's collision k -> k+1 against verify.step from its float state
    checked = 0
    for k in range(jf, min(jf + 5, len(fast.t) - 1)):
        if np.any((fast.sticking[:, 0] > fast.t[k]) & (fast.sticking[:, 0] < fast.t[k + 1])):
            break
        phi1, v1, tau = verify.step(fast.phi[k], fast.v[k], eps, restitution=r)
        tol_phi, tol_v = _step_tolerances(fast.phi[k], fast.v[k], eps, tau)
        assert _phase_distance(fast.phi[k + 1], phi1) <= tol_phi
        assert abs(fast.v[k + 1] - v1) <= tol_v
        checked += 1
    assert checked >= 1
