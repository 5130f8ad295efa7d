"""verify.orbit through chattering, accumulation, sticking and detachment WITH drag (r < 1;
verify/dissipative/drag_sticking.py), against closed forms, fastpath.orbit and itself at 70 digits.

Tolerances (u = 2**-53, D = 10**-dps the digits of verify's states):

- Detachment phase in verify: a proved box of width ~2**(24 - prec) at dps + 10 digits; the
  orbit's t_end = t_acc + (theta* - phase) mod 2*pi at dps + 10 digits from phases at dps:
  phi0 + t_end = theta* (mod 2*pi) within 8*D*(1 + t_end), as without drag.
- fastpath's t_acc (tests/fastpath/test_drag_sticking.py, its documented bound):
  8u*t_acc/(1 - r) for the short flights' roundings plus, for the start and every ordinary flight
  (which forms w from the absolute state), that departure's w bound
  (``fastpath.elastic.gap.departure``) times T0's conditioning 2/(a*(1 - r)), a the riding force at
  the accumulation.
- fastpath's t_end: its clock and its phase are summed separately: 2*flights*u*(t_end + 8*pi),
  plus its theta*'s own error: linear 2u*(|x| + y)/g + 2u*(beta + alpha) + 16u (x = e**2 - 1,
  y = (e*k)**2, g = x + y), quadratic 2*F/|a'(theta*)| + 4*pi*u + 16u, F = 4u*(e + k*e**2)*
  (1 + 2*pi) (its bisection's stop).
- The impact ending the flight from detachment: fastpath's root of its float gap is within
  2.5*d_err/|d'(tau)| + 2 ulp(tau) of the root of that gap
  (``fastpath.dissipative.drag.gap_state``'s rounding bound d_err;
  tests/fastpath/drag_reference.tau_tolerance), and its departure phase is off by the theta*
  tolerance dth above, which moves the gap by |dd/dtheta| <= |eps|*(tau + 2)*dth (|dY/dv| <= t for a
  nondecreasing eta, |u'| <= |eps|), so the root by that over |d'(tau)|; the phase adds the
  reductions (2 ulp(tau + 2*pi) + 8 ulp(2*pi)) and dth, v1 = (1 + r)*u - r*v_in weighs a phase error
  by <= (1 + r)*|eps| + r*(1 + |eta(v_in)|) plus 4 ulps.
- 50 against 70 digits, accumulation time: as without drag (tests/verify/test_sticking.py):
  D*(1/2 + N*(2*(|v0| + |eps|)/(a*(1 - r)) + t)), N impacts before the tail.
- drag -> 0 (k = 2**-100): every drag effect on the times is O(k) with O(1) coefficients over
  these short orbits (|dY| <= k*|v|*t**2, theta* moves by <= 2k): 100*k*(1 + t)**2, plus the
  digits of the two runs (the 50-digit bounds above).
"""

import math
import time
from fractions import Fraction

import numpy as np
import pytest
from mpmath import mp

import fastpath
import verify
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state
from fastpath.dissipative.short_flight import drag_short_window
from fastpath.dissipative.sticking import drag_detachment_phase
from fastpath.elastic.gap import departure
from fastpath.physics import LINEAR, QUADRATIC
from tests.verify.cases import internal
from verify.dissipative.drag_sticking import drag_accumulation, leaves_plate_with_drag, riding

U = 2.0**-53
LAW = {"linear": LINEAR, "quadratic": QUADRATIC}
TIMES = {}


def _eta(v, k, law):
    return k * v if law == "linear" else k * v * abs(v)


def _force(theta, eps, k, law):
    """a(theta) = 1 + eta(u) - eps*cos(theta), u = -eps*sin(theta) (mp)."""
    return 1 + _eta(-eps * mp.sin(theta), k, law) - eps * mp.cos(theta)


