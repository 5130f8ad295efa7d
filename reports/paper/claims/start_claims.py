"""The paper's claims about the measure of initial conditions (Section 3): another start set or
density gives the same results at long times; starts on an island not connected with the hole
give a survival that tends to a constant; a hole over part of an island destroys its orbits.

Runs: the scene escape-second-box (a second box in the chaotic sea, the paper's holes and bins)
and escape-island-start (starts touching the island around (0, pi), holes at 0 and pi), through
``reports.paper.studies.paper_runs.ensure_run``; sampled studies
(``reports.paper.studies.followed_samples``) for the smooth density and for the island orbits' fate.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import make_claim
from reports.paper.claims.window_family import LATE_MEMBERS, late_windows
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


def resolves(ci):
    """True if an interval of this width could lie inside the holds band of "the same"
    hazards: the log-rank interval's width follows from the escapes and the particles at risk
    alone (its variance is taken under equal hazards), not from the ratio measured, so this
    says whether a window holds enough escapes to decide, whatever it finds."""
    lo, hi = ci
    return lo > 0 and math.log(hi / lo) <= math.log(HR_BAND[1] / HR_BAND[0])


def long_time_members(ref, other, level, part):
    """The family of 'the same at long times' for one curve pair: the hazard ratio of ``other``
    to ``ref`` on the long-time window's latest windows (``window_family.late_windows`` on the
    escapes of both, the latest ``window_family.LATE_MEMBERS`` of those with enough escapes to
    decide, ``resolves``), each under the two-band rule of "the same" hazards."""
    w = long_time_window(ref, other, level)
    if w is None:
        return [F.in_part(part, [F.too_few("no long-time window", "hazard ratio")])[0]]
    both = dataclasses.replace(ref, escapes=ref.escapes + other.escapes)
    measured = [(a, b, *hazard_ratio(ref, other, a, b))
                for a, b in late_windows(both, *w, R.MIN_ESCAPES_TAIL)]
    members = []
    for a, b, hr, ci, used in [m for m in measured if resolves(m[3])][-LATE_MEMBERS:]:
        members.append(F.band_member(f"[{ref.x[a]:.3g}, {ref.x[b]:.3g}] ({used:,} escapes)",
                                     "hazard ratio", hr, *ci, HR_BAND, HR_FAILS_BAND))
    if not members:
        members.append(F.too_few(f"no window of [{ref.x[w[0]]:.3g}, {ref.x[w[1]]:.3g}] holds "
                                 "enough escapes to decide", "hazard ratio"))
    return F.in_part(part, members)


def same_results_claim(claim_id, ref_curves, other_curves, levels, what, particles, run):
    """Compare every (hole, clock) of two escape ensembles at long times; ``levels``: the late
    tail's survival level of each hole of the reference run ({experiment: level or None})."""
    members = []
    for key, ref in ref_curves.items():
        if key not in other_curves:
            continue
        part = f"{key[0]} ({'n' if key[1] == 'collisions' else 't'})"
        if levels.get(key[0]) is None:
            members.append(F.in_part(part, [F.too_few("the reference has no late tail",
                                                      "hazard ratio")])[0])
            continue
        members += long_time_members(ref, other_curves[key], levels[key[0]], part)
    evidence = (f"{what} against the paper-scale run, hazard ratio (log-rank) over the late "
                "tail's latest windows (from the reference's tail level), the same inside "
                f"[{HR_BAND[0]:.3f}, {HR_BAND[1]:.3f}], different wholly outside "
                f"[{HR_FAILS_BAND[0]:.3f}, {HR_FAILS_BAND[1]:.3f}]: "
                + F.family_text(members) + ".")
    return make_claim(claim_id, evidence, analyses=members, particles_per_curve=particles,
                      run=run)


def curves_by_key(run_dir):
    return {(c.experiment, c.clock): c for c in read_run(run_dir)}


def other_box_claim(ref_run, box_run, levels):
    ref, box = curves_by_key(ref_run), curves_by_key(box_run)
    n = next(iter(box.values())).particles
    return same_results_claim("sec3-other-box", ref, box, levels, f"Run {Path(box_run).name} "
                              f"({n:,} per hole)", n, Path(box_run).name)


