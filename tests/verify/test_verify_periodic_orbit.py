"""verify.periodic_orbit: certified periodic orbits (Krawczyk), their stability, refusals.

Oracles independent of the certificate: the fixed points' trace 2 - 4*eps (the paper's
equation (3)); the period-2 orbits (s, pi*m - s), (-s, pi*m + s), eps*sin(s) = s, whose
monodromy is written in closed form here at 50 digits; the exact period-1 accelerator mode with
det = (2m - 1)/(2m + 1); fastpath's float orbits (the enclosure must hold them within their
rounding).
"""

import math
import threading

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fastpath
import verify
from fastpath.dynamics import approximants, residue_crossing, symmetric_orbit
from fastpath.dynamics.greene import TARGET
from verify.dynamics.numbers import Enclosure
from verify.dynamics.periodic_orbit import classify

U = 2.0**-53


def two_start(eps, digits=50):
    with mpmath.workdps(digits):
        return mpmath.findroot(lambda s: eps * mpmath.sin(s) - s, 1.9 * math.sqrt(eps - 1))


def two_trace(eps, m, digits=50):
    """tr DF^2 of the period-2 orbit in closed form (tau = 2*v, w = pi*m at both states)."""
    with mpmath.workdps(digits):
        eps = mpmath.mpf(eps)
        s = mpmath.findroot(lambda x: eps * mpmath.sin(x) - x, 1.9 * mpmath.sqrt(eps - 1))
        w = mpmath.pi * m
        c = 2 * eps * mpmath.cos(s)

        def jac(a, b):
            return mpmath.matrix([[1 + a, b], [a - c * (1 + a), -1 + b - c * b]])

        product = jac(2 * s / w, 2 * (w + s) / w) * jac(-2 * s / w, 2 * (w - s) / w)
        return product[0, 0] + product[1, 1]


@settings(max_examples=25)
@given(eps=st.floats(-0.95, 1.95), m=st.integers(1, 4))
def test_fixed_point_trace_is_two_minus_four_eps_and_stability_follows(eps, m):
    if abs(eps) < 1e-3:
        return  # eps = 0: not isolated (refused, tested below)
    orbit = verify.periodic_orbit(0.0, math.pi * m, eps, 1, dps=30)
    exact = mpmath.mpf(eps).__rmul__(4)  # 4*eps is exact (a power of two times a double)
    exact = mpmath.mp.make_mpf(mpmath.libmp.mpf_sub(mpmath.libmp.from_int(2), exact._mpf_, 0))
    assert exact in orbit.trace  # precision 0: the exact difference 2 - 4*eps
    assert orbit.trace.width < 1e-20
    if abs(eps - 1) > 1e-15:
        assert orbit.stability == ("elliptic" if 0 < eps < 1 else "hyperbolic")


def test_eps_one_is_the_undecidable_period_doubling():
    orbit = verify.periodic_orbit(0.0, math.pi, 1.0, 1, dps=30)
    assert 1 in orbit.residue
    assert orbit.stability == "undecided"


@settings(max_examples=15)
@given(eps=st.floats(1.001, 1.55), m=st.integers(1, 3))
def test_period_two_trace_enclosure_holds_the_closed_form_and_the_float_trace(eps, m):
    s = float(two_start(eps))
    orbit = verify.periodic_orbit(s, math.pi * m - s, eps, 2, dps=30)
    exact = two_trace(eps, m)
    assert exact in orbit.trace
    found = fastpath.periodic_orbit(s, math.pi * m - s, eps, 2)
    slack = 4 * found.residue_error
    assert orbit.trace.lo - slack <= found.trace <= orbit.trace.hi + slack


def test_period_two_orbits_are_elliptic_above_one_then_hyperbolic():
    for eps, want in ((1.001, "elliptic"), (1.1, "elliptic"), (1.198, "elliptic"),
                      (1.2, "hyperbolic"), (1.5, "hyperbolic")):
        s = float(two_start(eps))
        assert verify.periodic_orbit(s, math.pi - s, eps, 2).stability == want


