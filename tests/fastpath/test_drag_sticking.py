"""Chattering and sticking with drag (restitution r < 1): detachment condition and phase,
accumulation tail, orbits (``fastpath.dissipative.sticking``), against a 100-digit mpmath reference.

Tolerances (u = 2**-53):

- Linear detachment phase theta* = beta - alpha (+ pi, mod 2*pi): beta = atan(k) within an ulp
  (2u*beta); alpha = atan(sqrt(g)), g = (e - 1)*(e + 1) + (e*k)**2 with a relative error
  <= 8u*(|x| + y)/g (``detach_kind``), halved by the square root and shrunk by atan's slope
  tan/(1 + tan**2) <= 1/2: <= 2u*(|x| + y)/g, plus atan's ulp (2u*alpha); the sum and the
  reduction by 2*pi (or pi) round twice by half an ulp of 2*pi and add the constant's low part:
  16u. tol = 2u*(|x| + y)/g + 2u*(beta + alpha) + 16u.
- Quadratic detachment phase: the bisection stops where |f - 1| <= F = 4u*(e + k*e**2)*(1 +
  |theta|) or at adjacent floats, so |theta - theta*| <= F/|f'(theta*)| (to first order; factor
  2 for the slope's change over that interval) + an ulp, plus the reduction's 16u.
- Tail alone: model error C*q*T0 with q <= u and C <= 1/2 (the claim tested here), the formula's
  roundings: a = 1 + eta(u) - eps*cos(theta) rounds by u*(1 + |eps| + |eta(u)|) (relative: that
  over a), and a handful of roundings of u each: |T - T_ref| <= u*T*(1/2 + 4*(1 + |eps| +
  |eta(u)|)/a).
- Accumulation time of an orbit from a start: as without drag (test_sticking_accumulation):
  8u*t_acc/(1 - r) for the short flights' roundings (relative to w) plus, for the start and
  for every ordinary (long) flight, which forms w from the absolute state, that departure's w
  bound B (``fastpath.elastic.gap.departure``: absolute, ~u*(|v| + |eps|)) weighted by T0's
  conditioning 2/(a*(1 - r)), a the riding force at the accumulation phase.
"""

import math
from fractions import Fraction

import drag_reference as dref
import drag_sticking_reference as ref
import numpy as np
import pytest
from fastpath_figures import record
from mpmath import mp

import fastpath
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state
from fastpath.dissipative.laws import offset
from fastpath.dissipative.short_flight import drag_short_window
from fastpath.dissipative.sticking import (
    DETACHES,
    NEVER,
    UNDECIDED,
    detach_kind,
    detachment_frame,
    detachment_phase,
    drag_accumulation_tail,
    drag_detachment,
    drag_detachment_phase,
)
from fastpath.elastic.gap import departure
from fastpath.physics import LINEAR, QUADRATIC, dissipative

U = 2.0**-53
LAW = {"linear": LINEAR, "quadratic": QUADRATIC}


def _phase_error(theta, theta_ref):
    d = (mp.mpf(theta) - theta_ref) % (2 * mp.pi)
    return float(min(d, 2 * mp.pi - d))


@pytest.mark.slow
@pytest.mark.parametrize("eps, k", [(1.5, 0.1), (1.5, 2.0), (0.9, 0.6), (-1.2, 0.3),
                                    (3.0, 1e-3), (0.5, 2.0), (1.0 + 1e-6, 0.01)])
def test_linear_detachment_phase_matches_mpmath(eps, k):
    theta = drag_detachment_phase(eps, k, LINEAR)
    theta_ref, _ = ref.detachment_phase(eps, k, "linear")
    e = abs(eps)
    x, y = (e - 1.0) * (e + 1.0), (e * k) ** 2
    alpha = math.atan(math.sqrt(x + y))
    tol = 2 * U * (abs(x) + y) / (x + y) + 2 * U * (math.atan(k) + alpha) + 16 * U
    err = _phase_error(theta, theta_ref)
    record(f"drag detachment phase error linear eps={eps} k={k} (tol)", err / tol)
    assert 0.0 <= theta < 2.0 * math.pi
    assert err <= tol


