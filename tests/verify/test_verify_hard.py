"""eps -> 1 and near-triple roots held to the certificate, exact
reduction of huge phases, overflow-size inputs, one validator for every public function, and
the hard-case table."""

from __future__ import annotations

import math
import time
from collections import Counter

import pytest
from hypothesis import example, given, settings
from mpmath import iv, mp

import verify
from tests.verify.cases import mpmath_dps, small_w0_velocity
from verify import strategies as vs
from verify.hard_cases import ALL_CASES, HARD_CASES, OVERFLOW_CASES
from verify.numerics.inputs import exact_real
from verify.numerics.phase import reduce_phase
from verify.numerics.precision import hi, lo, working_dps

DPS = 50
REL = mp.mpf(10) ** (-DPS + 2)  # certified enclosure width, relative


def _iv_gap(phi, v, eps, t, dps=120):
    """Independent interval evaluation of d(t), reducing phi at 2000 digits first."""
    with mp.workdps(2000):
        r = mp.mpf(phi) % (2 * mp.pi)
    with mpmath_dps(dps):
        half = iv.mpf(t) / 2
        val = 2 * iv.mpf(eps) * iv.sin(iv.mpf(r) + half) * iv.sin(half)
        val += iv.mpf(t) * (iv.mpf(v) - half)
        return lo(val), hi(val)


def _assert_certified(phi, v, eps, cert):
    lo_, hi_ = cert.enclosure
    assert 0 < cert.free_until <= lo_ < hi_ and (hi_ - lo_) / hi_ <= REL
    assert _iv_gap(phi, v, eps, lo_)[0] > 0 > _iv_gap(phi, v, eps, hi_)[1]


# --- eps -> 1 and the triple-root family phi = -x, v = x (exact flight time 2x) -------------

@settings(max_examples=40, deadline=None)
@given(vs.near_triple_root(eps=(1.0 - 1e-6, 1.0), x=(1e-8, 10.0)))
@example((-3e-5, 3e-5, 1.0))  # a near-triple root at eps = 1 exactly
@example((-1e-8, 1e-8, 1.0))
@example((-10.0, 10.0, 1.0))
@example((-1e-8, 1e-8, 1.0 - 1e-6))
def test_triple_root_family_is_certified_at_two_x(case):
    phi, v, eps = case
    cert = verify.certify_flight(phi, v, eps, dps=DPS)
    lo_, hi_ = cert.enclosure
    assert lo_ < 2 * mp.mpf(v) < hi_  # d(2x) = 0 exactly for the float inputs
    assert (hi_ - lo_) / hi_ <= REL


_TRIPLE_XS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
_ABOVE_ONE = (1.0 + 2.0**-52, 1.0 + 1e-12, 1.0 + 1e-9, 1.0 + 1e-6)


def _exact_w0(phi, v, eps):
    with mpmath_dps(60):
        return mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi))


@pytest.mark.slow
def test_near_triple_roots_just_above_eps_one_are_certified_in_milliseconds():
    """phi = -x, v = x (and phi = fl(pi - x) for eps < 0), x = 1e-3 .. 1e-8, |eps| = 1 + 2**-52
    .. 1 + 1e-6: d has a near-triple root at 2x where d'' ~ |eps| - 1 is tiny (the global
    curvature bound 1 + |eps| would make the candidate search crawl). Each departure is either
    rejected as no departure (w0 <= 0, checked independently) or certified: d > 0 before the
    enclosure (interval evaluations on a grid and at its lower end) and < 0 at its upper end,
    all 48 within seconds in total (18 are departures)."""
    start = time.perf_counter()
    certified = 0
    for x in _TRIPLE_XS:
        for size in _ABOVE_ONE:
            for phi, eps in ((-x, size), (math.pi - x, -size)):
                if _exact_w0(phi, x, eps) <= 0:
                    with pytest.raises(ValueError, match="no departure"):
                        verify.certify_flight(phi, x, eps, dps=DPS)
                    continue
                cert = verify.certify_flight(phi, x, eps, dps=DPS)
                _assert_certified(phi, x, eps, cert)
                lo_ = cert.enclosure[0]
                assert all(_iv_gap(phi, x, eps, lo_ * k / 32)[0] > 0 for k in range(1, 32))
                certified += 1
    assert certified == 18  # the departures of the table (w0 > 0 exactly)
    assert time.perf_counter() - start < 20  # each flight takes milliseconds


