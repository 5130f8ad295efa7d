"""Drag flights in closed form and their certificates.

References here are independent of verify/dissipative/drag.py: the closed forms written directly
(tan/atan, tanh/atanh, exp) at 200 digits, where the cancellation they suffer costs far fewer
than the 150 spare digits, and the equations of motion checked by numerical differentiation.
"""

from __future__ import annotations

import math

import pytest
from mpmath import mp

import verify
from verify.dissipative import drag_gap
from verify.dissipative.drag import DragFlight, motion
from verify.hard_cases import DISSIPATIVE_CASES
from verify.numerics.precision import hi, lo, working_dps

DPS = 40
REF_DPS = 200
LAWS = ("linear", "quadratic")


def naive_motion(v, k, law, t):
    """(Y(t), V(t)) from the spec's formulas, evaluated as written (call at REF_DPS)."""
    v, k, t = mp.mpf(v), mp.mpf(k), mp.mpf(t)
    if k == 0:
        return t * (v - t / 2), v - t
    if law == "linear":
        y = (v + 1 / k) * (1 - mp.exp(-k * t)) / k - t / k
        return y, v * mp.exp(-k * t) + mp.expm1(-k * t) / k
    s = mp.sqrt(k)
    if v > 0:
        a = mp.atan(s * v)
        if t <= a / s:
            return mp.log(mp.cos(a - s * t) / mp.cos(a)) / k, mp.tan(a - s * t) / s
        top = mp.log(1 / mp.cos(a)) / k
        return top - mp.log(mp.cosh(s * t - a)) / k, -mp.tanh(s * t - a) / s
    if -s * v < 1:
        a = mp.atanh(-s * v)
        return -mp.log(mp.cosh(a + s * t) / mp.cosh(a)) / k, -mp.tanh(a + s * t) / s
    if -s * v == 1:  # at the terminal velocity: V stays -1/s
        return v * t, v
    a = mp.acoth(-s * v)  # below it: V = -coth(a + s*t)/s decelerates towards -1/s
    return -mp.log(mp.sinh(a + s * t) / mp.sinh(a)) / k, -mp.coth(a + s * t) / s


def naive_gap(phi, v, eps, k, law, t):
    with mp.workdps(REF_DPS):
        y, _ = naive_motion(v, k, law, t)
        return y + mp.mpf(eps) * (mp.cos(mp.mpf(phi)) - mp.cos(mp.mpf(phi) + mp.mpf(t)))


MOTIONS = [(law, v, k, t) for law in LAWS for v in (3.0, 0.5, 1e-3, -0.3, -2.0, -30.0)
           for k in (0.0, 1e-30, 1e-8, 0.1, 2.0, 0.25) for t in (1e-9, 0.3, 2.0, 7.5)]


@pytest.mark.parametrize(("law", "v", "k", "t"), MOTIONS)
def test_enclosure_contains_the_reference_and_is_tight(law, v, k, t):
    with working_dps(DPS):
        y, vel = DragFlight(mp.mpf(v), mp.mpf(k), law).motion(mp.mpf(t))
    with mp.workdps(REF_DPS):
        y_ref, v_ref = naive_motion(v, k, law, t)
        assert lo(y) <= y_ref <= hi(y) and lo(vel) <= v_ref <= hi(vel)
        # each of the ~50 interval operations widens by ~2**-prec relative to the scale
        # (1 + |v| + t)**2 of Y and (1 + |v| + t) of V: 10**(5 - DPS) leaves a factor ~1e3
        scale = 1 + abs(v) + t
        assert hi(y) - lo(y) <= mp.mpf(10) ** (5 - DPS) * scale**2
        assert hi(vel) - lo(vel) <= mp.mpf(10) ** (5 - DPS) * scale


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("v", [2.0, -0.4])
def test_closed_forms_solve_the_equation_of_motion(law, v):
    """Y' = V and V' = -1 - eta(V) by numerical differentiation of the point values."""
    k = 0.7

    def point(t, which):
        return motion(v, t, k, law, dps=200)[which]  # diff works at raised precision

    with mp.workdps(60):
        for t in (mp.mpf("0.3"), mp.mpf("1.7"), mp.mpf("4.1")):
            vel = point(t, 1)
            eta = k * vel if law == "linear" else k * vel * abs(vel)
            assert abs(mp.diff(lambda x: point(x, 0), t) - vel) < mp.mpf(10) ** -25
            assert abs(mp.diff(lambda x: point(x, 1), t) - (-1 - eta)) < mp.mpf(10) ** -25


def _assert_certified(phi, v, eps, k, law, cert, samples=30):
    lo_, hi_ = cert.enclosure
    assert 0 < cert.free_until <= lo_ < hi_ and (hi_ - lo_) / hi_ <= mp.mpf(10) ** -48
    assert naive_gap(phi, v, eps, k, law, lo_) > 0 > naive_gap(phi, v, eps, k, law, hi_)
    with mp.workdps(REF_DPS):
        for j in range(1, samples + 1):
            assert naive_gap(phi, v, eps, k, law, lo_ * j / samples) > 0


