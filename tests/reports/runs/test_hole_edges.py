"""Hole edges, probed at the floats on and next to them.

The convention (``fastpath/ensemble.py`` module docstring and ``exit_hole``, ``Experiment`` in
``reports/runs/scenes.py``, README "arcs of collision phase mod 2*pi"): hole j is the half-open
arc [lo, lo + width) mod 2*pi with lo in [0, 2*pi); a reduced collision phase phi is inside iff
((phi - lo) mod 2*pi) < width. A scene gives a hole as centre c and width w: lo = (c - w/2) mod
2*pi. The phase of collision n >= 1 is tested, never the start.

``exit_hole`` evaluates that rule with d = phi - lo carried as an unevaluated double-double
sum (plus TWO_PI if negative), so the comparison with width is exact to O(u**2): the rule holds
at every probe, including the upper edge of a hole that wraps through 2*pi (rounding
(phi - lo) + TWO_PI first misplaced phases up to ~14 ulps from that edge).
"""

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import fastpath
import verify
from fastpath.arithmetic.phase import TWO_PI
from fastpath.kernels.arrays import (
    Bins,
    EscapeCounts,
    Flags,
    Holes,
    Horizon,
    Sample,
    Starts,
)
from fastpath.kernels.escape import escape_chunk
from fastpath.kernels.histogram import bin_index, exit_hole
from fastpath.physics import elastic
from reports.runs import chunk
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.scenes import parse_scene

EPS = 0.6
ROUNDING = 2.0**-50  # two roundings of |x| < 8 (half an ulp each, ulp(x) <= 2**-50)
with mpmath.workdps(40):
    TRUE_TWO_PI = Fraction(mpmath.nstr(2 * mpmath.pi, 40))


def up(x, k=1):
    for _ in range(k):
        x = np.nextafter(x, np.inf)
    return float(x)


def down(x, k=1):
    for _ in range(k):
        x = np.nextafter(x, -np.inf)
    return float(x)


def inside(phi, lo, width, two_pi=Fraction(TWO_PI)):
    """The convention in exact rational arithmetic: ((phi - lo) mod 2*pi) < width."""
    return (Fraction(phi) - Fraction(lo)) % two_pi < Fraction(width)


def hole(phi, lo, width):
    return exit_hole(phi, np.array([lo]), np.array([width]))


# lo = 1, width = 0.5: edges 1 and 1.5; lo = 6, width = 4.5 + TWO_PI - 6 (exact): the hole wraps
# through 2*pi and ends at 4.5, where float arithmetic is exact (ulp(phi) = ulp(d) = 2**-50)
PLAIN = (1.0, 0.5, 1.5)
WRAPS = (6.0, (4.5 - 6.0) + TWO_PI, 4.5)


def test_probe_holes_are_exact():
    for lo, width, end in (PLAIN, WRAPS):
        assert Fraction(lo) + Fraction(width) == Fraction(end) + (lo > end) * Fraction(TWO_PI)
    assert WRAPS[0] + WRAPS[1] > TWO_PI


@pytest.mark.parametrize(("lo", "width", "end"), [PLAIN, WRAPS], ids=["plain", "wraps"])
@pytest.mark.parametrize(("probe", "expected"), [
    ("lo", True), ("below lo", False), ("above lo", True),
    ("end", False), ("below end", True), ("above end", False),
])
def test_edges_are_half_open(lo, width, end, probe, expected):
    phi = {"lo": lo, "below lo": down(lo), "above lo": up(lo),
           "end": end, "below end": down(end), "above end": up(end)}[probe]
    assert inside(phi, lo, width) == expected  # the probe means what its name says
    assert (hole(phi, lo, width) == 0) == expected


@pytest.mark.parametrize(("phi", "expected"), [
    (0.0, True), (down(TWO_PI), True), (math.pi, True), (down(4.5, 1000), True),
    (up(4.5, 1000), False), (5.9, False),
])
def test_wrapping_hole_covers_both_sides_of_zero(phi, expected):
    lo, width, _ = WRAPS
    assert inside(phi, lo, width) == expected
    assert (hole(phi, lo, width) == 0) == expected


def test_hole_at_zero_starts_at_zero():
    assert hole(0.0, 0.0, 0.5) == 0
    assert hole(down(TWO_PI), 0.0, 0.5) == -1
    assert hole(down(0.5), 0.0, 0.5) == 0 and hole(0.5, 0.0, 0.5) == -1


