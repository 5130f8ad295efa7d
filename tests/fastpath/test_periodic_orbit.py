"""fastpath.periodic_orbit, the symmetric orbits and Greene's criterion, accelerator blocks.

Known cases: the fixed points (0, pi*m) with DF = [[1, 2], [-2*eps, 1 - 4*eps]] (the paper's
equation (3)); the period-2 orbits (s, pi*m - s), (-s, pi*m + s) with eps*sin(s) = s, whose
Jacobians follow in closed form from tau = 2*v and w = pi*m at both states; the exact period-1
accelerator modes (v = pi*m, -2*eps*sin(phi) = pi*l) with det = (2m - l)/(2m + l); the
standard map's K_c = 0.971635... in the Holmes map and in the exact map's high-velocity limit.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import brentq

import fastpath
from fastpath.dynamics import (
    OrbitNotFound,
    accelerator_search,
    approximants,
    critical_amplitude,
    periodic_orbit,
    residue_crossing,
    symmetric_orbit,
)
from fastpath.dynamics.greene import STANDARD_MAP_K_C, noble
from fastpath.dynamics.periodic_orbit import classify

U = 2.0**-53
K_C_QUARTER = STANDARD_MAP_K_C / 4


def two_start(eps):
    return brentq(lambda s: eps * math.sin(s) - s, 1e-12, math.pi)


def two_monodromy(eps, m):
    """Closed-form DF^2 of the period-2 orbit: at both states w = pi*m and tau = 2*v, so
    a = eps*(sin(phi1) - sin(phi))/(pi*m) = -+2s/(pi*m), b = tau/(pi*m), c = 2*eps*cos(s)."""
    s = two_start(eps)
    w = math.pi * m
    c = 2 * eps * math.cos(s)

    def jac(a, b):
        return np.array([[1 + a, b], [a - c * (1 + a), -1 + b - c * b]])

    first = jac(-2 * s / w, 2 * (w - s) / w)
    second = jac(2 * s / w, 2 * (w + s) / w)
    return second @ first


@given(eps=st.floats(-0.9, 1.9), m=st.integers(1, 5), dphi=st.floats(-1e-3, 1e-3),
       dv=st.floats(-1e-3, 1e-3))
def test_newton_from_a_perturbed_guess_finds_the_fixed_point_and_its_matrix(eps, m, dphi, dv):
    if abs(eps) < 0.05:
        return  # near eps = 0 every orbit is nearly periodic: Newton's basin shrinks
    orbit = periodic_orbit(dphi, math.pi * m + dv, eps, 1)
    assert orbit.winding == m
    assert min(orbit.phi[0], 2 * math.pi - orbit.phi[0]) < 1e-12
    assert abs(orbit.v[0] - math.pi * m) < 1e-12 * m
    expected = np.array([[1, 2], [-2 * eps, 1 - 4 * eps]])
    assert np.allclose(orbit.monodromy, expected, rtol=0, atol=1e-12)
    assert abs(orbit.residue - eps) <= orbit.residue_error + 1e-12
    want = "elliptic" if 0 < eps < 1 else "hyperbolic"
    assert orbit.stability in (want, "undecided")
    if min(abs(eps), abs(eps - 1)) > 1e-9:
        assert orbit.stability == want


@pytest.mark.parametrize("m", [1, 2, 3])
@pytest.mark.parametrize("eps", [1.001, 1.05, 1.15, 1.3])
def test_period_two_orbit_matches_its_closed_form(eps, m):
    s = two_start(eps)
    orbit = periodic_orbit(s + 1e-4, math.pi * m - s, eps, 2)
    assert orbit.winding == 2 * m
    assert np.allclose(sorted(orbit.phi), sorted([s, 2 * math.pi - s]), atol=1e-12)
    assert np.allclose(sorted(orbit.v), [math.pi * m - s, math.pi * m + s], atol=1e-12)
    closed = two_monodromy(eps, m)
    assert abs(orbit.trace - np.trace(closed)) < 1e-11
    assert abs(orbit.determinant - 1) < 1e-12


def test_period_two_orbit_is_elliptic_just_above_one_and_hyperbolic_later():
    assert periodic_orbit(two_start(1.01), math.pi - two_start(1.01), 1.01, 2).stability == \
        "elliptic"
    assert periodic_orbit(two_start(1.3), math.pi - two_start(1.3), 1.3, 2).stability == \
        "hyperbolic"


def test_a_found_orbit_returns_to_its_start_under_fastpath_step():
    s = two_start(1.1)
    orbit = periodic_orbit(s, math.pi - s, 1.1, 2)
    phi, v = orbit.phi[0], orbit.v[0]
    for _ in range(2):
        phi, v, _ = fastpath.step(phi, v, 1.1)
    assert abs(math.remainder(phi - orbit.phi[0], 2 * math.pi)) < 1e-12
    assert abs(v - orbit.v[0]) < 1e-12


@pytest.mark.parametrize("m,eps", [(1, 1.6), (4, 1.6), (10, 1.7)])
def test_exact_period_one_accelerator_mode(m, eps):
    phi = -math.asin(math.pi / (2 * eps))
    orbit = periodic_orbit(phi, math.pi * m, eps, 1, velocity_shift=1)
    assert abs(orbit.v[0] - math.pi * m) < 1e-12 * m
    assert abs(orbit.determinant - (2 * m - 1) / (2 * m + 1)) < 1e-13
    tau_v = 4 * m / (2 * m + 1)
    assert abs(orbit.trace - tau_v * (1 - 2 * eps * math.cos(phi))) < 1e-12
    assert orbit.stability == "elliptic"


def test_holmes_model_has_the_standard_map_fixed_point_matrix():
    orbit = periodic_orbit(0.0, 2 * math.pi, 0.4, 1, model="holmes")
    assert np.allclose(orbit.monodromy, [[1, 2], [-0.8, 1 - 1.6]], atol=1e-14)


@given(residue=st.floats(-10, 10), error=st.floats(0, 1))
def test_classification_never_claims_a_class_the_residue_does_not_prove(residue, error):
    kind = classify(residue, error)
    if kind == "elliptic":
        assert 0 < residue - error and residue + error < 1
    elif kind == "hyperbolic":
        assert residue + error < 0 or residue - error > 1
    else:
        assert kind == "undecided"


@pytest.mark.parametrize("bad", [
    dict(phi=math.nan), dict(v=math.inf), dict(eps=True), dict(period=0), dict(period=1.5),
    dict(v=-1.0), dict(model="standard"), dict(winding=0), dict(velocity_shift=0.5),
])
def test_bad_input_raises_value_error(bad):
    args = dict(phi=0.0, v=math.pi, eps=0.3, period=1) | bad
    with pytest.raises(ValueError):
        periodic_orbit(**args)


def test_no_isolated_orbit_at_eps_zero_is_reported_not_returned():
    with pytest.raises(OrbitNotFound):
        periodic_orbit(0.0, math.pi, 0.0, 1)


def test_symmetric_orbit_agrees_with_the_two_dimensional_newton():
    a = approximants(1, (), levels=4)[-1]
    sym = symmetric_orbit(math.pi * a.winding / a.period, 0.2, a.period, a.winding)
    full = periodic_orbit(sym.phi[0], sym.v[0], 0.2, a.period, winding=a.winding)
    assert abs(sym.residue - full.residue) < 1e-9
    assert 0 < sym.residue < 1


def test_convergents_of_the_noble_numbers():
    assert [(a.period, a.winding) for a in approximants(0, (), 5)] == \
        [(3, 2), (5, 3), (8, 5), (13, 8), (21, 13)]
    assert [(a.period, a.winding) for a in approximants(2, (2,), 4)] == \
        [(3, 7), (5, 12), (8, 19), (13, 31)]
    assert abs(noble(()) - (math.sqrt(5) - 1) / 2) < 1e-15
    assert abs(noble((2,)) - ((math.sqrt(5) - 1) / 2) ** 2) < 1e-15


def test_holmes_map_reproduces_the_standard_map_critical_k():
    c = critical_amplitude(1, (), model="holmes", levels=12)
    assert abs(c.eps_c - K_C_QUARTER) <= c.uncertainty
    assert c.uncertainty < 3e-6


def test_exact_map_tends_to_the_standard_map_at_high_velocity():
    bands = (10, 20, 30, 50, 100)
    rows = [critical_amplitude(b, (), levels=11) for b in bands]
    v = np.array([math.pi * (b + noble(())) for b in bands])
    eps_c = np.array([r.eps_c for r in rows])
    design = np.vstack([np.ones_like(v), 1 / v, 1 / v**2]).T
    a, b, _ = np.linalg.lstsq(design, eps_c, rcond=None)[0]
    uncertainty = max(r.uncertainty for r in rows)
    assert abs(a - K_C_QUARTER) < 10 * uncertainty
    assert b < 0  # the golden curve of band j breaks below K_c/4, by about 0.015/v
    assert np.all(eps_c < K_C_QUARTER)


def test_lowest_band_keeps_its_curves_beyond_the_standard_map_value():
    assert critical_amplitude(0, (2,), levels=9).eps_c > 1.4 * K_C_QUARTER


def test_period_one_accelerator_blocks_exist_exactly_from_half_pi():
    above = accelerator_search(1.6, 1, grid=16)
    assert {o.velocity_shift for o in above} == {-1, 1}
    residues = sorted({round(o.residue, 9) for o in above})
    expected = math.sqrt((4 * 1.6) ** 2 - (2 * math.pi) ** 2) / 4  # |R| = K cos(theta*)/4
    assert np.allclose(residues, [-expected, expected], atol=1e-9)
    assert accelerator_search(1.55, 1, grid=16) == []


def test_continuation_follows_one_branch_through_the_steep_rise_of_the_residue():
    # omega = 0.7236 (prefix (1, 2)) reaches period 843 at 13 levels, where the residue rises
    # by orders of magnitude within 1e-3 in eps and neighbouring orbits lie 1e-5 apart in v
    c = critical_amplitude(0, (1, 2), levels=13)
    eps = [x.eps for x in c.crossings]
    assert c.crossings[-1].approximant.period == 843
    assert abs(eps[-1] - eps[-2]) < 1e-5
    assert all(x.slope > 0 for x in c.crossings)  # the residue rises through 1/4


def test_no_accelerator_block_where_the_kicks_cannot_add_up():
    # p kicks of at most 2*eps each must add up to pi*|l|: none for eps < pi/(2p)
    assert accelerator_search(0.6, 2, grid=16) == []
    assert accelerator_search(0.3, 4, grid=12) == []
    for block in accelerator_search(1.6, 3, grid=12):
        assert block.residual < 1e-9
        assert block.velocity_shift != 0


# --- the minimal period, windings taken from the guess, velocity shifts ------------------------

@pytest.mark.parametrize("eps,period", [(0.6, 2), (0.6, 3), (0.3, 5), (1.5, 2), (-0.3, 4)])
def test_a_fixed_point_asked_at_a_longer_period_is_reported_at_period_one(eps, period):
    orbit = periodic_orbit(0.0, math.pi, eps, period)
    assert (orbit.period, orbit.winding, len(orbit.phi)) == (1, 1, 1)
    assert abs(orbit.trace - (2 - 4 * eps)) < 1e-12


def test_a_period_two_orbit_asked_at_period_four_is_reported_at_period_two():
    s = two_start(1.1)
    orbit = periodic_orbit(s, math.pi - s, 1.1, 4)
    assert (orbit.period, orbit.winding) == (2, 2)
    assert np.allclose(orbit.monodromy, two_monodromy(1.1, 1), atol=1e-10)


@pytest.mark.parametrize("guess", [
    (math.pi, math.pi, math.pi**2 / 4 + 1e-12, 1),  # the first root falls just below pi
    (math.pi, math.pi, 3.0, 1),
    (0.5, 0.05, 0.3, 1),                            # a short hop, t ~ 0.4
    (0.5, 0.05, 0.3, 3),
])
def test_a_guess_whose_flights_last_less_than_pi_is_not_an_orbit(guess):
    with pytest.raises(OrbitNotFound, match="winding"):
        periodic_orbit(*guess)


def test_a_one_off_shifted_block_of_the_exact_map_is_refused():
    with pytest.raises(OrbitNotFound, match="period-1 accelerator mode"):
        periodic_orbit(3.8980936554827061, 60.422221713212743, 1.05, 2, velocity_shift=1)
    with pytest.raises(OrbitNotFound):
        periodic_orbit(0.3, 20.0, 1.2, 3, velocity_shift=3)


def test_a_decelerating_mode_of_the_exact_map_is_refused_but_not_in_the_holmes_model():
    phi = math.asin(math.pi / 3.2)  # -2*eps*sin(phi) = -pi
    with pytest.raises(OrbitNotFound, match="time reverse"):
        periodic_orbit(phi, 4 * math.pi, 1.6, 1, velocity_shift=-1)
    holmes = periodic_orbit(phi, 4 * math.pi, 1.6, 1, velocity_shift=-1, model="holmes")
    assert holmes.velocity_shift == -1


def test_a_mode_asked_as_two_blocks_is_reported_as_one():
    phi = -math.asin(math.pi / 3.2)
    orbit = periodic_orbit(phi, 4 * math.pi, 1.6, 2, velocity_shift=2, winding=9)
    assert (orbit.period, orbit.winding, orbit.velocity_shift) == (1, 4, 1)


def test_the_exact_map_search_keeps_only_accelerating_period_one_modes():
    found = accelerator_search(1.6, 1, model="exact", grid=16, v_base=4 * math.pi)
    assert found and all(o.velocity_shift > 0 and o.period == 1 for o in found)
    assert accelerator_search(1.6, 2, model="exact", grid=8, v_base=4 * math.pi) == []


# --- Greene's criterion: the critical residue, the extrapolation and its uncertainty -----------

def test_crossings_of_the_critical_residue_converge_geometrically_to_k_c_over_4():
    """The Holmes map is the standard map: its golden curve breaks at K_c/4. The crossings of
    R_c alternate around it with a steady ratio near -0.376 (measured: -0.3751 to -0.3768 over
    the last five levels); the Aitken extrapolation is within its stated uncertainty of K_c/4
    (Greene's value to its 9 digits, +-1.25e-10 in eps)."""
    from fastpath.dynamics.greene import extrapolate

    c = critical_amplitude(1, (), model="holmes", levels=12)
    eps = np.array([x.eps for x in c.crossings])
    ratios = np.diff(eps)[1:] / np.diff(eps)[:-1]
    assert np.all(np.abs(ratios[-5:] + 0.376) < 0.005)
    value, uncertainty = extrapolate(eps, [x.eps_error for x in c.crossings])
    assert abs(value - K_C_QUARTER) <= uncertainty + 1.25e-10
    assert abs(c.eps_c - K_C_QUARTER) <= c.uncertainty  # the last crossing and its tail


def test_crossings_of_one_quarter_lie_below_the_critical_amplitude():
    """The bias of targeting R = 1/4: every crossing of 1/4 comes before that of R_c (the
    residue rises through both), so a sequence of them approaches eps_c from below."""
    for a in approximants(1, (), levels=9)[-3:]:
        quarter = residue_crossing(a, model="holmes", target=0.25)
        critical = residue_crossing(a, model="holmes")
        assert quarter.eps < critical.eps


def test_extrapolation_recovers_a_geometric_limit_and_carries_the_crossing_errors():
    from fastpath.dynamics.greene import extrapolate

    limit, rho = 0.2429088515, -0.376
    eps = [limit + 1e-3 * rho**k for k in range(8)]
    value, uncertainty = extrapolate(eps, [0.0] * 8)
    assert abs(value - limit) < 1e-15 and uncertainty < 1e-14
    _, with_errors = extrapolate(eps, [1e-9] * 8)
    assert 0.9e-9 <= with_errors <= 2e-9  # weights summing to about 1