@pytest.mark.slow
@pytest.mark.parametrize("eps, k", [(1.5, 0.1), (1.5, 2.0), (0.9, 1.0), (-1.2, 0.3),
                                    (3.0, 1e-3), (0.8, 3.0), (1.1, 0.2), (-0.95, 0.8)])
def test_quadratic_detachment_phase_matches_mpmath(eps, k):
    theta = drag_detachment_phase(eps, k, QUADRATIC)
    theta_ref, slope = ref.detachment_phase(eps, k, "quadratic")
    e = abs(eps)
    f_bound = 4 * U * (e + k * e * e) * (1 + 2 * math.pi)
    tol = 2 * f_bound / float(abs(slope)) + 2 * U * 2 * math.pi + 16 * U
    err = _phase_error(theta, theta_ref)
    record(f"drag detachment phase error quadratic eps={eps} k={k} (tol)", err / tol)
    assert 0.0 <= theta < 2.0 * math.pi
    assert err <= tol


@pytest.mark.parametrize("eps", [1.5, 3.0, -1.5, 1.0001])
def test_zero_drag_gives_the_no_drag_detachment(eps):
    """k = 0: the linear closed form is the no-drag one bit for bit. k -> 0 approaches
    2*pi - arccos(1/eps) at rate k: linear theta* moves by beta = atan(k) <= k less alpha's
    change O(k**2); quadratic f gains k*e**2*sin|sin| <= k*e**2, moving the root by <= that over
    |f'| = sqrt(e**2 - 1), plus the bisection's F/|f'|. Factor 2 for the second-order terms."""
    assert drag_detachment_phase(eps, 0.0, LINEAR) == detachment_phase(eps)
    e = abs(eps)
    slope = math.sqrt(e * e - 1.0)
    f_bound = 4 * U * (e + e * e) * (1 + 2 * math.pi)
    for k in (1e-4, 1e-8, 1e-12):
        lin = _phase_error(drag_detachment_phase(eps, k, LINEAR), mp.mpf(detachment_phase(eps)))
        quad = _phase_error(drag_detachment_phase(eps, k, QUADRATIC),
                            mp.mpf(detachment_phase(eps)))
        assert lin <= 2 * k + 64 * U
        assert quad <= 2 * k * e * e / slope + 2 * f_bound / slope + 64 * U
        assert lin > 0.5 * k or k < 64 * U  # it does move, by about beta = k


def _exact_kind(eps, k, law):
    """The exact decision from the floats as rationals (module docstring of drag_sticking)."""
    e, kk = abs(Fraction(eps)), Fraction(k)
    if law == LINEAR:
        g = e * e * (1 + kk * kk) - 1
    elif 2 * kk * e > 1:
        g = (2 * kk * e - 1) ** 2 - 4 * kk * (1 - e)
    else:
        g = e - 1
    return DETACHES if g > 0 else NEVER


def test_detach_kind_agrees_with_exact_rational_decision():
    rng = np.random.default_rng(16)
    undecided = 0
    for _ in range(4000):
        law = LINEAR if rng.random() < 0.5 else QUADRATIC
        k = float(rng.uniform(0.0, 3.0))
        if law == LINEAR:
            e_star = 1.0 / math.sqrt(1.0 + k * k)  # the threshold, then perturbed by ~ulps
        elif 2.0 * k > 1.0 + 1e-9:
            e_star = float(rng.uniform(0.3, 1.2))
        else:
            e_star = 1.0
        eps = e_star * (1.0 + float(rng.choice([-1, 1])) * float(rng.integers(0, 64)) * U)
        if rng.random() < 0.3:
            eps = float(rng.uniform(0.0, 2.0))
        kind = detach_kind(eps, k, law)
        if kind == UNDECIDED:
            undecided += 1
            continue
        assert kind == _exact_kind(eps, k, law), (eps, k, law)
    record("drag detach_kind undecided of 4000 near-threshold draws", undecided)