def test_a_near_triple_root_above_eps_one_is_its_first_root():
    """eps = -(1 + 2**-52) at phi = fl(pi - 1e-4), v = 1e-4: the flight lands just before
    2e-4 (the phase's rounding by -3.3e-16 moves this ill-conditioned root by 4e-7); the root
    found independently (mpmath's findroot at 60 digits) and no earlier sign change."""
    phi, v, eps = 3.141492653589793, 0.0001, -1.0000000000000002
    tau = verify.flight_time(phi, v, eps, dps=30)
    with mpmath_dps(60):
        d = lambda t: mp.mpf(eps) * (mp.cos(phi) - mp.cos(phi + t)) + t * (v - t / 2)  # noqa
        root = mp.findroot(d, mp.mpf(2e-4) * (1 - mp.mpf(1e-3)))
        assert abs(tau - root) < 1e-29 * root
        assert all(d(root * k / 64) > 0 for k in range(1, 64))
    assert 1.99e-4 < tau < 2e-4


@pytest.mark.parametrize("eps", [1.0 - 1e-12, 1.0 - 1e-6, 1.0, -1.0, 1.0 + 1e-12, 1.0 + 1e-6])
@pytest.mark.parametrize("phi, v", [(-0.01, 0.01), (4.0, 3.0), (0.3, None), (2.0, 50.0)])
def test_eps_near_one_is_certified(phi, v, eps):
    v = small_w0_velocity(phi, eps, 1e-9) if v is None else v  # None: w0 ~ 1e-9
    _assert_certified(phi, v, eps, verify.certify_flight(phi, v, eps, dps=DPS))


def test_eps_one_uses_the_concave_certificate():
    """Two interval evaluations (d at lo and hi), not a box-by-box proof."""
    assert verify.certify_flight(-3e-5, 3e-5, 1.0).boxes == 2
    assert verify.certify_flight(4.0, 3.0, -1.0).boxes == 2


# --- huge phases ------------------------------------------------------------------------------

@pytest.mark.parametrize("phi", [1e12, 1e17, 1e300, -1e300, 1.7976931348623157e308])
def test_reduce_phase_is_exact_and_its_precision_grows_with_the_exponent(phi):
    with working_dps(60) as prec:
        red = reduce_phase(exact_real("phi", phi), prec)
        r_lo, r_hi = lo(red.enclosure), hi(red.enclosure)
    assert red.work_bits >= prec + math.frexp(abs(phi))[1]
    with mp.workdps(2000):
        exact = mp.mpf(phi) - 2 * mp.pi * red.k
        assert r_lo <= exact <= r_hi
        assert r_hi - r_lo <= mp.mpf(2) ** (-prec + 4)
        assert -1e-50 < exact < 2 * mp.pi + 1e-50


@pytest.mark.parametrize("eps", [0.6, 3.0])
@pytest.mark.parametrize("phi", [1e12, 1e17, 1e17 + 16, 1e300, -1e300])
def test_huge_phase_equals_its_exact_reduction(phi, eps):
    with mp.workdps(2000):
        reduced = mp.mpf(phi) % (2 * mp.pi)
    with mp.workdps(DPS + 30):
        reduced = +reduced
    a = verify.flight_time(phi, 3.0, eps, dps=DPS)
    b = verify.flight_time(reduced, 3.0, eps, dps=DPS)
    assert abs(a - b) <= REL * a


def test_huge_phases_give_different_flights():
    """Huge phases are reduced exactly: |phi| >= 1e17 keeps its information."""
    taus = {float(verify.flight_time(phi, 3.0, 0.6, dps=30)) for phi in (1e17, 1e17 + 16, 1e300)}
    assert len(taus) == 3


def test_huge_phase_at_high_digits_stays_decidable():
    """1e300 at dps = 100 needs > 400 digits if the precision does not grow with phi's exponent
    (the default max_dps is 400): the exact reduction settles it at the first attempt."""
    cert = verify.certify_flight(1e300, 3.0, 0.6, dps=100)
    assert cert.dps_used == 110


@settings(max_examples=20, deadline=None)
@given(vs.huge_phases(eps=(0.0, 5.0)))
def test_huge_phases_are_certified(case):
    phi, v, eps = case
    _assert_certified(phi, v, eps, verify.certify_flight(phi, v, eps, dps=DPS))


def test_step_phase_of_a_huge_phase_is_reduced():
    phi1, v1, tau = verify.step(-1e300, 3.0, 0.6)
    assert 0 <= phi1 < 2 * mp.pi
    with mp.workdps(2000):
        expected = (mp.mpf(-1e300) + tau) % (2 * mp.pi)
    assert abs(phi1 - expected) < mp.mpf(10) ** -45


# --- overflow-size inputs: a certified answer or a clear ValueError, never a hang ------------

@pytest.mark.parametrize("case", OVERFLOW_CASES, ids=[c.id for c in OVERFLOW_CASES])
def test_overflow_cases_are_certified_by_verify(case):
    _assert_certified(case.phi, case.v, case.eps,
                      verify.certify_flight(case.phi, case.v, case.eps, dps=DPS))


