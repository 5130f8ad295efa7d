"""No CONVERGED past the first root, for any finite input: the range of the error analysis.

The lower-bound steps' analysis needs every intermediate finite (fastpath/elastic/lower_bound.py,
"Range"): beyond RANGE_LIMIT a flight ends OVERFLOW, never CONVERGED at an arbitrary point (as
it did at |eps| >= 1e154, where r*r overflowed and the step vanished). Inside the stated input
range (30*A**2*(1 + |eps|) <= 2**1000, A = |v| + sqrt(|eps|) + 1) it never ends OVERFLOW.
Every CONVERGED answer is held to verify's certified root within the property suites' bound
(16*kappa*u, tests/fastpath/fastpath_tolerances.py).
"""

import math

import pytest

import fastpath
import verify

U = 2.0**-53
K = 16.0
LIMIT = 2.0**1000
PHASES = (math.pi / 2, 1.0, 4.0, -7.3)


def _check(phi, v, eps):
    """The flight's status, and for CONVERGED the error in kappa*u against verify."""
    res = fastpath.flight(phi, v, eps)
    if res.status != fastpath.FlightStatus.CONVERGED:
        return res.status, None
    ref = verify.flight_time(phi, v, eps, dps=25)
    kappa = float(verify.condition_number(phi, v, eps, ref))
    return res.status, abs(res.tau - float(ref)) / float(ref) / (kappa * U)


def _in_range(v, eps):
    a = abs(v) + math.sqrt(abs(eps)) + 1
    return 30 * a * a * (1 + abs(eps)) <= LIMIT


@pytest.mark.parametrize("phi,v,eps", [
    (1.5707963267948966, 0.5, 1e300),           # was CONVERGED at 4.185, the first root is pi
    (4.0, 7.578024953079282e299, 1e300),        # was 0.00427, the first root 0.00306
    (1.0, 8.424709848078965e299, -1e300),       # was 0.01366, the first root 0.00371
])
def test_huge_amplitudes_give_overflow_not_a_later_root(phi, v, eps):
    assert fastpath.flight(phi, v, eps).status == fastpath.FlightStatus.OVERFLOW
    with pytest.raises(ValueError):
        fastpath.flight_time(phi, v, eps)


@pytest.mark.parametrize("exponent", list(range(140, 309, 6)) + [150, 153, 154, 155, 160])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_amplitudes_ten_to_the_k_converge_right_or_overflow(exponent, sign):
    """eps = +-10^k at four phases and speeds from 0.5 to about |eps|: every answer is right
    to 16 kappa*u, or OVERFLOW / an undecided status; none inside the range is OVERFLOW."""
    eps = sign * 10.0**exponent
    for phi in PHASES:
        for v in (0.5, 3.0, 1e100, 0.7578 * abs(eps), 0.8425 * abs(eps), 1.3 * abs(eps)):
            if not v + eps * math.sin(phi) > 1e-9 * (v + abs(eps)):
                continue
            status, units = _check(phi, v, eps)
            if units is not None:
                assert units <= K, (phi, v, eps, units)
            elif status == fastpath.FlightStatus.OVERFLOW:
                assert not _in_range(v, eps), (phi, v, eps)


@pytest.mark.parametrize("v", [1e150, 3e151, 1e200, 1e300])
@pytest.mark.parametrize("eps", [0.6, -1.0, 0.999])
def test_huge_speeds_over_a_concave_gap_land_at_the_holmes_time(v, eps):
    """|eps| <= 1: the concave solver starts at 2*v, within 4|eps|/tau of the root (the Holmes
    limit), which is far below an ulp there; its answer is right even where its gap bound
    overflows (v > 5e153)."""
    for phi in PHASES:
        status, units = _check(phi, v, eps)
        assert status == fastpath.FlightStatus.CONVERGED
        assert units <= K


def test_the_lower_bound_method_overflows_where_its_range_ends():
    """|eps| <= 1 with the lower-bound steps: inside the stated range (|v| <= 4e149 here) the
    answer is right; a decade beyond, OVERFLOW."""
    assert _in_range(3e149, 0.6) and not _in_range(3e150, 0.6)
    inside = fastpath.flight(1.0, 3e149, 0.6, method="lower_bound")
    outside = fastpath.flight(1.0, 3e150, 0.6, method="lower_bound")
    assert inside.status == fastpath.FlightStatus.CONVERGED
    assert outside.status == fastpath.FlightStatus.OVERFLOW
    ref = verify.flight_time(1.0, 3e149, 0.6, dps=25)
    kappa = float(verify.condition_number(1.0, 3e149, 0.6, ref))
    assert abs(inside.tau - float(ref)) <= K * kappa * U * float(ref)
