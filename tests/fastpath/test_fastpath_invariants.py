"""Invariants over 10^6 collisions (fastpath.orbit) at eps = 0.6 and eps = 3, from (4.0, 3.0);
the quick tier checks the same over the first 10^4.

Every flight time (the differences of t) is finite and positive, every phase in [0, 2*pi), every
flight CONVERGED (eps = 3: an UNCERTAIN flight is settled with verify.step and the orbit goes
on; counted), and the gap is >= -gap_error at 8 interior points of every flight (a numba
checker). The checker also re-solves each flight from its float state with solve_flight: the
orbit, which carries sin/cos from one collision to the next, must agree with it within
2*K*kappa*u*tau + ulp(t) (both within K*kappa*u of the exact root; t rounds the difference),
and its phi1, v1 must agree with a fresh ``collide`` within twice the map tolerances.
A sample of flights (the 10 worst conditioned and 20 at random) is checked against verify.step.
"""

import math

import numba
import numpy as np
import pytest
from fastpath_figures import record
from fastpath_tolerances import K, U, phase_distance, phi1_tolerance, tau_tolerance, v1_tolerance
from mpmath import mp

import fastpath
from fastpath.elastic.collision import collide
from fastpath.elastic.flight import solve_flight
from fastpath.elastic.gap import gap, gap_error

N = 1_000_000
TWO_PI = 2.0 * math.pi


@numba.njit(cache=False)
def _check_flights(phi, v, t, eps, interior, k_factor, unit_roundoff):
    """Per flight: worst interior gap / gap_error, orbit-vs-fresh error / tolerance, kappa."""
    n = len(phi) - 1
    two_pi = 2.0 * math.pi
    gap_ratio = np.empty(n)
    tau_ratio = np.empty(n)
    kappas = np.empty(n)
    for k in range(n):
        tau = t[k + 1] - t[k]
        worst = np.inf
        for j in range(1, interior + 1):
            s = tau * j / (interior + 1)
            worst = min(worst, gap(phi[k], v[k], eps, s) / gap_error(phi[k], v[k], eps, s))
        gap_ratio[k] = worst
        fresh, _, _ = solve_flight(phi[k], v[k], eps)
        num = abs(v[k]) + fresh + abs(eps) * (1.0 + abs(phi[k]) + fresh)
        den = abs(v[k] - fresh + eps * math.sin(phi[k] + fresh))
        kap = num / den
        kappas[k] = kap
        # both within K*kappa*u*tau of the root; 2u*|t| >= ulp(t) for the rounded difference
        tol = 2.0 * k_factor * kap * unit_roundoff * fresh + 2.0 * unit_roundoff * abs(t[k + 1])
        ratio = abs(tau - fresh) / tol
        # the map outputs against a fresh collide(), free of the rounding of t: twice the
        # phi1/v1 tolerances of fastpath_tolerances (2u*x >= ulp(x))
        phi1, v1, _, _, _ = collide(phi[k], v[k], eps)
        tau_tol = k_factor * kap * unit_roundoff * fresh
        rounding = 4.0 * unit_roundoff * (abs(phi[k]) + fresh + two_pi)
        rounding += 16.0 * unit_roundoff * two_pi
        dphi = abs(phi1 - phi[k + 1])
        dphi = min(dphi, two_pi - dphi)
        ratio = max(ratio, dphi / (2.0 * (tau_tol + rounding)))
        e2 = 2.0 * abs(eps)
        v_tol = (1.0 + e2) * tau_tol + e2 * rounding
        v_tol += 8.0 * unit_roundoff * (fresh + abs(v[k]) + e2)
        ratio = max(ratio, abs(v1 - v[k + 1]) / (2.0 * v_tol))
        tau_ratio[k] = ratio
    return gap_ratio, tau_ratio, kappas


