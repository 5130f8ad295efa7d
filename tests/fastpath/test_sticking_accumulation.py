"""Accumulation time and detachment phase against a 60-digit mpmath reference (no ``verify``).

Tolerances (u = 2**-53):

- Tail alone (``accumulation_tail``): its model error is C*q*T with q <= u and C <= 1/2
  (``fastpath.dissipative.sticking``); its formula rounds a = 1 - eps*cos(theta) with an error of
  u*(1 + |eps|) (relative: u*(1 + |eps|)/a) plus a handful of roundings of u each:
  |T - T_ref| <= u*T*(1/2 + 4*(1 + |eps|)/a).
- Accumulation time from a start (phi0, v0) computed by the orbit: every impact leaves a relative
  error of a few u in w (and in its flight), which moves the rest of the sequence, T_rem, by as
  much; T_rem shrinks by r per impact, so the sum is (few u)*t_acc/(1 - r): 8u*t_acc/(1 - r).
  The start's w0 = v0 + eps*sin(phi0) is rounded by <= its bound B
  (``fastpath.elastic.gap.departure``), which the tail carries with weight 2/(a0*(1 - r)) (T0's
  conditioning).
- Detachment phase: arccos(1/|eps|) as atan(sqrt((|eps| - 1)*(|eps| + 1))): a relative error of
  ~4u, < 2*pi*u absolute; 2*pi - alpha rounds by half an ulp of 2*pi (4u), adding the constant's
  low part by as much again: 16u.
"""

import math

import numpy as np
import pytest
import sticking_reference as ref
from fastpath_figures import record
from mpmath import mp

import fastpath
from fastpath.dissipative.sticking import detachment_phase
from fastpath.dissipative.sticking import elastic_accumulation_tail as accumulation_tail
from fastpath.elastic.gap import departure

U = 2.0**-53


@pytest.mark.parametrize("eps", [1.5, 1.0 + 1e-8, 1.0001, 3.0, 1e6, -1.5, -1.2, -1.0 - 1e-6])
def test_detachment_phase_matches_mpmath(eps):
    theta = detachment_phase(eps)
    assert 0.0 <= theta < 2.0 * math.pi
    with mp.workdps(ref.DPS):
        err = abs(mp.mpf(theta) - ref.detachment_phase(eps))
        assert mp.mpf(eps) * mp.cos(mp.mpf(theta)) == pytest.approx(1.0, abs=32 * U * abs(eps))
    record(f"sticking detachment phase error eps={eps} (u)", float(err / U))
    assert err <= 16 * U


@pytest.mark.parametrize("eps", [1.0, -1.0, 0.5, 0.0, -0.99])
def test_no_detachment_for_abs_eps_at_most_one(eps):
    assert math.isnan(detachment_phase(eps))


@pytest.mark.slow
@pytest.mark.parametrize(
    "eps, r, theta, w",
    [(1.5, 0.8, 2.0, 1e-9), (1.5, 0.8, 5.0, 1e-10), (0.5, 0.5, 1.0, 1e-9),
     (1.5, 0.99, 2.5, 1e-11), (3.0, 0.3, 1.6, 1e-9), (-1.5, 0.8, 0.5, 1e-10)],
)
def test_tail_sum_matches_iterated_impacts(eps, r, theta, w):
    """The geometric tail with its first correction against 60-digit impacts plus tail."""
    tail = accumulation_tail(math.sin(theta), math.cos(theta), w, eps, r)
    assert tail == tail, "q <= u expected at this w"
    t_ref, impacts = ref.chatter(theta, w, eps, r)
    a = 1.0 - eps * math.cos(theta)
    err = abs(mp.mpf(tail) - t_ref)
    record(f"sticking tail error eps={eps} r={r} (u*T)", float(err / (U * t_ref)))
    assert impacts > 20
    assert err <= U * t_ref * (0.5 + 4.0 * (1.0 + abs(eps)) / a)


def test_tail_first_correction_is_needed():
    """Without J*T0/(3a) the tail is wrong by far more than the tolerance above (the test bites)."""
    eps, r, theta, w = 1.5, 0.8, 2.0, 1e-9
    a = 1.0 - eps * math.cos(theta)
    t0 = 2.0 * w / (a * (1.0 - r))
    t_ref, _ = ref.chatter(theta, w, eps, r)
    assert abs(mp.mpf(t0) - t_ref) > 100 * U * t_ref * (0.5 + 4.0 * (1.0 + eps) / a)


@pytest.mark.parametrize(
    "eps, r, theta, w",
    [(1.5, 0.8, 0.5, 1e-9),  # a < 0: the plate pulls the particle off, no accumulation
     (1.5, 0.8, 2.0, 1e-3),  # q >> u: impacts are computed one by one
     (0.5, 0.5, 1.0, 0.0)],
)
def test_no_tail_where_it_does_not_apply(eps, r, theta, w):
    assert math.isnan(accumulation_tail(math.sin(theta), math.cos(theta), w, eps, r))


CHATTER_STARTS = [
    (1.5, 0.8, math.pi, 1e-2), (1.5, 0.8, math.pi, 1e-5), (1.5, 0.3, math.pi, 1e-2),
    (1.5, 0.95, math.pi, 1e-3), (3.0, 0.5, math.pi, 1e-3), (0.5, 0.5, 0.0, 0.1),
    (0.5, 0.5, 0.0, 1e-3), (0.5, 0.9, 0.0, 0.05), (1.5, 0.8, 2.0, 1e-2), (-1.5, 0.8, 0.5, 1e-3),
    (0.9, 0.99, 0.0, 1e-2),
]


@pytest.mark.slow
@pytest.mark.parametrize("eps, r, phi0, w0", CHATTER_STARTS)
def test_accumulation_time_matches_reference(eps, r, phi0, w0):
    """sticking[0, 0] of an orbit started near chattering against the 60-digit impacts + tail."""
    v0 = w0 - eps * math.sin(phi0)
    orb = fastpath.orbit(phi0, v0, eps, 100_000, restitution=r)
    assert orb.sticking.shape[0] >= 1
    t_acc = orb.sticking[0, 0]
    with mp.workdps(ref.DPS):
        w_exact = mp.mpf(v0) + eps * mp.sin(mp.mpf(phi0))
        t_ref, _ = ref.chatter(phi0, w_exact, eps, r)
        err = abs(mp.mpf(t_acc) - t_ref)
    _, w0_bound = departure(phi0, math.sin(phi0), v0, eps, 0.0)
    a0 = 1.0 - eps * math.cos(phi0)
    tol = 8.0 * U * float(t_ref) / (1.0 - r) + w0_bound * 2.0 / (a0 * (1.0 - r))
    record(f"sticking t_acc error eps={eps} r={r} phi0={phi0:.3g} w0={w0:g} (u*t_acc)",
           float(err / (U * t_ref)))
    assert err <= tol
    assert np.all(np.diff(orb.t[orb.t <= t_acc]) > 0)