@pytest.mark.slow
@pytest.mark.parametrize(
    "law, eps, k, r, theta, w",
    [("linear", 1.5, 0.1, 0.8, 2.0, 1e-9), ("linear", 0.5, 0.5, 0.5, 1.0, 1e-10),
     ("linear", 0.9, 0.6, 0.8, 2.5, 1e-11), ("quadratic", 1.5, 0.1, 0.8, 2.0, 1e-10),
     ("quadratic", 0.5, 1.0, 0.5, 1.0, 1e-10), ("quadratic", -1.5, 0.3, 0.9, 0.5, 1e-11),
     ("linear", 3.0, 2.0, 0.3, 3.5, 1e-11)],
)
def test_drag_tail_matches_iterated_impacts(law, eps, k, r, theta, w):
    """The tail with its first corrections (jerk and drag) against 100-digit impacts + tail."""
    tail = drag_accumulation_tail(math.sin(theta), math.cos(theta), w, eps, k, LAW[law], r)
    assert tail == tail, "q <= u expected at this w"
    t_ref, impacts = ref.chatter(theta, w, eps, k, law, r)
    u_plate = -eps * math.sin(theta)
    eta_u = abs(k * u_plate * (1.0 if law == "linear" else abs(u_plate)))
    a = 1.0 + (k * u_plate if law == "linear" else k * u_plate * abs(u_plate)) \
        - eps * math.cos(theta)
    err = abs(mp.mpf(tail) - t_ref)
    record(f"drag tail error {law} eps={eps} k={k} r={r} (u*T)", float(err / (U * t_ref)))
    assert impacts > 20
    assert err <= U * t_ref * (0.5 + 4.0 * (1.0 + abs(eps) + eta_u) / a)


def test_drag_term_of_the_tail_is_needed():
    """Without -c*T0**2/6 the tail misses by far more than the tolerance (the test bites)."""
    law, eps, k, r, theta, w = "linear", 0.5, 0.5, 0.5, 1.0, 1e-10
    tail = drag_accumulation_tail(math.sin(theta), math.cos(theta), w, eps, k, LINEAR, r)
    a = 1.0 + k * (-eps * math.sin(theta)) - eps * math.cos(theta)
    t0 = 2.0 * w / (a * (1.0 - r))
    t_ref, _ = ref.chatter(theta, w, eps, k, law, r)
    tol = U * float(t_ref) * (0.5 + 4.0 * (1.0 + eps + k * eps) / a)
    assert abs(mp.mpf(tail + k * t0 * t0 / 6.0) - t_ref) > 100 * tol


CHATTER_STARTS = [
    ("linear", 0.5, 0.5, 0.5, 0.0, 0.1), ("linear", 1.5, 0.1, 0.8, math.pi, 1e-2),
    ("linear", 0.9, 0.6, 0.8, math.pi, 1e-3), ("quadratic", 0.5, 1.0, 0.5, 0.0, 0.05),
    ("quadratic", 1.5, 0.1, 0.8, math.pi, 1e-2), ("quadratic", 0.9, 0.3, 0.9, 0.0, 1e-2),
]


