"""The flight certificate at its edges (verify/elastic/certificate.py and
verify/numerics/first_root.py).

Each test states a documented property of the certifier: the precision hint, the ``boxes``
count, the ``|eps| > 1`` side of the concave test, the positive window of fast particles, the
box-size proposal ``_first_zero``, the proof step ``certify_candidate`` at exact zeros, the
give-up paths of the box loop and what the error messages state.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from mpmath import mp

import verify
from tests.verify.cases import internal
from verify.elastic import certificate
from verify.elastic.gap import iv_gap, iv_gap_prime, mp_gap
from verify.numerics import first_root
from verify.numerics.phase import reduce_phase
from verify.numerics.precision import NotDecided, escalate, hi, lo, working_dps
from verify.numerics.precision import iv as viv
from verify.numerics.precision import mp as vmp

NUMBER = r"(-?[0-9.]+(?:e[-+][0-9]+)?)"


def _significant_digits(token):
    mantissa = token.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa)


def test_flight_time_default_is_50_digits():
    """``flight_time(phi, v, eps)`` is ``certify_flight(..., dps=50).tau``, rounded to 50 digits
    (a 51-digit default would round the same enclosure differently)."""
    args = (0.3, 1 / 3, 0.5)
    assert verify.flight_time(*args) == verify.certify_flight(*args, dps=50).tau
    assert verify.flight_time(*args) != verify.certify_flight(*args, dps=51).tau


# --- the precision hint -------------------------------------------------------------------

def _short_flight_with_huge_phase():
    """phi = 2**40 (exactly reduced), eps = 0.5, w0 = 1e-55 (up to v's rounding at 190 bits):
    kappa ~ eps*|phi|/w0 ~ 5e66, while w0 > 0 is already decided at 60 digits."""
    phi, eps = mp.mpf(2) ** 40, mp.mpf(0.5)
    with mp.workprec(400):
        v = -eps * mp.sin(phi % (2 * mp.pi)) + mp.mpf(10) ** -55
    with mp.workprec(190):
        v = +v
    return phi, v, eps


def test_escalation_takes_the_larger_of_doubling_and_the_hint():
    """``escalate`` retries at ``max(2*wdps, needed)``: a hint above the doubling is taken, one
    below it is not; the first attempt is at ``dps + 10``."""
    tried = []

    def attempt(wdps):
        tried.append(wdps)
        if len(tried) == 1:
            raise NotDecided("first", needed=150)
        if len(tried) == 2:
            raise NotDecided("second", needed=10)
        return wdps

    assert escalate(attempt, 50, 1000, lambda wdps, why: AssertionError(why)) == 300
    assert tried == [60, 150, 300]


def test_precision_hint_follows_the_condition_number():
    """The hint for a sign left undecided near ``c`` is ``dps + 10 + ceil(log10(kappa))``,
    kappa from the reduced phase (here phi = 2**40, w0 = 1e-55: kappa ~ 1e55, not ~1e67)."""
    phi, v, eps = _short_flight_with_huge_phase()
    tau = verify.certify_flight(phi, v, eps, dps=50).tau
    kappa = verify.condition_number(phi, v, eps, tau)
    assert 1e54 < kappa < 1e57
    with working_dps(60):
        hint = certificate._needed_dps(*internal(phi, v, eps, tau), 50)
    assert hint == 50 + 10 + int(mp.ceil(mp.log10(kappa)))


def test_concave_undecided_message_states_the_candidate_and_delta():
    """One attempt only (max_dps = 60): the message names the candidate (20 digits, near the
    root) and delta = c*10**-50 (3 digits)."""
    phi, v, eps = _short_flight_with_huge_phase()
    tau = verify.certify_flight(phi, v, eps, dps=50).tau
    with pytest.raises(verify.UndecidableCollision) as info:
        verify.certify_flight(phi, v, eps, dps=50, max_dps=60)
    m = re.fullmatch(rf"sign change of d across tau={NUMBER} \+- {NUMBER} not resolved",
                     info.value.what)
    assert m, info.value.what
    c = mp.mpf(m.group(1))
    assert _significant_digits(m.group(1)) == 20
    assert abs(c - tau) < 1e-3 * tau
    with working_dps(60):
        assert m.group(2) == mp.nstr(c * mp.mpf(10) ** -50, 3)
    assert (info.value.phi, info.value.v, info.value.eps) == (phi, v, eps)


# --- the boxes count ----------------------------------------------------------------------

def _count_interval_evaluations(monkeypatch):
    """Count the calls of iv_gap (a point: d, with d' in the box loop) and iv_gap_second
    (a box) made through the elastic certificate's module globals by the proof (the candidate
    search's own curvature enclosures are not part of the proof and are not counted)."""
    calls = {"n": 0, "searching": False}
    for name in ("iv_gap", "iv_gap_second"):
        real = getattr(certificate, name)

        def counted(*args, _real=real):
            calls["n"] += not calls["searching"]
            return _real(*args)

        monkeypatch.setattr(certificate, name, counted)
    real_candidate = certificate.local_candidate

    def candidate(*args):
        calls["searching"] = True
        try:
            return real_candidate(*args)
        finally:
            calls["searching"] = False

    monkeypatch.setattr(certificate, "local_candidate", candidate)
    return calls


@pytest.mark.parametrize("case", ["tangency passed (eps=3)", "two roots (eps=3)", "concave"])
def test_boxes_counts_every_interval_evaluation(monkeypatch, case):
    """``FlightCertificate.boxes`` is the number of interval evaluations (points and boxes)
    the successful attempt made: one attempt here (dps_used = dps + 10)."""
    if case == "concave":
        args = (4.0, 3.0, 0.6)
    else:
        clearance = 1e-3 if case.startswith("tangency") else -1e-3
        g = verify.grazing_contact(3.0, 0.2, 4.0, clearance)
        args = (g.phi, g.v, 3.0)
    calls = _count_interval_evaluations(monkeypatch)
    cert = verify.certify_flight(*args)
    assert cert.dps_used == 60
    assert cert.boxes == calls["n"] >= 2


# --- |eps| just above the concave range, and the positive window --------------------------

def _first_root_by_scanning(phi, v, eps, t_max, n=20000):
    """Reference: the first sign change of d on a grid of n steps (60 digits), then bisection
    to 60 digits. Valid when the grid step is below the roots' spacing."""
    with mp.workdps(60):
        P, V, E = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        step = mp.mpf(t_max) / n
        t = step
        while mp_gap(P, V, E, t) > 0:
            t += step
            assert t < t_max
        return mp.findroot(lambda s: mp_gap(P, V, E, s), (t - step, t), solver="illinois")


@pytest.mark.slow
def test_eps_between_one_and_two_takes_the_general_path():
    """eps = 1.5 is not concave: a dip below 0 gives roots r1 < r2 < r3; the first is r1
    (a concave search from the right would return the last one)."""
    g = verify.grazing_contact(1.5, 0.2, 4.0, -1e-3)
    tau = verify.flight_time(g.phi, g.v, 1.5)
    ref = _first_root_by_scanning(g.phi, g.v, 1.5, g.T)
    assert tau < g.T
    with mp.workdps(60):
        assert abs(tau - ref) < mp.mpf(10) ** -45 * ref


def test_fast_particle_over_a_strong_plate_lands_before_the_window():
    """eps = 10, v = 6.4: d > 0 is known analytically on (t_-, t_+) = (5.4, 7.4) only; this
    departure lands at 3.45 < t_-, after the analytic start w0/(1+eps) = 1.2."""
    phi, v, eps = 2.371902453460294, 6.4, 10.0
    tau = verify.flight_time(phi, v, eps)
    ref = _first_root_by_scanning(phi, v, eps, 5.4)
    assert 1.3 < tau < 5.4
    with mp.workdps(60):
        assert abs(tau - ref) < mp.mpf(10) ** -45 * ref


# --- _first_zero: the box-size proposal -----------------------------------------------------

@pytest.mark.parametrize(("d0", "p", "q", "expected"), [
    (1, -2, 2, 1),  # double root: touches 0 at s = 1
    (1, 1, 0, None),  # increasing line
    (1, -1, 0, 1),  # decreasing line
    (1, 0, 1, None),  # convex, no real root
    (1, 0, -2, 1),  # concave: 1 - s**2
    (0.5, -1.5, 2, 0.5),  # 0.5 - 1.5 s + s**2: roots 0.5 and 1
    (1, 3, -2, (3 + math.sqrt(13)) / 2),  # 1 + 3s - s**2: positive root only
])
def test_first_zero_is_the_first_positive_zero_of_the_quadratic(d0, p, q, expected):
    with working_dps(30):
        got = first_root._first_zero(mp.mpf(d0), mp.mpf(p), mp.mpf(q))
        if expected is None:
            assert got is None
        else:
            assert abs(got - expected) < 1e-15 * expected  # float64 expectations


def test_first_zero_against_numpy_roots():
    rng = np.random.default_rng(7)
    with working_dps(30):
        for _ in range(300):
            d0, p, q = rng.uniform(0.01, 2), rng.uniform(-3, 3), rng.uniform(-3, 3)
            roots = [r.real for r in np.roots([q / 2, p, d0]) if abs(r.imag) < 1e-12 and r.real > 0]
            got = first_root._first_zero(mp.mpf(d0), mp.mpf(p), mp.mpf(q))
            if not roots:
                assert got is None, (d0, p, q)
            else:
                assert abs(float(got) - min(roots)) <= 1e-9 * min(roots), (d0, p, q)


# --- certify_candidate ----------------------------------------------------------------------

def test_certify_candidate_at_an_exact_zero_of_d():
    """eps = 0, v = 1: d(t) = t*(1 - t/2) is evaluated exactly, d(2) = [0, 0]. The enclosure
    must hold the root strictly inside: (2, 2.5) and (1.5, 2) are refused."""
    assert verify.gap(0.0, 1.0, 0.0, 2.0) == 0
    assert certificate.certify_candidate(0.0, 1.0, 0.0, 1.5, 2.5)
    assert not certificate.certify_candidate(0.0, 1.0, 0.0, 2.0, 2.5)
    assert not certificate.certify_candidate(0.0, 1.0, 0.0, 1.5, 2.0)


def test_certify_candidate_uses_w0_with_the_plate_velocity_sign():
    """phi = 1, eps = 0.6, v = 0.1: w0 = v + eps*sin(phi) = 0.6 > 0 (v - eps*sin(phi) < 0)."""
    tau = verify.certify_flight(1.0, 0.1, 0.6).tau
    with mp.workdps(60):
        lo_, hi_ = tau * (1 - mp.mpf(10) ** -40), tau * (1 + mp.mpf(10) ** -40)
    assert certificate.certify_candidate(1.0, 0.1, 0.6, lo_, hi_)


def test_certify_candidate_refuses_an_undecided_departure():
    """w0 ~ 1e-1000: not provably > 0 at 60 digits, so no enclosure is certified."""
    with mp.workdps(1100):
        phi = mp.mpf(0.3)
        v = -2 * mp.sin(phi) + mp.mpf(10) ** -1000
    assert not certificate.certify_candidate(phi, v, 2.0, 1e-300, 1e-299)


def _enclosure_of_r1(g):
    tau = verify.flight_time(g.phi, g.v, 1.5)
    with mp.workdps(60):
        delta = tau * mp.mpf(10) ** -45
        return tau - delta, tau + delta


def test_certify_candidate_refuses_the_third_root_for_eps_in_one_to_two():
    """eps = 1.5 (d not concave): r3, after the dip's r1 < r2, has d(lo) > 0 > d(hi) but is
    not the first root; the boxes from the analytic start refuse it."""
    g = verify.grazing_contact(1.5, 0.2, 4.0, -1e-3)
    with mp.workdps(60):
        f = lambda t: mp_gap(g.phi, g.v, mp.mpf(1.5), t)  # noqa: E731
        r2 = mp.findroot(f, g.T + mp.sqrt(2e-3 / (1.5 * mp.cos(0.2) - 1)))
    assert r2 > g.T
    with mp.workdps(60):  # the next down-crossing after r2, by a 1e-2 grid and bisection
        t = r2 + mp.mpf(10) ** -3
        while f(t) > 0:
            t += mp.mpf(10) ** -2
        r3 = mp.findroot(f, (t - mp.mpf(10) ** -2, t), solver="illinois")
    assert r3 > r2
    with mp.workdps(60):
        delta = r3 * mp.mpf(10) ** -45
        lo_, hi_ = r3 - delta, r3 + delta
    assert certificate.certify_candidate(g.phi, g.v, 1.5, *_enclosure_of_r1(g))
    assert not certificate.certify_candidate(g.phi, g.v, 1.5, lo_, hi_)


def test_certify_candidate_default_is_50_digits():
    """An enclosure of relative half-width 10**-60.8 around the root: d's sign at its ends is
    decided at 61 working digits (dps = 51) but not at 60 (dps = 50, the default)."""
    tau = verify.certify_flight(0.3, 1 / 3, 0.5, dps=90).tau
    with mp.workdps(110):
        delta = tau * mp.mpf(10) ** mp.mpf(-60.8)
        lo_, hi_ = tau - delta, tau + delta
    assert certificate.certify_candidate(0.3, 1 / 3, 0.5, lo_, hi_, dps=51)
    assert not certificate.certify_candidate(0.3, 1 / 3, 0.5, lo_, hi_, dps=50)
    assert not certificate.certify_candidate(0.3, 1 / 3, 0.5, lo_, hi_)


@pytest.mark.parametrize(("lo_", "hi_", "needle"), [
    (math.nan, 1.0, "^lo must be finite, got lo=nan"),
    (0.5, math.inf, "^hi must be finite, got hi=inf"),
    (0.0, 1.0, "^need 0 < lo < hi, got lo=0"), (1.0, 1.0, "^need 0 < lo < hi, got lo=1.0, hi=1.0"),
])
def test_certify_candidate_rejects_bad_enclosures(lo_, hi_, needle):
    with pytest.raises(ValueError, match=needle):
        certificate.certify_candidate(0.3, 1.0, 0.6, lo_, hi_)


# --- certify_flight's precision arguments and messages --------------------------------------

def test_max_dps_equal_to_dps_is_one_attempt():
    cert = verify.certify_flight(0.3, 1 / 3, 0.5, dps=30, max_dps=30)
    assert cert.dps_used == 30


@pytest.mark.parametrize(("max_dps", "message"), [
    (20, "max_dps must be >= dps, got max_dps=20, dps=30"),
    (10, "max_dps must be >= 15, got max_dps=10"),
])
def test_bad_max_dps_is_named(max_dps, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        verify.certify_flight(0.3, 1.0, 0.6, dps=30, max_dps=max_dps)


@pytest.mark.slow
@pytest.mark.parametrize(("dps", "reached"), [(50, 400), (120, 480)])
def test_default_max_dps_is_max_of_4_dps_and_400(dps, reached):
    g = verify.grazing_contact(3.0, 0.2, 4.0, 0, dps=600)  # exact tangency to ~600 digits
    with pytest.raises(verify.UndecidableCollision) as info:
        verify.certify_flight(g.phi, g.v, 3.0, dps=dps)
    assert info.value.dps_reached == reached
    assert (info.value.phi, info.value.v, info.value.eps) == (g.phi, g.v, 3.0)


def _w0_near_zero(w0):
    with mp.workdps(200):
        v = -2 * mp.sin(mp.mpf(0.3)) + mp.mpf(w0)
    return mp.mpf(0.3), v, mp.mpf(2)


def test_negative_w0_found_at_working_precision_is_no_departure():
    """w0 = -1.234567891e-40: check_state's quick enclosure cannot exclude w0 > 0, the first
    attempt can; the message states hi(w0) to 8 digits."""
    phi, v, eps = _w0_near_zero("-1.234567891e-40")
    with pytest.raises(ValueError) as info:
        verify.certify_flight(phi, v, eps, dps=50)
    m = re.match(rf"no departure: w0 = v \+ eps\*sin\(phi\) = {NUMBER} <= 0 \(phi=",
                 str(info.value))
    assert m, str(info.value)
    assert m.group(1) == "-1.2345679e-40"


def test_undecided_w0_message_states_the_enclosure_width():
    phi, v, eps = _w0_near_zero("1e-1000")
    with pytest.raises(verify.UndecidableCollision) as info:
        verify.certify_flight(phi, v, eps, dps=20, max_dps=60)
    phi, v, eps = internal(phi, v, eps)
    with working_dps(60) as prec:
        w0 = viv.mpf(v) + viv.mpf(eps) * viv.sin(reduce_phase(phi, prec).enclosure)
        width = vmp.nstr(hi(w0) - lo(w0), 3)
    assert info.value.what == f"w0 = v + eps*sin(phi) is within {width} of 0: departure or not"


def test_general_graze_message_and_hint():
    """Exact tangency at 40 digits (one attempt, |eps| > 1): the candidate's d(c + delta)
    straddles 0; the message states its size and the candidate, the hint exceeds dps + 10."""
    g = verify.grazing_contact(3.0, 0.2, 4.0, 0, dps=500)
    with working_dps(40), pytest.raises(NotDecided) as info:
        certificate.elastic_attempt(*internal(g.phi, g.v, 3), 30, 40)
    what = info.value.what
    m = re.fullmatch(rf"d has a minimum within {NUMBER} of 0 near tau={NUMBER}"
                     rf"(?: \(\|d'\| <= {NUMBER} there\))?: graze or not", what)
    assert m, what
    assert _significant_digits(m.group(1)) == 3 and _significant_digits(m.group(2)) == 20
    assert 0 < mp.mpf(m.group(1)) < 1e-35
    assert abs(mp.mpf(m.group(2)) - g.T) < 1e-15
    assert info.value.needed > 40


# --- the box loop's give-up paths (forced) ---------------------------------------------------

def _box_loop_context():
    g = verify.grazing_contact(3.0, 0.2, 4.0, 1e-3)
    return g, certificate.elastic_gap(*internal(g.phi, g.v, 3), 30, 40)


@pytest.mark.parametrize("force", ["no box proved", "no progress"])
def test_box_loop_gives_up_undecided_with_message_and_hint(monkeypatch, force):
    """A box loop that can prove nothing (``_taylor_lower`` never positive) or make no
    progress (the proposed box rounds to nothing) must end in ``_Undecided`` naming the stuck
    point, with the precision hint, never in a silent success or a budget error."""
    if force == "no box proved":
        monkeypatch.setattr(first_root, "taylor_lower", lambda d0, p, q, h: vmp.mpf(0))
    else:
        monkeypatch.setattr(first_root, "_first_zero", lambda d0, p, q: vmp.mpf(0))
    with working_dps(40):
        g, ctx = _box_loop_context()
        (contact,) = internal(g.T)
        a = contact / 2
        with pytest.raises(NotDecided) as info:
            first_root.prove_positive(ctx, a, contact)
        ia = viv.mpf(a)
        expected = first_root._unresolved(a, iv_gap(ctx.iphi, ctx.iv_v, ctx.ieps, ia),
                                       iv_gap_prime(ctx.iphi, ctx.iv_v, ctx.ieps, ia))
    assert info.value.what == expected
    with working_dps(40):
        needed = certificate._needed_dps(*internal(g.phi, g.v, 3), a, 30)
    assert info.value.needed == needed > 40


def test_box_loop_refusal_at_a_root_states_where():
    """d(a) <= 0 at a point of the stretch: the message names that point and |d|, |d'| there."""
    g = verify.grazing_contact(3.0, 0.2, 4.0, 0, dps=500)
    with working_dps(40):
        ctx = certificate.elastic_gap(*internal(g.phi, g.v, 3), 30, 40)
        (contact,) = internal(g.T)
        with pytest.raises(NotDecided) as info:
            first_root.prove_positive(ctx, contact / 2, contact * (1 + vmp.mpf(10) ** -5))
    m = re.fullmatch(rf"d has a minimum within {NUMBER} of 0 near tau={NUMBER} "
                     rf"\(\|d'\| <= {NUMBER} there\): graze or not", info.value.what)
    assert m, info.value.what
    assert [_significant_digits(m.group(i)) for i in (1, 2, 3)] == [3, 20, 3]
    a = mp.mpf(m.group(2))
    assert abs(a - g.T) < 1e-15 and mp.mpf(m.group(1)) < 1e-35 and mp.mpf(m.group(3)) < 1e-15
    assert info.value.needed > 40


# --- budgets ------------------------------------------------------------------------------------

_BUDGET = (r"flight beyond verify's search budget: (.+) reached tau={n} with the gap still"
           r" positive \(phi={n}, v={n}, eps={n}\): too many plate periods to cross one by one")


def _budget_message(message, phi, v, eps):
    m = re.fullmatch(_BUDGET.format(n=NUMBER), message)
    assert m, message
    assert [m.group(i) for i in (3, 4, 5)] == [mp.nstr(mp.mpf(x), 8) for x in (phi, v, eps)]
    assert mp.nstr(mp.mpf(m.group(2)), 8) == m.group(2) and mp.mpf(m.group(2)) > 0
    return m.group(1), mp.mpf(m.group(2))


def test_box_budget_message(monkeypatch):
    """phi = -1e-300/3, v = 1e154/3, eps = 1e300/3: the particle leaves from the top of the
    plate and stays ahead for ~1e153 plate periods, with a near-tangency in each."""
    monkeypatch.setattr(first_root, "MAX_BOXES", 300)
    phi, v, eps = -1e-300 / 3, 1e154 / 3, 1e300 / 3
    with pytest.raises(ValueError) as info:
        verify.certify_flight(phi, v, eps)
    what, _ = _budget_message(str(info.value), phi, v, eps)
    assert what == "300 proof boxes"


def test_candidate_step_budget_message(monkeypatch):
    monkeypatch.setattr(first_root, "MAX_STEPS", 3)
    phi, v, eps = -1e-300 / 3, 1e154 / 3, 1e300 / 3
    with pytest.raises(ValueError) as info:
        verify.certify_flight(phi, v, eps)
    what, _ = _budget_message(str(info.value), phi, v, eps)
    assert what == "3 lower-bound steps"


def test_candidate_behind_the_proved_part_is_refused(monkeypatch):
    g = verify.grazing_contact(3.0, 0.2, 4.0, -1e-3)
    offered = []

    def behind(ctx, curv, t):
        offered.append(t / 2)
        return t / 2

    monkeypatch.setattr(certificate, "local_candidate", behind)
    with pytest.raises(verify.UndecidableCollision) as info:
        verify.certify_flight(g.phi, g.v, 3.0, dps=30, max_dps=40)
    with working_dps(40):
        c = vmp.nstr(offered[-1], 20)
    assert info.value.what == f"candidate tau={c} is behind the proved part"


def test_concave_bracket_budget_message(monkeypatch):
    monkeypatch.setattr(certificate, "_MAX_BISECTIONS", 3)
    monkeypatch.setattr(certificate, "_newton_from_right", lambda ctx, t: vmp.mpf(0))
    with pytest.raises(verify.UndecidableCollision) as info:
        verify.certify_flight(4.0, 3.0, 0.6, dps=30, max_dps=40)
    assert info.value.what == "no enclosure of the root in 3 bracket steps"


# --- the concave bracket: ends already proved, and a check point exactly on the root ---------

@pytest.mark.parametrize("side", [-1, 1])
def test_concave_candidate_just_off_the_root(monkeypatch, side):
    """phi = -x, v = x, eps = 1: the root is exactly 2x. A first candidate 1.5 deltas off the
    root proves one bracket end next to it; Newton's next candidate then has that end within
    delta, so the end's known sign is used (no evaluation): still one attempt at 60 digits."""
    x = 3e-5
    real, calls = certificate._newton_from_right, []

    def first_off(ctx, t):
        calls.append(t)
        if len(calls) == 1:
            return 2 * vmp.mpf(x) * (1 + side * vmp.mpf(1.5) * vmp.mpf(10) ** -50)
        return real(ctx, t)

    monkeypatch.setattr(certificate, "_newton_from_right", first_off)
    cert = verify.certify_flight(-x, x, 1.0)
    lo_, hi_ = cert.enclosure
    assert lo_ < 2 * mp.mpf(x) < hi_ and cert.dps_used == 60 and len(calls) == 2
    assert (hi_ - lo_) / hi_ <= 3 * mp.mpf(10) ** -50


def _candidate_with_an_end_on(root, side):
    """A candidate c whose check point c + side*c*10**-dps rounds exactly to ``root`` at the
    working precision (searched among the neighbours of root/(1 + side*10**-dps))."""

    def candidate(ctx, t):
        scale = vmp.mpf(10) ** (-ctx.dps)
        c0 = root / (1 + side * scale)
        ulp = vmp.mpf(2) ** (vmp.mag(c0) - vmp.prec)
        for k in range(-8, 9):
            c = c0 + k * ulp
            if c + side * (c * scale) == root:
                return c
        raise AssertionError("no candidate found")

    return candidate


@pytest.mark.parametrize("side", [-1, 1])
def test_concave_check_point_exactly_on_the_root(monkeypatch, side):
    """eps = 0, v = 1: d(t) = t*(1 - t/2) is evaluated exactly and d(2) = [0, 0]. A candidate
    whose check point is exactly 2 decides no sign there (the attempt is undecided); the next
    attempt encloses 2 strictly."""
    real, calls = certificate._newton_from_right, []
    on_root = _candidate_with_an_end_on(vmp.mpf(2), side)

    def first_on_root(ctx, t):
        calls.append(t)
        return on_root(ctx, t) if len(calls) == 1 else real(ctx, t)

    monkeypatch.setattr(certificate, "_newton_from_right", first_on_root)
    cert = verify.certify_flight(0.0, 1.0, 0.0, dps=30)
    lo_, hi_ = cert.enclosure
    assert lo_ < 2 < hi_ and cert.dps_used == 80


def _early_candidate():
    """The two-roots departure (eps = 3) and a point just before its first root r1 where
    d ~ 2e-4 > 0 (well decided at any precision)."""
    g = verify.grazing_contact(3.0, 0.2, 4.0, -1e-3)
    with mp.workdps(80):
        f = lambda t: mp_gap(g.phi, g.v, mp.mpf(3), t)  # noqa: E731
        r1 = mp.findroot(f, g.T - mp.sqrt(2e-3 / (3 * mp.cos(0.2) - 1)))
        (early,) = internal(r1 * (1 - mp.mpf(10) ** -3))
        assert 0 < f(mp.mpf(early)) < 1e-2
    return g, r1, early


def _offer_first(monkeypatch, early):
    """Make ``early`` the first candidate of the search; the later ones are the real ones."""
    real, calls = certificate.local_candidate, []

    def first_early(ctx, curv, t):
        calls.append(t)
        return early if len(calls) == 1 else real(ctx, curv, t)

    monkeypatch.setattr(certificate, "local_candidate", first_early)
    return calls


def test_general_candidate_with_a_small_positive_gap_is_passed(monkeypatch):
    """|eps| > 1: a first candidate just before the first root r1 is a near-tangency that
    does not touch: the proof covers it and the search goes on to r1, in the same attempt (a
    positive d(right) is never taken for a landing), counting every evaluation in ``boxes``."""
    g, r1, early = _early_candidate()
    calls = _offer_first(monkeypatch, early)
    counted = _count_interval_evaluations(monkeypatch)
    cert = verify.certify_flight(g.phi, g.v, 3.0)
    assert cert.dps_used == 60 and len(calls) == 2
    assert cert.boxes == counted["n"]
    with mp.workdps(80):
        assert abs(cert.tau - r1) < mp.mpf(10) ** -45 * r1


def test_box_budget_counts_every_box_of_the_flight(monkeypatch):
    """The budget check after a near-tangency counts the boxes so far (B: the proof up to the
    candidate, d(right), the proof across it): a limit of B - 1 stops there, naming
    right = c + c*10**-50; a limit of B passes it (and stops later, in a longer stretch)."""
    g, r1, early = _early_candidate()
    proofs = []
    real_prove = first_root.prove_positive

    def recording(ctx, a, end):
        proofs.append(real_prove(ctx, a, end))
        return proofs[-1]

    monkeypatch.setattr(first_root, "prove_positive", recording)
    _offer_first(monkeypatch, early)
    verify.certify_flight(g.phi, g.v, 3.0)
    budget = proofs[0] + 1 + proofs[1]  # boxes at the check: proof to left, d(right), across
    assert max(proofs[:2]) < budget - 1 < proofs[2]
    with working_dps(60):
        right = vmp.nstr(early + early * vmp.mpf(10) ** -50, 8)
    reached = {}
    for limit in (budget - 1, budget):  # the check at the near-tangency fails, then passes
        _offer_first(monkeypatch, early)
        monkeypatch.setattr(first_root, "MAX_BOXES", limit)
        with pytest.raises(ValueError) as info:
            verify.certify_flight(g.phi, g.v, 3.0)
        what, tau = _budget_message(str(info.value), g.phi, g.v, 3.0)
        assert what == f"{limit} proof boxes"
        reached[limit] = tau
    assert mp.nstr(reached[budget - 1], 8) == right  # stopped at the near-tangency
    assert reached[budget] > reached[budget - 1]  # stopped later, in the next stretch


def test_near_tangency_step_budget(monkeypatch):
    """At most _MAX_STEPS candidates per search: with one allowed, the near-tangency that
    does not touch ends the search (the budget error names the point reached)."""
    g, r1, early = _early_candidate()
    _offer_first(monkeypatch, early)
    monkeypatch.setattr(first_root, "MAX_STEPS", 1)
    with pytest.raises(ValueError) as info:
        verify.certify_flight(g.phi, g.v, 3.0)
    what, _ = _budget_message(str(info.value), g.phi, g.v, 3.0)
    assert what == "1 near-tangencies"


def test_box_loop_budget_is_per_stretch(monkeypatch):
    """A stretch proved with exactly _MAX_BOXES evaluations passes (the limit is > not >=)."""
    g = verify.grazing_contact(3.0, 0.2, 4.0, -1e-3)
    proofs = []
    real_prove = first_root.prove_positive

    def recording(ctx, a, end):
        proofs.append(real_prove(ctx, a, end))
        return proofs[-1]

    monkeypatch.setattr(first_root, "prove_positive", recording)
    verify.certify_flight(g.phi, g.v, 3.0)
    assert len(proofs) == 1 and proofs[0] > 2
    monkeypatch.setattr(first_root, "MAX_BOXES", proofs[0])
    with working_dps(60):
        ctx = certificate.elastic_gap(*internal(g.phi, g.v, 3), 50, 60)
        free = lo(ctx.iv_v + ctx.ieps * viv.sin(ctx.iphi)) / 4
        (tau,) = internal(verify.certify_flight(g.phi, g.v, 3.0).tau)
        left = tau * (1 - vmp.mpf(10) ** -50)
        assert real_prove(ctx, free, left) == proofs[0]


@pytest.mark.parametrize(("psi", "t_guess"), [(0.2, 4.0), (0.25, 3.0)])
def test_general_graze_message_when_the_stretch_is_proved(monkeypatch, psi, t_guess):
    """Forced (the stretch before the candidate taken as proved): the exact tangency's
    candidate then meets an undecided d(c + delta); the message states |d| there (3 digits)
    and the candidate (20 digits), with the precision hint."""
    g = verify.grazing_contact(3.0, psi, t_guess, 0, dps=500)
    monkeypatch.setattr(first_root, "prove_positive", lambda ctx, a, end: 1)
    with working_dps(40), pytest.raises(NotDecided) as info:
        certificate.elastic_attempt(*internal(g.phi, g.v, 3), 30, 40)
    m = re.fullmatch(rf"d has a minimum within {NUMBER} of 0 near tau={NUMBER}: graze or not",
                     info.value.what)
    assert m, info.value.what
    assert _significant_digits(m.group(1)) == 3 and _significant_digits(m.group(2)) == 20
    assert 0 < mp.mpf(m.group(1)) < 1e-35 and abs(mp.mpf(m.group(2)) - g.T) < 1e-15
    assert info.value.needed > 40


# --- interval ends exactly 0.0 ----------------------------------------------------------------
#
# An end of an interval enclosure is exactly 0 only by construction: v is chosen (an exact mpf
# with the working precision's bits) so that it cancels one end of the rounded enclosure of
# eps*sin(phi), or of the plate term of d, computed exactly as the certifier computes it.

def _v_cancelling_w0_end(phi, eps, wdps, end):
    """v with ``end(w0) == 0`` for ``w0 = iv(v) + iv(eps)*iv.sin(phi)`` at ``wdps`` digits."""
    phi, eps = internal(phi, eps)
    with working_dps(wdps) as prec:
        plate = viv.mpf(eps) * viv.sin(reduce_phase(phi, prec).enclosure)
        v = -end(plate)
        w0 = viv.mpf(v) + plate
    assert end(w0) == 0 and lo(w0) < hi(w0)
    return v


def test_w0_with_upper_end_exactly_zero_is_rejected_at_that_precision():
    """``hi(w0) == 0`` proves ``w0 <= 0``: no departure, decided at the first attempt. With
    ``max_dps`` equal to its precision, a ``hi(w0) < 0`` test would report it undecidable."""
    phi, eps = mp.mpf(1), mp.mpf(0.5)
    v = _v_cancelling_w0_end(phi, eps, 60, hi)
    with pytest.raises(ValueError, match=r"no departure: w0 = v \+ eps\*sin\(phi\) = 0\.0 <= 0"):
        verify.certify_flight(phi, v, eps, dps=50, max_dps=60)


def test_w0_with_lower_end_exactly_zero_is_not_a_proved_departure():
    """``lo(w0) == 0`` does not prove ``w0 > 0`` (the concave proof needs ``d'(0) > 0``): at that
    precision the flight is undecidable BECAUSE of w0 (not of a later sign); one precision step
    later (120 digits) w0 > 0 is proved and the flight certified."""
    phi, eps = mp.mpf(1), mp.mpf(0.5)
    v = _v_cancelling_w0_end(phi, eps, 60, lo)
    with pytest.raises(verify.UndecidableCollision) as err:
        verify.certify_flight(phi, v, eps, dps=50, max_dps=60)
    assert err.value.what.startswith("w0 = v + eps*sin(phi) is within ")
    assert err.value.what.endswith(" of 0: departure or not")
    cert = verify.certify_flight(phi, v, eps, dps=50)
    assert cert.dps_used == 120 and cert.tau > 0


def test_certify_candidate_at_eps_one_uses_the_concave_criterion():
    """``|eps| = 1`` is the concave case, so the proof is ``d(lo) > 0`` in ``iv``. A
    lower end inside the analytic free stretch ``(0, w0/2]`` whose gap ``d(lo) ~ 1e-52`` is
    below the resolution of 25 digits: the concave criterion cannot prove it (False), the box
    criterion of ``|eps| > 1`` would accept it without evaluating ``d(lo)``. At 40 digits the
    same enclosure is proved (it is right)."""
    (phi, eps), dps = internal(1, 1), 15
    with working_dps(dps + 10) as prec:
        sine = viv.sin(reduce_phase(phi, prec).enclosure)
        v = -lo(sine) + (hi(sine) - lo(sine))  # w0 ~ 1e-26: one ulp of the sine above 0
        w0 = viv.mpf(v) + viv.sin(reduce_phase(phi, prec).enclosure)
        lo_ = lo(w0) / 2
        assert lo(w0) > 0 and lo(certificate.elastic_gap(phi, v, eps, dps, dps + 10).d(lo_)) <= 0
    hi_ = mp.mpf(2) ** -60
    tau = verify.certify_flight(phi, v, eps, dps=40).tau
    assert lo_ < tau < hi_
    assert not certificate.certify_candidate(phi, v, eps, lo_, hi_, dps=dps)
    assert certificate.certify_candidate(phi, v, eps, lo_, hi_, dps=30)


def _search_at_four(end, eps0):
    """phi = 0, eps = eps0 + k*2**-40 (the first k that makes the cancellation exact), v such
    that ``end(d(4)) == 0`` at 60 digits (the plate term's end cancelled by ``4*(v - 2)``), and
    a candidate whose right end ``c + c*10**-50`` is exactly 4. Returns the context, the
    candidate and the enclosure of d(4); the first root is within rounding of 4 (d' ~ -4.3 for
    eps ~ 2, ~ -2.3 for eps ~ 0.5)."""
    dps, wdps, four = 50, 60, vmp.mpf(4)
    with working_dps(wdps):
        for k in range(64):
            eps = vmp.mpf(eps0) + k * vmp.mpf(2) ** -40
            half = viv.mpf(four) / 2
            plate = 2 * viv.mpf(eps) * viv.sin(half) * viv.sin(half)
            with vmp.workprec(1000):
                v = 2 - end(plate) / 4
            if vmp.mpf(v) == v:  # exact at 60 digits: the cancellation is exact
                break
        ctx = certificate.elastic_gap(vmp.zero, v, eps, dps, wdps)
        scale = vmp.mpf(10) ** -dps
        c = next(c for c in (four / (1 + scale) + j * vmp.eps * 4 for j in range(-5, 6))
                 if c + c * scale == four)
        d4 = ctx.d(four)
        assert end(d4) == 0 and lo(d4) < hi(d4)
    return ctx, c, d4


@pytest.mark.parametrize("eps0, concave", [(2.0, False), (0.5, True)],
                         ids=["eps~2 boxes", "eps~0.5 concave shortcut"])
@pytest.mark.parametrize("end", [hi, lo], ids=["d(right) in [-x, 0]", "d(right) in [0, x]"])
def test_search_needs_a_strict_sign_at_the_candidate(end, eps0, concave):
    """The certificate is ``d(right) < 0`` and a skipped near-tangency ``d(right) > 0``, both
    strict, in the box path and in the concave shortcut of ``_search`` (used by the drag
    certificate; here with a true claim, ``|eps| <= 1``): an enclosure of ``d(right)`` with an
    end exactly 0 decides neither, and the attempt reports the minimum of d at the candidate
    (its enclosure's size there), not elsewhere."""
    ctx, c, d4 = _search_at_four(end, eps0)
    with working_dps(ctx.wdps), pytest.raises(NotDecided) as err:
        first_root.search_first_root(ctx, 1 + abs(ctx.eps), lo(ctx.iv_v) / (1 + abs(ctx.eps)),
                                     None, concave_from=(lambda right: True) if concave else None,
                                     candidate=lambda ctx, curv, t: c)
    size = max(abs(lo(d4)), abs(hi(d4)))
    assert err.value.what == (f"d has a minimum within {vmp.nstr(size, 3)} of 0 near "
                              "tau=4.0: graze or not")


def test_precision_hint_at_an_exact_zero_of_the_slope():
    """``condition_number`` is infinite where ``d'(tau) = 0`` exactly (eps = 0, tau = v: the apex
    of the parabola); the precision hint is then the guard precision, not an overflow."""
    assert verify.condition_number(0.0, 1.0, 0.0, 1.0) == mp.inf
    with working_dps(60):
        assert certificate._needed_dps(vmp.zero, vmp.one, vmp.zero, vmp.one, 50) == 60
