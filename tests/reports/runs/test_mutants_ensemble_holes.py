"""Tests that kill mutants of ``fastpath/ensemble.py`` (scripts/mutation/ensemble.py).

``exit_hole`` adds TWO_PI to a negative ``d = phi - lo`` with ``two_sum``; that sum is exact
(zero carry) whenever ``d_hi + TWO_PI`` stays on ``d_hi``'s grid, which is why the edge probes
of ``test_hole_edges.py`` (phases in [4, 8), ulp 2**-50 like TWO_PI) never see the carry. A
phase in [2, 4) (ulp 2**-51) with a wide wrapped hole (``d >= 4``, ulp 2**-50) does: there the
carry is +-2**-51, as large as the distance of the nearest probes from the edge.
"""

from fractions import Fraction

import numpy as np

from fastpath.ensemble import exit_hole
from fastpath.phase import TWO_PI

LO = 5.0
WIDTH = (3.0 - LO) + TWO_PI  # rounded: the upper edge lo + width - TWO_PI is within 2**-51 of 3


def _inside(phi):
    """The rule in exact rational arithmetic: ((phi - lo) mod TWO_PI) < width."""
    return (Fraction(phi) - Fraction(LO)) % Fraction(TWO_PI) < Fraction(WIDTH)


def test_wrapped_edge_of_a_wide_hole_with_a_fine_phase_grid():
    end = float(Fraction(LO) + Fraction(WIDTH) - Fraction(TWO_PI))
    assert 2.0 <= end < 4.0 and WIDTH >= 4.0  # phase ulp 2**-51, d ulp 2**-50: carry != 0
    phis = [end]
    for _ in range(6):
        phis = [np.nextafter(phis[0], -np.inf), *phis, np.nextafter(phis[-1], np.inf)]
    verdicts = [_inside(float(p)) for p in phis]
    assert True in verdicts and False in verdicts  # the probes straddle the edge
    for phi, expected in zip(phis, verdicts, strict=True):
        got = exit_hole(float(phi), np.array([LO]), np.array([WIDTH]))
        assert (got == 0) == expected, phi