@pytest.mark.slow
@pytest.mark.parametrize("law, eps, k, r, phi0, w0", CHATTER_STARTS)
def test_accumulation_time_matches_reference(law, eps, k, r, phi0, w0):
    """sticking[0, 0] of an orbit started near chattering against the 100-digit impacts."""
    v0 = w0 - eps * math.sin(phi0)
    orb = fastpath.orbit(phi0, v0, eps, 100_000, restitution=r, drag=k, drag_law=law)
    assert orb.sticking.shape[0] >= 1
    t_acc = orb.sticking[0, 0]
    with mp.workdps(ref.DPS):
        w_exact = mp.mpf(v0) + eps * mp.sin(mp.mpf(phi0))
        t_ref, _ = ref.chatter(phi0, w_exact, eps, k, law, r)
        err = abs(mp.mpf(t_acc) - t_ref)
    before = orb.t <= t_acc
    bounds = [departure(p, math.sin(p), v, eps, 0.0)[1] for p, v in
              zip(orb.phi[before], orb.v[before], strict=True)
              if drag_short_window(math.sin(p), math.cos(p), v + eps * math.sin(p), v, eps, k,
                                   LAW[law]) == 0.0]
    theta = orb.phi[before][-1]
    u_acc = -eps * math.sin(theta)
    eta_acc = k * u_acc if law == "linear" else k * u_acc * abs(u_acc)
    a_acc = 1.0 + eta_acc - eps * math.cos(theta)
    tol = 8.0 * U * float(t_ref) / (1.0 - r) + sum(bounds) * 2.0 / (a_acc * (1.0 - r))
    record(f"drag t_acc {law} eps={eps} k={k} r={r}: long flights", len(bounds))
    record(f"drag t_acc error {law} eps={eps} k={k} r={r} (u*t_acc)", float(err / (U * t_ref)))
    assert err <= tol


def test_linear_drag_detaches_below_eps_one_and_sticks_just_below_threshold():
    """|eps| = 0.9 <= 1 with 0.9*sqrt(1 + k**2) > 1 detaches (episodes with finite ends); with
    k just below the threshold sqrt(1/0.81 - 1) the particle is stuck for good."""
    eps = 0.9
    k_star = math.sqrt(1.0 / (eps * eps) - 1.0)
    orb = fastpath.orbit(math.pi, 1e-2 - eps * math.sin(math.pi), eps, 2000, restitution=0.8,
                         drag=0.6)
    assert orb.stopped == "collisions" and orb.sticking.shape[0] >= 2
    assert np.all(np.isfinite(orb.sticking))
    theta_ref, _ = ref.detachment_phase(eps, 0.6, "linear")
    for t_end in orb.sticking[:, 1]:
        # the orbit's clock against its phase: k flights round each by half an ulp (t: u*t,
        # phase: u*4*pi, reduction a few ulps of 2*pi), factor 2 in hand
        # (test_sticking_orbit); the phase itself is within 1e-14 (linear test above)
        flights = int(np.searchsorted(orb.t, t_end)) + 1
        tol = 2.0 * flights * U * (t_end + 8.0 * math.pi) + 1e-14
        err = _phase_error(math.pi + t_end, theta_ref)
        record("drag detachment phase from the orbit clock eps=0.9 k=0.6 (tol)", err / tol)
        assert err <= tol
    below = k_star * (1.0 - 1e-6)
    assert detach_kind(eps, below, LINEAR) == NEVER
    stuck = fastpath.orbit(math.pi, 1e-2, eps, 100_000, restitution=0.8, drag=below)
    assert stuck.stopped == "stuck" and stuck.sticking[-1, 1] == math.inf
    above = k_star * (1.0 + 1e-6)
    assert detach_kind(eps, above, LINEAR) == DETACHES


