"""Subnormal and tiny inputs: every answer is UNCERTAIN or right.

Below 2**-1022 float64 rounds in absolute terms (half of SUBNORMAL = 2**-1074 per operation), so
the relative bounds of the departure test and of the gap no longer bound the error; fastpath
adds the absolute term (``fastpath.elastic.gap``). Right means: NOT_DEPARTING only where the exact
w0 = v + eps*sin(phi) is <= 0, and a CONVERGED tau within K*kappa*u*tau of verify's, plus the
rounding of a subnormal result itself (half of SUBNORMAL: no float is nearer).
"""

import math

import numpy as np
import pytest
from fastpath_tolerances import tau_tolerance
from hypothesis import example, given
from hypothesis import strategies as st
from mpmath import mp

import fastpath
import verify
from fastpath.arithmetic.rounding import SUBNORMAL, plus_underflow
from fastpath.status import FlightStatus

TINY = 5e-324  # the smallest subnormal, 2**-1074


def exact_w0(phi, v, eps):
    with mp.workdps(60):
        return mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi))


def judge(phi, v, eps, method="auto"):
    """Assert the module docstring's rule for one flight; return its status."""
    res = fastpath.flight(phi, v, eps, method=method)
    status = FlightStatus(int(res.status))
    if status == FlightStatus.NOT_DEPARTING:
        assert exact_w0(phi, v, eps) <= 0, (phi, v, eps)
    elif status == FlightStatus.CONVERGED:
        ref = verify.flight_time(phi, v, eps, dps=30)
        with mp.workdps(60):
            error = abs(mp.mpf(res.tau) - ref)
            assert error <= tau_tolerance(phi, v, eps, ref) + mp.mpf(TINY) / 2, (phi, v, eps, res)
    return status


def test_a_subnormal_departure_speed_is_not_judged_certain():
    """w0 = 5e-324 - 5e-324*sin(1) rounds to 0, while the exact w0 = 7.9e-325 > 0 (verify's
    flight is 1.57e-324 long): the departure is within its rounding, UNCERTAIN."""
    assert exact_w0(1.0, TINY, -TINY) > 0
    assert fastpath.flight(1.0, TINY, -TINY).status == FlightStatus.UNCERTAIN


@pytest.mark.parametrize(("v", "eps"), [(TINY, TINY), (0.0, TINY)])
def test_a_subnormal_flight_is_uncertain_or_right(v, eps):
    """Flights 1.8e-323 and 8.3e-324 long, whose gap values all underflow: the nearest floats
    are 8.6% and 18.8% off, and the solver cannot know it is there; UNCERTAIN or right."""
    assert judge(1.0, v, eps) in (FlightStatus.UNCERTAIN, FlightStatus.CONVERGED)


SCALES = (0.0, TINY, 7 * TINY, 1e-320, 3e-310, 2.2e-308, 1e-300, 1e-200, 1e-160, 1e-150, 1e-100)


@pytest.mark.parametrize("method", ["auto", "lower_bound"])
def test_tiny_and_subnormal_inputs_are_uncertain_or_right(method):
    """Speeds and amplitudes from 0 through the subnormal range to 1e-100, both signs, random
    phases: every answer obeys the module docstring's rule."""
    rng = np.random.default_rng(3)
    seen = set()
    for _ in range(120):
        v = float(rng.choice(SCALES)) * float(rng.choice([1.0, -1.0, 0.5]))
        eps = float(rng.choice(SCALES + (0.5, 2.0))) * float(rng.choice([1.0, -1.0]))
        phi = float(rng.choice([0.0, 1.0, -2.0, math.pi / 2, rng.uniform(-math.pi, math.pi)]))
        seen.add(judge(phi, v, eps, method))
    assert FlightStatus.UNCERTAIN in seen and FlightStatus.CONVERGED in seen


@pytest.mark.parametrize("eps", [TINY, -3 * TINY, 1e-320, -2.5e-310, 1e-308])
def test_departures_within_a_subnormal_of_zero_are_judged_by_the_exact_w0(eps):
    """v = -fl(eps*sin(phi)) + k*TINY, k = -2 .. 2, over several phases: the exact
    w0 = v + eps*sin(phi) is a few subnormals either side of 0, where w0's rounding is absolute;
    NOT_DEPARTING only where the exact w0 <= 0."""
    for phi in (1.0, -0.7, 2.5, math.pi / 2):
        base = -(eps * math.sin(phi))
        for k in range(-2, 3):
            judge(phi, base + k * TINY, eps)


# bounds from the subnormal range to the largest floats, and the weights the bounds use
_BOUNDS = st.one_of(
    st.floats(min_value=0.0, max_value=2.0**-1000),
    st.floats(min_value=0.0, allow_nan=False),
    st.sampled_from([0.0, 2.0**-1074, 2.0**-1022, 2.0**-900, math.nextafter(2.0**-900, 0.0),
                     math.inf, math.nan]),
)
_WEIGHTS = st.one_of(
    st.floats(min_value=0.0, max_value=1e6),
    st.floats(min_value=0.0, allow_nan=False),
    st.sampled_from([0.0, 2.0, 2.5, 2.0**100, math.nextafter(2.0**100, 0.0), math.inf]),
)


@given(bound=_BOUNDS, weight=_WEIGHTS)
@example(bound=2.0**-1040, weight=2.0)  # the allowance moves a bound this small
@example(bound=2.0**-900, weight=2.0**150)  # and a larger one, by a large weight
def test_underflow_allowance_is_the_plain_sum_bit_for_bit(bound, weight):
    """plus_underflow skips the subnormal product where it cannot change the sum: its result is
    the float bound + SUBNORMAL*weight exactly, wherever that skip applies and wherever not."""
    expected = bound + SUBNORMAL * weight
    got = plus_underflow(bound, weight)
    assert np.float64(got).tobytes() == np.float64(expected).tobytes() or (
        math.isnan(got) and math.isnan(expected)), (bound, weight, got, expected)