@settings(max_examples=10)
@given(eps=st.floats(1.02, 1.5), m=st.integers(1, 3), shift=st.floats(-1e-4, 1e-4))
def test_a_perturbed_guess_certifies_the_same_orbit(eps, m, shift):
    s = float(two_start(eps))
    a = verify.periodic_orbit(s, math.pi * m - s, eps, 2, dps=30)
    b = verify.periodic_orbit(s + shift, math.pi * m - s - shift, eps, 2, dps=30)
    for x, y in zip(a.box, b.box, strict=True):
        assert max(x.lo, y.lo) <= min(x.hi, y.hi)  # the enclosures meet: one orbit


@settings(max_examples=10)
@given(eps=st.floats(1.02, 1.5), m=st.integers(1, 3))
def test_a_certified_orbit_maps_to_itself_within_its_enclosure(eps, m):
    s = float(two_start(eps))
    orbit = verify.periodic_orbit(s, math.pi * m - s, eps, 2, dps=30)
    points = orbit.points + (orbit.points[0],)
    for here, there in zip(points[:-1], points[1:], strict=True):
        phi1, v1, _ = fastpath.step(here[0].mid, here[1].mid, eps)
        slack = 64 * U * (1 + abs(v1)) * 8  # float64 step from the rounded midpoint
        gap_phi = abs(math.remainder(phi1 - there[0].mid, 2 * math.pi))
        assert gap_phi <= there[0].width / 2 + slack
        assert abs(v1 - there[1].mid) <= there[1].width / 2 + slack


def test_accelerator_mode_determinant_and_trace():
    m, eps = 4, 1.6
    phi = -math.asin(math.pi / (2 * eps))
    orbit = verify.periodic_orbit(phi, math.pi * m, eps, 1, velocity_shift=1)
    assert mpmath.mpf(2 * m - 1) / (2 * m + 1) in Enclosure(orbit.determinant.lo - 1e-40,
                                                           orbit.determinant.hi + 1e-40)
    assert orbit.stability == "elliptic"
    assert orbit.velocity_shift == 1


def test_greene_orbit_certified_on_both_sides_of_its_crossing():
    a = approximants(1, (2,), levels=6)[-1]  # period 34
    crossing = residue_crossing(a)
    for eps, below in ((crossing.bracket[0] - 1e-7, True), (crossing.bracket[1] + 1e-7, False)):
        guess = symmetric_orbit(crossing.v, eps, a.period, a.winding)
        orbit = verify.periodic_orbit(guess.phi[0], guess.v[0], eps, a.period,
                                      winding=a.winding)
        assert (orbit.residue.hi < TARGET) if below else (orbit.residue.lo > TARGET)
        assert orbit.residue.lo - 4 * guess.residue_error <= guess.residue
        assert guess.residue <= orbit.residue.hi + 4 * guess.residue_error


@given(lo=st.floats(-3, 3), width=st.floats(0, 2))
def test_elliptic_and_hyperbolic_are_never_both_claimed(lo, width):
    from verify.dynamics.numbers import contexts

    iv = contexts(20).iv
    residue = iv.mpf([lo, lo + width])
    kind = classify(residue)
    inside = lo > 0 and lo + width < 1
    outside = lo + width < 0 or lo > 1
    assert kind == ("elliptic" if inside else "hyperbolic" if outside else "undecided")


@pytest.mark.parametrize("guess", [
    (0.5, 3.0, 0.3, 1),          # no fixed point near: Newton goes to (0, pi), too far
    (0.3, math.pi - 0.3, 0.5, 2),  # no period-2 orbit below eps = 1
    (0.0, math.pi, 0.0, 1),      # eps = 0: every orbit periodic, none isolated
])
def test_wrong_guesses_are_refused(guess):
    with pytest.raises(verify.NotCertified):
        verify.periodic_orbit(*guess)


