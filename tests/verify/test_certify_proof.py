"""The proof step of the certificate on its own: the Taylor-form box bound against brute-force
minima, and certificates offered wrong candidates (a later root, a non-root) must refuse."""

from __future__ import annotations

import numpy as np
import pytest
from mpmath import mp

import verify
from tests.verify.cases import internal
from verify.elastic import certificate
from verify.elastic.gap import iv_gap, iv_gap_prime, iv_gap_second, mp_gap
from verify.numerics import first_root
from verify.numerics.precision import NotDecided, lo, to_user, working_dps
from verify.numerics.precision import iv as viv

WDPS = 40  # digits of the interval evaluations in the box-bound test
REF_DPS = 60  # digits of the brute-force sampling (WDPS + 20)


def _box_bound(phi, v, eps, a, h):
    """The proof step's lower bound of d on [a, a+h] and its three inputs (d, d', min d'')."""
    with working_dps(WDPS):
        ctx = certificate.elastic_gap(*internal(phi, v, eps), WDPS - 10, WDPS)
        a, h = internal(a, h)
        ia = viv.mpf(a)
        d_a = lo(iv_gap(ctx.iphi, ctx.iv_v, ctx.ieps, ia))
        p_a = lo(iv_gap_prime(ctx.iphi, ctx.iv_v, ctx.ieps, ia))
        q = lo(iv_gap_second(ctx.iphi, ctx.ieps, viv.mpf([a, a + h])))
        return to_user(first_root.taylor_lower(d_a, p_a, q, h)), *to_user((d_a, p_a, q))


