"""Input validation (verify/numerics/inputs.py) and exact phase reduction
(verify/numerics/phase.py).

Each test pins a documented behaviour: the value a
validation message names, the boundary of an inclusive rule, the exactness of a conversion, and
the documented fields of a ``ReducedPhase``.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from mpmath import mp

import verify
from verify.numerics.inputs import MIN_DPS, check_state, exact_real
from verify.numerics.phase import _GUARD_BITS, reduce_phase, reduction_bits


@pytest.mark.parametrize("bad", [0, 1, 2])
def test_non_finite_input_is_named(bad):
    """The message names the argument that is bad (phi, v or eps), not another one."""
    args = [0.0, 1.0, 0.5]
    args[bad] = math.nan
    name = ("phi", "v", "eps")[bad]
    with pytest.raises(ValueError, match=rf"^{name} must be finite, got {name}=nan$"):
        verify.flight_time(*args)


def test_no_departure_message_names_w0_and_each_argument():
    """phi = 0 makes sin(phi) = 0 exactly, so w0 = v: the message shows it to 8 digits, then
    each argument under its own name (including the orbit's phi0, v0)."""
    v = -1 / 3
    with pytest.raises(ValueError) as err:
        verify.flight_time(0.0, v, 0.5)
    msg = str(err.value)
    assert f"= {mp.nstr(mp.mpf(v), 8)} <= 0" in msg
    assert mp.nstr(mp.mpf(v), 8) == "-0.33333333"
    assert msg.endswith(f"(phi=0.0, v={v!r}, eps=0.5)")
    with pytest.raises(ValueError, match=r"\(phi0=0\.0, v0=-0\.333"):
        verify.orbit(0.0, v, 0.5, 3)


def test_bad_tau_is_named():
    with pytest.raises(ValueError, match=r"^tau must be finite, got tau=inf$"):
        verify.condition_number(0.0, 1.0, 0.5, math.inf)
    with pytest.raises(ValueError, match=r"^tau must be > 0, got tau=0\.0$"):
        verify.condition_number(0.0, 1.0, 0.5, 0.0)


def test_tau_is_none_when_not_passed():
    assert check_state(0.0, 1.0, 0.5).tau is None
    assert check_state(0.0, 1.0, 0.5, tau=2.0).tau == 2


def test_min_dps_is_accepted():
    """``dps >= 15`` is the rule: 15 itself is valid, 14 is not."""
    assert verify.flight_time(0.0, 1.0, 0.0, dps=MIN_DPS) == 2
    with pytest.raises(ValueError, match="dps=14"):
        verify.flight_time(0.0, 1.0, 0.0, dps=MIN_DPS - 1)


def test_large_integer_converts_exactly():
    """An int wider than 53 bits is taken exactly, whatever the caller's precision."""
    n = 2**80 + 1
    with mp.workprec(53):
        assert int(exact_real("v", n)) == n


def test_small_phase_is_returned_unreduced():
    """|phi| < 8: the phase itself, k = 0, at the caller's precision."""
    r = reduce_phase(mp.mpf(1), 53)
    assert (r.value, r.k, r.work_bits) == (1, 0, 53)
    assert r.enclosure.a == 1 and r.enclosure.b == 1


def test_phase_eight_is_reduced():
    """The no-reduction rule is strict (|phi| < 8): phi = 8 is reduced by one period."""
    r = reduce_phase(mp.mpf(8), 53)
    assert r.k == 1
    assert 0 < r.value < 2 * mp.pi


def test_reduction_bits_never_subtracts_for_small_phases():
    """prec + max(0, exponent) + guard: a phase below 1 adds no bits."""
    assert reduction_bits(mp.mpf(0.25), 53) == 53 + _GUARD_BITS
    assert reduction_bits(mp.mpf(2) ** 100, 53) == 53 + 101 + _GUARD_BITS


def test_rationals_with_a_power_of_two_denominator_are_taken_exactly():
    """Fraction(3, 8) and Fraction(2**60 + 1, 2**62) are binary numbers: taken exactly (the
    second is not a float64), so the flight is that of the mpf of the same value."""
    assert verify.flight_time(Fraction(3, 8), 3, 0.6) == verify.flight_time(0.375, 3.0, 0.6)
    wide = Fraction(2**60 + 1, 2**62)
    with mp.workprec(200):
        exact = mp.mpf(2**60 + 1) / 2**62
    assert exact_real("phi", wide) == exact
    assert verify.flight_time(wide, 3.0, 0.6) == verify.flight_time(exact, 3.0, 0.6)
    assert verify.flight_time(wide, 3.0, 0.6) != verify.flight_time(float(wide), 3.0, 0.6)


@pytest.mark.parametrize("bad", [Fraction(1, 3), Fraction(-7, 10)])
def test_rationals_that_are_not_binary_numbers_are_rejected(bad):
    with pytest.raises(ValueError, match="must be a binary number"):
        verify.flight_time(1.0, 3.0, bad)


def test_long_double_is_taken_exactly():
    """np.longdouble carries more bits than float64 where the platform has them: the flight is
    that of its exact value (not of its rounding to float64)."""
    third = np.longdouble(1) / np.longdouble(3)
    num, den = third.as_integer_ratio()
    with mp.workprec(200):
        exact = mp.mpf(num) / den
    assert exact_real("phi", third) == exact
    assert verify.flight_time(third, 3.0, 0.6) == verify.flight_time(exact, 3.0, 0.6)
    if exact != float(third):  # an 80-bit or 128-bit long double
        assert verify.flight_time(third, 3.0, 0.6) != verify.flight_time(float(third), 3.0, 0.6)


@pytest.mark.parametrize("bad", [np.longdouble("inf"), np.float32("nan")])
def test_non_finite_numpy_floats_are_rejected(bad):
    with pytest.raises(ValueError, match="must be finite"):
        verify.flight_time(bad, 3.0, 0.6)
