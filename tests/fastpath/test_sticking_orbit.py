"""Orbits with restitution r < 1: sticking episodes, detachment, stuck for good, impacts, API.

Tolerances (u = 2**-53):

- Phase of a detachment seen from the orbit's clock, (phi0 + t_end) mod 2*pi: the orbit
  tracks its phase and its time separately, each addition of a flight rounding both by <= half
  an ulp (t: u*t, phase: u*4*pi after reduction, a few ulps of 2*pi for the reduction itself).
  After k flights they differ by <= k*u*(t + 8*pi) (factor 2 in hand: 2*k*u*(t + 8*pi)); the
  detachment phase itself is within 16u (test_sticking_accumulation).
- An impact's outgoing relative velocity w1 = v1 + eps*sin(phi1) (exact from the floats) against
  -r*d'(tau_ref): the errors of v1 are those of the elastic map's v1 (tau's error through the
  slope and the phase, the phase rounding, a few roundings of the formula: fastpath_tolerances.
  v1_tolerance), since v1 = (1 + r)*u - r*v_in weighs the same ingredients by at most as much;
  phi1's rounding adds |eps|*phase_rounding. Kinetic energy relative to the plate: w1**2/w_in**2 =
  r**2 (a loss of 1 - r**2) within 2*r*tol/|w_in| + tol**2/w_in**2.
- The w0 = 0 departure from detachment against the exact model's first root: the fastpath flight
  is that of the float state (theta*, u(theta*)), which differs from the exact one by a few u in
  phase and velocity, a gap perturbation inside the gap error that tau_tolerance (K*kappa*u*tau)
  is derived from.
"""

import math

import numpy as np
import pytest
import sticking_reference as ref
from fastpath_figures import record
from fastpath_tolerances import phase_rounding, tau_tolerance, v1_tolerance
from mpmath import mp

import fastpath
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.sticking import detachment_flight, detachment_phase, detachment_velocity
from fastpath.elastic.collision import CARRIED_SINE_ERROR

U = 2.0**-53


def detachment_phase_error(orb, phi0, k):
    """|(phi0 + sticking[k, 1]) - theta*| mod 2*pi (60 digits) and its tolerance."""
    t_end = float(orb.sticking[k, 1])
    flights = int(np.searchsorted(orb.t, t_end)) + 1
    with mp.workdps(ref.DPS):
        d = (mp.mpf(phi0) + mp.mpf(t_end) - ref.detachment_phase(orb.eps)) % (2 * mp.pi)
        err = float(min(d, 2 * mp.pi - d))
    return err, 2.0 * flights * U * (t_end + 8.0 * math.pi) + 16.0 * U


def test_eps_1_5_r_0_8_sticks_and_detaches_at_the_right_phase():
    """eps = 1.5, r = 0.8: sticking episodes, each ending at 2*pi - arccos(1/eps)."""
    phi0, eps = 4.0, 1.5
    orb = fastpath.orbit(phi0, 3.0, eps, 20_000, restitution=0.8)
    assert orb.stopped == "collisions" and len(orb.phi) == 20_001
    assert orb.status == fastpath.FlightStatus.CONVERGED
    assert orb.sticking.shape[0] >= 3
    assert np.all(np.isfinite(orb.sticking)) and np.all(orb.sticking[:, 1] > orb.sticking[:, 0])
    assert np.all(orb.sticking[1:, 0] > orb.sticking[:-1, 1])
    worst = 0.0
    for k in range(orb.sticking.shape[0]):
        err, tol = detachment_phase_error(orb, phi0, k)
        worst = max(worst, err / tol)
        assert err <= tol
    record("sticking eps=1.5 r=0.8 episodes in 2e4 collisions", orb.sticking.shape[0])
    record("sticking eps=1.5 r=0.8 worst detachment phase error (tol)", worst)
    # every detachment starts the same flight: the episodes after the first repeat, up to the
    # rounding of t_start and t_end (each half an ulp of t_end, from the same local times)
    lengths = orb.sticking[1:, 1] - orb.sticking[1:, 0]
    assert np.all(np.abs(lengths - lengths[0]) <= 2.0 * np.spacing(orb.sticking[1:, 1]))


@pytest.mark.parametrize("eps, r", [(1.5, 0.8), (3.0, 0.5), (-1.5, 0.8), (1.2, 0.3)])
def test_detachment_phase_after_a_short_chatter(eps, r):
    phi0 = math.pi if eps > 0 else 0.5
    orb = fastpath.orbit(phi0, 1e-3 - eps * math.sin(phi0), eps, 3000, restitution=r)
    assert orb.sticking.shape[0] >= 1
    err, tol = detachment_phase_error(orb, phi0, 0)
    record(f"sticking detachment phase error eps={eps} r={r} (u)", err / U)
    assert err <= tol