def _force_slope(theta, eps, k, law):
    u = -eps * mp.sin(theta)
    c = k if law == "linear" else 2 * k * abs(u)
    return -c * eps * mp.cos(theta) + eps * mp.sin(theta)


def _phase_distance(a, b):
    with mp.workdps(60):
        d = (mp.mpf(a) - mp.mpf(b)) % (2 * mp.pi)
        return min(d, 2 * mp.pi - d)


def _closed_linear(eps, k):
    """theta* = atan(k) - arccos(1/E) (+ pi for eps < 0) mod 2*pi, E = |eps|*sqrt(1 + k**2)."""
    e = abs(mp.mpf(eps))
    big_e = e * mp.sqrt(1 + mp.mpf(k) ** 2)
    theta = mp.atan(k) - mp.acos(1 / big_e) + (0 if eps > 0 else mp.pi)
    return theta % (2 * mp.pi)


def _fastpath_phase_tol(eps, k, law, theta_star):
    e = abs(eps)
    if law == "linear":
        x, y = (e - 1.0) * (e + 1.0), (e * k) ** 2
        alpha = math.atan(math.sqrt(x + y))
        return 2 * U * (abs(x) + y) / (x + y) + 2 * U * (math.atan(k) + alpha) + 16 * U
    slope = float(abs(_force_slope(theta_star, mp.mpf(eps), mp.mpf(k), law)))
    f_bound = 4 * U * (e + k * e * e) * (1 + 2 * math.pi)
    return 2 * f_bound / slope + 4 * math.pi * U + 16 * U


# --- detachment phase, never-detaches ---------------------------------------------------------

@pytest.mark.parametrize("eps, k", [(1.5, 0.1), (0.9, 0.6), (-1.2, 0.3), (3.0, 2.0),
                                    (1.0, 1e-3), (-0.8, 1.0)])
def test_linear_detachment_box_holds_the_closed_form(eps, k):
    ride = riding(*internal(eps, k), "linear", 50)
    with mp.workdps(80):
        theta = _closed_linear(eps, k)
        lo_, hi_ = mp.mpf(ride.theta_star.a), mp.mpf(ride.theta_star.b)
        shift = 2 * mp.pi * mp.floor((lo_ - theta) / (2 * mp.pi) + mp.mpf(1) / 2)
        assert lo_ <= theta + shift <= hi_
        assert hi_ - lo_ < mp.mpf(10) ** -50
        # a falls through 0 there: a > 0 before, < 0 after (the sign convention, checked here)
        h = mp.mpf(10) ** -20
        assert _force(theta - h, eps, k, "linear") > 0 > _force(theta + h, eps, k, "linear")
        # the arc where a < 0 is 2*alpha long
        big_e = abs(eps) * mp.sqrt(1 + mp.mpf(k) ** 2)
        assert abs(ride.free - 2 * mp.acos(1 / big_e)) < mp.mpf(10) ** -45


@pytest.mark.parametrize("eps, k", [(1.5, 0.1), (0.9, 1.0), (-1.5, 0.3), (0.8, 3.0),
                                    (1.1, 0.2), (-0.95, 0.8)])
def test_quadratic_detachment_box_holds_the_root_and_fastpath_agrees(eps, k):
    ride = riding(*internal(eps, k), "quadratic", 50)
    with mp.workdps(80):
        lo_, hi_ = mp.mpf(ride.theta_star.a), mp.mpf(ride.theta_star.b)
        root = mp.findroot(lambda x: _force(x, eps, k, "quadratic"), (lo_ + hi_) / 2)
        assert lo_ <= root <= hi_ and hi_ - lo_ < mp.mpf(10) ** -50
        assert _force_slope(root, eps, k, "quadratic") < 0
    theta_fast = drag_detachment_phase(eps, k, QUADRATIC)
    assert _phase_distance(theta_fast, root) <= _fastpath_phase_tol(eps, k, "quadratic", root)


