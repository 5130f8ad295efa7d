"""The paper's claims about the measure of initial conditions (Section 3): another start set or
density gives the same results at long times; starts on an island not connected with the hole
give a survival that tends to a constant; a hole over part of an island destroys its orbits.

Runs: the scene escape-second-box (a second box in the chaotic sea, the paper's holes and bins)
and escape-island-start (starts touching the island around (0, pi), holes at 0 and pi), through
``reports.paper.runs.ensure_run``; sampled studies (``reports.paper.studies``) for the smooth
density and for the island orbits' fate.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from reports.paper import rules as R
from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.register import make_claim
from reports.runs.survival import wilson
from reports.stats.analysis import usable_range
from reports.stats.hazard import all_cause_survival, first_below, hazard_ratio
from reports.stats.histogram import read_run

MIN_AT_RISK = 10
HR_BAND = R.ratio_band(R.SAME)              # "the same" hazards: holds inside
HR_FAILS_BAND = R.ratio_band(R.SAME_FAILS)  # fails wholly outside


def followed_curve(followed, ref):
    """The ``Followed`` records binned on the boundaries of the run curve ``ref`` (same clock):
    escapes in the bin of their n (or t), particles still inside at the horizon censored in the
    bin of theirs."""
    if ref.clock == "collisions":
        value, edges = followed.n.astype(np.float64), ref.x[:-1] + 1.0
    else:
        value, edges = followed.t, ref.x[:-1].copy()
    k = np.clip(np.searchsorted(edges, value, side="right") - 1, 0, len(edges) - 1)
    esc = followed.exit >= 0
    escapes = np.bincount(k[esc], minlength=len(edges)).astype(np.int64)
    censored = np.bincount(k[~esc], minlength=len(edges)).astype(np.int64)
    return dataclasses.replace(ref, source="sampled study", escapes=escapes, censored=censored,
                               competing=np.zeros_like(escapes), particles=followed.particles)


def long_time_window(ref, other, level):
    """(a, b): from where ref's survival falls to ``level`` (its late tail's) to the last
    boundary with MIN_AT_RISK particles at risk in both curves, inside both usable ranges; or
    None."""
    a = first_below(all_cause_survival(ref), level)
    if a is None:
        return None
    risk_ok = np.flatnonzero((all_cause_survival(ref) * ref.particles >= MIN_AT_RISK)
                             & (all_cause_survival(other) * other.particles >= MIN_AT_RISK))
    if not len(risk_ok):
        return None
    b = min(int(risk_ok[-1]), usable_range(ref)[1], usable_range(other)[1])
    return (a, b) if b - a >= 2 else None


def compare_long_times(ref, other, level):
    """Verdict of the 'same results at long times' rule for one curve pair, with its text."""
    w = long_time_window(ref, other, level)
    if w is None:
        return INCONCLUSIVE, "no long-time window", []
    a, b = w
    both = ref.escapes + other.escapes
    cum = np.cumsum(both[a:b])
    mid = a + int(np.searchsorted(cum, cum[-1] / 2)) + 1 if cum[-1] > 0 else b
    mid = min(max(mid, a + 1), b - 1)
    parts, verdicts = [], []
    for lo, hi in ((a, mid), (mid, b)):
        hr, ci, used = hazard_ratio(ref, other, lo, hi)
        verdicts.append(R.two_band_verdict(*ci, HR_BAND, HR_FAILS_BAND))
        note = R.two_band_note(*ci, HR_BAND, HR_FAILS_BAND)
        parts.append(f"[{ref.x[lo]:.3g}, {ref.x[hi]:.3g}] HR {hr:.3f} [{ci[0]:.3f}, {ci[1]:.3f}]"
                     f" ({used:,} escapes{', ' + note if note else ''})")
    return R.all_of(verdicts), ", ".join(parts), verdicts


def same_results_claim(claim_id, ref_curves, other_curves, levels, what, particles, run):
    """Compare every (hole, clock) of two escape ensembles at long times; ``levels``: the late
    tail's survival level of each hole of the reference run ({experiment: level or None})."""
    verdicts, parts = [], []
    for key, ref in ref_curves.items():
        if key not in other_curves:
            continue
        if levels.get(key[0]) is None:
            verdicts.append(INCONCLUSIVE)
            parts.append(f"{key[0]}: the reference has no late tail")
            continue
        v, text, _ = compare_long_times(ref, other_curves[key], levels[key[0]])
        verdicts.append(v)
        parts.append(f"{key[0]} ({'n' if key[1] == 'collisions' else 't'}): {text}")
    evidence = (f"{what} against the paper-scale run, hazard ratio (log-rank) over the earlier "
                "and later half of the late tail (from the reference's tail level), the same "
                f"inside [{HR_BAND[0]:.3f}, {HR_BAND[1]:.3f}], different wholly outside "
                f"[{HR_FAILS_BAND[0]:.3f}, {HR_FAILS_BAND[1]:.3f}]: " + "; ".join(parts) + ".")
    return make_claim(claim_id, R.all_of(verdicts) if verdicts else INCONCLUSIVE, evidence,
                      particles_per_curve=particles, run=run)