@pytest.mark.parametrize("bad", [
    dict(phi=math.nan), dict(v=math.inf), dict(eps="0.3"), dict(eps=True), dict(period=0),
    dict(dps=10), dict(v=-1.0), dict(tolerance=0.0), dict(max_dps=20), dict(winding=0),
    dict(velocity_shift=1.5),
])
def test_bad_input_raises_value_error(bad):
    args = dict(phi=0.0, v=math.pi, eps=0.3, period=1, dps=30) | bad
    with pytest.raises(ValueError):
        verify.periodic_orbit(**args)


def test_global_precision_is_never_touched():
    before = mpmath.mp.prec, mpmath.iv.prec
    errors = []

    def work():
        try:
            for _ in range(3):
                verify.periodic_orbit(0.0, math.pi, 0.3, 1, dps=40)
        except Exception as err:  # noqa: BLE001 - reported below
            errors.append(err)

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert (mpmath.mp.prec, mpmath.iv.prec) == before


MULTI_ROOT = (3.752457891787808, 2.35, 1.5)  # d has roots near 2.635, 3.260 and 4.095


def _roots_of_gap(phi, v, eps):
    from scipy.optimize import brentq

    def d(t):
        return eps * (math.cos(phi) - math.cos(phi + t)) + t * (v - t / 2)

    return [brentq(d, a, b, xtol=1e-14) for a, b in ((2.5, 2.9), (3.1, 3.5), (3.9, 4.3))]


def test_box_flight_certifies_the_first_root_and_refuses_the_others():
    from verify.dynamics.box_flight import Undecided, box_flight
    from verify.dynamics.numbers import contexts

    ctx = contexts(30)
    phi, v, eps = MULTI_ROOT
    box = (ctx.iv.mpf(phi), ctx.iv.mpf(v))
    first, second, third = _roots_of_gap(phi, v, eps)
    bracket, links = box_flight(ctx, *box, eps, first - 1e-6, first + 1e-6)
    assert links >= 1
    for t_lo, t_hi in ((third - 1e-6, third + 1e-6),   # a later root: d < 0 before it
                       (second - 1e-6, second + 1e-6),  # the gap reopening: d' > 0 there
                       (2.0, 2.1)):                     # before the collision: d(t_hi) > 0
        with pytest.raises(Undecided):
            box_flight(ctx, *box, eps, t_lo, t_hi)


def test_krawczyk_image_leaves_a_box_without_the_zero():
    from verify.dynamics.numbers import contexts
    from verify.dynamics.periodic_orbit import _inside, _krawczyk

    ctx = contexts(30)
    iv = ctx.iv
    # G(x) = A (x - z), so J = A + I and, with C = A^-1, K(X) = {z} exactly
    a = (2.0, 1.0, 0.5, 3.0)
    det = a[0] * a[3] - a[1] * a[2]
    c = tuple(iv.mpf(e) for e in (a[3] / det, -a[1] / det, -a[2] / det, a[0] / det))
    jac = (iv.mpf(a[0] + 1), iv.mpf(a[1]), iv.mpf(a[2]), iv.mpf(a[3] + 1))
    z = (0.25, -0.5)
    for centre, inside in (((0.25 + 1e-3, -0.5), True), ((0.25 + 1e-1, -0.5), False)):
        box = (iv.mpf([centre[0] - 1e-2, centre[0] + 1e-2]),
               iv.mpf([centre[1] - 1e-2, centre[1] + 1e-2]))
        g = (iv.mpf(a[0] * (centre[0] - z[0]) + a[1] * (centre[1] - z[1])),
             iv.mpf(a[2] * (centre[0] - z[0]) + a[3] * (centre[1] - z[1])))
        k = _krawczyk(iv, centre, box, c, g, jac)
        assert all(_inside(ctx, k[i], box[i]) for i in range(2)) is inside