def test_first_hole_containing_the_phase_is_reported():
    lo, width = np.array([1.0, 1.5]), np.array([0.5, 0.5])
    assert exit_hole(down(1.5), lo, width) == 0
    assert exit_hole(1.5, lo, width) == 1
    assert exit_hole(down(1.0), lo, width) == -1 and exit_hole(2.0, lo, width) == -1


phases = st.floats(0.0, TWO_PI, exclude_max=True)


@given(phases, phases, st.floats(1e-9, TWO_PI, exclude_max=True),
       st.integers(-40, 40), st.sampled_from(["free", "lo", "end"]))
def test_exit_hole_follows_the_rule_beyond_rounding(phi, lo, width, k, near):
    """Any phase: exit_hole agrees with the exact rule unless d lies within 2**-50 of an edge
    (probes are drawn at k ulps from either edge as well as anywhere)."""
    if near != "free":
        edge = lo if near == "lo" else (lo + width) % TWO_PI
        phi = up(edge, k) if k > 0 else down(edge, -k)
        if not 0.0 <= phi < TWO_PI:
            return
    d = (Fraction(phi) - Fraction(lo)) % Fraction(TWO_PI)
    if min(abs(d), abs(d - Fraction(width)), abs(d - Fraction(TWO_PI))) <= ROUNDING:
        return
    assert (hole(phi, lo, width) == 0) == (d < Fraction(width))


@pytest.mark.parametrize(("lo", "width", "k"), [(6.0, 0.5, -11), ((0.0 - 0.15) % TWO_PI, 0.3, 8)],
                         ids=["missed escape", "false escape"])
def test_wrapped_upper_edge_is_exact(lo, width, k):
    end = lo + width - TWO_PI
    phi = up(end, k) if k > 0 else down(end, -k)
    expected = inside(phi, lo, width)
    assert expected == inside(phi, lo, width, TRUE_TWO_PI)  # the reading of 2*pi is immaterial
    assert (hole(phi, lo, width) == 0) == expected


# ---- a collision landing on an edge, in the kernel and through a scene's chunk ----------------

SCENE = """
name = "edge"
kind = "escape"
eps = 0.6
particles = 1
seed = 14
[start]
phi = [1.0, 2.0]
v = [2.0, 4.0]
[holes]
centres = [{centre!r}]
widths = [1.0]
[horizon]
collisions = 1
"""


def start():
    """The one start of the edge scene (its first landing phase lies in [4, 6), where
    phi1 +- 0.5 and phi1 - 1 are exact)."""
    phi, v, *_ = chunk_starts(make_plan(parse_scene(SCENE.format(centre=3.0))), 0, 0)
    return float(phi[0]), float(v[0])


def fast_landing():
    return fastpath.step(*start(), EPS)[0]


def verify_landing():
    return float(verify.step(*start(), EPS, dps=chunk.VERIFY_DPS)[0])


# hole (centre, width 1) around the landing phase phi1 -> does collision 1 escape?
EDGE_CASES = {
    "phi1 = lo": (lambda p: p + 0.5, True),
    "phi1 one ulp below lo": (lambda p: up(p) + 0.5, False),
    "phi1 = lo + width": (lambda p: p - 0.5, False),
    "phi1 one ulp below lo + width": (lambda p: up(p) - 0.5, True),
}


def test_kernel_escape_at_a_landing_phase_on_an_edge():
    phi0, v0 = start()
    phi1 = fast_landing()
    assert 4.0 <= phi1 < 6.0
    for name, (centre, escapes) in EDGE_CASES.items():
        c = centre(phi1)
        lo = (c - 0.5) % TWO_PI
        assert Fraction(lo) == Fraction(c) - Fraction(1, 2), name  # exact construction
        assert inside(phi1, lo, 1.0) == escapes, name
        esc_n = np.zeros((1, 1, 2), np.int64)
        cens_n = np.zeros((1, 2), np.int64)
        escape_chunk(elastic(EPS), Starts(phi=np.array([phi0]), v=np.array([v0]),
                                          t=np.zeros(1), n=np.zeros(1, np.int64)),
                     Holes(lo=np.array([lo]), width=np.array([1.0])),
                     Horizon(max_collisions=1, max_time=np.inf),
                     Bins(n_edges=np.array([1.0, 2.0]), t_edges=np.array([0.0, 1.0]),
                          record_n=True, record_t=True),
                     Sample.none(1),
                     EscapeCounts.zeros(1, 1, 2, 2)._replace(esc_n=esc_n, cens_n=cens_n),
                     Flags.zeros(1))
        assert esc_n.sum() == escapes and cens_n.sum() == (not escapes), name