def curves_by_key(run_dir):
    return {(c.experiment, c.clock): c for c in read_run(run_dir)}


def other_box_claim(ref_run, box_run, levels):
    ref, box = curves_by_key(ref_run), curves_by_key(box_run)
    n = next(iter(box.values())).particles
    return same_results_claim("sec3-other-box", ref, box, levels, f"Run {Path(box_run).name} "
                              f"({n:,} per hole)", n, Path(box_run).name)


def other_density_claim(ref_run, samples, levels):
    """``samples``: {hole name: Followed} of the smooth density."""
    ref = curves_by_key(ref_run)
    other = {key: followed_curve(samples[key[0]], c) for key, c in ref.items()
             if key[0] in samples}
    n = next(iter(samples.values())).particles
    return same_results_claim("sec3-other-density", ref, other, levels,
                              f"Sampled study, smooth density ({n:,} per hole)", n, None)


def island_start_claim(run_dir, box_classified):
    """The survival with the hole at pi of the run of scene escape-island-start tends to a
    constant equal to the regular share of the box (``box_classified``: (regular count,
    samples)). Tending to a constant: the escapes of the last decade before the horizon T are
    significantly fewer than those of the decade before (a decelerating fall; the share of the
    two decades' escapes in the last one has its Wilson interval below 1/2); the limit then lies
    between S(T) and S(T) - k2 r/(1 - r)/N (the falls continuing as a geometric series of ratio
    r = k2/k1), and is compared with the regular share by the 'the same' rule on that range."""
    curves = curves_by_key(run_dir)
    key = next(k for k in curves if k[1] == "time" and not k[0].endswith("=0"))
    c = curves[key]
    s = all_cause_survival(c)
    n = c.particles
    k_h = int(np.flatnonzero(c.censored)[0]) if c.censored.any() else usable_range(c)[1]
    t_h = float(c.x[k_h])
    k_10 = int(np.searchsorted(c.x, t_h / 10))
    k_100 = int(np.searchsorted(c.x, t_h / 100))
    inside = [round(s[k] * n) for k in (k_100, k_10, k_h)]
    k1, k2 = inside[0] - inside[1], inside[1] - inside[2]
    share_ci = tuple(float(x) for x in wilson(k2, max(k1 + k2, 1)))
    if k1 + k2 == 0:
        converging = CONFIRMED
    elif share_ci[1] < 0.5:
        converging = CONFIRMED
    elif share_ci[0] > 0.5:
        converging = REFUTED
    else:
        converging = INCONCLUSIVE
    r = k2 / k1 if k1 else 0.0
    low = (inside[2] - (k2 * r / (1 - r) if r < 1 else inside[2])) / n
    high = inside[2] / n
    reg, m = box_classified
    f_ci = tuple(float(x) for x in wilson(reg, m))
    p_ci = tuple(float(x) for x in wilson(inside[2], n))
    lo_, hi_ = min(low, p_ci[0]), p_ci[1]
    same_args = (0.5 * (lo_ + hi_), 0.5 * (hi_ - lo_), reg / m, 0.5 * (f_ci[1] - f_ci[0]))
    same = R.same_verdict(*same_args)
    note = R.same_note(*same_args)
    evidence = (f"Run {Path(run_dir).name} ({n:,} starts, hole at phi_c = pi): still inside "
                f"{inside[0]:,}, {inside[1]:,} and {inside[2]:,} at t = {c.x[k_100]:.3g}, "
                f"{c.x[k_10]:.3g} and the horizon {t_h:.3g}; escapes in the last two decades "
                f"{k1} then {k2} (share of the last {k2 / max(k1 + k2, 1):.3f}, 95% "
                f"[{share_ci[0]:.3f}, {share_ci[1]:.3f}] against 1/2: the fall "
                f"{'decelerates' if converging == CONFIRMED else 'does not clearly decelerate'})"
                f"; limit between {low:.4f} and {high:.4f}; regular share of the box "
                f"{reg / m:.4f} (95% [{f_ci[0]:.4f}, {f_ci[1]:.4f}], {m} random starts "
                f"classified by their orbits): {same} under 'the same' (within "
                f"{R.pct(R.SAME)}, different beyond {R.pct(R.SAME_FAILS)}"
                f"{'; ' + note if note else ''}).")
    return make_claim("sec3-island-start", R.all_of([converging, same]), evidence,
                      particles_per_curve=n,
                      statistical={"survival_at_horizon": high, "limit_low": low,
                                   "regular_share": reg / m},
                      run=Path(run_dir).name)