def other_density_claim(ref_run, samples, levels, density_run=None):
    """The run of scene escape-other-density (``density_run``, the same density on the same
    box) where one is given, else ``samples``: {hole name: Followed} of the smooth density."""
    ref = curves_by_key(ref_run)
    if density_run is not None:
        other = curves_by_key(density_run)
        n = next(iter(other.values())).particles
        return same_results_claim("sec3-other-density", ref, other, levels,
                                  f"Run {Path(density_run).name} ({n:,} per hole)", n,
                                  Path(density_run).name)
    other = {key: followed_curve(samples[key[0]], c) for key, c in ref.items()
             if key[0] in samples}
    n = next(iter(samples.values())).particles
    return same_results_claim("sec3-other-density", ref, other, levels,
                              f"Sampled study, smooth density ({n:,} per hole)", n, None)


SPANS = ((10.0, "the last two decades"), (10 ** 0.5, "the last two half decades"))


def island_start_claim(run_dir, box_classified):
    """The survival with the hole at pi of the run of scene escape-island-start tends to a
    constant equal to the regular share of the box (``box_classified``: (regular count,
    samples)). Over two spans before the horizon T, each a factor f wide (``SPANS``: decades
    and half decades): tending to a constant, the escapes of the last span are significantly
    fewer than those of the span before (a decelerating fall: the share of the two spans'
    escapes in the last one has its Wilson interval below 1/2); the limit then lies between
    S(T) and S(T) - k2 r/(1 - r)/N (the falls continuing as a geometric series of ratio
    r = k2/k1), and is compared with the regular share by the 'the same' rule on that range."""
    curves = curves_by_key(run_dir)
    key = next(k for k in curves if k[1] == "time" and not k[0].endswith("=0"))
    c = curves[key]
    s = all_cause_survival(c)
    n = c.particles
    k_h = int(np.flatnonzero(c.censored)[0]) if c.censored.any() else usable_range(c)[1]
    t_h = float(c.x[k_h])
    reg, m = box_classified
    f_ci = tuple(float(x) for x in wilson(reg, m))
    members = []
    for factor, name in SPANS:
        k_1 = int(np.searchsorted(c.x, t_h / factor))
        k_2 = int(np.searchsorted(c.x, t_h / factor ** 2))
        inside = [round(s[k] * n) for k in (k_2, k_1, k_h)]
        k1, k2 = inside[0] - inside[1], inside[1] - inside[2]
        lo, hi = (float(x) for x in wilson(k2, max(k1 + k2, 1)))
        members.append(F.in_part("tends to a constant", [F.threshold_member(
            f"{name} (t = {c.x[k_2]:.3g}, {c.x[k_1]:.3g}, {t_h:.3g}): still inside "
            f"{inside[0]:,}, {inside[1]:,}, {inside[2]:,}; escapes {k1} then {k2}",
            "share of the escapes in the last span", k2 / max(k1 + k2, 1),
            0.0 if k1 + k2 == 0 else lo, 0.0 if k1 + k2 == 0 else hi, 0.5, True)])[0])
        r = k2 / k1 if k1 else 0.0
        low = (inside[2] - (k2 * r / (1 - r) if r < 1 else inside[2])) / n
        p_ci = tuple(float(x) for x in wilson(inside[2], n))
        lo_, hi_ = min(low, p_ci[0]), p_ci[1]
        members.append(F.in_part("giving the probability", [F.same_member(
            f"{name}: limit between {low:.4f} and {inside[2] / n:.4f} against the regular "
            f"share {reg / m:.4f} (95% [{f_ci[0]:.4f}, {f_ci[1]:.4f}], {m} starts)",
            "relative difference", 0.5 * (lo_ + hi_), 0.5 * (hi_ - lo_), reg / m,
            0.5 * (f_ci[1] - f_ci[0]))])[0])
    evidence = (f"Run {Path(run_dir).name} ({n:,} starts, hole at phi_c = pi), horizon t = "
                f"{t_h:.3g}: {F.family_text(members)}.")
    return make_claim("sec3-island-start", evidence, analyses=members, particles_per_curve=n,
                      statistical={"survival_at_horizon": float(s[k_h]),
                                   "regular_share": reg / m},
                      run=Path(run_dir).name)