def test_never_detaches_is_decided_exactly_at_the_threshold():
    """Linear: eps**2*(1 + k**2) > 1 on the binary values, one ulp either side of the float
    threshold; quadratic: e = 1 with 2ke <= 1 touches a = 0 without crossing (never), and e = 1
    with 2ke > 1 detaches at a degenerate root (a' = 0 there): verify raises, it does not guess."""
    eps = 0.9
    k_star = math.sqrt(1.0 / (eps * eps) - 1.0)
    for k in (math.nextafter(k_star, 0), k_star, math.nextafter(k_star, 2)):
        exact = Fraction(eps) ** 2 * (1 + Fraction(k) ** 2) > 1
        assert leaves_plate_with_drag(*internal(eps, k), "linear") == exact
    assert riding(*internal(0.5, 0.5), "linear", 50) is None
    assert not leaves_plate_with_drag(*internal(1.0, 0.25), "quadratic")
    assert leaves_plate_with_drag(*internal(1.0, 1.0), "quadratic")
    with pytest.raises(verify.UndecidableCollision, match="detachment"):
        riding(*internal(1.0, 1.0), "quadratic", 20, max_dps=80)


# --- orbits ---------------------------------------------------------------------------------

def _fastpath_t_acc_tol(fast, eps, k, law, r, t_acc, w0, phi0):
    before = fast.t <= t_acc
    bounds = [departure(phi0, math.sin(phi0), w0 - eps * math.sin(phi0), eps, 0.0)[1]]
    for p, v in zip(fast.phi[before][1:], fast.v[before][1:], strict=True):
        if drag_short_window(math.sin(p), math.cos(p), v + eps * math.sin(p), v, eps, k,
                             LAW[law]) == 0.0:
            bounds.append(departure(p, math.sin(p), v, eps, 0.0)[1])
    theta = fast.phi[before][-1]
    a_acc = float(_force(mp.mpf(theta), eps, k, law))
    return 8.0 * U * float(t_acc) / (1.0 - r) + sum(bounds) * 2.0 / (a_acc * (1.0 - r))