def destruction_claim(sample, hole_width=0.3):
    """``sample``: (phi, v, Classified, Followed) of ``studies.island_box_sample(0.0)``."""
    _, _, cls, fol = sample
    large = cls.large
    m = int(large.sum())
    if m == 0:
        return make_claim("sec3-destruction", INCONCLUSIVE, "No start of the box is on the "
                          "large island.", particles_per_curve=len(large))
    left = int((large & (fol.exit < 0)).sum())
    ci = tuple(float(x) for x in wilson(left, m))
    destroyed = R.word_verdict(*ci, R.DESTROYED, R.DESTROYED_FAILS)
    note = R.word_note(*ci, R.DESTROYED, R.DESTROYED_FAILS)
    # the phase extent of the island's orbits: 5th and 95th percentiles of their lowest and
    # highest phases (a few orbits locked by chance while they wander are left out)
    width = float(np.percentile(cls.phase_hi[large], 95) - np.percentile(cls.phase_lo[large], 5))
    smaller = R.word_verdict(width / hole_width, width / hole_width, R.MUCH_SMALLER,
                             R.MUCH_SMALLER_FAILS)
    others = int((~large & cls.regular & (fol.exit < 0)).sum())
    evidence = (f"Sampled study, {len(large):,} starts in the box 0.3 < phi < 0.9, 2.7 < v < 3.3:"
                f" {m:,} on the large island around (0, pi) (locked orbits); with the hole of "
                f"width {hole_width:g} at phi_c = 0, {left} of them are still inside after "
                f"{int(fol.n.max())} collisions (share {left / m:.4f}, 95% [{ci[0]:.4f}, "
                f"{ci[1]:.4f}]; 'destroy all' {R.bounds_text(R.DESTROYED, R.DESTROYED_FAILS)}"
                f"{': ' + note if note else ''}); {others} starts on other islands survive too; "
                f"the island's orbits span a phase width of {width:.2f} = "
                f"{width / hole_width:.1f} hole widths ('quite a lot smaller' "
                f"{R.bounds_text(R.MUCH_SMALLER, R.MUCH_SMALLER_FAILS, '{:g}'.format)}).")
    return make_claim("sec3-destruction", R.all_of([destroyed, smaller]), evidence,
                      particles_per_curve=len(large),
                      statistical={"surviving_share": left / m, "surviving_ci95": list(ci),
                                   "island_phase_width": width})


__all__ = ["destruction_claim", "followed_curve", "island_start_claim", "other_box_claim",
           "other_density_claim"]
