"""Certified flight times: pinned values, symmetries and the rigour of the certificate."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from mpmath import iv, mp

import verify
from tests.verify.cases import STATES, float_gap, small_w0_velocity

DPS = 50
TOL = mp.mpf(10) ** -45


def _iv_gap(phi, v, eps, t, dps=120):
    old = iv.prec
    iv.dps = dps
    try:
        half = iv.mpf(t) / 2
        val = 2 * iv.mpf(eps) * iv.sin(iv.mpf(phi) + half) * iv.sin(half)
        val += iv.mpf(t) * (iv.mpf(v) - half)
        return mp.make_mpf(val._mpi_[0]), mp.make_mpf(val._mpi_[1])
    finally:
        iv.prec = old


def _check_certificate(phi, v, eps, cert, samples=40):
    lo_, hi_ = cert.enclosure
    assert 0 < cert.free_until <= lo_ < hi_
    assert lo_ <= cert.tau <= hi_
    assert (hi_ - lo_) / hi_ <= mp.mpf(10) ** (-DPS + 2)
    assert _iv_gap(phi, v, eps, lo_)[0] > 0
    assert _iv_gap(phi, v, eps, hi_)[1] < 0
    with mp.workdps(120):
        for k in range(1, samples + 1):
            t = cert.free_until * mp.mpf(k) / samples
            assert verify.gap(phi, v, eps, t, dps=120) > 0


@pytest.mark.parametrize("m", [1, 2, 5])
@pytest.mark.parametrize("eps", [0.2429, 0.6, 3.0, -0.6])
def test_fixed_point_flight(m, eps):
    with mp.workdps(DPS + 20):
        v = mp.pi * m
        two_pi_m = 2 * mp.pi * m
    phi1, v1, tau = verify.step(0, v, eps, dps=DPS)
    with mp.workdps(DPS + 20):
        assert abs(tau - two_pi_m) < TOL * m
        assert min(phi1, 2 * mp.pi - phi1) < TOL
        assert abs(v1 - v) < TOL * m


@pytest.mark.parametrize("v", [1e-300, 1e-12, 0.5, 3.0, 123.456, 1e6])
def test_eps_zero_is_two_v(v):
    assert verify.flight_time(0.7, v, 0.0) == 2 * mp.mpf(v)


@pytest.mark.parametrize(("phi", "v", "eps"), STATES)
def test_certificate_is_rigorous(phi, v, eps):
    cert = verify.certify_flight(phi, v, eps, dps=DPS)
    _check_certificate(phi, v, eps, cert, samples=10)
    assert verify.flight_time(phi, v, eps, dps=DPS) == cert.tau


@pytest.mark.parametrize("eps", [0.0, 1e-8, 0.2429, 0.6, 0.999999, 1.0, 1.000001, 3.0, 100.0])
@pytest.mark.parametrize("w0", [1e-3, 1e-6, 1e-9, 1e-12])
def test_small_departure_velocity(eps, w0):
    v = small_w0_velocity(0.3, eps, w0)
    cert = verify.certify_flight(0.3, v, eps, dps=DPS)
    _check_certificate(0.3, v, eps, cert, samples=5)
    if abs(eps) < 1:
        with mp.workdps(60):
            w0_exact = mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(0.3))
            assert 2 * w0_exact / (1 + abs(eps)) <= cert.tau <= 2 * w0_exact / (1 - abs(eps))


@pytest.mark.parametrize(("phi", "v"), [(0.3, 2.0), (4.0, 3.0), (1.0, 7.5)])
@pytest.mark.parametrize("eps", [0.6, 3.0])
def test_eps_sign_is_a_phase_shift_by_pi(phi, v, eps):
    with mp.workdps(DPS + 30):
        shifted = mp.mpf(phi) + mp.pi
    a = verify.flight_time(phi, v, eps, dps=DPS)
    b = verify.flight_time(shifted, v, -eps, dps=DPS)
    assert abs(a - b) < TOL * a


def test_unreduced_phase_equals_reduced():
    phi = 1e6 + 0.3
    with mp.workdps(DPS + 30):
        reduced = mp.mpf(phi) - 2 * mp.pi * mp.floor(mp.mpf(phi) / (2 * mp.pi))
    for eps in (0.6, 3.0):
        a = verify.flight_time(phi, 2.0, eps, dps=DPS)
        b = verify.flight_time(reduced, 2.0, eps, dps=DPS)
        assert abs(a - b) < TOL * a


def test_global_precision_is_restored():
    before_mp, before_iv = mp.prec, iv.prec
    verify.certify_flight(0.3, 2.0, 3.0, dps=80)
    assert (mp.prec, iv.prec) == (before_mp, before_iv)


@settings(max_examples=40, deadline=None)
@given(
    phi=st.floats(-10, 10, allow_nan=False),
    v=st.floats(0.01, 20, allow_nan=False),
    eps=st.floats(-5, 5, allow_nan=False),
)
def test_no_grid_point_before_tau_is_below_the_plate(phi, v, eps):
    assume(v + eps * math.sin(phi) > 1e-6)
    cert = verify.certify_flight(phi, v, eps, dps=30)
    tau = float(cert.tau)
    grid = np.linspace(0.0, tau, 4001)[1:-1]
    scale = abs(v) * tau + tau * tau + abs(eps) * (1 + abs(phi) + tau)
    assert np.all(float_gap(phi, v, eps, grid) > -1e-12 * scale)
    lo_, hi_ = cert.enclosure
    assert _iv_gap(phi, v, eps, lo_)[0] > 0 > _iv_gap(phi, v, eps, hi_)[1]