def _detachment_impact_tol(eps, k, law, r, theta_star, dth, tau_fast):
    phi = centre_phase(float(theta_star))
    v_star = -eps * math.sin(phi)
    _, d1, _, d_err, _, vel, _ = gap_state(phi, v_star, eps, k, LAW[law], tau_fast)
    tau_tol = (2.5 * d_err + abs(eps) * (tau_fast + 2) * dth) / abs(d1) \
        + 2 * math.ulp(tau_fast)
    phase = tau_tol + dth + 2 * math.ulp(tau_fast + 2 * math.pi) + 8 * math.ulp(2 * math.pi)
    weight = (1 + r) * abs(eps) + r * (1 + abs(_eta(vel, k, law)))
    return phase, weight * phase + 4 * math.ulp(abs(vel) + abs(eps) + 1)


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_eps_1_5_r_0_8_sticks_detaches_at_theta_star_and_agrees_with_fastpath(law):
    """Two sticking episodes (dps = 30 keeps it to ~6 s a law: ~110 certified impacts per
    chattering run), each ending at the certified theta*; fastpath's first episode, the impact
    ending its flight from detachment and the next impacts (fastpath's collision k -> k+1 against
    verify.step from its float state k) within the bounds of the module docstring."""
    eps, k, r, phi0, w0 = 1.5, 0.1, 0.8, math.pi, 1e-3
    v0 = w0 - eps * math.sin(phi0)
    start = time.perf_counter()
    ref = verify.orbit(phi0, v0, eps, 230, dps=30, drag=k, drag_law=law, restitution=r)
    TIMES[law] = time.perf_counter() - start
    assert ref.stopped == "collisions" and len(ref.sticking) >= 2
    d30 = mp.mpf(10) ** -30
    ride = riding(*internal(eps, k), law, 30)
    with mp.workdps(40):
        theta_star = (mp.mpf(ride.theta_star.a) + mp.mpf(ride.theta_star.b)) / 2
        if law == "linear":
            assert _phase_distance(theta_star, _closed_linear(eps, k)) < d30
        for t_start, t_end in ref.sticking:
            assert t_start < t_end < t_start + 2 * mp.pi
            assert _phase_distance(phi0 + t_end, theta_star) <= 8 * d30 * (1 + t_end)
    fast = fastpath.orbit(phi0, v0, eps, 230, drag=k, drag_law=law, restitution=r)
    assert fast.stopped == "collisions" and fast.sticking.shape[0] >= 1
    t_acc, t_end = ref.sticking[0]
    tol = _fastpath_t_acc_tol(fast, eps, k, law, r, t_acc, w0, phi0)
    assert abs(fast.sticking[0, 0] - t_acc) <= tol, (fast.sticking[0, 0] - t_acc, tol)
    flights = int(np.searchsorted(fast.t, fast.sticking[0, 1])) + 1
    dth = _fastpath_phase_tol(eps, k, law, theta_star)
    tol = 2 * flights * U * (float(t_end) + 8 * math.pi) + dth
    assert abs(fast.sticking[0, 1] - t_end) <= tol, (fast.sticking[0, 1] - t_end, tol)
    # the impact ending the flight from detachment
    jf = int(np.searchsorted(fast.t, fast.sticking[0, 1]))
    jr = next(j for j, t in enumerate(ref.t) if t > t_end)
    tau_fast = fast.t[jf] - fast.sticking[0, 1]
    tol_phi, tol_v = _detachment_impact_tol(eps, k, law, r, theta_star, dth, tau_fast)
    assert _phase_distance(fast.phi[jf], ref.phi[jr]) <= tol_phi
    assert abs(fast.v[jf] - ref.v[jr]) <= tol_v
    # the next impacts, stepwise from fastpath's float states
    for j in range(jf, jf + 3):
        phi1, v1, tau = verify.step(fast.phi[j], fast.v[j], eps, dps=30, drag=k, drag_law=law,
                                    restitution=r)
        p = centre_phase(fast.phi[j])
        _, d1, _, d_err, _, vel, _ = gap_state(p, fast.v[j], eps, k, LAW[law], float(tau))
        tau_tol = 2.5 * d_err / abs(d1) + 2 * math.ulp(float(tau))
        phase = tau_tol + 2 * math.ulp(float(tau) + 2 * math.pi) + 8 * math.ulp(2 * math.pi)
        weight = (1 + r) * abs(eps) + r * (1 + abs(_eta(vel, k, law)))
        assert _phase_distance(fast.phi[j + 1], phi1) <= phase + 16 * U
        assert abs(fast.v[j + 1] - v1) <= weight * (phase + 16 * U) \
            + 4 * math.ulp(abs(vel) + abs(eps) + 1)


@pytest.mark.slow
@pytest.mark.parametrize("law, eps, k", [("linear", -1.5, 0.3), ("linear", 0.9, 0.6),
                                         ("quadratic", -1.5, 0.3), ("quadratic", 0.9, 1.0)])