# --- the minimal period -----------------------------------------------------------------------

def _two_minus_four_eps(eps):
    return mpmath.mp.make_mpf(mpmath.libmp.mpf_sub(
        mpmath.libmp.from_int(2), mpmath.libmp.mpf_mul(mpmath.libmp.from_int(4),
                                                       mpmath.libmp.from_float(eps), 0), 0))


@pytest.mark.parametrize("eps,period", [(0.6, 2), (0.6, 3), (0.3, 5), (1.5, 2), (0.45, 4),
                                        (-0.3, 6), (1.2, 3)])
def test_a_fixed_point_asked_at_a_longer_period_is_relabelled_period_one(eps, period):
    orbit = verify.periodic_orbit(0.0, math.pi, eps, period, dps=30)
    assert (orbit.period, orbit.winding, len(orbit.points)) == (1, 1, 1)
    assert _two_minus_four_eps(eps) in orbit.trace  # the fixed point's own trace, not F^p's
    assert orbit.stability == ("elliptic" if 0 < eps < 1 else "hyperbolic")


def test_a_fixed_point_with_a_given_winding_is_relabelled_with_its_own_winding():
    orbit = verify.periodic_orbit(0.0, 2 * math.pi, 0.4, 3, dps=30, winding=6)
    assert (orbit.period, orbit.winding) == (1, 2)


@pytest.mark.parametrize("eps,m,factor", [(1.05, 1, 2), (1.1, 2, 3), (1.3, 1, 2)])
def test_a_period_two_orbit_asked_at_a_multiple_is_relabelled_period_two(eps, m, factor):
    s = float(two_start(eps))
    orbit = verify.periodic_orbit(s, math.pi * m - s, eps, 2 * factor, dps=30)
    assert (orbit.period, orbit.winding) == (2, 2 * m)
    assert two_trace(eps, m) in orbit.trace


def test_a_genuine_period_two_orbit_keeps_its_period():
    s = float(two_start(1.1))
    orbit = verify.periodic_orbit(s, math.pi - s, 1.1, 2, dps=30)
    assert orbit.period == 2 and len(orbit.points) == 2
    first, second = orbit.points
    assert first[0].hi < second[0].lo or second[0].hi < first[0].lo  # two distinct states


def test_a_shorter_period_neither_excluded_nor_proved_is_refused_by_name(monkeypatch):
    import importlib

    module = importlib.import_module("verify.dynamics.periodic_orbit")
    monkeypatch.setattr(module._Problem, "distinct", lambda self, found, d, turns: False)
    s = float(two_start(1.3))
    with pytest.raises(verify.NotCertified, match="may have period 1"):
        verify.periodic_orbit(s, math.pi - s, 1.3, 2, dps=30)


# --- velocity shifts: only accelerator modes of the exact map ------------------------------------

def _mode_phase(eps, shift, branch=1):
    a = math.asin(math.pi * shift / (2 * eps))
    return -a if branch > 0 else math.pi + a


def test_a_one_off_block_with_a_velocity_shift_is_refused():
    # the zero of a 2-block with v gaining pi: not repeated by the next block (exact map)
    with pytest.raises(verify.NotCertified, match="period-1 accelerator mode"):
        verify.periodic_orbit(3.8980936554827061, 60.422221713212743, 1.05, 2,
                              velocity_shift=1)


@pytest.mark.parametrize("guess", [
    (0.0, math.pi, 0.6, 2, 2),     # a fixed point asked with a shift: no mode there
    (3.8980936554827061, 60.422221713212743, 1.05, 2, 2),
    (0.3, 20.0, 1.2, 3, 3),
])
def test_blocks_of_several_collisions_with_a_shift_are_refused(guess):
    phi, v, eps, period, shift = guess
    with pytest.raises(verify.NotCertified):
        verify.periodic_orbit(phi, v, eps, period, velocity_shift=shift, dps=30)


