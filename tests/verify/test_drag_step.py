"""Impacts with restitution and drag, orbits, and the default physics running the elastic
code unchanged."""

from __future__ import annotations

import math

import pytest
from mpmath import mp

import verify
from tests.verify.cases import STATES
from tests.verify.test_drag_flight import naive_motion
from verify import flight

TOL = mp.mpf(10) ** -45


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
@pytest.mark.parametrize("r", [1.0, 0.8, 0.3])
@pytest.mark.parametrize(("phi", "v", "eps", "k"), [(4.0, 3.0, 0.6, 0.1), (0.3, 1.5, 1.5, 0.05),
                                                     (1.0, 2.0, 0.3, 0.0)])
def test_impact_law(phi, v, eps, k, r, law):
    """v1 - u = -r*(v_in - u) with v_in = V(tau) from the spec's closed form (independent)."""
    phi1, v1, tau = verify.step(phi, v, eps, drag=k, drag_law=law, restitution=r)
    with mp.workdps(80):
        _, v_in = naive_motion(v, k, law, tau)
        u = -mp.mpf(eps) * mp.sin(mp.mpf(phi) + tau)
        assert abs((v1 - u) + mp.mpf(r) * (v_in - u)) < TOL * (1 + abs(v1))
        assert abs(mp.sin(phi1) - mp.sin(mp.mpf(phi) + tau)) < TOL


@pytest.mark.parametrize(("phi", "v", "eps"), STATES[::3])
def test_default_physics_never_reaches_the_drag_code(monkeypatch, phi, v, eps):
    """Defaults (and drag = 0, r = 1 spelled out, either law) call today's elastic code: the
    drag certificate is not entered and the results are identical."""
    before = verify.certify_flight(phi, v, eps), verify.step(phi, v, eps)

    def forbidden(*args):
        raise AssertionError("drag certificate entered for the default physics")

    monkeypatch.setattr(flight, "drag_attempt", forbidden)
    for law in ("linear", "quadratic"):
        kw = {"drag": 0.0, "drag_law": law}
        assert verify.certify_flight(phi, v, eps, **kw) == before[0]
        assert verify.step(phi, v, eps, **kw, restitution=1.0) == before[1]
    assert verify.certify_flight(phi, v, eps) == before[0]


def test_restitution_one_with_drag_zero_is_the_elastic_map_and_limits():
    """r -> 1: v1 moves by (1 - r)*(v_in - u) exactly (linear in 1 - r)."""
    base = verify.step(4.0, 3.0, 0.6)
    near = verify.step(4.0, 3.0, 0.6, restitution=1 - 1e-9)
    assert near[2] == base[2]  # restitution does not change the flight
    with mp.workdps(60):
        v_in = mp.mpf(3.0) - base[2]
        u = -mp.mpf(0.6) * mp.sin(mp.mpf(4.0) + base[2])
        one_minus_r = 1 - mp.mpf(1 - 1e-9)  # exact: the float r is not 1 - 1e-9 exactly
        assert abs((base[1] - near[1]) - one_minus_r * (u - v_in)) < TOL


def test_orbit_with_drag_and_restitution():
    """Each entry is the step from the previous one: the orbit carries the exact impact state,
    the step starts from the entry rounded to 50 digits, so they agree to ~50 digits (this
    orbit's map has derivatives of order 1)."""
    orb = verify.orbit(1.0, 2.0, 0.6, 4, drag=0.05, restitution=0.9)
    assert orb.sticking == () and orb.stopped == "collisions" and len(orb.v) == 5
    for j in range(4):
        phi1, v1, tau = verify.step(orb.phi[j], orb.v[j], 0.6, drag=0.05, restitution=0.9)
        with mp.workdps(60):
            assert abs(phi1 - orb.phi[j + 1]) < mp.mpf(10) ** -47
            assert abs(v1 - orb.v[j + 1]) < mp.mpf(10) ** -47
            assert abs(orb.t[j] + tau - orb.t[j + 1]) < mp.mpf(10) ** -47


def test_orbit_has_fastpaths_field_names():
    """The fields fastpath.Orbit has and that mean the same here, with their values."""
    orb = verify.orbit(4.0, 3.0, 0.6, 2)
    assert orb.sticking == () and orb.stopped == "collisions"
    assert orb.model == "exact" and orb.eps == mp.mpf(0.6) and orb.dps == 50
    assert len(orb.phi) == len(orb.v) == len(orb.t) == 3


def test_a_tiny_restitution_keeps_the_orbit_a_departure():
    """r = 1e-40 leaves each impact with w ~ 1e-40*|w_in|: rounded to 30 digits, (phi1, v1)
    would not depart; the orbit carries the exact state, sums the tail at once, rides the plate
    and leaves it at theta* (|eps| = 1.5 > 1), impact after impact."""
    orb = verify.orbit(4.0, 3.0, 1.5, 10, dps=30, restitution=1e-40)
    assert orb.stopped == "collisions" and len(orb.phi) == 11
    assert len(orb.sticking) >= 3
    with mp.workdps(40):
        theta_star = 2 * mp.pi - mp.acos(1 / mp.mpf(1.5))
        for t_start, t_end in orb.sticking:
            assert t_start < t_end
            off = (mp.mpf(4.0) + t_end - theta_star) % (2 * mp.pi)
            assert min(off, 2 * mp.pi - off) < 1e-25


def test_chattering_with_drag_accumulates_and_sticks_not_a_hang():
    """eps = 0.5, r = 0.5 with drag: impacts accumulate, the tail with drag is summed
    (verify.dissipative.drag_sticking) and the particle is stuck for good
    (0.5*sqrt(1 + 0.01**2) < 1)."""
    orb = verify.orbit(1.0, 1.0, 0.5, 400, dps=30, drag=0.01, restitution=0.5)
    assert orb.stopped == "stuck" and len(orb.t) < 60  # ratio ~0.5 per impact
    assert len(orb.sticking) == 1 and orb.sticking[0][1] == mp.inf


def test_orbit_validates_physics():
    with pytest.raises(ValueError, match="restitution=2"):
        verify.orbit(1.0, 1.0, 0.5, 3, restitution=2)
    with pytest.raises(ValueError, match=r"drag=-0\.1"):
        verify.orbit(1.0, 1.0, 0.5, 3, drag=-0.1)


def test_w0_zero_default_step_still_rejected():
    """Default physics keeps today's validation: a departure at rest is a ValueError there."""
    with pytest.raises(ValueError, match="no departure"):
        verify.step(0.0, 0.0, 1.5)
    assert math.isfinite(float(verify.step(0.0, 0.0, 1.5, drag=0.1)[2]))