def test_other_signs_and_drag_made_detachment_agree_with_fastpath(law, eps, k):
    """eps < 0 (theta* + pi) and |eps| < 1 leaving the plate only through the drag (linear
    0.9*sqrt(1.36) > 1; quadratic (2ke - 1)**2 > 4k(1 - e)), r = 0.3 at 30 digits: every episode
    ends at the certified theta*; fastpath's first episode within the module docstring's bounds."""
    r, phi0, w0 = 0.3, math.pi, 1e-3
    v0 = w0 - eps * math.sin(phi0)
    ref = verify.orbit(phi0, v0, eps, 40, dps=30, drag=k, drag_law=law, restitution=r)
    assert ref.stopped == "collisions" and len(ref.sticking) >= 2
    ride = riding(*internal(eps, k), law, 30)
    d30 = mp.mpf(10) ** -30
    with mp.workdps(40):
        theta_star = (mp.mpf(ride.theta_star.a) + mp.mpf(ride.theta_star.b)) / 2
        if law == "linear":
            assert _phase_distance(theta_star, _closed_linear(eps, k)) < d30
        for _, t_end in ref.sticking:
            assert _phase_distance(phi0 + t_end, theta_star) <= 8 * d30 * (1 + t_end)
    fast = fastpath.orbit(phi0, v0, eps, 40, drag=k, drag_law=law, restitution=r)
    t_acc, t_end = ref.sticking[0]
    tol = _fastpath_t_acc_tol(fast, eps, k, law, r, t_acc, w0, phi0)
    assert abs(fast.sticking[0, 0] - t_acc) <= tol
    flights = int(np.searchsorted(fast.t, fast.sticking[0, 1])) + 1
    tol = 2 * flights * U * (float(t_end) + 8 * math.pi) + _fastpath_phase_tol(eps, k, law,
                                                                                theta_star)
    assert abs(fast.sticking[0, 1] - t_end) <= tol


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_chatter_next_to_theta_star_rides_only_until_theta_star(law):
    """Hard case (fastpath's test_chattering_next_to_drag_detachment_leaves_the_plate): a chatter
    started 0.05 before theta*: its tail is summed only where the window proves a > 0, so the
    episode starts before theta* and ends exactly there (t_end = theta* - phi0), never inside the
    arc where the plate pulls away; fastpath agrees."""
    eps, k, r = 1.5, 0.1, 0.5
    ride = riding(*internal(eps, k), law, 30)
    theta_star = float((mp.mpf(ride.theta_star.a) + mp.mpf(ride.theta_star.b)) / 2)
    phi0 = theta_star - 0.05
    v0 = 2e-4 - eps * math.sin(phi0)
    ref = verify.orbit(phi0, v0, eps, 45, dps=30, drag=k, drag_law=law, restitution=r)
    t_acc, t_end = ref.sticking[0]
    assert 0 < t_acc < t_end
    with mp.workdps(40):
        theta = (mp.mpf(ride.theta_star.a) + mp.mpf(ride.theta_star.b)) / 2
        assert abs(t_end - (theta - phi0)) <= 8 * mp.mpf(10) ** -30
        assert _force(phi0 + t_acc, eps, k, law) > 0
    fast = fastpath.orbit(phi0, v0, eps, 45, drag=k, drag_law=law, restitution=r)
    assert abs(fast.sticking[0, 1] - t_end) <= 4 * U * 8 * math.pi + _fastpath_phase_tol(
        eps, k, law, theta)
    # fastpath's accumulation time here: see the strict xfail below
    tol = _fastpath_t_acc_tol(fast, eps, k, law, r, t_acc, 2e-4, phi0)
    print(f"near theta* {law}: fastpath t_acc error {float(abs(fast.sticking[0, 0] - t_acc)):.3g}"
          f" against its documented bound {tol:.3g}")


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="fastpath finding: near theta* (riding force a ~ 0.04) "
                   "fastpath's t_acc misses by 5.5e-14, 1.5x the bound of tests/fastpath/"
                   "test_drag_sticking.py (verify agrees with an independent 100-digit "
                   "iteration of the impacts to 1e-28)")
def test_fastpath_accumulation_bound_next_to_theta_star():
    eps, k, r, law = 1.5, 0.1, 0.5, "linear"
    ride = riding(*internal(eps, k), law, 30)
    phi0 = float((mp.mpf(ride.theta_star.a) + mp.mpf(ride.theta_star.b)) / 2) - 0.05
    v0 = 2e-4 - eps * math.sin(phi0)
    t_acc = verify.orbit(phi0, v0, eps, 45, dps=30, drag=k, drag_law=law,
                         restitution=r).sticking[0][0]
    fast = fastpath.orbit(phi0, v0, eps, 45, drag=k, drag_law=law, restitution=r)
    tol = _fastpath_t_acc_tol(fast, eps, k, law, r, t_acc, 2e-4, phi0)
    assert abs(fast.sticking[0, 0] - t_acc) <= tol