@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_impacts_keep_r_of_relative_velocity_with_drag(law):
    """Energy bookkeeping at impacts: the kinetic energy relative to the plate keeps r**2 of
    itself, w1 = -r*w_in, with w_in from a 100-digit flight of the recorded departure; and in
    flight the drag only takes energy: E = v**2/2 + y at the impact <= E at departure. The
    tolerance is the recorded v1's rounding relative to its size (|v1| + |u| + |V|)*16u plus
    the flight time's effect, |d'|*tau*1e-12 (tau to 12 digits: generous against the solver's
    kappa*u bounds, the point here is the factor r)."""
    eps, k, r = 0.9, 0.2, 0.7
    orb = fastpath.orbit(4.0, 3.0, eps, 300, restitution=r, drag=k, drag_law=law)
    checked = 0
    for j in range(len(orb.iterations)):
        if np.any((orb.sticking[:, 0] >= orb.t[j]) & (orb.sticking[:, 0] <= orb.t[j + 1])):
            continue
        with mp.workdps(ref.DPS):
            phi, v = mp.mpf(orb.phi[j]), mp.mpf(orb.v[j])
            tau = mp.mpf(orb.t[j + 1]) - mp.mpf(orb.t[j])
            w0 = v + eps * mp.sin(phi)
            if w0 < 1e-3:
                continue  # chattering: the recorded (phi, v) do not carry w to full precision
            tau = mp.findroot(lambda t, p=phi, x=v: ref.gap(p, x, eps, k, law, t)[0], tau)
            y, v_in = ref.motion(v, mp.mpf(k), law, tau)
            u = -eps * mp.sin(phi + tau)
            w_in, w1 = v_in - u, mp.mpf(orb.v[j + 1]) - u
            tol = 16 * U * float(abs(w1) + abs(u) + abs(v_in)) + float(abs(w_in)) * 1e-12
            assert abs(w1 + r * w_in) <= tol
            assert v_in**2 / 2 + y <= v**2 / 2  # drag works against the motion
        checked += 1
    assert checked >= 10


@pytest.mark.slow
@pytest.mark.parametrize("law, eps, k", [("linear", 1.5, 0.1), ("linear", 0.9, 0.6),
                                         ("quadratic", 1.5, 0.1), ("quadratic", 0.9, 1.0),
                                         ("linear", -1.2, 0.3), ("quadratic", 3.0, 0.5)])
def test_w0_zero_departure_from_drag_detachment(law, eps, k):
    """The flight from detachment (w0 = 0, d'' = 0): positive on (0, t_c] for the exact state
    (the module's argument x > 0, sampled at 100 digits), and fastpath's first root after t_c
    within drag_reference.tau_tolerance (the solver's own gap bound) of the 60-digit first root
    of the float state's gap, searched from t_c."""
    tau, iterations, status, theta_star, v_star, kind = drag_detachment(
        dissipative(eps, k, LAW[law], 0.5))
    assert kind == DETACHES and status == fastpath.FlightStatus.CONVERGED
    _, t_c = detachment_frame(eps, k, LAW[law])
    with mp.workdps(ref.DPS):
        theta_ref, _ = ref.detachment_phase(eps, k, law, dps=ref.DPS)
        u_ref = -eps * mp.sin(theta_ref)
        for j in range(1, 41):
            t = mp.mpf(t_c) * j / 40
            assert ref.gap(theta_ref, u_ref, mp.mpf(eps), mp.mpf(k), law, t)[0] > 0
    phi = centre_phase(theta_star)
    with mp.workdps(dref.DPS):
        ts = [t_c + (tau * 1.5 - t_c) * j / 400 for j in range(401)]
        ds = [dref.gap(phi, v_star, eps, k, LAW[law], t) for t in ts]
        assert ds[0] > 0
        j = next(i for i, d in enumerate(ds) if d <= 0)
        tau_ref = mp.findroot(lambda t: dref.gap(phi, v_star, eps, k, LAW[law], t),
                              (ts[j - 1], ts[j]), solver="anderson")
    d_error = gap_state(phi, v_star, eps, k, LAW[law], tau)[3]
    tol = dref.tau_tolerance(d_error, phi, v_star, eps, k, LAW[law], tau_ref)
    record(f"drag w0=0 departure error {law} eps={eps} k={k} (tol)",
           float(abs(tau - tau_ref)) / tol)
    assert abs(tau - tau_ref) <= tol