STATES = [(4.0, 3.0, 0.6), (1.0, 2.0, 0.3), (4.0, 3.0, 3.0), (0.3, 1.5, 1.5), (0.5, 1.0, -0.6)]


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("k", [1e-12, 1e-3, 0.1, 1.0])
@pytest.mark.parametrize(("phi", "v", "eps"), STATES)
def test_drag_flight_is_certified(phi, v, eps, k, law):
    cert = verify.certify_flight(phi, v, eps, drag=k, drag_law=law)
    _assert_certified(phi, v, eps, k, law, cert)
    assert verify.flight_time(phi, v, eps, drag=k, drag_law=law) == cert.tau


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize(("phi", "v", "eps"), STATES)
def test_drag_to_zero_limit_is_linear_in_drag(phi, v, eps, law):
    """tau(k) - tau(0) = c*k + O(k**2): the ratio for 2k and k is 2 up to O(k)."""
    tau0 = verify.flight_time(phi, v, eps)
    k = mp.mpf(10) ** -12
    d1 = verify.flight_time(phi, v, eps, drag=k, drag_law=law) - tau0
    d2 = verify.flight_time(phi, v, eps, drag=2 * k, drag_law=law) - tau0
    assert d1 != 0 and abs(d2 / d1 - 2) < mp.mpf(10) ** -9
    tiny = verify.flight_time(phi, v, eps, drag=1e-40, drag_law=law)
    assert abs(tiny - tau0) <= mp.mpf(10) ** -38 * tau0


@pytest.mark.slow
@pytest.mark.parametrize("case", DISSIPATIVE_CASES, ids=[c.id for c in DISSIPATIVE_CASES])
def test_dissipative_hard_cases(case):
    cert = verify.certify_flight(case.phi, case.v, case.eps, drag=case.drag,
                                 drag_law=case.drag_law)
    _assert_certified(case.phi, case.v, case.eps, case.drag, case.drag_law, cert, samples=60)
    assert float(cert.tau) == case.tau


def _root_pair():
    """The drag near-graze with clearance -1e-6 at eps = 1.5: roots r1 < r2 near T = 2.769."""
    case = next(c for c in DISSIPATIVE_CASES if c.id == "drag-graze-linear-eps=1.5-c=-1e-6")
    r1 = verify.flight_time(case.phi, case.v, case.eps, drag=case.drag)
    with mp.workdps(REF_DPS):
        r2 = mp.findroot(lambda t: naive_gap(case.phi, case.v, case.eps, case.drag, "linear", t),
                         r1 + 2 * mp.mpf("0.0022"))
    return case, r1, r2


def test_root_pair_is_real():
    case, r1, r2 = _root_pair()
    assert r1 < r2 < 2.7690574729565074 + 0.01  # the elastic contact time of this graze
    mid = (r1 + r2) / 2
    assert naive_gap(case.phi, case.v, case.eps, case.drag, "linear", mid) < 0


def test_certificate_refuses_the_second_root(monkeypatch):
    case, _, r2 = _root_pair()
    monkeypatch.setattr(drag_gap, "local_candidate", lambda ctx, curv, t: +r2)
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(case.phi, case.v, case.eps, dps=30, max_dps=60, drag=case.drag)


def test_concave_shortcut_refuses_a_wrong_candidate(monkeypatch):
    """eps < 1 with light drag: the concave check passes, a wrong candidate fails the sign
    checks and the box-by-box proof must refuse it too."""
    tau = verify.flight_time(4.0, 3.0, 0.6, drag=0.01)
    monkeypatch.setattr(drag_gap, "local_candidate", lambda ctx, curv, t: tau * 1.01)
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(4.0, 3.0, 0.6, dps=30, max_dps=60, drag=0.01)


def test_concave_shortcut_is_used_where_the_gap_is_concave():
    """Concave from the global bound (eps = 0.6) or from the enclosure of d'' over [0, T]
    (eps = 3 from phase 4: cos < 0 over the short flight); not from phase 0 (d''(0) > 0)."""
    assert verify.certify_flight(4.0, 3.0, 0.6, drag=0.01).boxes == 2
    assert verify.certify_flight(4.0, 3.0, 3.0, drag=0.01).boxes == 2
    assert verify.certify_flight(0.0, 3.0, 3.0, drag=0.01).boxes > 2


# --- departures at rest (w0 = 0 exactly) ----------------------------------------------------

@pytest.mark.parametrize(("eps", "law"), [(1.5, "linear"), (1.5, "quadratic"), (1.0, "linear")])
def test_departure_at_rest_is_certified(eps, law):
    cert = verify.certify_flight(0.0, 0.0, eps, drag=0.1, drag_law=law)
    _assert_certified(0.0, 0.0, eps, 0.1, law, cert)


def test_departure_at_rest_without_drag():
    """eps > 1, no drag: the elastic code rejects w0 = 0; the drag certificate with k = 0 takes it
    (d = eps*(1 - cos t) - t**2/2)."""
    cert = verify.certify_flight(0.0, 0.0, 1.5)
    _assert_certified(0.0, 0.0, 1.5, 0.0, "linear", cert)


