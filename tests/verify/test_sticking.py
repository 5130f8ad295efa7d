"""verify.orbit through chattering and sticking (r < 1, no drag; verify/dissipative/sticking.py).

Tolerances (D = 10**-dps, the digits of the orbit's states):

- Accumulation time at dps = 50 against the same start at dps = 70 (impacts iterated until
  w ~ 10**-23, tail remainder ~10**-70): the dps = 50 tail's model remainder is <= q*T0/2 <= D/2;
  each of the N impacts rounds (phi, v) to 50 digits, an error <= D*(|v| + |eps|) in w (v and
  eps*sin(phi) each rounded), which moves the rest of the accumulation by 2/(a*(1 - r)) times
  that (T0's conditioning, a = 1 - eps*cos at the start); the last-digit roundings of the times
  add N*D*t. So |dt| <= D*(1/2 + N*(2*(|v| + |eps|)/(a*(1 - r)) + t)).
- Detachment: phi0 + t_end = theta* (mod 2*pi); t_end = t_acc + (theta* - phase) mod 2*pi at
  60 digits from phases at 50: a few D*(1 + t_end).
"""

import math

import pytest
from mpmath import mp

import verify
from tests.verify.cases import internal
from verify.dissipative.sticking import accumulation, detachment_phase, detachment_step
from verify.numerics.precision import to_user, working_dps

D50 = mp.mpf(10) ** -50


def _detachment_step(eps, r, dps=50):
    """``(phi1, v1, tau)`` of the impact ending the flight from detachment, as mpmath numbers."""
    hit = detachment_step(*internal(eps, r), dps)
    return to_user((hit.phi1, hit.v1, hit.tau))


def _start(theta, w, eps):
    """(phi0, v0) exact at 50 digits with v0 + eps*sin(phi0) = w to 50 digits."""
    with mp.workdps(50):
        phi0 = mp.mpf(theta)
        return phi0, +(mp.mpf(w) - eps * mp.sin(phi0))


@pytest.mark.slow
@pytest.mark.parametrize("eps, r, theta, w", [(1.5, 0.8, 2.0, 1e-3), (0.5, 0.5, 1.0, 1e-2),
                                              (-3.0, 0.3, 1.0, 1e-3)])
def test_accumulation_time_agrees_with_more_impacts_at_higher_precision(eps, r, theta, w):
    phi0, v0 = _start(theta, w, eps)
    lo_res = verify.orbit(phi0, v0, eps, 400, dps=50, restitution=r)
    hi_res = verify.orbit(phi0, v0, eps, 400, dps=70, restitution=r)
    t50, t70 = lo_res.sticking[0][0], hi_res.sticking[0][0]
    impacts = sum(1 for t in lo_res.t if t < t50) - 1
    assert sum(1 for t in hi_res.t if t < t70) - 1 > impacts + 10  # w ~ 1e-23, not 1e-17
    a = 1 - eps * math.cos(theta)
    tol = D50 * (mp.mpf(1) / 2 + impacts * (2 * (abs(v0) + abs(eps)) / (a * (1 - r)) + t70))
    assert abs(t50 - t70) <= tol, (t50 - t70, tol)


@pytest.mark.slow
def test_tail_enclosure_contains_the_tail_from_more_impacts():
    """The proved [T_lo, T_hi] of the last impact before the tail holds the 70-digit value."""
    eps, r = 1.5, 0.8
    phi0, v0 = _start(2.0, 1e-3, eps)
    orb = verify.orbit(phi0, v0, eps, 400, dps=50, restitution=r)
    k = next(k for k, t in enumerate(orb.t) if t > orb.sticking[0][0]) - 1
    acc = accumulation(*internal(orb.phi[k], orb.v[k], eps, r), 50)
    ref = verify.orbit(orb.phi[k], orb.v[k], eps, 400, dps=70, restitution=r)
    tail = ref.sticking[0][0]
    assert acc.enclosure[0] <= tail <= acc.enclosure[1]
    assert acc.enclosure[1] - acc.enclosure[0] < mp.mpf(10) ** -30  # O(T0**2) wide


def test_tail_is_not_summed_before_w_is_tiny():
    eps, r = 1.5, 0.8
    phi0, v0 = _start(2.0, 1e-6, eps)
    assert accumulation(*internal(phi0, v0, eps, r), 50) is None  # q*T0 ~ 1e-18 > 1e-50
    phi0, v0 = _start(0.3, 1e-20, eps)  # eps*cos(0.3) > 1: the plate pulls away, no tail
    assert accumulation(*internal(phi0, v0, eps, r), 50) is None


@pytest.mark.slow
@pytest.mark.parametrize("eps, r, theta", [(1.5, 0.8, math.pi), (3.0, 0.5, math.pi),
                                           (-1.5, 0.8, 0.5), (1.2, 0.3, math.pi)])