@pytest.mark.parametrize(
    "eps, r, phi0, v0",
    [(0.5, 0.5, 4.0, 3.0),
     (1.0, 0.8, math.pi, 1e-2), (-1.0, 0.5, 0.0, 1.0), (0.0, 0.9, 1.0, 5.0),
     (0.99, 0.7, math.pi, 0.05)],
)
def test_abs_eps_at_most_one_ends_stuck_for_good(eps, r, phi0, v0):
    """Once accumulated, never detached. (Not every orbit accumulates: from (4, 3) at eps = 1,
    r = 0.8 the orbit is attracted to a bouncing orbit of period 2*pi instead.)"""
    n = 100_000
    orb = fastpath.orbit(phi0, v0, eps, n, restitution=r)
    assert orb.stopped == "stuck"
    assert orb.status == fastpath.FlightStatus.CONVERGED
    assert orb.sticking.shape == (1, 2) and orb.sticking[0, 1] == math.inf
    assert orb.t[-1] < orb.sticking[0, 0] < math.inf
    assert len(orb.phi) == len(orb.v) == len(orb.t) == len(orb.iterations) + 1 < n + 1
    record(f"sticking eps={eps} r={r} phi0={phi0:.3g} impacts before stuck", len(orb.iterations))


def test_flat_plate_accumulates_after_2v_over_1_minus_r():
    """eps = 0: the bouncing ball, flights 2*v*r**k, t_acc = 2*v/(1 - r) (the tail model is exact
    here, summed after the first impact); a few roundings of 100: 8 ulps."""
    orb = fastpath.orbit(1.0, 5.0, 0.0, 10, restitution=0.9)
    assert orb.stopped == "stuck" and len(orb.t) == 2 and orb.t[1] == 10.0
    assert abs(orb.sticking[0, 0] - 100.0) <= 8 * math.ulp(100.0)


def test_elastic_default_has_no_sticking_and_is_unchanged():
    a = fastpath.orbit(4.0, 3.0, 0.6, 500)
    b = fastpath.orbit(4.0, 3.0, 0.6, 500, drag=0.0, drag_law="linear", restitution=1.0)
    assert a.sticking.shape == (0, 2) and a.stopped == "collisions"
    for name in ("phi", "v", "t", "iterations"):
        assert np.array_equal(getattr(a, name), getattr(b, name))


def _impact_check(phi, v, eps, r, phi1, v1):
    """(error of w1 against -r*d'(tau_ref), tolerance, w_in_ref) for one recorded impact."""
    with mp.workdps(ref.DPS):
        w = mp.mpf(v) + eps * mp.sin(mp.mpf(phi))
        tau, w_in = ref.flight(phi, w, eps)
        w1 = mp.mpf(v1) + eps * mp.sin(mp.mpf(phi1))
        err = abs(w1 + r * w_in)
    tol = v1_tolerance(phi, v, eps, tau) + abs(eps) * phase_rounding(phi, tau)
    return float(err), tol, float(w_in)


@pytest.mark.slow
@pytest.mark.parametrize("eps, r, phi0, v0", [(0.5, 0.5, 4.0, 3.0), (0.9, 0.8, 1.0, 2.0),
                                              (1.5, 0.8, math.pi, 1e-2), (3.0, 0.5, 2.0, 0.0)])
def test_impact_keeps_r_of_relative_velocity_and_1_minus_r2_of_its_energy(eps, r, phi0, v0):
    """Every impact of the orbit (before it sticks) that the reference can certify."""
    if v0 == 0.0:
        v0 = 1e-2 - eps * math.sin(phi0)
    orb = fastpath.orbit(phi0, v0, eps, 400, restitution=r)
    checked, worst = 0, 0.0
    for k in range(len(orb.iterations)):
        if np.any((orb.sticking[:, 0] > orb.t[k]) & (orb.sticking[:, 0] < orb.t[k + 1])):
            continue  # entry k+1 follows a sticking episode: its flight left from theta*
        try:
            err, tol, w_in = _impact_check(orb.phi[k], orb.v[k], eps, r, orb.phi[k + 1],
                                           orb.v[k + 1])
        except AssertionError:  # a flight the concave reference cannot certify (eps > 1)
            continue
        checked += 1
        worst = max(worst, err / tol)
        assert err <= tol
        with mp.workdps(ref.DPS):
            w1 = mp.mpf(orb.v[k + 1]) + eps * mp.sin(mp.mpf(orb.phi[k + 1]))
            loss = 1 - (w1 / w_in) ** 2
        assert abs(float(loss) - (1 - r * r)) <= 2 * r * tol / abs(w_in) + (tol / w_in) ** 2
    record(f"sticking impact w1 error eps={eps} r={r} worst (tol)", worst)
    assert checked >= 10