@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_moments_with_drag_and_restitution_count_every_particle(law):
    """fastpath.kernels.moments with drag and r < 1 (eps = 0.6, k = 0.1: never detaches): at every
    n of the grid, moving + stuck + flagged = particles, and particles do get stuck."""
    from fastpath import moments

    n = 64
    m = moments(np.full(n, 4.0), np.linspace(2.0, 4.0, n), 0.6, [10, 100, 1000], drag=0.1,
                drag_law=law, restitution=0.5)
    moving, stuck = m.count_n.sum(axis=0), m.stuck_n.sum(axis=0)
    assert np.all(moving + stuck + m.flagged == n)
    assert stuck[-1] > 0


@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_short_flight_offset_is_cancellation_free(law):
    """(Y - v*t, V - v) of drag_short_flight against 100 digits for tiny and moderate t, v of
    either sign and near 0 (the quadratic's top inside the flight). Bound: a few roundings of
    each term of the formulas (module docstring): 32u*(t**2 + k*|v|*t**3 + k*v**2*t**2 + t*|v|*
    [t > t_top]) for Y - v*t (after the top v*(t - t_top) is a term) and 32u*t*(1 + k*v**2) for
    V - v."""
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(300):
        k = 10 ** rng.uniform(-6, 0.3)
        t = 10 ** rng.uniform(-12, -2)
        v = float(rng.choice([-1, 1])) * 10 ** rng.uniform(-14, 0.3)
        if k * t * t > 0.25:
            continue
        dy, dv = offset(v, k, LAW[law], t)
        with mp.workdps(ref.DPS):
            y, vel = ref.motion(mp.mpf(v), mp.mpf(k), law, mp.mpf(t))
            err_y = abs(mp.mpf(dy) - (y - mp.mpf(v) * t))
            err_v = abs(mp.mpf(dv) - (vel - mp.mpf(v)))
        top = math.atan(math.sqrt(k) * v) / math.sqrt(k) if v > 0 else 0.0
        after = law == "quadratic" and t > top
        tol_y = 32 * U * (t * t + k * abs(v) * t**3 + k * v * v * t * t + after * t * abs(v))
        tol_v = 32 * U * t * (1.0 + k * v * v)
        worst = max(worst, float(err_y) / tol_y, float(err_v) / tol_v)
        assert err_y <= tol_y and err_v <= tol_v, (v, k, t)
    record(f"drag particle offset worst error {law} (tol)", worst)


@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_chattering_next_to_drag_detachment_leaves_the_plate(law):
    """Hard case: a chatter that reaches theta* (riding force a -> 0+) before it accumulates:
    the short-flight window fails, the certified drag solver takes the tiny w, the particle
    leaves (a flight far longer than the chatter's), or the orbit stops UNCERTAIN, never a
    wrong sticking episode: any episode ends at the detachment phase."""
    eps, k, r = 1.5, 0.1, 0.5
    theta_star = drag_detachment_phase(eps, k, LAW[law])
    phi0 = theta_star - 0.05
    orb = fastpath.orbit(phi0, 2e-4 - eps * math.sin(phi0), eps, 5000, restitution=r, drag=k,
                         drag_law=law, on_uncertain="stop")
    assert orb.status in (fastpath.FlightStatus.CONVERGED, fastpath.FlightStatus.UNCERTAIN)
    assert np.max(np.diff(orb.t[:200])) > 1.0
    assert orb.sticking.shape[0] >= 1  # later the orbit does stick, and detaches at theta*
    theta_ref, slope = ref.detachment_phase(eps, k, law)
    # the phase's own tolerance as in the quadratic test (it bounds the linear one too)
    phase_tol = 2 * 4 * U * (eps + k * eps * eps) * (1 + 2 * math.pi) / float(abs(slope)) \
        + 4 * math.pi * U + 16 * U
    for t_end in orb.sticking[:, 1]:
        flights = int(np.searchsorted(orb.t, t_end)) + 1
        tol = 2.0 * flights * U * (t_end + 8.0 * math.pi) + phase_tol
        assert _phase_error(phi0 + t_end, theta_ref) <= tol
