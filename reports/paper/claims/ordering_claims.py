"""Claims that order escape curves (Section 3): a hole over the islands decays "initially
slower ... faster at intermediate times" than the holes in the sea; where the hole is in the
sea, "decay is generally slowed by the available large elliptic islands".

An ordering of two survivals P and Q at the same n is read on the ratio P/Q with the interval
[P_lo/Q_hi, P_hi/Q_lo] of their 95% Wilson intervals; of two escape rates on their ratio with
Poisson intervals: "above" ("faster") holds if the interval lies at or above 1 and fails if it
lies at or below 1 (an ordering has one threshold, decided beyond the data's resolution).
"""

from __future__ import annotations

import math

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import ISLAND_HOLES, SEA_HOLES, make_claim
from reports.paper.claims.window_family import STEP
from reports.runs.survival import wilson
from reports.stats.hazard import all_cause_survival, first_below, hazard

EARLY_LEVELS = (0.75, 0.5)  # "initially": where this hole's P falls to 3/4 and to 1/2


def survival_at(curve, k):
    """(S(x_k), its 95% Wilson interval)."""
    s = all_cause_survival(curve)[k]
    lo, hi = wilson(round(s * curve.particles), curve.particles)
    return float(s), (float(lo), float(hi))


def above_member(variant, mine, other, part):
    """Member: ``mine`` lies above ``other`` (module docstring)."""
    (p, (p_lo, p_hi)), (q, (q_lo, q_hi)) = mine, other
    ratio = p / q if q > 0 else math.inf
    lo = p_lo / q_hi if q_hi > 0 else math.inf
    hi = p_hi / q_lo if q_lo > 0 else math.inf
    return F.in_part(part, [F.threshold_member(variant, "ratio of survivals", ratio, lo, hi,
                                               1.0, False)])[0]


def hazard_at(curve, x):
    """(escape rate per collision, escapes) over the quarter-decade hazard group holding x."""
    groups, lam = hazard(curve)
    for (a, b), rate in zip(groups, lam, strict=True):
        if curve.x[a] <= x < curve.x[b]:
            return float(rate), int(curve.escapes[a:b].sum())
    return math.nan, 0


def faster_member(variant, mine, other, part):
    """Member: the hazard ``mine`` = (rate, escapes) exceeds ``other``: their ratio with the
    95% interval exp(+-1.96 sqrt(1/E_1 + 1/E_2)) of Poisson counts, above 1."""
    (r1, e1), (r2, e2) = mine, other
    if not (e1 and e2 and r2 > 0):
        return F.in_part(part, [F.too_few(variant, "ratio of escape rates")])[0]
    ratio = r1 / r2
    spread = math.exp(1.96 * math.sqrt(1 / e1 + 1 / e2))
    return F.in_part(part, [F.threshold_member(variant, "ratio of escape rates", ratio,
                                               ratio / spread, ratio * spread, 1.0, False)])[0]


