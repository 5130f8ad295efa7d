"""The two bounds of the paper's qualitative words, on synthetic numbers whose verdict is known.

Each rule of ``reports.paper.rules`` that reads a vague word ("the same", "many fewer", "large",
"effectively traps", "almost entirely", "well approximated", ...) is applied by its claim module
to a measurement placed inside the word's holds zone (confirmed), inside its fails zone
(refuted), wholly between the two bounds (inconclusive, the evidence saying so) and straddling a
bound (inconclusive). No runs: every input is built here, and each test takes well under a second.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from reports.paper import escape_claims, fermi, geometry_claims, start_claims, transport_claims
from reports.paper import rules as R
from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.follow import Followed
from reports.paper.islands import Strip
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


def fermi_of(beta_n, beta_t, err=0.002):
    """A Fermi ensemble whose <v> follows n^beta_n and t^beta_t exactly (no window systematic)."""
    n = np.geomspace(1, 3e4, 61)
    t = np.geomspace(1, 3e6, 61)
    return fermi.Fermi(8000, n, n ** beta_n, t, t ** beta_t, np.full(61, 8000), beta_n, err,
                       1.0, beta_t, err, 1.0, (1000.0, 3e4), (1e4, 3e6), 0, 0,
                       {"sampled": 1, "worst_error": 0.1, "overstepped": 0}, 0.0)


@pytest.mark.parametrize(("beta_n", "beta_t", "verdict"), [
    (0.5, 1 / 3, CONFIRMED),
    (0.58, 0.38, INCONCLUSIVE),   # 16% and 14% off: between the bounds
    (0.70, 0.45, REFUTED),        # 40% and 35% off
])
def test_fermi_exponents_are_the_paper_s_within_ten_percent_not_beyond_twenty_five(
        beta_n, beta_t, verdict):
    claims = fermi.fermi_claims(fermi_of(beta_n, beta_t))
    assert [c.verdict for c in claims] == [verdict, verdict]
    if verdict == INCONCLUSIVE:
        assert all(R.BETWEEN in c.evidence for c in claims)


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
    got, text, _ = start_claims.compare_long_times(ref, other, 0.5)
    assert got == verdict, text
    assert (R.BETWEEN in text) == (note == R.BETWEEN)


def alpha_detail(alpha, u):
    fit = SimpleNamespace(params={"alpha": alpha}, ci95={"alpha": (alpha - u, alpha + u)})
    return {"fits": {"power_law": fit}, "systematic": {"power_law": {"alpha": 0.0}},
            "escapes": 10**4}


def analysis_with_tails(alphas, u=0.02):
    curves = {"collisions": SimpleNamespace(particles=10**6)}
    return {h: {"details": {("collisions", "tail"): alpha_detail(a, u)}, "curves": curves}
            for h, a in alphas.items()}


@pytest.mark.parametrize(("alphas", "verdict"), [
    ({"0": 2.0, "2": 2.05}, REFUTED),       # every pair the same: a universal law
    ({"0": 2.0, "2": 3.0}, CONFIRMED),      # 40% apart: no universal law
    ({"0": 2.0, "2": 2.4}, INCONCLUSIVE),   # 18% apart: between the bounds
])
def test_no_universal_law_needs_a_pair_at_least_twenty_five_percent_apart(alphas, verdict):
    claim = escape_claims.universal_claim(analysis_with_tails(alphas), "run")
    assert claim.verdict == verdict
    assert (R.BETWEEN in claim.evidence) == (verdict == INCONCLUSIVE)


# ---- transport: "many fewer", "large velocities", "effectively traps", "very strong" --------

def followed(exit, n, t, v_max):
    exit = np.asarray(exit)
    return Followed(0.6, exit.astype(np.int8), np.asarray(n, np.int64), np.asarray(t, float),
                    np.asarray(v_max, float), np.zeros(len(exit)))


def transport_samples(ratio, v_transport, m=20_000, seed=0):
    """Entry hole 1: half the orbits reflected (n = t/5), half transmitted with n = ratio t/5,
    escape times log-uniform on [100, 10^4]; transmitted orbits reach ``v_transport``."""
    rng = np.random.default_rng(seed)
    t = 10 ** rng.uniform(2, 4, m)
    exit = np.where(np.arange(m) % 2 == 0, 0, 1)
    n = np.where(exit == 0, t / 5, ratio * t / 5).round().astype(np.int64) + 1
    v = np.where(exit == 0, 3.0, v_transport)
    return {1: followed(exit, n, t, v)}


@pytest.mark.parametrize(("ratio", "verdict"), [
    (0.25, CONFIRMED), (0.7, INCONCLUSIVE), (1.0, REFUTED)])
def test_many_fewer_collisions_at_half_and_about_as_many_at_nine_tenths(ratio, verdict):
    claim = transport_claims.fewer_collisions_claim(transport_samples(ratio, 3.0), reps=40)
    assert claim.verdict == verdict, claim.evidence
    if verdict == INCONCLUSIVE:
        assert f"0 bins in the holds zone, {len(claim.statistical['ratios'])} {R.BETWEEN}" in \
            claim.evidence


@pytest.mark.parametrize(("v_transport", "verdict", "note"), [
    (50.0, CONFIRMED, ""),            # above 10 times the largest start velocity 4
    (27.0, INCONCLUSIVE, R.BETWEEN),  # above twice it, below ten times
    (6.0, REFUTED, ""),               # none above twice it
])
def test_large_velocities_above_ten_times_the_start_and_not_below_twice(v_transport, verdict,
                                                                       note):
    """100,000 transporting orbits: none above v = 8 has a Wilson upper bound below 10^-4."""
    claim = transport_claims.large_velocity_claim(transport_samples(0.5, v_transport, 200_000))
    assert claim.verdict == verdict
    assert (R.BETWEEN in claim.evidence) == (note == R.BETWEEN)


def test_large_velocities_undecided_when_too_few_reach_twice_the_start():
    """Eight above v = 8 in 100,000: their share's upper bound is not below 10^-4, nor is its
    lower bound above it: the sample cannot say whether the orbits stay near the start."""
    samples = transport_samples(0.5, 6.0, 200_000)
    samples[1].v_max[1:16:2] = 9.0
    claim = transport_claims.large_velocity_claim(samples)
    assert claim.verdict == INCONCLUSIVE and "straddles a bound" in claim.evidence


def trapping_curves(share_out, m=10**7):
    """Curves of both entry holes: 99.9% of the entrants leave by their own hole at t ~ 1, the
    slow 0.1% spread evenly over 40 bins from t = 10^3, a share ``share_out`` of them in every
    bin through the other hole; the survival falls to 10^-4 with 1000 of them left."""
    edges = np.concatenate([[0.0], np.geomspace(0.1, 1e7, 161)])
    x = survival_boundaries(edges, "time")
    k_fast = np.searchsorted(edges, 1.0, side="right") - 1
    k_slow = np.searchsorted(edges, 1e3, side="right") - 1
    slow, bins = m // 1000, 40
    own, other = np.zeros(len(edges), np.int64), np.zeros(len(edges), np.int64)
    own[k_fast] = m - slow
    other[k_slow:k_slow + bins] = round(share_out * slow / bins)
    own[k_slow:k_slow + bins] += slow // bins - other[k_slow:k_slow + bins]
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
    assert trap.statistical["share_hole_2"] == pytest.approx(share_out, abs=1e-3)
    if note:
        assert note in trap.evidence


@pytest.mark.parametrize(("ratio", "verdict"), [
    (15.0, CONFIRMED), (5.0, INCONCLUSIVE), (1.5, REFUTED), (1.0, REFUTED),
    (10.0, INCONCLUSIVE), (2.0, INCONCLUSIVE),  # one bin of the grid either way crosses a bound
    (math.inf, CONFIRMED), (math.nan, INCONCLUSIVE)])
def test_very_strong_p11_outlives_the_others_by_a_decade_and_fails_at_twice(ratio, verdict):
    assert transport_claims.strong_verdict(ratio) == verdict


# ---- "well approximated" ---------------------------------------------------------------------

@pytest.mark.parametrize(("best", "excess", "verdict"), [
    ("stretched_exponential", 0.05, CONFIRMED),
    ("stretched_exponential", 0.18, INCONCLUSIVE),
    ("stretched_exponential", 0.30, REFUTED),
    ("power_law", 0.0, REFUTED),
    ("inconclusive", 0.0, INCONCLUSIVE),
    ("stretched_exponential", math.inf, INCONCLUSIVE),
])
def test_well_approximated_within_a_tenth_and_not_from_a_quarter(monkeypatch, best, excess,
                                                                 verdict):
    monkeypatch.setattr(R, "residual_excess", lambda curve, fit: excess)
    detail = {"fits": {"stretched_exponential": None}, "escapes": 10**4, "best": best}
    got, measured = R.well_approximated_verdict(None, detail, "stretched_exponential", 100)
    assert (got, measured) == (verdict, excess)


# ---- where the holes are ---------------------------------------------------------------------

def fake_strips(monkeypatch, shares, m=2000):
    """strip_fractions replaced: ``shares(lo, hi)`` -> (regular share, large-island share)."""
    def strips(lo, hi, eps, samples):
        regular, large = shares(lo, hi)
        return Strip(lo, hi, samples, round(regular * samples), round(large * samples))
    monkeypatch.setattr(geometry_claims, "strip_fractions", strips)


@pytest.mark.parametrize(("sea_islands", "verdict"), [
    (0.05, CONFIRMED), (0.124, INCONCLUSIVE), (0.6, REFUTED)])
def test_almost_entirely_in_the_sea_at_a_tenth_and_not_from_half(monkeypatch, sea_islands,
                                                                 verdict):
    fake_strips(monkeypatch, lambda lo, hi: (sea_islands, 0.0) if lo > 1.8 else (0.3, 0.3))
    claims = {c.id: c for c in geometry_claims.escape_hole_claims()}
    assert claims["fig2-hole-phi_c=2"].verdict == verdict
    assert (R.BETWEEN in claims["fig2-hole-phi_c=2"].evidence) == (verdict == INCONCLUSIVE)
    assert claims["fig2-hole-phi_c=0"].verdict == CONFIRMED


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
    assert (R.BETWEEN in claim.evidence) == (verdict == INCONCLUSIVE)


# ---- start sets: "destroy all", "quite a lot smaller" ----------------------------------------

def island_sample(left, m=4000, width=2.5):
    large = np.ones(m, bool)
    cls = SimpleNamespace(large=large, regular=large, phase_lo=np.full(m, 0.0),
                          phase_hi=np.full(m, width))
    exit = np.zeros(m, np.int8)
    exit[:left] = -1
    return None, None, cls, SimpleNamespace(exit=exit, n=np.full(m, 3000))


@pytest.mark.parametrize(("left", "width", "verdict"), [
    (10, 2.5, CONFIRMED),        # 0.25% left, island 8 hole widths
    (400, 2.5, INCONCLUSIVE),    # 10% left: between 1% and 50%
    (2400, 2.5, REFUTED),        # 60% left: most of the island survives
    (10, 0.75, INCONCLUSIVE),    # island 2.5 hole widths: between 2 and 3
    (10, 0.5, REFUTED),          # island 1.7 hole widths: not much larger than the hole
])
def test_destruction_at_one_percent_left_and_survival_from_half(left, width, verdict):
    claim = start_claims.destruction_claim(island_sample(left, width=width))
    assert claim.verdict == verdict
    if (left, width) == (400, 2.5):
        assert R.BETWEEN in claim.evidence


# ---- escape: "tightly bounded velocity", "slowed by the large islands" -----------------------

@pytest.mark.parametrize(("s", "verdict"), [(0.0, CONFIRMED), (0.17, INCONCLUSIVE),
                                            (0.5, REFUTED)])
def test_tightly_bounded_velocity_at_a_tenth_and_diffusing_from_a_quarter(s, verdict):
    rng = np.random.default_rng(4)
    n = np.round(10 ** rng.uniform(2, 4, 4000)).astype(np.int64)
    t = n * 6.0 * (n / 100.0) ** s * rng.uniform(0.95, 1.05, len(n))
    study = followed(np.zeros(len(n)), n, t, np.full(len(n), 3.0))
    a = {"windows": SimpleNamespace(n_at={"half": 100})}
    claim = escape_claims.bounded_velocity_claim("2", a, study, "r")
    assert claim.verdict == verdict, claim.evidence
    assert (R.BETWEEN in claim.evidence) == (verdict == INCONCLUSIVE)


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
    study = SimpleNamespace(particles=10**6, snapshots={50: snapshot_with(locked)})
    claim = escape_claims.sea_slowed_claim("2", sea_analysis(), study, 50, "r")
    assert claim.verdict == verdict, claim.evidence
    assert (R.BETWEEN in claim.evidence) == (verdict == INCONCLUSIVE)
