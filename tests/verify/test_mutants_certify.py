"""Tests that kill mutants of ``verify/certify.py`` (scripts/mutation.sh certify)."""

import verify


def test_flight_time_default_is_50_digits():
    """``flight_time(phi, v, eps)`` is ``certify_flight(..., dps=50).tau``, rounded to 50 digits
    (a 51-digit default would round the same enclosure differently)."""
    args = (0.3, 1 / 3, 0.5)
    assert verify.flight_time(*args) == verify.certify_flight(*args, dps=50).tau
    assert verify.flight_time(*args) != verify.certify_flight(*args, dps=51).tau