def flag_first_flights(real):
    """A stand-in for ``escape_chunk`` that flags every flight before the collision horizon, so
    ``simulate_chunk`` settles collision 1 with verify and tests the hole itself."""

    def kernel(physics, starts, holes, horizon, bins, sample, counts, flags):
        if np.all(starts.n >= horizon.max_collisions):
            return real(physics, starts, holes, horizon, bins, sample, counts, flags)
        flags.status[:] = 1  # FlightStatus.UNCERTAIN
        flags.state[:] = np.column_stack(starts)

    return kernel


@pytest.mark.parametrize("path", ["fast kernel", "settled by verify"])
@pytest.mark.parametrize("case", list(EDGE_CASES))
def test_scene_hole_edge_in_a_whole_chunk(monkeypatch, path, case):
    """Through the scene (centre, width) -> lo and ``simulate_chunk``; for the settled path the
    hole is built around verify's landing phase (it may differ from fastpath's in the last
    bit, and then the fast phase would sit on the other side of the edge)."""
    phi1 = fast_landing() if path == "fast kernel" else verify_landing()
    assert 4.0 <= phi1 < 6.0
    centre, escapes = EDGE_CASES[case]
    plan = make_plan(parse_scene(SCENE.format(centre=centre(phi1))))
    (lo,), (width,) = plan.experiments[0].hole_lo, plan.experiments[0].hole_width
    assert Fraction(lo) == Fraction(centre(phi1)) - Fraction(1, 2)
    assert inside(phi1, lo, width) == escapes
    if path == "settled by verify":
        monkeypatch.setattr(chunk, "escape_chunk", flag_first_flights(chunk.escape_chunk))
    counts, _ = chunk.simulate_chunk(plan, 0, 0)
    assert counts.settled == (path == "settled by verify")
    one = bin_index(plan.n_edges, 1.0)
    assert counts.esc_n[0, one] == escapes and counts.cens_n[one] == (not escapes)


def test_settled_and_fast_landings_differ_here():
    """Why the settled case builds its own hole: for this start verify's phase is one ulp
    below fastpath's, so the edge cases really are different floats on the two paths."""
    assert verify_landing() == down(fast_landing())


# a wide wrapped hole: its upper edge lo + width - TWO_PI is within 2**-51 of 3 (rounded)
WIDE_LO = 5.0
WIDE_WIDTH = (3.0 - WIDE_LO) + TWO_PI


def _inside_wide(phi):
    """The rule in exact rational arithmetic: ((phi - lo) mod TWO_PI) < width."""
    return (Fraction(phi) - Fraction(WIDE_LO)) % Fraction(TWO_PI) < Fraction(WIDE_WIDTH)


def test_wrapped_edge_of_a_wide_hole_with_a_fine_phase_grid():
    """``exit_hole`` adds TWO_PI to a negative ``d = phi - lo`` with ``two_sum``; that sum is
    exact (zero carry) whenever ``d_hi + TWO_PI`` stays on ``d_hi``'s grid, as for the phases in
    [4, 8) (ulp 2**-50 like TWO_PI) of the other edge probes. A phase in [2, 4) (ulp 2**-51) with
    a wide wrapped hole (``d >= 4``, ulp 2**-50) has a carry of +-2**-51, as large as the
    distance of the nearest probes from the edge: the probes on either side of the upper edge
    lo + width - TWO_PI must follow the rule in exact rational arithmetic."""
    end = float(Fraction(WIDE_LO) + Fraction(WIDE_WIDTH) - Fraction(TWO_PI))
    assert 2.0 <= end < 4.0 and WIDE_WIDTH >= 4.0  # phase ulp 2**-51, d ulp 2**-50: carry != 0
    phis = [end]
    for _ in range(6):
        phis = [np.nextafter(phis[0], -np.inf), *phis, np.nextafter(phis[-1], np.inf)]
    verdicts = [_inside_wide(float(p)) for p in phis]
    assert True in verdicts and False in verdicts  # the probes straddle the edge
    for phi, expected in zip(phis, verdicts, strict=True):
        got = exit_hole(float(phi), np.array([WIDE_LO]), np.array([WIDE_WIDTH]))
        assert (got == 0) == expected, phi