def _orbit_settling_uncertain(phi0, v0, eps, n):
    """fastpath.orbit, settling each UNCERTAIN flight with verify.step; returns arrays + count."""
    import verify

    phis, vs, ts, its = [np.array([phi0 % TWO_PI])], [np.array([v0])], [np.array([0.0])], []
    settled, phi, v, t0, left = 0, phi0, v0, 0.0, n
    while left > 0:
        orb = fastpath.orbit(phi, v, eps, left, on_uncertain="stop")
        phis.append(orb.phi[1:])
        vs.append(orb.v[1:])
        ts.append(t0 + orb.t[1:])
        its.append(orb.iterations)
        done = len(orb.phi) - 1
        left -= done
        if left == 0:
            break
        assert orb.status in (fastpath.FlightStatus.UNCERTAIN, fastpath.FlightStatus.MAX_ITERATIONS)
        p1, v1, tau = verify.step(float(orb.phi[-1]), float(orb.v[-1]), eps)
        settled += 1
        phi, v, t0 = float(p1), float(v1), float(t0 + orb.t[-1] + float(tau))
        phis.append(np.array([phi]))
        vs.append(np.array([v]))
        ts.append(np.array([t0]))
        left -= 1
    cat = np.concatenate
    return cat(phis), cat(vs), cat(ts), cat(its) if its else np.zeros(0), settled


@pytest.mark.slow
@pytest.mark.parametrize("eps", [0.6, 3.0])
def test_invariants_over_a_million_collisions(eps):
    _check_invariants(eps, N, "1e6")


@pytest.mark.parametrize("eps", [0.6, 3.0])
def test_invariants_over_ten_thousand_collisions(eps):
    _check_invariants(eps, 10_000, "1e4")


def _check_invariants(eps, n, label):
    phi, v, t, iterations, settled = _orbit_settling_uncertain(4.0, 3.0, eps, n)
    assert len(phi) == len(v) == len(t) == n + 1
    record(f"orbit {label} eps={eps}: UNCERTAIN flights settled with verify.step", settled)
    record(
        f"orbit {label} eps={eps}: iterations per flight mean/max",
        f"{iterations.mean():.3f} / {iterations.max()}",
    )
    tau = np.diff(t)
    assert np.all(np.isfinite(tau)) and np.all(tau > 0), np.flatnonzero(~(tau > 0))[:10]
    assert np.all((phi >= 0.0) & (phi < TWO_PI))
    assert np.all(np.isfinite(v))
    gap_ratio, tau_ratio, kappas = _check_flights(phi, v, t, eps, 8, float(K), U)
    bad = np.flatnonzero(gap_ratio < -1.0)
    assert bad.size == 0, f"gap < -gap_error inside flights {bad[:10]}"
    record(
        f"orbit {label} eps={eps}: worst orbit vs fresh solve (tau, phi1, v1) / tolerance",
        f"{tau_ratio.max():.3g}",
    )
    worst = np.flatnonzero(tau_ratio > 1.0)
    assert worst.size == 0, (
        f"{worst.size} flights disagree with a fresh solve, first k={worst[0]}: "
        f"phi={phi[worst[0]]!r}, v={v[worst[0]]!r}, ratio {tau_ratio[worst[0]]:.3g}"
    )
    _check_sample_against_verify(phi, v, t, eps, kappas)


def _check_sample_against_verify(phi, v, t, eps, kappas):
    import verify

    rng = np.random.default_rng(20260611)
    flights = len(kappas)
    sample = set(np.argsort(kappas)[-10:].tolist()) | set(rng.integers(0, flights, 20).tolist())
    for k in sorted(sample):
        p, w = float(phi[k]), float(v[k])
        phi1_ref, v1_ref, tau_ref = verify.step(p, w, eps)
        with mp.workdps(50):
            tau_orbit = mp.mpf(t[k + 1]) - mp.mpf(t[k])
            t_round = math.ulp(t[k + 1])
            dtau = abs(tau_orbit - tau_ref)
        assert dtau <= float(tau_tolerance(p, w, eps, tau_ref)) + t_round, (k, p, w, dtau)
        assert float(phase_distance(phi[k + 1], phi1_ref)) <= phi1_tolerance(p, w, eps, tau_ref)
        assert abs(float(v[k + 1] - v1_ref)) <= v1_tolerance(p, w, eps, tau_ref), (k, p, w)