@pytest.mark.parametrize("eps, phi, v", [(0.6, 4.0, 3.0), (1.5, 1.0, 2.0), (0.3, 2.0, 0.5)])
@pytest.mark.parametrize("delta", [1e-2, 1e-5, 1e-8])
def test_r_to_one_approaches_the_elastic_map_linearly(eps, phi, v, delta):
    """One collision: same flight; v1(r) - v1_elastic = (1 - r)*w_in, w_in = v_in - u."""
    phi1, v1, tau = fastpath.step(phi, v, eps)
    orb = fastpath.orbit(phi, v, eps, 1, restitution=1.0 - delta)
    w_in = (v - tau) + eps * math.sin(phi + tau)
    tol = 2.0 * v1_tolerance(phi, v, eps, tau)
    assert abs(orb.t[1] - tau) <= 2.0 * float(tau_tolerance(phi, v, eps, tau))
    assert abs((orb.v[1] - v1) - delta * w_in) <= tol


@pytest.mark.parametrize("eps", [1.0001, 1.001, 1.2, 1.5, 3.0, -1.5, 10.0])
def test_departure_from_detachment_w0_zero(eps):
    """tau > t_c > 0, within K*kappa*u*tau of the exact first root, never beyond it."""
    tau, sin1, cos1, _, status = detachment_flight(eps)
    tau_ref, t_c = ref.detachment_flight(eps)
    phi, v = centre_phase(detachment_phase(eps)), detachment_velocity(eps)
    tol = tau_tolerance(phi, v, eps, tau_ref)
    assert status == fastpath.FlightStatus.CONVERGED
    assert tau > float(t_c) > 0.0
    record(f"sticking w0=0 departure error eps={eps} (tol)", float(abs(tau - tau_ref) / tol))
    assert abs(tau - tau_ref) <= tol
    assert tau <= tau_ref + tol
    # the sine and cosine of the exact sum phi + tau (not of its rounding, which is off by up to
    # ulp(phi + tau)/2), within the bound the next flight assumes for a carried sine
    with mp.workdps(40):
        angle = mp.mpf(phi) + mp.mpf(tau)
        assert abs(sin1 - mp.sin(angle)) <= CARRIED_SINE_ERROR
        assert abs(cos1 - mp.cos(angle)) <= CARRIED_SINE_ERROR


def test_departure_from_detachment_too_close_to_eps_1_is_uncertain():
    """d(t_c) ~ (8/3)*(eps - 1)**2 ~ 3e-24 is below the gap's rounding: UNCERTAIN, not a guess."""
    *_, status = detachment_flight(1.0 + 1e-12)
    assert status == fastpath.FlightStatus.UNCERTAIN


def test_chattering_next_to_detachment_hands_over_to_the_ordinary_solver():
    """Hard case: a chatter sequence that reaches theta* before it accumulates (A -> 0-): the
    short-flight window fails, the ordinary solver takes the tiny w, the particle leaves."""
    eps, r = 1.5, 0.9
    theta_star = detachment_phase(eps)
    phi0 = theta_star - 0.05
    orb = fastpath.orbit(phi0, 2e-4 - eps * math.sin(phi0), eps, 200, restitution=r,
                         on_uncertain="stop")
    assert orb.status in (fastpath.FlightStatus.CONVERGED, fastpath.FlightStatus.UNCERTAIN)
    # it left the plate region before accumulating: a flight much longer than the chatter ones
    assert np.max(np.diff(orb.t)) > 1.0
    for k in range(len(orb.iterations)):
        try:
            err, tol, _ = _impact_check(orb.phi[k], orb.v[k], eps, r, orb.phi[k + 1],
                                        orb.v[k + 1])
        except AssertionError:
            continue
        assert err <= tol


@pytest.mark.parametrize(
    "kwargs, name",
    [({"restitution": 0.0}, "restitution"), ({"restitution": 1.5}, "restitution"),
     ({"restitution": -0.1}, "restitution"), ({"restitution": math.nan}, "restitution"),
     ({"restitution": "0.5"}, "restitution"), ({"restitution": True}, "restitution"),
     ({"drag": -1.0}, "drag"), ({"drag": math.inf}, "drag"), ({"drag": math.nan}, "drag"),
     ({"drag_law": "cubic"}, "drag_law")],
)
def test_bad_physics_keywords_name_the_value(kwargs, name):
    with pytest.raises(ValueError, match=name):
        fastpath.orbit(4.0, 3.0, 0.6, 10, **kwargs)


def test_holmes_model_has_no_restitution():
    with pytest.raises(ValueError, match="model='holmes'"):
        fastpath.orbit(4.0, 3.0, 0.6, 10, model="holmes", restitution=0.5)


def test_everything_after_n_is_keyword_only():
    with pytest.raises(TypeError):
        fastpath.orbit(4.0, 3.0, 0.6, 10, "exact")


def test_not_departing_start_is_rejected_with_restitution():
    with pytest.raises(ValueError, match="w0"):
        fastpath.orbit(4.0, 0.0, 0.6, 10, restitution=0.5)