def destroy_all_claim(sample):
    """"may in fact destroy all orbits surrounding that island": ``sample`` (phi, v,
    Classified, Followed) of ``studies.island_box_sample(0.0)``; the share of the starts on the
    large island still inside at the study's horizon and at half of it. "All" is an exact word,
    read at the measurement's floor ``rules.DESTROYED`` (one threshold, as "eventually
    escapes"): confirmed if the share's Wilson interval lies at or below it, refuted if it lies
    at or above it."""
    _, _, cls, fol = sample
    large = cls.large
    m = int(large.sum())
    horizon = int(fol.n.max())
    members = []
    for k in (horizon // 2, horizon):
        left = int((large & ((fol.exit < 0) | (fol.n > k))).sum())
        lo, hi = (float(x) for x in wilson(left, m)) if m else (math.nan, math.nan)
        members.append(F.threshold_member(f"after {k} collisions: {left} of {m:,} still inside",
                                          "share left", left / m if m else math.nan, lo, hi,
                                          R.DESTROYED, True) if m else
                       F.too_few(f"after {k} collisions", "share left"))
    others = int((~large & cls.regular & (fol.exit < 0)).sum())
    evidence = (f"Sampled study, {len(large):,} starts in the box of scene escape-island-start, "
                f"{m:,} on the large island around (0, pi) (locked orbits), the hole of width "
                f"0.3 at phi_c = 0: {F.family_text(members)}; {others} starts on other islands "
                f"survive too ('destroy all': at most {R.pct(R.DESTROYED)} left, the "
                "measurement's floor).")
    return make_claim("sec3-destroy-all", evidence, analyses=members,
                      particles_per_curve=len(large))


def island_width_members(cls, hole_width, part):
    """The large island's phase width in hole widths, from the 5th-95th and the 1st-99th
    percentiles of its orbits' lowest and highest phases (a few orbits locked by chance while
    they wander are left out)."""
    large = cls.large
    out = []
    for q in (5, 1):
        width = float(np.percentile(cls.phase_hi[large], 100 - q)
                      - np.percentile(cls.phase_lo[large], q))
        ratio = width / hole_width
        out.append(F.word_member(f"percentiles {q}-{100 - q}: width {width:.2f}",
                                 "island width in hole widths", ratio, ratio, ratio,
                                 R.MUCH_SMALLER, R.MUCH_SMALLER_FAILS))
    return F.in_part(part, out)


def effective_destruction_claim(escape, island_sample, hole_width=0.3):
    """"effective destruction of islands using holes quite a lot smaller than the islands", in
    the escape problem (starts in the sea): escape through the hole over the island (phi_c = 0)
    is fast where the sea holes' is slowed by the islands' sticky orbits. Members:
    P_0(n)/P_sea(n) of the escape run at the sea holes' tail start n_tail and half a decade
    later, for both sea holes; and the island's width in hole widths (``island_sample``, the
    escape-island-start box classified)."""
    from reports.paper.claims.ordering_claims import survival_at
    from reports.paper.claims.register import SEA_HOLES
    from reports.paper.claims.window_family import STEP

    part = "effective destruction"
    members = []
    c0 = escape["0"]["curves"]["collisions"]
    for sea in SEA_HOLES:
        cs = escape[sea]["curves"]["collisions"]
        n_tail = escape[sea]["windows"].n_at.get("tail")
        if n_tail is None:
            continue
        for n_at in (n_tail, n_tail * STEP ** 2):
            k = int(np.searchsorted(c0.x, n_at))
            (p, (p_lo, p_hi)), (q, (q_lo, q_hi)) = survival_at(c0, k), survival_at(cs, k)
            members.append(F.in_part(part, [F.word_member(
                f"escape run, n = {c0.x[k]:.4g}: P = {p:.3g} (phi_c = 0) against {q:.3g} "
                f"(phi_c = {sea})", "survival ratio", p / q if q > 0 else math.nan,
                p_lo / q_hi if q_hi > 0 else math.nan, p_hi / q_lo if q_lo > 0 else math.nan,
                R.DESTROYED, R.DESTROYED_FAILS)])[0])
    cls = island_sample[2]
    if cls.large.any():
        members += island_width_members(cls, hole_width, "quite a lot smaller")
    return make_claim("sec3-effective-destruction", F.family_text(members) + ".",
                      analyses=members, particles_per_curve=c0.particles)


__all__ = ["destroy_all_claim", "effective_destruction_claim", "followed_curve",
           "island_start_claim", "other_box_claim", "other_density_claim"]
