"""The phase tolerance of verify.check (verify/check/tolerance.py): an integrator's landing phase
is held to its own flight time's error plus the rounding of the exactly reduced phase, so a
phase that loses the departure phase in a rounded sum ``phi + tau`` fails at large ``v``."""

from __future__ import annotations

import math
import random

import pytest
from mpmath import mp

import verify
from verify.check.tolerance import map_tolerances, phase_distance, phase_rounding

K = 16.0


def _reference(phi, v, eps):
    """The exact step (to 40 digits) and kappa of the phase as given (as verify.check uses)."""
    phi1, v1, tau = verify.step(phi, v, eps, dps=40)
    return phi1, v1, tau, verify.condition_number(phi, v, eps, tau, reduced=False)


def _careful(phi, v, eps):
    """An integrator that gets tau right to its rounding and reduces phi + tau exactly."""
    _, _, tau = verify.step(phi, v, eps, dps=40)
    tau_f = float(tau)
    with mp.workdps(60 + int(math.log10(abs(phi) + tau_f + 1))):
        phi1 = float((mp.mpf(phi) + mp.mpf(tau_f)) % (2 * mp.pi))
    return phi1, tau_f


def _rounded_sum(phi, v, eps):
    """The same tau, but the phase reduced from the rounded float sum phi + tau."""
    _, tau_f = _careful(phi, v, eps)
    return math.fmod(phi + tau_f, 2 * math.pi) % (2 * math.pi), tau_f


def _departures(count=12, seed=7):
    rng = random.Random(seed)
    return [(rng.uniform(-3.0, 3.0), v, rng.choice((0.6, 3.0)))
            for v in (1e12, 1e16) for _ in range(count)]


CASES = [(1.0, 1e16, 0.6), (-0.5, 1e16, 0.6), (1.9, 1e16, 0.6), *_departures()]


@pytest.mark.parametrize(("phi", "v", "eps"), CASES)
def test_a_phase_reduced_exactly_passes(phi, v, eps):
    phi1_x, _, tau_x, kappa = _reference(phi, v, eps)
    phi1, tau_f = _careful(phi, v, eps)
    _, phi1_tol, _ = map_tolerances(K, phi, v, eps, tau_x, kappa, tau_error=tau_f - tau_x)
    with mp.workdps(40):
        assert phase_distance(phi1, phi1_x) <= phi1_tol


@pytest.mark.parametrize(("phi", "v", "eps"), CASES)
def test_a_phase_from_the_rounded_sum_fails(phi, v, eps):
    """Up to ulp(phi + tau)/2 is lost (2 rad at v = 1e16, 1e-4 at v = 1e12): more than the
    flight time's own error plus 8 ulps of 4*pi on each of these departures, while the tau
    tolerance k*kappa*u*tau plus ulps of |phi| + tau (the bound the phase used to be held to)
    accepts it. (At v ~ 1e8 the loss, ~1e-8, is often within the float tau's own rounding.)"""
    phi1_x, _, tau_x, kappa = _reference(phi, v, eps)
    phi1, tau_f = _rounded_sum(phi, v, eps)
    tau_tol, phi1_tol, _ = map_tolerances(K, phi, v, eps, tau_x, kappa, tau_error=tau_f - tau_x)
    with mp.workdps(40):
        loss = phase_distance(phi1, phi1_x)
        assert loss > phi1_tol
        assert loss <= tau_tol + K / 2 * math.ulp(abs(phi) + float(tau_x) + 2 * math.pi)


def test_phase_rounding_does_not_grow_with_the_flight():
    assert phase_rounding(K) == 8 * math.ulp(4 * math.pi) < 2e-14