@pytest.mark.slow
@pytest.mark.parametrize("law, k", [("linear", 0.5), ("quadratic", 1.0)])
def test_eps_half_r_half_with_drag_stops_stuck(law, k):
    """With drag: from (4, 3) the particle sticks for good (linear:
    0.5*sqrt(1.25) < 1; quadratic: 2ke = 1, max a-deficit e - 1 < 0); fastpath agrees."""
    orb = verify.orbit(4.0, 3.0, 0.5, 10_000, drag=k, drag_law=law, restitution=0.5)
    assert orb.stopped == "stuck" and len(orb.sticking) == 1 and orb.sticking[0][1] == mp.inf
    assert orb.t[-1] < orb.sticking[0][0] and len(orb.t) < 10_001
    fast = fastpath.orbit(4.0, 3.0, 0.5, 10_000, drag=k, drag_law=law, restitution=0.5)
    assert fast.stopped == "stuck" and fast.sticking[-1, 1] == math.inf
    assert len(fast.sticking) == 1


@pytest.mark.slow
@pytest.mark.parametrize("law, k", [("linear", 0.1), ("quadratic", 0.1)])
def test_dps_50_against_70_and_the_proved_tail_enclosure(law, k):
    """eps = 1.5, r = 0.3 from next to chattering: the accumulation and detachment times at 50
    and 70 digits (the 70-digit run iterates to w ~ 1e-23 and sums a tail ~1e-70 accurate); the
    proved enclosure of the 50-digit tail holds the 70-digit time from the same impact, and the
    model's remainder is measured: |T - T_70| <= q*T0/2 (the constant C <= 1/2 of the module
    docstring; measured, not proved)."""
    eps, r, phi0, w0 = 1.5, 0.3, math.pi, 1e-3
    v0 = w0 - eps * math.sin(phi0)
    lo_res = verify.orbit(phi0, v0, eps, 40, dps=50, drag=k, drag_law=law, restitution=r)
    t50, end50 = lo_res.sticking[0]
    impacts = sum(1 for t in lo_res.t if t < t50) - 1
    hi_res = verify.orbit(phi0, v0, eps, impacts + 40, dps=70, drag=k, drag_law=law,
                          restitution=r)
    t70, end70 = hi_res.sticking[0]
    assert sum(1 for t in hi_res.t if t < t70) - 1 > impacts + 10  # w ~ 1e-23, not 1e-17
    d50 = mp.mpf(10) ** -50
    a = float(_force(mp.mpf(phi0), eps, k, law))
    tol = d50 * (mp.mpf(1) / 2 + impacts * (2 * (abs(v0) + abs(eps)) / (a * (1 - r)) + t70))
    assert abs(t50 - t70) <= tol, (t50 - t70, tol)
    assert abs(end50 - end70) <= tol + 8 * d50 * (1 + end70)
    # the tail from the last impact before it: proved enclosure, measured model constant
    j = impacts  # t[impacts] is the last impact before the tail
    with mp.workdps(60):
        phi_j, v_j, eps_, k_, r_ = internal(lo_res.phi[j], lo_res.v[j], eps, k, r)
        acc = drag_accumulation(phi_j, v_j, eps_, k_, law, r_, 50)
    ref = verify.orbit(lo_res.phi[j], lo_res.v[j], eps, 40, dps=70, drag=k, drag_law=law,
                       restitution=r)
    tail70 = ref.sticking[0][0]
    assert acc.enclosure[0] <= tail70 <= acc.enclosure[1]
    assert acc.enclosure[1] - acc.enclosure[0] < mp.mpf(10) ** -30
    with mp.workdps(70):
        theta = mp.mpf(lo_res.phi[j])
        w = lo_res.v[j] + eps * mp.sin(theta)
        a_j = _force(theta, eps, k, law)
        u = -eps * mp.sin(theta)
        c = k if law == "linear" else 2 * k * abs(u)
        jerk = c * eps * mp.cos(theta) - eps * mp.sin(theta)
        a2, p2 = (eps * (1 + k), 0) if law == "linear" else (eps + 2 * k * eps**2, 2 * k)
        t0 = 2 * w / (a_j * (1 - r))
        q = t0**2 * (jerk**2 / a_j**2 + abs(jerk) * c / a_j + c**2 + a2 / a_j + p2 * a_j)
        ratio = abs(acc.tail - tail70) / (q * t0)
    print(f"drag tail model constant {law}: |T - T_70|/(q*T0) = {mp.nstr(ratio, 3)}")
    assert ratio <= 0.5


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_vanishing_drag_reproduces_the_no_drag_orbit(law):
    """drag = 2**-100: the accumulation and detachment times and the impacts in between agree
    with the no-drag verify.orbit (verify.dissipative.sticking) within the module docstring's
    O(k) bound."""
    eps, r, phi0, w0 = 1.5, 0.5, math.pi, 1e-3
    v0 = w0 - eps * math.sin(phi0)
    k = 2.0**-100
    drag = verify.orbit(phi0, v0, eps, 60, drag=k, drag_law=law, restitution=r)
    free = verify.orbit(phi0, v0, eps, 60, restitution=r)
    assert len(drag.sticking) >= 1 and len(free.sticking) >= 1
    d50 = mp.mpf(10) ** -50
    for (a1, b1), (a2, b2) in zip(drag.sticking, free.sticking, strict=False):
        tol = 100 * k * (1 + b2) ** 2 + 8 * d50 * len(free.t) * (1 + b2) * 100
        assert abs(a1 - a2) <= tol and abs(b1 - b2) <= tol
    # the impact ending the flight from detachment
    j1 = next(j for j, t in enumerate(drag.t) if t > drag.sticking[0][1])
    j2 = next(j for j, t in enumerate(free.t) if t > free.sticking[0][1])
    tol = 100 * k * (1 + free.t[j2]) ** 2 + 8 * d50 * len(free.t) * (1 + free.t[j2]) * 100
    assert abs(drag.t[j1] - free.t[j2]) <= tol
    assert abs(drag.v[j1] - free.v[j2]) <= 10 * tol


