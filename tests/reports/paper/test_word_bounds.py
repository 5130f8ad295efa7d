"""The two bounds of the paper's qualitative words, on synthetic numbers whose verdict is known.

Each rule of ``reports.paper.claims.rules`` that reads a vague word ("the same", "many fewer",
"large", "effectively traps", "almost entirely", "well approximated", ...) is applied by its claim
module to a measurement placed inside the word's holds zone (confirmed), inside its fails zone
(refuted), wholly between the two bounds (inconclusive, the evidence saying so) and straddling a
bound (inconclusive). No runs: every input is built here, and each test takes well under a second.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from reports.paper.claims import (
    escape_claims,
    fermi_claims,
    geometry_claims,
    start_claims,
    transport_claims,
    transport_joint_claims,
)
from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import BETWEEN_BOUNDS, CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.studies.fermi_ensemble import Fermi
from reports.paper.studies.islands import Strip
from reports.paper.studies.joint_sample import JointSample
from reports.runs.survival import wilson
from reports.stats.calibration import draw
from reports.stats.histogram import Curve, bin_means, survival_boundaries

# ---- the generic rule ------------------------------------------------------------------------

@pytest.mark.parametrize(("lo", "hi", "verdict", "note"), [
    (0.00, 0.01, CONFIRMED, ""),
    (0.02, 0.05, INCONCLUSIVE, R.BETWEEN),
    (0.10, 0.20, REFUTED, ""),
    (0.005, 0.02, INCONCLUSIVE, "straddles a bound"),
    (0.05, 0.15, INCONCLUSIVE, "straddles a bound"),
    (math.nan, 0.01, INCONCLUSIVE, "not a number"),
])
def test_a_word_that_holds_for_small_values(lo, hi, verdict, note):
    assert R.word_verdict(lo, hi, 0.01, 0.1) == verdict
    assert R.word_note(lo, hi, 0.01, 0.1) == note


@pytest.mark.parametrize(("lo", "hi", "verdict", "note"), [
    (12.0, 20.0, CONFIRMED, ""),
    (3.0, 8.0, INCONCLUSIVE, R.BETWEEN),
    (1.0, 1.8, REFUTED, ""),
    (8.0, 12.0, INCONCLUSIVE, "straddles a bound"),
])
def test_a_word_that_holds_for_large_values(lo, hi, verdict, note):
    assert R.word_verdict(lo, hi, 10.0, 2.0) == verdict
    assert R.word_note(lo, hi, 10.0, 2.0) == note


@pytest.mark.parametrize(("lo", "hi", "verdict", "note"), [
    (-0.05, 0.05, CONFIRMED, ""),
    (0.12, 0.2, INCONCLUSIVE, R.BETWEEN),
    (-0.2, -0.12, INCONCLUSIVE, R.BETWEEN),
    (0.3, 0.6, REFUTED, ""),
    (-0.6, -0.3, REFUTED, ""),
    (0.05, 0.15, INCONCLUSIVE, "straddles a bound"),
    (0.2, 0.3, INCONCLUSIVE, "straddles a bound"),
])
def test_a_word_that_bounds_both_sides(lo, hi, verdict, note):
    assert R.two_band_verdict(lo, hi, R.BOUNDED, R.BOUNDED_FAILS) == verdict
    assert R.two_band_note(lo, hi, R.BOUNDED, R.BOUNDED_FAILS) == note


def test_every_word_has_its_fails_bound_beyond_its_holds_bound():
    """A fails bound on the far side of the holds bound: a gap where neither applies."""
    below = [(R.SAME, R.SAME_FAILS), (R.FEWER, R.FEWER_FAILS), (R.TRAP_SHARE, R.TRAP_SHARE_FAILS),
             (R.DESTROYED, R.DESTROYED_FAILS), (R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS),
             (R.MOSTLY, R.MOSTLY_FAILS), (R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS), (R.FAR, R.FAR_FAILS)]
    above = [(R.LARGE_VELOCITY, R.LARGE_VELOCITY_FAILS), (R.DECADE, R.STRONG_FAILS),
             (R.OVER_OR_NEAR, R.OVER_OR_NEAR_FAILS), (R.BOTH, R.BOTH_FAILS),
             (R.MUCH_SMALLER, R.MUCH_SMALLER_FAILS)]
    assert all(h < f for h, f in below)
    assert all(h > f for h, f in above)
    assert R.BOUNDED_FAILS[0] < R.BOUNDED[0] < R.BOUNDED[1] < R.BOUNDED_FAILS[1]


# ---- "the same" ------------------------------------------------------------------------------

@pytest.mark.parametrize(("a", "ua", "b", "ub", "verdict", "note"), [
    (2.0, 0.02, 2.05, 0.02, CONFIRMED, ""),           # 2.5% apart
    (2.0, 0.02, 2.8, 0.02, REFUTED, ""),              # 33% apart
    (2.0, 0.02, 2.35, 0.02, INCONCLUSIVE, R.BETWEEN),  # 16% apart: between 10% and 25%
    (2.0, 0.02, 2.5, 0.02, INCONCLUSIVE, R.BETWEEN),   # 22% apart, 20-24% with uncertainties
    (2.0, 0.02, 2.6, 0.02, INCONCLUSIVE, "straddles a bound"),  # 26%, 24-28% with them
    (2.0, 0.2, 2.2, 0.2, INCONCLUSIVE, "straddles a bound"),
    (2.0, math.inf, 2.0, 0.0, INCONCLUSIVE, "not finite"),
])
def test_the_same_within_ten_percent_and_different_beyond_twenty_five(a, ua, b, ub, verdict,
                                                                       note):
    assert R.same_verdict(a, ua, b, ub) == verdict
    assert R.same_note(a, ua, b, ub) == note


def fermi_of(beta_n, beta_t):
    """A Fermi ensemble whose <v> follows n^beta_n and t^beta_t, from 16 particle blocks each
    scaled and tilted by +-0.002 in the exponent (the bootstrap's spread)."""
    n = np.geomspace(1, 3e4, 61)
    t = np.geomspace(1, 3e6, 61)
    rng = np.random.default_rng(0)

    def blocks(x, beta):
        tilt = 0.002 * np.repeat([1.0, -1.0], 8)[:, None]
        v = x ** beta * (1 + 0.01 * rng.standard_normal((16, 1))) * (x / x[30]) ** tilt
        return v, np.ones_like(v)
    return Fermi(8000, n, n ** beta_n, t, t ** beta_t, np.full(61, 8000), beta_n, 0.002,
                       1.0, beta_t, 0.002, 1.0, (1000.0, 3e4), (1e4, 3e6), 0, 0,
                       {"sampled": 1, "worst_error": 0.1, "overstepped": 0}, 0.0,
                       blocks(n, beta_n), blocks(t, beta_t))


@pytest.mark.parametrize(("beta_n", "beta_t", "verdict", "kind"), [
    (0.5, 1 / 3, CONFIRMED, None),
    (0.58, 0.38, INCONCLUSIVE, BETWEEN_BOUNDS),   # 16% and 14% off: between the bounds
    (0.70, 0.45, REFUTED, None),                  # 40% and 35% off
])
def test_fermi_exponents_are_the_paper_s_within_ten_percent_not_beyond_twenty_five(
        beta_n, beta_t, verdict, kind):
    claims = fermi_claims.fermi_claims(fermi_of(beta_n, beta_t))
    assert [(c.verdict, c.inconclusive) for c in claims] == [(verdict, kind)] * 2
    assert all(len(c.analyses) == 4 for c in claims)  # the windows inside the regime


def exponential_curve(gamma, seed):
    return draw("exponential", 10**6, np.random.default_rng(seed), {"gamma": gamma})


@pytest.mark.parametrize(("gamma", "verdict", "note"), [
    (0.02, CONFIRMED, ""),
    (0.0234, INCONCLUSIVE, R.BETWEEN),   # hazard ratio 1.17
    (0.028, REFUTED, ""),                # hazard ratio 1.4
])
def test_hazards_are_the_same_within_ten_percent_and_differ_beyond_twenty_five(gamma, verdict,
                                                                              note):
    ref, other = exponential_curve(0.02, 1), exponential_curve(gamma, 2)
    members = start_claims.long_time_members(ref, other, 0.5, "p")
    assert len(members) >= 2
    assert F.family_verdict(members)[0] == verdict, F.family_text(members)
    assert (members[0].note == R.BETWEEN) == (note == R.BETWEEN)


def tails(monkeypatch, alphas, u=0.02, ranks=2):
    """An escape analysis whose holes' tails have ``ranks`` late windows each, every one fitted
    by a power law of exponent alphas[hole] +- u."""
    x = np.geomspace(1, 1e4, 9)
    curve = SimpleNamespace(x=x, escapes=np.full(9, 1000), particles=10**6)
    monkeypatch.setattr(escape_claims, "late_windows", lambda c, a, b, m: [(r, 8)
                                                                          for r in range(ranks)])
    monkeypatch.setattr(escape_claims, "alpha_of",
                        lambda c, w: (c.alpha, (c.alpha - u, c.alpha + u), u))
    return {h: {"windows": SimpleNamespace(n={"tail": (0, 8)}),
                "curves": {"collisions": SimpleNamespace(**vars(curve), alpha=a)}}
            for h, a in alphas.items()}


@pytest.mark.parametrize(("alphas", "verdict"), [
    ({"0": 2.0, "2": 2.05}, REFUTED),       # every pair the same: a universal law
    ({"0": 2.0, "2": 3.0}, CONFIRMED),      # 40% apart: no universal law
    ({"0": 2.0, "2": 2.4}, INCONCLUSIVE),   # 18% apart: between the bounds
])
def test_no_universal_law_needs_a_pair_at_least_twenty_five_percent_apart(monkeypatch, alphas,
                                                                        verdict):
    claim = escape_claims.universal_claim(tails(monkeypatch, alphas), "run")
    assert claim.verdict == verdict and len(claim.analyses) == 2
    assert (claim.inconclusive == BETWEEN_BOUNDS) == (verdict == INCONCLUSIVE)


# ---- transport: "many fewer", "large velocities", "effectively traps", "very strong" --------

def joint(n, t, exit):
    exit = np.asarray(exit)
    return JointSample(exit.astype(np.int64), np.asarray(n, float), np.asarray(t, float),
                       np.ones(len(exit)), len(exit), "synthetic")


def transport_joint(ratio, m=20_000, seed=0):
    """Entry hole 1: half reflected (n = t/5), half transmitted with n = ratio t/5, escape times
    log-uniform on [100, 10^4]."""
    rng = np.random.default_rng(seed)
    t = 10 ** rng.uniform(2, 4, m)
    exit = np.where(np.arange(m) % 2 == 0, 0, 1)
    n = np.where(exit == 0, t / 5, ratio * t / 5).round() + 1
    return {1: joint(n, t, exit)}


@pytest.mark.parametrize(("ratio", "verdict", "note"), [
    (0.25, CONFIRMED, ""), (0.7, INCONCLUSIVE, R.BETWEEN), (1.0, REFUTED, "")])
def test_many_fewer_collisions_at_half_and_about_as_many_at_nine_tenths(ratio, verdict, note):
    members = transport_joint_claims.same_time_members("P12", transport_joint(ratio))
    assert len(members) == 2 and {a.verdict for a in members} == {verdict}
    assert {a.note for a in members} == {note}


def velocities(v_transport, m=100_000, seed=0, spread=0.5):
    """Largest velocities of m transporting orbits: ``v_transport`` minus an exponential of
    mean ``spread``."""
    rng = np.random.default_rng(seed)
    return v_transport - rng.exponential(spread, m)


@pytest.mark.parametrize(("v_transport", "verdict", "note"), [
    (50.0, CONFIRMED, ""),            # above 10 times the largest start velocity 4
    (27.0, INCONCLUSIVE, F.TOO_FEW),  # above twice it; 40 out of the sample's reach
    (6.0, REFUTED, ""),               # none above twice it
])
def test_large_velocities_above_ten_times_the_start_and_not_below_twice(v_transport, verdict,
                                                                       note):
    """100,000 transporting orbits: none above v = 8 has a Wilson upper bound below 10^-4."""
    a = transport_joint_claims.velocity_member(velocities(v_transport), "study")
    assert (a.verdict, a.note) == (verdict, note), a.variant
    if note == F.TOO_FEW:
        assert "orbits expected above 40" in a.variant


def test_large_velocities_undecided_when_too_few_reach_twice_the_start():
    """Eight above v = 8 in 100,000: their share's upper bound is not below 10^-4, nor is its
    lower bound above it: the sample cannot say whether the orbits stay near the start."""
    v = velocities(6.0)
    v[1:16:2] = 9.0
    a = transport_joint_claims.velocity_member(v, "study")
    assert a.verdict == INCONCLUSIVE


def trapping_curves(share_out, m=10**7):
    """Curves of both entry holes: 99.9% of the entrants leave by their own hole at t ~ 1, the
    slow 0.1% from t = 10^3 on, fewer in every bin (by a factor e^(-1/8)), a share
    ``share_out`` of them in every bin through the other hole; the survival falls to 10^-4
    with 1000 of them left, and to 400 a quarter decade after."""
    edges = np.concatenate([[0.0], np.geomspace(0.1, 1e7, 161)])
    x = survival_boundaries(edges, "time")
    k_fast = np.searchsorted(edges, 1.0, side="right") - 1
    k_slow = np.searchsorted(edges, 1e3, side="right") - 1
    slow, bins = m // 1000, 60
    per_bin = np.round(slow * np.exp(-np.arange(bins) / 8) * (1 - np.exp(-1 / 8))).astype(int)
    own, other = np.zeros(len(edges), np.int64), np.zeros(len(edges), np.int64)
    own[k_fast] = m - per_bin.sum()
    other[k_slow:k_slow + bins] = np.round(share_out * per_bin)
    own[k_slow:k_slow + bins] += per_bin - other[k_slow:k_slow + bins]
    zero = np.zeros(len(edges), np.int64)
    means = bin_means(edges, "time")

    def entry(stay, leave):
        curves = {stay: Curve("synthetic", "h", stay, "time", x, own, other, zero, means, m),
                  leave: Curve("synthetic", "h", leave, "time", x, other, own, zero, means, m)}
        return {"time": curves, "collisions": curves}
    return {1: entry("P11", "P12"), 2: entry("P22", "P21")}


@pytest.mark.parametrize(("share_out", "traps", "does_not_trap", "note"), [
    (0.0, CONFIRMED, REFUTED, ""),
    (0.04, INCONCLUSIVE, INCONCLUSIVE, R.BETWEEN),   # 40 of 1000 out by hole 2
    (0.3, REFUTED, CONFIRMED, ""),
    (0.012, INCONCLUSIVE, INCONCLUSIVE, "straddles a bound"),
])
def test_effectively_traps_below_one_percent_and_does_not_from_ten(share_out, traps,
                                                                    does_not_trap, note):
    tr = trapping_curves(share_out)
    trap = transport_claims.trap_claim("fig3-trap-h=1", tr, "r", True)
    leak = transport_claims.trap_claim("fig3-h=0.1", tr, "r", False)
    assert (trap.verdict, leak.verdict) == (traps, does_not_trap), trap.evidence
    assert trap.statistical["share_hole_2"] == pytest.approx(share_out, abs=0.005)  # rounding
    if note:
        assert note in trap.evidence


def test_a_trapping_member_needs_enough_entrants_to_reach_its_bound():
    """None of m leaving shows a share at most 1% only from m = 384 on (Wilson)."""
    m = R.fewest_to_reach(R.TRAP_SHARE)
    assert wilson(0, m)[1] <= R.TRAP_SHARE < wilson(0, m - 1)[1]


@pytest.mark.parametrize(("ratio", "verdict"), [
    (15.0, CONFIRMED), (5.0, INCONCLUSIVE), (1.5, REFUTED), (1.0, REFUTED),
    (10.0, INCONCLUSIVE), (2.0, INCONCLUSIVE),  # one bin of the grid either way crosses a bound
    (math.inf, CONFIRMED), (math.nan, INCONCLUSIVE)])
def test_very_strong_p11_outlives_the_others_by_a_decade_and_fails_at_twice(ratio, verdict):
    assert transport_claims.strong_verdict(ratio) == verdict


# ---- where the holes are ---------------------------------------------------------------------

def fake_strips(monkeypatch, shares):
    """strips_together replaced: ``shares(lo, hi)`` -> (regular share, large-island share), the
    same in every velocity period."""
    def strips(specs, eps, samples, seed=0):
        out = []
        for lo, hi, m in specs:
            regular, large = shares(lo, hi)
            out.append(Strip(lo, hi, samples, round(regular * samples), round(large * samples),
                             m))
        return out
    monkeypatch.setattr(geometry_claims, "strips_together", strips)


@pytest.mark.parametrize(("sea_islands", "verdict"), [
    (0.05, CONFIRMED), (0.124, INCONCLUSIVE), (0.6, REFUTED)])
def test_almost_entirely_in_the_sea_at_a_tenth_and_not_from_half(monkeypatch, sea_islands,
                                                                 verdict):
    fake_strips(monkeypatch, lambda lo, hi: (sea_islands, 0.0) if lo > 1.8 else (0.3, 0.3))
    claims = {c.id: c for c in geometry_claims.escape_hole_claims()}
    assert claims["fig2-hole-phi_c=2"].verdict == verdict
    assert (claims["fig2-hole-phi_c=2"].inconclusive == BETWEEN_BOUNDS) == (
        verdict == INCONCLUSIVE)
    assert claims["fig2-hole-phi_c=0"].verdict == CONFIRMED
    assert len(claims["fig2-hole-phi_c=2"].analyses) == 2  # two velocity periods


@pytest.mark.parametrize(("large", "verdict"), [
    (0.05, CONFIRMED), (0.004, INCONCLUSIVE), (0.0, INCONCLUSIVE)])
def test_over_or_near_from_one_percent_and_a_trace_is_not_refuted_by_two_thousand_starts(
        monkeypatch, large, verdict):
    """0 of 2000 has the Wilson upper bound 0.0019, above the trace 0.1%: not refuted."""
    fake_strips(monkeypatch, lambda lo, hi: (large, large) if lo < 1.8 else (0.0, 0.0))
    claims = {c.id: c for c in geometry_claims.escape_hole_claims()}
    assert claims["fig2-hole-phi_c=0"].verdict == verdict


def test_over_or_near_is_refuted_by_a_trace(monkeypatch):
    fake_strips(monkeypatch, lambda lo, hi: (0.0, 0.0))
    monkeypatch.setattr(geometry_claims, "SAMPLES", {False: 20000, True: 200})
    claims = {c.id: c for c in geometry_claims.escape_hole_claims()}
    assert claims["fig2-hole-phi_c=0"].verdict == REFUTED


@pytest.mark.parametrize(("hole2_islands", "hole2_large", "holes", "hole_2"), [
    (0.05, 0.0, CONFIRMED, CONFIRMED),
    (0.124, 0.0, CONFIRMED, INCONCLUSIVE),   # 12.4% on islands: between 10% and 50%
    (0.35, 0.0, INCONCLUSIVE, INCONCLUSIVE),  # mostly sea: between 25% and 50%
    (0.6, 0.0, REFUTED, REFUTED),
    (0.2, 0.15, CONFIRMED, REFUTED),          # 15% of the strip on the large island: not far
    (0.08, 0.04, CONFIRMED, INCONCLUSIVE),    # 4% on the large island: between 1% and 10%
])
def test_the_holes_of_section_4(monkeypatch, hole2_islands, hole2_large, holes, hole_2):
    fake_strips(monkeypatch, lambda lo, hi: (0.3, 0.3) if lo < 0 else (hole2_islands,
                                                                      hole2_large))
    got = {c.id: c for c in geometry_claims.transport_hole_claims()}
    assert got["sec4-holes"].verdict == holes
    assert got["sec4-hole-2"].verdict == hole_2


@pytest.mark.parametrize(("hole1_islands", "verdict"), [
    (0.3, CONFIRMED), (0.004, INCONCLUSIVE), (0.0, REFUTED), (1.0, REFUTED)])
def test_both_islands_and_sea_from_one_percent_each_and_not_on_a_trace_of_either(
        monkeypatch, hole1_islands, verdict):
    """20,000 starts per strip: 0 of them has the Wilson upper bound 0.00019, a trace."""
    fake_strips(monkeypatch, lambda lo, hi: (hole1_islands, hole1_islands) if lo < 0 else
                (0.05, 0.0))
    monkeypatch.setattr(geometry_claims, "SAMPLES", {False: 20000, True: 200})
    claim = geometry_claims.transport_hole_claims()[0]
    assert claim.verdict == verdict
    assert (claim.inconclusive == BETWEEN_BOUNDS) == (verdict == INCONCLUSIVE)


# ---- start sets: "destroy all", "quite a lot smaller" ----------------------------------------

def island_sample(left, m=4000, width=2.5):
    large = np.ones(m, bool)
    cls = SimpleNamespace(large=large, regular=large, phase_lo=np.full(m, 0.0),
                          phase_hi=np.full(m, width))
    exit = np.zeros(m, np.int8)
    exit[:left] = -1
    n = np.where(exit < 0, 3000, 100)  # the others escape early
    return None, None, cls, SimpleNamespace(exit=exit, n=n)


@pytest.mark.parametrize(("left", "verdict"), [
    (10, CONFIRMED),       # 0.25% left: all destroyed at the measurement's floor
    (40, INCONCLUSIVE),    # 1% left: the interval straddles the floor
    (400, REFUTED),        # 10% left: not all
])
def test_destroy_all_is_read_at_the_measurement_floor(left, verdict):
    claim = start_claims.destroy_all_claim(island_sample(left))
    assert claim.verdict == verdict, claim.evidence


@pytest.mark.parametrize(("width", "verdict"), [
    (2.5, CONFIRMED),        # island 8 hole widths
    (0.75, INCONCLUSIVE),    # island 2.5 hole widths: between 2 and 3
    (0.5, REFUTED),          # island 1.7 hole widths: not much larger than the hole
])
def test_quite_a_lot_smaller_from_three_hole_widths_and_not_at_two(width, verdict):
    members = start_claims.island_width_members(island_sample(10, width=width)[2], 0.3, "p")
    assert {a.verdict for a in members} == {verdict}


# ---- escape: "tightly bounded velocity", "slowed by the large islands" -----------------------

@pytest.mark.parametrize(("s", "verdict"), [(0.0, CONFIRMED), (0.17, INCONCLUSIVE),
                                            (0.5, REFUTED)])
def test_tightly_bounded_velocity_at_a_tenth_and_diffusing_from_a_quarter(s, verdict):
    rng = np.random.default_rng(4)
    n = np.round(10 ** rng.uniform(2, 4, 4000))
    t = n * 6.0 * (n / 100.0) ** s * rng.uniform(0.95, 1.05, len(n))
    a = {"windows": SimpleNamespace(n_at={"half": 100})}
    claim = escape_claims.bounded_velocity_claim("2", a, joint(n, t, np.zeros(len(n))), "r")
    assert claim.verdict == verdict, claim.evidence
    assert (claim.inconclusive == BETWEEN_BOUNDS) == (verdict == INCONCLUSIVE)


def sea_analysis():
    """Survival curves (collisions) where the sea hole's P(n) lies far above the island holes'."""
    edges = np.arange(1, 202, dtype=float)
    x = survival_boundaries(edges, "collisions")
    zero = np.zeros(len(edges), np.int64)

    def curve(kept):
        esc = zero.copy()
        esc[0] = 10**6 - kept
        cens = zero.copy()
        cens[-1] = kept
        return Curve("synthetic", "h", "all", "collisions", x, esc, zero, cens,
                     bin_means(edges, "collisions"), 10**6)
    out = {h: {"curves": {"collisions": curve(10)}} for h in escape_claims.ISLAND_HOLES}
    out["2"] = {"curves": {"collisions": curve(10**4)}}
    return out


def snapshot_with(locked, watched=100):
    """Survivors watched for 200 collisions: ``locked`` with flights of 2 pi (period-1), the
    others with flights of 5."""
    step = np.where(np.arange(watched) < locked, 2 * math.pi, 5.0)
    t = step[:, None] * np.arange(200)[None, :]
    v = np.full((watched, 200), 3.0)
    return None, None, v, t


@pytest.mark.parametrize(("locked", "verdict"), [(95, CONFIRMED), (64, INCONCLUSIVE),
                                                 (30, REFUTED)])
def test_slowed_by_the_islands_when_most_late_survivors_are_on_them(locked, verdict):
    study = SimpleNamespace(particles=10**6, snapshots={50: snapshot_with(locked),
                                                        80: snapshot_with(locked)})
    claim = escape_claims.sea_slowed_claim("2", sea_analysis(), study, (50, 80), "r")
    assert claim.verdict == verdict, claim.evidence
    assert (claim.inconclusive == BETWEEN_BOUNDS) == (verdict == INCONCLUSIVE)
