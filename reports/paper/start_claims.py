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

LONG_TIME_LEVEL = 1e-2
MIN_AT_RISK = 10
HR_BAND = (1 / (1 + R.SAME), 1 + R.SAME)


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


def long_time_window(ref, other):
    """(a, b): from where ref's survival falls to LONG_TIME_LEVEL to the last boundary with
    MIN_AT_RISK particles at risk in both curves, inside both usable ranges; or None."""
    a = first_below(all_cause_survival(ref), LONG_TIME_LEVEL)
    if a is None:
        return None
    risk_ok = np.flatnonzero((all_cause_survival(ref) * ref.particles >= MIN_AT_RISK)
                             & (all_cause_survival(other) * other.particles >= MIN_AT_RISK))
    if not len(risk_ok):
        return None
    b = min(int(risk_ok[-1]), usable_range(ref)[1], usable_range(other)[1])
    return (a, b) if b - a >= 2 else None


def compare_long_times(ref, other):
    """Verdict of the 'same results at long times' rule for one curve pair, with its text."""
    w = long_time_window(ref, other)
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
        verdicts.append(R.band_verdict(*ci, *HR_BAND))
        parts.append(f"[{ref.x[lo]:.3g}, {ref.x[hi]:.3g}] HR {hr:.3f} [{ci[0]:.3f}, {ci[1]:.3f}]"
                     f" ({used:,} escapes)")
    return R.all_of(verdicts), ", ".join(parts), verdicts


def same_results_claim(claim_id, ref_curves, other_curves, what, particles, run):
    """Compare every (hole, clock) of two escape ensembles at long times."""
    verdicts, parts = [], []
    for key, ref in ref_curves.items():
        if key not in other_curves:
            continue
        v, text, _ = compare_long_times(ref, other_curves[key])
        verdicts.append(v)
        parts.append(f"{key[0]} ({'n' if key[1] == 'collisions' else 't'}): {text}")
    evidence = (f"{what} against the paper-scale run, hazard ratio (log-rank) over the earlier "
                f"and later half of the long-time window, band [{HR_BAND[0]:.3f}, "
                f"{HR_BAND[1]:.3f}]: " + "; ".join(parts) + ".")
    return make_claim(claim_id, R.all_of(verdicts) if verdicts else INCONCLUSIVE, evidence,
                      particles_per_curve=particles, run=run)


def curves_by_key(run_dir):
    return {(c.experiment, c.clock): c for c in read_run(run_dir)}


def other_box_claim(ref_run, box_run):
    ref, box = curves_by_key(ref_run), curves_by_key(box_run)
    n = next(iter(box.values())).particles
    return same_results_claim("sec3-other-box", ref, box, f"Run {Path(box_run).name} "
                              f"({n:,} per hole)", n, Path(box_run).name)


def other_density_claim(ref_run, samples):
    """``samples``: {hole name: Followed} of the smooth density."""
    ref = curves_by_key(ref_run)
    other = {key: followed_curve(samples[key[0]], c) for key, c in ref.items()
             if key[0] in samples}
    n = next(iter(samples.values())).particles
    return same_results_claim("sec3-other-density", ref, other,
                              f"Sampled study, smooth density ({n:,} per hole)", n, None)


def island_start_claim(run_dir, box_classified):
    """Survival with the hole at pi of the run of scene escape-island-start against the regular
    share of the box (``box_classified``: (regular count, samples))."""
    curves = curves_by_key(run_dir)
    key = next(k for k in curves if k[1] == "time" and not k[0].endswith("=0"))
    c = curves[key]
    s = all_cause_survival(c)
    k_h = int(np.flatnonzero(c.censored)[0]) if c.censored.any() else usable_range(c)[1]
    t_h = float(c.x[k_h])
    k_10 = int(np.searchsorted(c.x, t_h / 10))
    n = c.particles
    inside_10, inside_h = round(s[k_10] * n), round(s[k_h] * n)
    fell = inside_10 - inside_h
    fall_ci = tuple(float(x) for x in wilson(fell, max(inside_10, 1)))
    plateau = R.fraction_at_most(fell, inside_10, R.PLATEAU_FALL, fall_ci) if inside_10 else \
        INCONCLUSIVE
    reg, m = box_classified
    p_ci = tuple(float(x) for x in wilson(inside_h, n))
    f_ci = tuple(float(x) for x in wilson(reg, m))
    same = R.same_verdict(inside_h / n, 0.5 * (p_ci[1] - p_ci[0]), reg / m,
                          0.5 * (f_ci[1] - f_ci[0]))
    evidence = (f"Run {Path(run_dir).name} ({n:,} starts, hole at phi_c = pi): P(t) = "
                f"{s[k_10]:.4f} at t = {c.x[k_10]:.3g} and {s[k_h]:.4f} at the horizon t = "
                f"{t_h:.3g}: {fell} of {inside_10} left in the last decade (share "
                f"{fell / max(inside_10, 1):.4f}, 95% [{fall_ci[0]:.4f}, {fall_ci[1]:.4f}], "
                f"against {R.pct(R.PLATEAU_FALL)}); regular share of the box "
                f"{reg / m:.4f} (95% [{f_ci[0]:.4f}, {f_ci[1]:.4f}], {m} random starts "
                f"classified by their orbits) against P = {inside_h / n:.4f} "
                f"[{p_ci[0]:.4f}, {p_ci[1]:.4f}]: {same}.")
    return make_claim("sec3-island-start", R.all_of([plateau, same]), evidence,
                      particles_per_curve=n,
                      statistical={"plateau": inside_h / n, "regular_share": reg / m,
                                   "fall_last_decade": fell / max(inside_10, 1)},
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
    destroyed = R.fraction_at_most(left, m, R.TRAP_SHARE, ci)
    width = float(np.max(cls.phase_hi[large]) - np.min(cls.phase_lo[large]))
    smaller = CONFIRMED if width >= 3 * hole_width else REFUTED
    others = int((~large & cls.regular & (fol.exit < 0)).sum())
    evidence = (f"Sampled study, {len(large):,} starts in the box 0.3 < phi < 0.9, 2.7 < v < 3.3:"
                f" {m:,} on the large island around (0, pi) (locked orbits); with the hole of "
                f"width {hole_width:g} at phi_c = 0, {left} of them are still inside after "
                f"{int(fol.n.max())} collisions (share {left / m:.4f}, 95% [{ci[0]:.4f}, "
                f"{ci[1]:.4f}], against {R.pct(R.TRAP_SHARE)}); {others} starts on other "
                f"islands survive too; the island's orbits span a phase width of {width:.2f} = "
                f"{width / hole_width:.1f} hole widths.")
    return make_claim("sec3-destruction", R.all_of([destroyed, smaller]), evidence,
                      particles_per_curve=len(large),
                      statistical={"surviving_share": left / m, "surviving_ci95": list(ci),
                                   "island_phase_width": width})


__all__ = ["destruction_claim", "followed_curve", "island_start_claim", "other_box_claim",
           "other_density_claim"]