@pytest.mark.parametrize("m,eps", [(4, 1.6), (2, 2.5)])
def test_a_mode_asked_as_several_blocks_is_relabelled_period_one(m, eps):
    phi = _mode_phase(eps, 1)
    orbit = verify.periodic_orbit(phi, math.pi * m, eps, 2, velocity_shift=2, dps=30,
                                  winding=2 * m + 1)  # blocks of 2*pi*m and 2*pi*(m + 1)
    assert (orbit.period, orbit.winding, orbit.velocity_shift) == (1, m, 1)


def test_a_decelerating_shift_is_refused():
    with pytest.raises(verify.NotCertified, match="time reverse"):
        verify.periodic_orbit(-_mode_phase(1.6, 1), 4 * math.pi, 1.6, 1, velocity_shift=-1)


@pytest.mark.parametrize("eps,shift,m,branch,stability", [
    (1.6, 1, 4, 1, "elliptic"),
    (1.7, 1, 10, -1, "hyperbolic"),
    (10.0, 1, 1, 1, "hyperbolic"),   # blocks at v = 2pi .. 6pi below 2|eps| certified one by one
    (10.0, 3, 2, 1, "hyperbolic"),
    (1.571, 1, 1, 1, "undecided"),   # limit elliptic, first block hyperbolic
])
def test_accelerator_modes_go_on_and_their_stability_holds_for_every_block(eps, shift, m, branch,
                                                                          stability):
    phi = _mode_phase(eps, shift, branch)
    orbit = verify.periodic_orbit(phi, math.pi * m, eps, 1, velocity_shift=shift, dps=30)
    assert (orbit.period, orbit.winding, orbit.velocity_shift) == (1, m, shift)
    assert orbit.stability == stability
    with mpmath.workdps(50):  # the exact mode's eps*cos(phi*), sin(phi*) = -pi*l/(2*eps)
        limit = mpmath.mpf(eps) * mpmath.cos(mpmath.asin(mpmath.pi * shift / (2 * eps)))
        limit = limit if branch > 0 else -limit
        assert orbit.limit_residue.lo - 1e-25 <= limit <= orbit.limit_residue.hi + 1e-25
    # every block's normalised residue lies between the first block's and the limit's
    first = (2 - (orbit.trace.lo / mpmath.sqrt(orbit.determinant.lo))) / 4
    later = []
    for k in range(1, 6):
        v = math.pi * (m + k * shift)
        b = 2 * v / (v + math.pi * shift / 2)
        c = 2 * eps * math.cos(phi)
        later.append((2 - b * (1 - c) / math.sqrt(b - 1)) / 4)
    lo, hi = sorted((float(first), float(orbit.limit_residue.mid)))
    assert all(lo - 1e-9 <= r <= hi + 1e-9 for r in later)


def test_a_mode_whose_later_flight_is_not_proved_is_refused(monkeypatch):
    import importlib

    from verify.dynamics.box_flight import Undecided

    module = importlib.import_module("verify.dynamics.accelerator")
    calls = []

    def refuse(*args):
        calls.append(args)
        raise Undecided("refused for the test")

    monkeypatch.setattr(module, "box_flight", refuse)
    # eps = 10, m = 1: the blocks at v = 2*pi .. 6*pi (<= 2*eps) are certified one by one
    with pytest.raises(verify.NotCertified, match="not proved to go on"):
        verify.periodic_orbit(_mode_phase(10.0, 1), math.pi, 10.0, 1, velocity_shift=1, dps=30)
    assert calls
    calls.clear()
    # eps = 1.6, m = 4: every later block is above 2*eps, proved by the bound alone
    verify.periodic_orbit(_mode_phase(1.6, 1), 4 * math.pi, 1.6, 1, velocity_shift=1, dps=30)
    assert not calls