def _random_boxes(n, seed=12):
    """n random boxes of random departures (eps in [1, 10]), and n/2 boxes straddling the dip
    of a near-graze (d' < 0 < d'' on the box: the quadratic's vertex inside the box)."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        eps = float(rng.uniform(1.0, 10.0))
        phi = float(rng.uniform(0.0, 2 * np.pi))
        v = float(rng.uniform(0.0, 10.0)) + eps  # w0 > 0
        a = float(rng.uniform(0.0, 8.0))
        h = float(10.0 ** rng.uniform(-3, 0))
        yield phi, v, eps, a, h
    made = 0
    while made < n // 2:
        eps = float(rng.uniform(1.5, 10.0))
        psi = float(rng.uniform(-0.5, 0.5)) * np.arccos(1.2 / eps)  # eps*cos(psi) > 1.2
        clearance = float(10.0 ** rng.uniform(-8, -1)) * float(rng.choice([-1.0, 1.0]))
        try:
            g = verify.grazing_contact(eps, psi, float(rng.uniform(1.0, 6.0)), clearance, dps=30)
        except ValueError:  # no departure reaches a contact from this guess: draw again
            continue
        made += 1
        h = float(10.0 ** rng.uniform(-4, -1))
        yield float(g.phi), float(g.v), eps, float(g.T) - h * float(rng.uniform(0.1, 0.9)), h


@pytest.mark.slow
def test_box_bound_is_below_the_sampled_minimum_and_not_loose():
    """On 450 random boxes: bound <= min of d over 101 samples (60 digits), and
    bound >= d(a + s*) - |eps|*h**3/2 - rounding, where s* minimises the quadratic model: the
    model differs from d by at most (max d'' - min d'')*s**2/2 <= |eps|*h*s**2/2 (d''' <= |eps|).
    """
    branches = {"q<=0": 0, "p>=0": 0, "vertex outside": 0, "vertex inside": 0}
    for phi, v, eps, a, h in _random_boxes(300):
        bound, d_a, p_a, q = _box_bound(phi, v, eps, mp.mpf(a), mp.mpf(h))
        with mp.workdps(REF_DPS):
            P, V, E, A, H = (mp.mpf(x) for x in (phi, v, eps, a, h))
            samples = [A + H * k / 100 for k in range(101)]
            if q > 0 and p_a < 0:
                s_star = min(-p_a / q, H)
                branches["vertex inside" if -p_a / q < H else "vertex outside"] += 1
            else:
                s_star = H if (q <= 0 and d_a + p_a * H + q * H * H / 2 < d_a) else 0
                branches["q<=0" if q <= 0 else "p>=0"] += 1
            samples.append(A + s_star)
            values = [mp_gap(P, V, E, t) for t in samples]
            scale = abs(d_a) + abs(p_a) * H + abs(q) * H * H + 1
            rounding = mp.mpf(10) ** (-(WDPS - 5)) * scale
            assert bound <= min(values), (phi, v, eps, a, h)
            assert bound >= values[-1] - abs(E) * H**3 / 2 - rounding, (phi, v, eps, a, h)
    assert all(count >= 10 for count in branches.values()), branches  # no branch untested


def _two_roots():
    """A departure (eps = 3) whose gap dips to -1e-3 near T: two close roots r1 < r2 < T."""
    g = verify.grazing_contact(3.0, 0.2, 4.0, -1e-3)
    with mp.workdps(80):
        f = lambda t: mp_gap(g.phi, g.v, mp.mpf(3), t)  # noqa: E731
        half = mp.sqrt(2 * mp.mpf(1e-3) / (3 * mp.cos(mp.mpf(0.2)) - 1))
        r1 = mp.findroot(f, g.T - half)
        r2 = mp.findroot(f, g.T + half)
    assert r1 < g.T < r2
    return g, r1, r2


def _enclosure(r, dps=50):
    with mp.workdps(dps + 30):
        r = mp.mpf(r)
        delta = r * mp.mpf(10) ** (-dps)
        return r - delta, r + delta


def test_certify_candidate_accepts_the_first_root_and_refuses_the_second():
    g, r1, r2 = _two_roots()
    assert certificate.certify_candidate(g.phi, g.v, 3.0, *_enclosure(r1))
    assert not certificate.certify_candidate(g.phi, g.v, 3.0, *_enclosure(r2))
    # the dip bottom (d < 0 there): not a root, refused
    assert not certificate.certify_candidate(g.phi, g.v, 3.0, *_enclosure(g.T))
    # a point well before the first root (d > 0 on both sides): refused
    assert not certificate.certify_candidate(g.phi, g.v, 3.0, *_enclosure(r1 / 2))


@pytest.mark.parametrize("phi, v, eps", [(-3e-5, 3e-5, 1.0), (4.0, 3.0, 0.6), (-0.5, 0.5, 1.0)])
def test_certify_candidate_concave(phi, v, eps):
    tau = verify.certify_flight(phi, v, eps).tau
    assert certificate.certify_candidate(phi, v, eps, *_enclosure(tau, 45))
    assert not certificate.certify_candidate(phi, v, eps, *_enclosure(tau * 1.001))
    assert not certificate.certify_candidate(phi, v, eps, *_enclosure(tau * 0.999))


def test_general_certifier_refuses_a_candidate_at_the_second_root(monkeypatch):
    g, r1, r2 = _two_roots()
    assert abs(verify.certify_flight(g.phi, g.v, 3.0).tau - r1) < mp.mpf(10) ** -45 * r1
    (r2,) = internal(r2)
    monkeypatch.setattr(certificate, "local_candidate", lambda ctx, curv, t: r2)
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(g.phi, g.v, 3.0, dps=30, max_dps=60)


def test_general_certifier_refuses_a_candidate_that_is_no_root(monkeypatch):
    g, r1, _ = _two_roots()
    contact, half_r1 = internal(g.T, r1 / 2)
    monkeypatch.setattr(certificate, "local_candidate", lambda ctx, curv, t: contact)  # d = -1e-3
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(g.phi, g.v, 3.0, dps=30, max_dps=60)
    monkeypatch.setattr(certificate, "local_candidate", lambda ctx, curv, t: half_r1)  # d > 0
    with pytest.raises(verify.UndecidableCollision):
        verify.certify_flight(g.phi, g.v, 3.0, dps=30, max_dps=60)


def test_general_certifier_survives_one_wrong_candidate(monkeypatch):
    """A candidate before the root that is not one (d > 0): the proof covers it and goes on."""
    g, r1, _ = _two_roots()
    real = certificate.local_candidate
    offered = []
    (half_r1,) = internal(r1 / 2)

    def first_wrong(ctx, curv, t):
        if not offered:
            offered.append(t)
            return half_r1
        return real(ctx, curv, t)

    monkeypatch.setattr(certificate, "local_candidate", first_wrong)
    assert abs(verify.certify_flight(g.phi, g.v, 3.0).tau - r1) < mp.mpf(10) ** -45 * r1


@pytest.mark.parametrize("wrong", [lambda t: 3 * t, lambda t: t / 3, lambda t: -t, lambda t: 0])
def test_concave_certifier_corrects_a_wrong_candidate(monkeypatch, wrong):
    """|eps| <= 1: the bracket is proved, so a wrong Newton candidate costs bisection steps
    and the result is still the exact flight time 2x of phi = -x, v = x."""
    x = 3e-5
    real = certificate._newton_from_right
    monkeypatch.setattr(certificate, "_newton_from_right", lambda ctx, t: wrong(real(ctx, t)))
    cert = verify.certify_flight(-x, x, 1.0)
    lo_, hi_ = cert.enclosure
    assert lo_ < 2 * mp.mpf(x) < hi_
    assert (hi_ - lo_) / hi_ <= mp.mpf(10) ** -48


def test_prove_positive_refuses_a_stretch_containing_a_root():
    g, r1, _ = _two_roots()
    with working_dps(60):
        ctx = certificate.elastic_gap(*internal(g.phi, g.v, 3), 50, 60)
        with mp.workdps(80):
            below, above, free = internal(r1 * (1 - mp.mpf(10) ** -40),
                                          r1 * (1 + mp.mpf(10) ** -40), r1 / 4)
        first_root.prove_positive(ctx, free, below)
        with pytest.raises(NotDecided):
            first_root.prove_positive(ctx, free, above)


def test_search_budget_ends_in_a_value_error(monkeypatch):
    """phi = 0, v = 1e154, eps = 1e300: the gap stays positive for ~1e153 plate periods with a
    near-tangency in each; the search stops with a ValueError instead of running for hours."""
    monkeypatch.setattr(first_root, "MAX_BOXES", 300)
    with pytest.raises(ValueError, match="search budget"):
        verify.certify_flight(0.0, 1e154, 1e300)
