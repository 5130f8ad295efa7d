"""Tests that kill mutants of ``fastpath/ensemble.py`` (scripts/mutation/ensemble.py): the
wrapped hole edge (the two_sum carry) and the time horizon (a collision at t = max_time).

``exit_hole`` adds TWO_PI to a negative ``d = phi - lo`` with ``two_sum``; that sum is exact
(zero carry) whenever ``d_hi + TWO_PI`` stays on ``d_hi``'s grid, which is why the edge probes
of ``test_hole_edges.py`` (phases in [4, 8), ulp 2**-50 like TWO_PI) never see the carry. A
phase in [2, 4) (ulp 2**-51) with a wide wrapped hole (``d >= 4``, ulp 2**-50) does: there the
carry is +-2**-51, as large as the distance of the nearest probes from the edge.
"""

from fractions import Fraction

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from fastpath.kernels.arrays import (
    NO_LIMIT,
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    Sample,
    Starts,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import exit_hole
from fastpath.physics import elastic

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


def _escape_one(phi, v, eps, hole_lo, hole_width, max_time, max_n=NO_LIMIT, target=None):
    """One particle through ``escape_chunk``, one block, unit bins: (esc_t, cens_t, collisions),
    and with a sample ``target`` also the sample row."""
    t_edges = np.arange(0.0, 10.0)
    esc_n, esc_t = np.zeros((1, 1, 10), np.int64), np.zeros((1, 1, 10), np.int64)
    cens_n, cens_t = np.zeros((1, 10), np.int64), np.zeros((1, 10), np.int64)
    collisions, samples = np.zeros(1, np.int64), np.zeros((1, 6))
    escape_chunk(elastic(eps), Starts(phi=np.array([phi]), v=np.array([v]), t=np.zeros(1),
                                      n=np.zeros(1, np.int64)),
                 Holes(lo=np.array([hole_lo]), width=np.array([hole_width])),
                 Horizon(max_collisions=max_n, max_time=max_time),
                 Bins(n_edges=t_edges, t_edges=t_edges, record_n=True, record_t=True),
                 Sample(slot=np.full(1, -1 if target is None else 0, np.int64),
                        target=np.full(1, target or 0, np.int64), rows=samples),
                 EscapeCounts(esc_n, esc_t, cens_n, cens_t, np.zeros((1, 10), np.int64),
                              np.zeros((1, 10), np.int64), collisions),
                 Flags.zeros(1))
    return esc_t[0, 0], cens_t[0], collisions[0], samples[0]


def test_collision_exactly_at_the_time_horizon_is_made():
    """Censoring needs t > max_time (module docstring): with eps = 0 the first flight is exactly
    tau = 2*v = 2, so a horizon of 2 still makes that collision and the particle escapes."""
    esc_t, cens_t, collisions, _ = _escape_one(0.0, 1.0, 0.0, 1.9, 0.2, max_time=2.0)
    assert collisions == 1
    assert esc_t[2] == 1 and esc_t.sum() == 1 and cens_t.sum() == 0
    esc_t, cens_t, collisions, _ = _escape_one(0.0, 1.0, 0.0, 1.9, 0.2, max_time=np.nextafter(2, 0))
    assert collisions == 0 and esc_t.sum() == 0 and cens_t[2] == 1  # the bound t1 = 2 is kept


def test_sample_is_the_target_collision_when_the_particle_gets_there():
    """eps = 0: every flight is tau = 2, phi advances by 2; the hole [5, 5.1) is never hit in 5
    collisions (phases 2, 4, 6, 8 - 2*pi, 10 - 2*pi). The sample of target 3 is collision 3,
    from (phi, v) = (4, 1) to (6, 1)."""
    _, _, collisions, row = _escape_one(0.0, 1.0, 0.0, 5.0, 0.1, np.inf, max_n=5, target=3)
    assert collisions == 5
    assert tuple(row) == (3.0, 4.0, 1.0, 6.0, 1.0, 2.0)
