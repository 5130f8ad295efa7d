"""verify.dynamics.residue: residues of symmetric orbits and Greene crossings in multiprecision.

Oracles: the fixed points (0, pi*m), whose residue is eps exactly in both maps (trace 2 - 4 eps;
the Holmes form's [[1, 2], [-2 eps, 1 - 4 eps]]); fastpath's float64 symmetric orbits and
crossings at moderate periods, where float64's rounding is far below what is compared.
"""

import math

import mpmath
import pytest

from fastpath.dynamics import approximants, residue_crossing, symmetric_orbit
from fastpath.dynamics.greene import CRITICAL_RESIDUE
from verify.dynamics import residue


@pytest.mark.parametrize("model", ["exact", "holmes"])
@pytest.mark.parametrize("eps,m", [(0.3, 1), (0.6, 2), (0.9, 3)])
def test_the_fixed_points_residue_is_eps(model, eps, m):
    orbit = residue.symmetric_orbit(math.pi * m + 1e-3, eps, 1, m, model=model, dps=40)
    with mpmath.workdps(40):
        assert abs(orbit.v - mpmath.pi * m) < mpmath.mpf(10) ** -35
        assert abs(orbit.residue - mpmath.mpf(eps)) < mpmath.mpf(10) ** -33


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_a_symmetric_orbit_agrees_with_fastpath_at_a_moderate_period(model):
    a = approximants(1, (2,), levels=6)[-1]  # period 34
    eps = 0.25
    v = math.pi * a.winding / a.period
    for e in (0.05, 0.1, 0.15, 0.2, eps):  # follow the orbit from near eps = 0
        found = symmetric_orbit(v, e, a.period, a.winding, model=model)
        v = float(found.v[0])
    mine = residue.symmetric_orbit(v, eps, a.period, a.winding, model=model, dps=40)
    assert abs(float(mine.v) - v) < 1e-11
    assert abs(float(mine.residue) - found.residue) <= 4 * found.residue_error + 1e-13


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_a_crossing_agrees_with_fastpath_and_reports_its_rounding(model):
    a = approximants(1, (), levels=7)[-1]  # period 55
    fast = residue_crossing(a, model=model, target=CRITICAL_RESIDUE)
    lo, hi = fast.bracket
    margin = 4 * fast.eps_error + 1e-12
    mine = residue.crossing(a.period, a.winding, (lo - margin, hi + margin), (fast.v, fast.v),
                            target=CRITICAL_RESIDUE, model=model, dps=40)
    assert abs(float(mine.eps) - fast.eps) <= fast.eps_error + float(mine.eps_error)
    assert float(mine.residue_error) < 1e-25  # 40 digits against 60
    assert float(mine.slope) > 0


def test_a_bracket_that_does_not_hold_the_crossing_is_refused():
    a = approximants(1, (), levels=4)[-1]
    with pytest.raises(residue.ResidueError, match="does not cross"):
        residue.crossing(a.period, a.winding, (0.01, 0.02), (math.pi * a.winding / a.period,) * 2,
                         target=CRITICAL_RESIDUE)


def test_the_exact_map_needs_a_concave_gap():
    with pytest.raises(ValueError, match="eps"):
        residue.symmetric_orbit(math.pi, 1.2, 1, 1)