@pytest.mark.parametrize("eps", [0.5, -1.5])
def test_no_departure_at_rest_is_rejected(eps):
    with pytest.raises(ValueError, match="no departure"):
        verify.certify_flight(0.0, 0.0, eps, drag=0.1)


# --- validation ------------------------------------------------------------------------------

_BAD_DRAG = [({"drag": -1.0}, "drag=-1.0"), ({"drag": math.inf}, "drag=inf"),
             ({"drag_law": "cubic"}, "drag_law='cubic'")]
_BAD_RESTITUTION = [({"restitution": 1.5}, "restitution=1.5"),
                    ({"restitution": 0.0}, "restitution=0.0"),
                    ({"restitution": math.nan}, "restitution=nan")]


_FLIGHT_FUNCS = (verify.certify_flight, verify.flight_time, verify.step)


@pytest.mark.parametrize(("func", "kwargs", "named"),
                         [(f, *bad) for f in _FLIGHT_FUNCS for bad in _BAD_DRAG]
                         + [(verify.step, *bad) for bad in _BAD_RESTITUTION])
def test_bad_physics_is_a_value_error_naming_it(func, kwargs, named):
    with pytest.raises(ValueError, match=named.replace("(", r"\(")):
        func(4.0, 3.0, 0.6, **kwargs)


@pytest.mark.parametrize("func", [verify.certify_flight, verify.flight_time])
def test_a_flight_refuses_a_restitution_other_than_1(func):
    """The restitution acts at the impact, not during a flight: the flight functions take only
    restitution 1 (the keyword fastpath's flights take), and refuse any other value rather than
    accepting and ignoring it."""
    assert func(4.0, 3.0, 0.6, restitution=1.0) == func(4.0, 3.0, 0.6)
    with pytest.raises(ValueError, match=r"restitution=0.5 does not act on a flight"):
        func(4.0, 3.0, 0.6, restitution=0.5)


@pytest.mark.parametrize(("phi", "v", "eps", "k"), [
    (1.5, -1.2, 1.5, 1.0), (1.5, -5.0, 6.0, 1.0), (1.5, -2.0, 2.5, 0.25), (1.2, -30.0, 40.0, 0.01),
])
def test_quadratic_departure_below_terminal_velocity_is_certified(phi, v, eps, k):
    """Below the terminal velocity -1/sqrt(k) (here v*sqrt(k) = -1.2, -5, -1 exactly, -3) the
    particle decelerates towards it (the coth branch); the first root is certified and lies
    where the textbook form of the gap changes sign, with the form positive before it."""
    cert = verify.certify_flight(phi, v, eps, drag=k, drag_law="quadratic")
    lo_, hi_ = cert.enclosure
    assert naive_gap(phi, v, eps, k, "quadratic", lo_) > 0 > naive_gap(phi, v, eps, k,
                                                                      "quadratic", hi_)
    assert all(naive_gap(phi, v, eps, k, "quadratic", lo_ * j / 64) > 0 for j in range(1, 64))


def test_certificate_refuses_the_landing_after_a_root_pair(monkeypatch):
    """The later landing r3 > r2 is a sign change + to - like the first root: only the proof of
    no earlier root can refuse it."""
    case, _, _ = _root_pair()
    with mp.workdps(REF_DPS):
        r3 = mp.findroot(lambda t: naive_gap(case.phi, case.v, case.eps, case.drag, "linear", t),
                         mp.mpf("4.23"))
    assert r3 > 4
    monkeypatch.setattr(drag_gap, "local_candidate", lambda ctx, curv, t: +r3)
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(case.phi, case.v, case.eps, dps=30, max_dps=60, drag=case.drag)


@pytest.mark.parametrize("phi,v,eps,k,law", [
    (0.5, 1e4, 0.6, 1000.0, "linear"),    # up to Y = 10, then 1e4 time units at speed 1e-3
    (0.5, 1e4, 0.6, 10.0, "linear"),
    (1.0, 1e6, 0.6, 1000.0, "linear"),
    (2.0, 1e3, 0.9, 1e-4, "quadratic"),   # up to Y = 2.3e4, falling at the terminal speed 100
    (0.5, 300.0, 1.6, 3.0, "linear"),
])
def test_a_long_fall_against_drag_is_proved_over_one_window(phi, v, eps, k, law):
    """Thousands of plate periods above the plate's reach are proved in one window
    (d >= Y - P with Y's minimum at an end): a few dozen boxes, where the box-by-box search
    took thousands. The enclosure is checked against the spec's closed forms at 200 digits."""
    cert = verify.certify_flight(phi, v, eps, dps=DPS, drag=k, drag_law=law)
    assert cert.boxes <= 100
    lo_, hi_ = cert.enclosure
    with mp.workdps(REF_DPS):
        def gap(t):
            y, _ = naive_motion(v, k, law, t)
            return y + mp.mpf(eps) * (mp.cos(phi) - mp.cos(mp.mpf(phi) + t))
        assert gap(lo_) > 0 > gap(hi_)
        # no earlier root: d > 0 on a fine grid up to lo (the window's claim, sampled)
        grid = [lo_ * j / 1000 for j in range(1, 1000)]
        assert min(gap(t) for t in grid) > 0
