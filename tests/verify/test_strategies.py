"""verify.strategies: every draw is a valid departure as floats, and each strategy reaches
the region it promises (small w0, huge v, unreduced phases, near-grazing dips, fixed points)."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import seed as hypothesis_seed
from hypothesis import strategies as st
from mpmath import mp

from verify import strategies as vs


def _draws(strategy, n=200, seed=0):
    """n draws (deterministic), as a list, through hypothesis' own engine."""
    out = []

    @hypothesis_seed(seed)
    @settings(max_examples=n, database=None, deadline=None, phases=(Phase.generate,),
              suppress_health_check=list(HealthCheck))
    @given(strategy)
    def collect(case):
        out.append(case)

    collect()
    return out


def _valid(case):
    phi, v, eps = case
    assert all(isinstance(x, float) and math.isfinite(x) for x in case), case
    assert vs.exact_w0(phi, v, eps) > 0, case


@given(vs.departures())
def test_departures_are_valid_as_floats(case):
    _valid(case)
    assert 0.0 <= case[2] <= 10.0


def test_departures_reach_small_departure_speeds():
    cases = _draws(vs.departures(eps=(0.0, 1.0)), n=200)
    w0 = [float(vs.exact_w0(*c)) for c in cases]
    assert sum(w < 1e-6 for w in w0) >= 20
    assert min(w0) < 1e-10
    assert max(w0) > 1.0
    assert any(abs(c[0]) > 2 * math.pi for c in cases)  # unreduced phases by default


def test_departures_options():
    for phi, v, eps in _draws(vs.departures(eps=0.6, w0=(1e-3, 2.0), unreduced=False), n=50):
        assert eps == 0.6
        assert 0.0 <= phi < 2 * math.pi
        assert 1e-3 * (1 - 1e-9) <= float(vs.exact_w0(phi, v, eps)) <= 2.0 * (1 + 1e-9)
    custom = vs.departures(eps=st.sampled_from([3.0]), phi=(1.0, 2.0))
    for phi, _, eps in _draws(custom, n=30):
        assert eps == 3.0 and 1.0 <= phi <= 2.0


@pytest.mark.parametrize(
    "kwargs",
    [{"eps": "big"}, {"eps": (1.0, 0.0)}, {"eps": math.nan}, {"w0": (0.0, 1.0)},
     {"w0": (-1.0, 1.0)}, {"phi": (0.0, math.inf)}],
)
def test_departures_reject_bad_ranges(kwargs):
    with pytest.raises(ValueError):
        vs.departures(**kwargs)


def test_hard_cases_cover_every_kind():
    cases = _draws(vs.hard_cases(), n=300)
    for case in cases:
        _valid(case)
    w0 = [float(vs.exact_w0(*c)) for c in cases]
    kinds = {
        "small w0": sum(w <= 1e-3 for w in w0),
        "huge v": sum(c[1] >= 1e3 for c in cases),
        "unreduced phase": sum(abs(c[0]) >= 1e3 for c in cases),
        "tiny eps": sum(0 < c[2] <= 1e-6 for c in cases),
        "huge eps": sum(c[2] >= 10 for c in cases),
        "special phase": sum(c[0] in (0.0, math.pi, 2 * math.pi) for c in cases),
    }
    assert all(count >= 5 for count in kinds.values()), kinds
    assert min(w0) < 1e-9


def _gap(phi, v, eps, t):
    return 2 * eps * np.sin(phi + t / 2) * np.sin(t / 2) + t * (v - t / 2)


@pytest.mark.parametrize("clearance", [1e-3, -1e-3])
def test_near_grazing_has_a_dip_of_the_requested_clearance(clearance):
    """The gap has a local minimum (d'' > 0) of value ~clearance within (0, 9)."""
    cases = _draws(vs.near_grazing(eps=(1.5, 4.0), clearance=clearance), n=15)
    assert cases
    t = np.linspace(1e-6, 9.0, 400_001)
    for phi, v, eps in cases:
        _valid((phi, v, eps))
        assert 1.5 <= eps <= 4.0
        d = _gap(phi, v, eps, t)
        inner = (d[1:-1] < d[:-2]) & (d[1:-1] < d[2:])
        minima = d[1:-1][inner]
        # grid error of a minimum ~ d''*dt**2/2 < 1e-8
        assert np.any(np.abs(minima - clearance) < 1e-6), (phi, v, eps, minima)


def test_near_grazing_default_clearances_have_both_signs():
    cases = _draws(vs.near_grazing(), n=40)
    for case in cases:
        _valid(case)
        assert case[2] >= 1.05
    assert len(cases) >= 20


def test_near_fixed_point_and_fixed_points():
    for phi, v, eps in _draws(vs.near_fixed_point(m=(1, 5), eps=(0.0, 1.0), radius=1e-4), 50):
        _valid((phi, v, eps))
        m = round(v / math.pi)
        assert 1 <= m <= 5 and abs(phi) <= 1e-4 and abs(v - m * math.pi) <= 1e-4 * 1.0001
        assert 0.0 <= eps <= 1.0
    for phi, v, eps in _draws(vs.fixed_points(m=3, eps=0.6), 5):
        assert (phi, v, eps) == (0.0, 3 * math.pi, 0.6)
    with pytest.raises(ValueError):
        vs.near_fixed_point(m=0)
    with pytest.raises(ValueError):
        vs.near_fixed_point(radius=-1.0)


def test_large_velocities():
    for phi, v, eps in _draws(vs.large_velocities(), 50):
        _valid((phi, v, eps))
        assert 30.0 <= v <= 1e6


def test_exact_w0_is_exact_for_floats():
    phi, eps = 4.0, 0.6
    v = -eps * math.sin(phi)  # w0 of the floats is the rounding residue, not 0
    with mp.workdps(60):
        expected = mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi))
    assert vs.exact_w0(phi, v, eps) == pytest.approx(expected, rel=1e-30)


def test_near_triple_root_family():
    cases = _draws(vs.near_triple_root(), n=100)
    for phi, v, eps in cases:
        _valid((phi, v, eps))
        assert phi == -v and 1e-8 <= v <= 10.0 and 1.0 - 1e-6 <= eps <= 1.0
    assert min(c[1] for c in cases) < 1e-6 and max(c[1] for c in cases) > 1.0  # decades reached
    above = _draws(vs.near_triple_root(eps=(1.0, 1.0 + 1e-6)), n=50)
    assert all(vs.exact_w0(*c) > 0 for c in above)  # eps > 1: only departures kept
    with pytest.raises(ValueError):
        vs.near_triple_root(x=(0.0, 1.0))


def test_huge_phases_reach_every_exponent_and_w0_range():
    cases = _draws(vs.huge_phases(eps=0.6, exponent=(12, 307)), n=100)
    for phi, v, eps in cases:
        _valid((phi, v, eps))
        assert 1e12 <= abs(phi) < 1e308
        assert 1e-3 * (1 - 1e-9) <= float(vs.exact_w0(phi, v, eps)) <= 30.0 * (1 + 1e-9)
    exponents = [math.floor(math.log10(abs(c[0]))) for c in cases]
    assert min(exponents) < 50 and max(exponents) > 250
    assert any(c[0] < 0 for c in cases) and any(c[0] > 0 for c in cases)
    with pytest.raises(ValueError):
        vs.huge_phases(exponent=(12, 400))
