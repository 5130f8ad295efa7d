"""Near-tangent departures (|eps| > 1), undecidable collisions and input validation."""

from __future__ import annotations

import math

import pytest
from mpmath import mp

import verify

EPS, PSI, T_GUESS = 3.0, 0.2, 4.0


@pytest.mark.parametrize("clearance", [1e-3, 1e-8, 1e-30])
def test_positive_clearance_flies_past_the_contact(clearance):
    g = verify.grazing_contact(EPS, PSI, T_GUESS, clearance)
    assert g.w0 > 0 and abs(verify.gap(g.phi, g.v, EPS, g.T) - g.clearance) < 1e-45
    cert = verify.certify_flight(g.phi, g.v, EPS)
    assert cert.free_until > g.T
    assert cert.tau > g.T + 1


@pytest.mark.parametrize("clearance", [-1e-3, -1e-8, -1e-30])
def test_negative_clearance_lands_just_before_the_contact(clearance):
    g = verify.grazing_contact(EPS, PSI, T_GUESS, clearance)
    tau = verify.flight_time(g.phi, g.v, EPS)
    curvature = EPS * math.cos(PSI) - 1
    assert g.T - 2 * math.sqrt(-2 * clearance / curvature) < tau < g.T


def test_grazing_departure_is_the_contact_state():
    g = verify.grazing_contact(EPS, PSI, T_GUESS, 1e-8)
    assert verify.grazing_departure(EPS, PSI, T_GUESS, 1e-8) == (g.phi, g.v)


def test_grazing_needs_a_convex_contact():
    with pytest.raises(ValueError, match="eps\\*cos\\(psi\\)"):
        verify.grazing_contact(0.6, 0.2, 4.0, 0.0)


def test_exact_tangency_is_undecidable_at_low_precision():
    g = verify.grazing_contact(EPS, PSI, T_GUESS, 0, dps=500)
    with pytest.raises(verify.UndecidableCollision, match="graze or not") as info:
        verify.certify_flight(g.phi, g.v, EPS, dps=30, max_dps=80)
    assert isinstance(info.value, ArithmeticError)
    assert info.value.dps_reached == 80
    assert "phi=" in str(info.value) and "80 digits" in str(info.value)


def test_w0_at_zero_is_undecidable():
    with mp.workdps(1000):
        phi = mp.mpf(0.3)
        v = -2 * mp.sin(phi)
    with pytest.raises(verify.UndecidableCollision, match="w0"):
        verify.certify_flight(phi, v, 2.0, dps=20, max_dps=60)


@pytest.mark.parametrize(
    ("args", "kwargs", "needle"),
    [
        ((math.nan, 1.0, 0.6), {}, "nan"),
        ((0.3, math.inf, 0.6), {}, "inf"),
        ((0.3, 1.0, -math.inf), {}, "inf"),
        ((0.3, 1.0, 0.6), {"dps": 10}, "dps=10"),
        ((0.3, 1.0, 0.6), {"dps": 50.5}, "dps=50.5"),
        ((0.0, -1.0, 0.6), {}, "w0"),
        ((0.0, 0.0, 0.6), {}, "w0"),
        ((4.0, 0.1, 0.6), {}, "w0"),
    ],
)
def test_bad_input_raises_value_error(args, kwargs, needle):
    with pytest.raises(ValueError, match=needle):
        verify.flight_time(*args, **kwargs)
