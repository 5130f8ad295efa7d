"""The "chattering-graze" rows of ``verify.hard_cases`` (``CHATTERING_GRAZES``).

Each row claims a dip of the gap at ``contact`` (t_m) with minimum ``clearance``, for a departure
just before theta* = 2*pi - arccos(1/eps) with a small w0. The claims are recomputed here at 80
digits from the textbook forms of the motion (independent of verify.dissipative.drag and of the
script that built the rows), and verify must certify every row: the first root before the dip
when the clearance is negative, past the dip (proved free of roots) when it is positive.
"""

from __future__ import annotations

import time

import pytest
from mpmath import mp

import verify
from verify.hard_cases import CHATTERING_GRAZES, DISSIPATIVE_CASES

DPS = 80
IDS = [c.id for c in CHATTERING_GRAZES]


def _motion(v, k, law, t):
    """(Y, V) from the textbook closed forms (the dips lie on the rising branch, V > 0)."""
    if k == 0:
        return t * (v - t / 2), v - t
    if law == "linear":
        e = mp.exp(-k * t)
        return (v + 1 / k) * (1 - e) / k - t / k, v * e + (e - 1) / k
    s = mp.sqrt(k)
    x0 = mp.atan(s * v)
    assert t <= x0 / s, "past the top: not a rising-branch point"
    return mp.log(mp.cos(x0 - s * t) / mp.cos(x0)) / k, mp.tan(x0 - s * t) / s


def _derivatives(case, t):
    """(d, d', d'') of the case's gap at t (mp, at the caller's precision)."""
    phi, v, eps, k = (mp.mpf(x) for x in (case.phi, case.v, case.eps, case.drag))
    y, vel = _motion(v, k, case.drag_law, t)
    eta = k * vel if case.drag_law == "linear" else k * vel * abs(vel)
    return (y + eps * (mp.cos(phi) - mp.cos(phi + t)), vel + eps * mp.sin(phi + t),
            -1 - eta + eps * mp.cos(phi + t))


def _dip(case):
    """(t_m, d(t_m)): Newton on d' = 0 from the recorded contact."""
    t = mp.mpf(case.contact)
    for _ in range(100):
        _, d1, d2 = _derivatives(case, t)
        assert d2 > 0, "not a dip"
        t -= d1 / d2
        if abs(d1 / d2) < mp.mpf(10) ** (10 - DPS):
            break
    return t, _derivatives(case, t)[0]


def test_the_class_is_in_the_dissipative_table():
    assert len(CHATTERING_GRAZES) >= 30 and set(CHATTERING_GRAZES) <= set(DISSIPATIVE_CASES)
    assert {c.drag for c in CHATTERING_GRAZES} == {0.0, 1e-8}
    assert {c.drag_law for c in CHATTERING_GRAZES if c.drag} == {"linear", "quadratic"}
    assert all(c.kind == "chattering-graze" and c.tau is not None for c in CHATTERING_GRAZES)
    assert len(set(IDS)) == len(IDS)


@pytest.mark.parametrize("case", CHATTERING_GRAZES, ids=IDS)
def test_dip_is_as_recorded(case):
    """A departure with small w0 before theta*, d'' changing sign before the dip, and the dip's
    minimum equal to the recorded clearance (sign as labelled; |c| within 1e-6 relative)."""
    with mp.workdps(DPS):
        eps = mp.mpf(case.eps)
        theta = 2 * mp.pi - mp.acos(1 / eps)
        w0 = mp.mpf(case.v) + eps * mp.sin(mp.mpf(case.phi))
        assert 0 < w0 < mp.mpf("2e-3")
        assert 0 < theta - case.phi < case.contact  # departs before theta*, dips after it
        assert _derivatives(case, mp.zero)[2] < 0 < _derivatives(case, mp.mpf(case.contact))[2]
        t_m, m = _dip(case)
        assert abs(t_m - case.contact) <= mp.mpf(10) ** -15 * t_m
        assert abs(m - case.clearance) <= mp.mpf(10) ** -6 * abs(m)
        nominal = case.id.rsplit("-c=", 1)[1]
        assert (m > 0) == (nominal == "0+" or not nominal.startswith(("-", "0")))
        if nominal in ("0+", "0-"):
            assert abs(m) < mp.mpf(10) ** -16  # the float64 neighbours of the tangency
        else:
            assert abs(m / mp.mpf(nominal) - 1) < mp.mpf(10) ** -3


@pytest.mark.slow
@pytest.mark.parametrize("case", CHATTERING_GRAZES, ids=IDS)
def test_verify_certifies_the_first_root(case):
    start = time.perf_counter()
    cert = verify.certify_flight(case.phi, case.v, case.eps, drag=case.drag,
                                 drag_law=case.drag_law)
    seconds = time.perf_counter() - start
    lo_, hi_ = cert.enclosure
    assert float(cert.tau) == case.tau
    if case.clearance < 0:  # the first root is in the dip, before its bottom
        assert hi_ < case.contact
    else:  # the proof of no root covers the dip; the landing is O(1) later
        assert cert.free_until > case.contact and lo_ > 1.0
    assert seconds < 5.0