# --- one validator ------------------------------------------------------------------------------

def _calls():
    """Every public verify function taking a state, as f(phi, v, eps) with valid extras."""
    return {
        "flight_time": lambda p, v, e, **k: verify.flight_time(p, v, e, **k),
        "certify_flight": lambda p, v, e, **k: verify.certify_flight(p, v, e, **k),
        "step": lambda p, v, e, **k: verify.step(p, v, e, **k),
        "orbit": lambda p, v, e, **k: verify.orbit(p, v, e, 1, **k),
        "jacobian": lambda p, v, e, **k: verify.jacobian(p, v, e, **k),
        "gap": lambda p, v, e, **k: verify.gap(p, v, e, 1.0, **k),
        "condition_number": lambda p, v, e: verify.condition_number(p, v, e, 1.0),
    }


BAD_STATES = [
    ((math.nan, 1.0, 0.6), "nan"),
    ((0.3, math.inf, 0.6), "inf"),
    ((0.3, 1.0, -math.inf), "-inf"),
    ((True, 1.0, 0.6), "True"),
    ((0.3, "1.0", 0.6), "'1.0'"),
    ((0.3, 1.0, None), "None"),
    ((4.0, 0.1, 0.6), "w0"),
    ((0.0, 0.0, 0.6), "w0"),
    ((0.0, -1.0, 0.0), "w0"),
]


@pytest.mark.parametrize("name", sorted(_calls()))
@pytest.mark.parametrize("args, needle", BAD_STATES, ids=[n for _, n in BAD_STATES])
def test_every_public_function_validates_the_same_way(name, args, needle):
    with pytest.raises(ValueError, match=needle.replace("(", r"\(")) as info:
        _calls()[name](*args)
    if needle == "w0":  # the message names the state
        assert repr(args[1]) in str(info.value)


@pytest.mark.parametrize("name", ["flight_time", "certify_flight", "step", "orbit", "jacobian",
                                  "gap"])
@pytest.mark.parametrize("dps", [0, 10, True, "50", 50.0])
def test_every_public_function_validates_dps(name, dps):
    with pytest.raises(ValueError, match=f"dps={dps!r}"):
        _calls()[name](0.3, 1.0, 0.6, dps=dps)


@pytest.mark.parametrize("tau", [0.0, -1.0, 0, math.nan, True])
def test_times_must_be_positive(tau):
    with pytest.raises(ValueError, match="tau"):
        verify.condition_number(0.3, 1.0, 0.6, tau)
    with pytest.raises(ValueError, match="tau"):
        verify.gap(0.3, 1.0, 0.6, tau)


def test_grazing_contact_validates():
    with pytest.raises(ValueError, match="T=0.0"):
        verify.grazing_contact(3.0, 0.2, 0.0, 1e-3)
    with pytest.raises(ValueError, match="psi=nan"):
        verify.grazing_contact(3.0, math.nan, 4.0, 1e-3)


# --- the hard-case table ------------------------------------------------------------------

def test_table_classes_and_entries():
    kinds = Counter(c.kind for c in ALL_CASES)
    assert all(c.kind for c in ALL_CASES)
    assert len({c.id for c in ALL_CASES}) == len(ALL_CASES)
    eps_one = {c.eps for c in ALL_CASES if c.kind == "eps->1"}
    assert {1.0 - 1e-12, 1.0 - 1e-6, 1.0, 1.0 + 1e-6, 1.0 + 1e-12} <= eps_one
    huge = {c.phi for c in ALL_CASES if c.kind == "huge-phase"}
    assert {1e12, 1e17, 1e300, -1e300} <= huge
    triple = [c for c in ALL_CASES if c.kind == "near-triple-root"]
    assert all(c.phi == -c.v for c in triple) and {1e-6, 1.0} <= {c.v for c in triple}
    assert all(c.expect == "ValueError" for c in OVERFLOW_CASES)
    assert {1e308} <= {c.v for c in OVERFLOW_CASES} and {1e300} <= {c.eps for c in OVERFLOW_CASES}
    assert all(c.expect == "flight" for c in HARD_CASES)
    assert kinds["overflow"] == len(OVERFLOW_CASES)


@pytest.mark.parametrize("case", HARD_CASES, ids=[c.id for c in HARD_CASES])
def test_every_hard_case_is_certified(case):
    cert = verify.certify_flight(case.phi, case.v, case.eps, dps=DPS)
    _assert_certified(case.phi, case.v, case.eps, cert)
    if case.kind == "near-triple-root" and abs(case.eps) <= 1:
        assert cert.enclosure[0] < 2 * mp.mpf(case.v) < cert.enclosure[1]