@pytest.mark.slow
@pytest.mark.parametrize("eps", [0.8944280854271067, 0.894427190999916],
                         ids=["E=1+1e-6", "E=1+1e-16"])
def test_linear_drag_just_past_the_detachment_threshold_runs_to_the_end(eps):
    """Linear drag k = 0.5, r = 0.5 from (4, 3) at E = |eps|*sqrt(1 + k**2) just above 1: the
    arc where the riding force a < 0 is 2.8e-3 (resp. 2.8e-8) wide with min a ~ -1e-6
    (resp. -1e-16), the flight from detachment a hop of that arc's length, the chatter after it
    lands where a is still tiny. The orbit makes its collisions, every episode ending at the
    closed-form theta* (no ChatteringDetected, no undecidable riding force)."""
    k = 0.5
    orb = verify.orbit(4.0, 3.0, eps, 100, dps=30, drag=k, drag_law="linear", restitution=0.5)
    assert orb.stopped == "collisions" and len(orb.phi) == 101 and len(orb.sticking) >= 2
    with mp.workdps(60):
        theta = _closed_linear(eps, k)
        for t_start, t_end in orb.sticking:
            assert t_start < t_end
            off = (mp.mpf(4.0) + t_end - theta) % (2 * mp.pi)
            assert min(off, 2 * mp.pi - off) < 1e-25