def stages_claim(hole, analysis, run):
    """"decay is initially slower ... faster at intermediate times" than through the sea
    holes: two parts, each read on the escape rate (the hazard per collision, a quarter decade
    of n) at two points of its stage and on the survival where the stage ends, against both sea
    holes. Early: where this hole's P falls to 3/4 and to 1/2 (the rates), P at the second;
    intermediate: the middle and the end of its intermediate window (the rates), P at the
    end."""
    cid = f"fig2-stages-phi_c={hole}"
    a = analysis[hole]
    cn = a["curves"]["collisions"]
    inter = a["windows"].n.get("intermediate")
    if inter is None:
        return make_claim(cid, "No intermediate window.", particles_per_curve=cn.particles,
                          run=run)
    s = all_cause_survival(cn)
    early = [first_below(s, q) for q in EARLY_LEVELS]
    a_i, b_i = inter
    middle = int(np.searchsorted(cn.x, math.sqrt(cn.x[a_i] * cn.x[b_i])))
    members = []
    for points, part, slower in ((early, "slower at first", True),
                                 ([middle, b_i], "faster at intermediate times", False)):
        points = [k for k in points if k is not None]
        for sea in SEA_HOLES:
            cs = analysis[sea]["curves"]["collisions"]
            for k in points:
                mine, other = hazard_at(cn, cn.x[k]), hazard_at(cs, cn.x[k])
                pair = (other, mine) if slower else (mine, other)
                members.append(faster_member(
                    f"rate at n = {cn.x[k]:.4g}: {mine[0]:.3g} against {other[0]:.3g} "
                    f"(phi_c = {sea})", *pair, part))
            if points:
                k = points[-1]
                mine, other = survival_at(cn, k), survival_at(cs, k)
                pair = (mine, other) if slower else (other, mine)
                members.append(above_member(
                    f"P at n = {cn.x[k]:.4g}: {mine[0]:.4g} against {other[0]:.4g} "
                    f"(phi_c = {sea})", *pair, part))
    return make_claim(cid, f"Escape rates (Poisson intervals) and survivals (95% Wilson): "
                      f"{F.family_text(members)}.", analyses=members,
                      particles_per_curve=cn.particles, run=run)


def locked_share(snapshot):
    """(locked count, watched count) of survivors whose watched collisions are locked to a
    period-1 resonance: mean flight time 2 pi m within 1% for an integer m >= 1 and velocity
    range below 5 (``reports.paper.studies.islands``)."""
    from reports.paper.studies.islands import LOCK_TOLERANCE, REGULAR_BAND

    _, _, v, t = snapshot
    full = np.all(np.isfinite(t), axis=1)
    v, t = v[full], t[full]
    if not len(t):
        return 0, 0
    flight = (t[:, -1] - t[:, 0]) / (t.shape[1] - 1)
    m = np.maximum(np.round(flight / TWO_PI), 1)
    locked = (np.abs(flight - TWO_PI * m) < LOCK_TOLERANCE * TWO_PI * m) & (
        v.max(axis=1) - v.min(axis=1) < REGULAR_BAND)
    return int(locked.sum()), int(len(t))


def snapshot_times(n_tail):
    """Collisions after which the sea holes' survivors are watched: the late tail's start and
    half a decade later."""
    return (int(n_tail), int(round(n_tail * STEP ** 2)))


def sea_slowed_claim(hole, analysis, study, snapshots, run):
    """``snapshots``: the collisions after which ``study`` watched survivors
    (``snapshot_times``)."""
    cid = f"fig2-sea-slowed-phi_c={hole}"
    a = analysis[hole]
    cn = a["curves"]["collisions"]
    members = []
    most, most_fails = 1 - R.MOSTLY, 1 - R.MOSTLY_FAILS
    for s in snapshots or ():
        if study is None or s not in study.snapshots:
            continue
        k, m = locked_share(study.snapshots[s])
        if m == 0:
            continue
        lo, hi = (float(x) for x in wilson(k, m))
        members.append(F.in_part("late survivors on the large islands", [F.word_member(
            f"{m} survivors after n = {s} watched for 200 collisions, {k} locked",
            "share locked to a period-1 resonance", k / m, lo, hi, most, most_fails)])[0])
        idx = int(np.searchsorted(cn.x, s))  # S(x = n): still inside after collision n
        mine = survival_at(cn, idx)
        for i in ISLAND_HOLES:
            other = survival_at(analysis[i]["curves"]["collisions"], idx)
            members.append(above_member(
                f"n = {cn.x[idx]:.4g}: P = {mine[0]:.3g} against {other[0]:.3g} (phi_c = {i})",
                mine, other, "slower than through the island holes"))
    source = f"Sampled study of {study.particles:,} starts" if study else "No sampled study"
    evidence = (f"{source}; 'most' {R.bounds_text(most, most_fails)}: "
                f"{F.family_text(members) or 'none'}.")
    return make_claim(cid, evidence, analyses=members, particles_per_curve=cn.particles,
                      run=run)