def test_detaches_at_2pi_minus_arccos_one_over_eps(eps, r, theta):
    phi0, v0 = _start(theta, 1e-3, eps)
    orb = verify.orbit(phi0, v0, eps, 300, restitution=r)
    assert orb.stopped == "collisions" and len(orb.sticking) >= 1
    with mp.workdps(60):
        alpha = mp.acos(1 / mp.mpf(abs(eps)))
        expected = 2 * mp.pi - alpha if eps > 0 else mp.pi - alpha
        for t_start, t_end in orb.sticking:
            assert t_start < t_end
            d = (phi0 + t_end - expected) % (2 * mp.pi)
            assert min(d, 2 * mp.pi - d) <= 8 * D50 * (1 + t_end)
        # the entry after an episode is the impact ending the flight from detachment
        t_start, t_end = orb.sticking[0]
        j = next(k for k, t in enumerate(orb.t) if t > t_end)
        assert orb.t[j - 1] < t_start
        phi1, v1, tau = _detachment_step(eps, r)
        assert (orb.phi[j], orb.v[j]) == (phi1, v1)
        assert abs(orb.t[j] - (t_end + tau)) <= 4 * D50 * orb.t[j]


@pytest.mark.parametrize("eps", [1.5, -1.5, 3.0, 1.01])
def test_flight_from_detachment_is_the_first_root_of_the_closed_form(eps):
    """tau > t_c = 2*arccos(1/|eps|), d(tau) = 0 at 50 digits, d > 0 on a grid before it."""
    _, _, tau = _detachment_step(eps, 0.5)
    with mp.workdps(70):
        s = mp.sqrt(mp.mpf(eps) ** 2 - 1)

        def d(t):
            return s * (t - mp.sin(t)) - (t**2 / 2 - 1 + mp.cos(t))

        root = mp.findroot(d, tau)
        assert abs(root - tau) <= 10 * D50 * tau
        assert tau > 2 * mp.acos(1 / mp.mpf(abs(eps)))
        assert all(d(tau * k / 400) > 0 for k in range(1, 400))
        # theta* + tau with v = sqrt(eps**2 - 1) from theta*: the elastic gap form agrees
        with working_dps(70):
            theta = to_user(detachment_phase(*internal(eps)))
        gap = s * tau - tau**2 / 2 + eps * (mp.cos(theta) - mp.cos(theta + tau))
        assert abs(gap) <= 100 * D50 * (1 + abs(eps)) * tau


def test_eps_half_r_half_stops_stuck():
    """eps = 0.5, r = 0.5 from (4, 3) sticks for good."""
    orb = verify.orbit(4.0, 3.0, 0.5, 10_000, restitution=0.5)
    assert orb.stopped == "stuck"
    assert len(orb.sticking) == 1 and orb.sticking[0][1] == mp.inf
    assert orb.t[-1] < orb.sticking[0][0]
    assert len(orb.phi) == len(orb.v) == len(orb.t) < 10_001


def test_flat_plate_accumulates_after_2v_over_1_minus_r():
    """eps = 0: flights 2*v*r**k, t_acc = 2*v/(1 - r) (the tail model is exact); r is the
    float 0.9, so t_acc = 10/(1 - r) = 100.000000000000022..., not 100: verify sees it."""
    orb = verify.orbit(1.0, 5.0, 0.0, 1000, restitution=0.9)
    assert orb.stopped == "stuck"
    with mp.workdps(60):
        expected = 10 / (1 - mp.mpf(0.9))
        assert abs(orb.sticking[0][0] - expected) <= 4 * D50 * 100 * len(orb.t)
        assert abs(expected - 100) > 1e-14


@pytest.mark.slow
def test_eps_1_5_r_0_8_from_4_3_sticks_and_detaches():
    """The first episodes (about 2.5 s of certified impacts per
    hundred); every episode ends at theta*, (the orbit between episodes is chaotic: see the
    cross-check in tests/test_sticking_cross_check.py)."""
    phi0, eps = 4.0, 1.5
    orb = verify.orbit(phi0, 3.0, eps, 1400, restitution=0.8)
    assert orb.stopped == "collisions" and len(orb.sticking) >= 2
    with mp.workdps(60):
        theta_star = 2 * mp.pi - mp.acos(1 / mp.mpf(eps))
        for _, t_end in orb.sticking:
            d = (phi0 + t_end - theta_star) % (2 * mp.pi)
            assert min(d, 2 * mp.pi - d) <= 8 * D50 * (1 + t_end)


def test_a_plate_just_above_eps_one_detaches_and_the_orbit_runs_on():
    """eps = 1 + 1e-10, r = 0.5 from (4, 3): the particle sticks, leaves at
    theta* = 2*pi - arccos(1/eps) (1.4e-5 before 2*pi) with u = sqrt(eps**2 - 1) ~ 1.4e-5, and
    the flight from there (5.7e-5 long, d' ~ 1e-14 at its root) is certified: the orbit makes
    its collisions, every episode ending at theta*."""
    eps = 1 + 1e-10
    orb = verify.orbit(4.0, 3.0, eps, 100, dps=30, restitution=0.5)
    assert orb.stopped == "collisions" and len(orb.phi) == 101 and len(orb.sticking) >= 2
    with mp.workdps(40):
        theta_star = 2 * mp.pi - mp.acos(1 / mp.mpf(eps))
        for t_start, t_end in orb.sticking:
            assert t_start < t_end
            off = (mp.mpf(4.0) + t_end - theta_star) % (2 * mp.pi)
            assert min(off, 2 * mp.pi - off) < 1e-25
