"""The paper's escape claims (Section 3, Fig. 2) decided on an escape run and the sampled studies.

``escape_analysis(run_dir, onset_t)`` reads every curve, places its regimes
(``reports.paper.studies.escape_regimes``) and fits the three laws on each (maximum likelihood on
the binned, censored counts, ``reports.stats``; the figure draws these). ``escape_claims(analysis,
run_dir, studies)`` decides every claim of the register (``reports.paper.claims.register``) as the
agreement of its family of analyses (``reports.paper.claims.family``): the form claims here, the
others in ``same_power_claims``, ``joint_claims`` and ``ordering_claims``.
"""

from __future__ import annotations

import itertools
from pathlib import Path

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.joint_claims import bounded_velocity_claim, n_sqrt_t_claim
from reports.paper.claims.ordering_claims import sea_slowed_claim, stages_claim
from reports.paper.claims.register import ISLAND_HOLES, SEA_HOLES, make_claim
from reports.paper.claims.same_power_claims import same_power_claim
from reports.paper.claims.window_family import (
    inside_windows,
    late_windows,
    limit_windows,
    window_label,
)
from reports.paper.claims.window_members import alpha_of, beta_member, escapes_in
from reports.paper.studies.escape_regimes import escape_windows, window_text
from reports.stats.histogram import read_run
from reports.stats.regime_fit import window_detail


def hole_of(name):
    return name.split("=", 1)[1]


def escape_analysis(run_dir, onset_t):
    """{hole: {"curves": {clock: Curve}, "windows": EscapeWindows, "details": {(clock,
    regime): window_detail}}} of an escape run."""
    curves = {}
    for c in read_run(run_dir):
        curves.setdefault(hole_of(c.experiment), {})[c.clock] = c
    out = {}
    for hole, cs in curves.items():
        w = escape_windows(hole, cs["collisions"], cs["time"], onset_t)
        details = {}
        for clock, regimes in (("collisions", w.n), ("time", w.t)):
            for regime, window in regimes.items():
                if window is not None:
                    details[clock, regime] = window_detail(cs[clock], *window)
        out[hole] = {"curves": cs, "windows": w, "details": details}
    return out


def regime_windows(curve, window, regime, min_escapes, limit=False):
    """The window family of a regime (``reports.paper.claims.window_family``): inside a bounded
    (intermediate) regime; the late windows of a tail; their latest ones where the words speak
    of a limit."""
    if regime == "intermediate":
        return inside_windows(curve, *window, min_escapes)
    if limit:
        return limit_windows(curve, *window, min_escapes)
    return late_windows(curve, *window, min_escapes)


def form_claim(claim_id, a, clock, regime, form, min_escapes, run, close=False, limit=False):
    """A form word ("exponential", "algebraic", "close to sqrt(t)") on every window of the
    regime's family: the form rule on each window's beta."""
    curve = a["curves"][clock]
    window = (a["windows"].n if clock == "collisions" else a["windows"].t).get(regime)
    unit = "n" if clock == "collisions" else "t"
    if window is None:
        return make_claim(claim_id, f"No {regime} window in {unit}: "
                          f"{window_text(curve, window, unit)} (the data do not reach it at "
                          f"{curve.particles:,} particles).",
                          particles_per_curve=curve.particles, run=run)
    members = [beta_member(curve, w, form, unit, close)
               for w in regime_windows(curve, window, regime, min_escapes, limit)]
    band = R.form_range(form, close)
    evidence = (f"{regime.capitalize()} regime {window_text(curve, window, unit)}; "
                f"{'band' if close else 'cell'} of '{form.replace('_', ' ')}' "
                f"[{band[0]:g}, {band[1]:g}]; windows with at least {min_escapes} escapes: "
                f"{F.family_text(members) or 'none'}.")
    return make_claim(claim_id, evidence, analyses=members,
                      particles_per_curve=curve.particles,
                      statistical={"beta": {m.variant: m.value for m in members}}, run=run)


def finite_times_claim(analysis, run):
    """"clear stretched exponential decay is observed, at least for finite times and in some
    situations": the continuous-time intermediate regime of each hole over the islands (a part
    each), every window inside it a member: confirmed if the model selection picks the
    stretched exponential and beta lies in the sqrt cell (neither exponential nor power law)."""
    from reports.paper.claims.well_approximated_claims import selection_member

    members = []
    for h in ISLAND_HOLES:
        a = analysis.get(h)
        window = a["windows"].t.get("intermediate") if a else None
        if window is None:
            continue
        c = a["curves"]["time"]
        for w in inside_windows(c, *window, R.MIN_ESCAPES_INTERMEDIATE):
            members.append(selection_member(c, w, "t", f"phi_c = {h}"))
            members.append(F.in_part(f"phi_c = {h}", [beta_member(c, w, "sqrt", "t")])[0])
    n = next(iter(analysis.values()))["curves"]["time"].particles
    return make_claim("intro-finite-times", f"{F.family_text(members) or 'no window'}.",
                      analyses=members, particles_per_curve=n, run=run)


def universal_claim(analysis, run):
    """"We do not observe a universal law": the late-tail exponents alpha_n of the holes
    differ. One member per rank r of the tail's late windows (each hole's window starting r
    quarter decades after its tail's start), among the holes whose tail holds such a window
    with enough escapes (at least two): the largest relative difference over pairs of holes,
    its interval [largest lower end, largest upper end] ("the same" rule per pair), confirmed
    if some pair differs beyond ``rules.SAME_FAILS``, refuted if every pair is the same within
    ``rules.SAME``."""
    windows = {}
    for hole, a in analysis.items():
        w = a["windows"].n.get("tail")
        if w is not None:
            c = a["curves"]["collisions"]
            windows[hole] = (c, late_windows(c, *w, R.MIN_ESCAPES_TAIL))
    members, texts = [], []
    for r in range(max((len(ws) for _, ws in windows.values()), default=0)):
        alphas = {}
        for hole, (c, ws) in windows.items():
            if r < len(ws):
                alpha, _, half = alpha_of(c, ws[r])
                alphas[hole] = (alpha, half, window_label(c, ws[r], "n"), escapes_in(c, ws[r]))
        pairs = []
        for (h1, (a1, u1, *_)), (h2, (a2, u2, *_)) in itertools.combinations(alphas.items(), 2):
            lo, hi, m = R.same_difference(a1, u1, a2, u2)
            pairs.append((lo / m, abs(a1 - a2) / m, hi / m, f"{h1} vs {h2}"))
        if not pairs:
            continue
        top = max(pairs, key=lambda p: p[0])
        rank = "from the tail's start" if r == 0 else f"{r} quarter decade(s) later"
        members.append(F.word_member(
            f"tail windows {rank} ({len(alphas)} holes): largest difference {top[3]}",
            "relative difference", top[1], top[0], max(p[2] for p in pairs), R.SAME_FAILS,
            R.SAME))
        texts.append(f"{rank}: " + ", ".join(f"phi_c = {h} alpha = {al:.3f} +- {u:.2g} "
                                              f"({lab}, {e:,} escapes)"
                                              for h, (al, u, lab, e) in alphas.items()))
    evidence = ("Late-tail power-law exponents (discrete time), the tail's late windows of "
                f"every hole: {'; '.join(texts) or 'no hole has a tail'}; family: "
                f"{F.family_text(members) or 'none'}.")
    n = next(iter(analysis.values()))["curves"]["collisions"].particles
    return make_claim("intro-universal", evidence, analyses=members, particles_per_curve=n,
                      run=run)


def escape_claims(analysis, run_dir, studies=None, tails=None):
    """Every Fig. 2 / Section 3 claim decided on the run and the joint (n, t) data:
    ``studies`` = {"joint": {hole: JointSample}, "follow": {hole: Followed} (the survivors'
    snapshots), "snapshot": {hole: (n, ...)}}, each optional. ``tails``: {hole: (analysis,
    run directory)} of runs of one island hole alone with more starts (scenes
    escape-tail-phi_c=H): its discrete-time tail claim is decided on that run."""
    tails = tails or {}
    run = Path(run_dir).name
    studies = studies or {}
    joint = studies.get("joint", {})
    follow = studies.get("follow", {})
    snap = studies.get("snapshot", {})
    claims = []
    for h in ISLAND_HOLES:
        if h in analysis:
            claims.append(form_claim(f"fig2-n-phi_c={h}", analysis[h], "collisions",
                                     "intermediate", "exponential",
                                     R.MIN_ESCAPES_INTERMEDIATE, run))
    for h in SEA_HOLES:
        if h in analysis:
            claims.append(form_claim(f"fig2-n-phi_c={h}", analysis[h], "collisions", "tail",
                                     "power_law", R.MIN_ESCAPES_TAIL, run))
    for h in ISLAND_HOLES:
        if h in analysis:
            tail, tail_run = tails.get(h, (analysis[h], run_dir))
            claims.append(form_claim(f"fig2-n-tail-phi_c={h}", tail, "collisions", "tail",
                                     "power_law", R.MIN_ESCAPES_TAIL, Path(tail_run).name,
                                     limit=True))
            claims.append(form_claim(f"fig2-t-phi_c={h}", analysis[h], "time", "intermediate",
                                     "sqrt", R.MIN_ESCAPES_INTERMEDIATE, run, close=True))
    for h in SEA_HOLES:
        if h in analysis:
            claims.append(form_claim(f"fig2-t-phi_c={h}", analysis[h], "time", "intermediate",
                                     "sqrt", R.MIN_ESCAPES_INTERMEDIATE, run))
    if any(h in analysis for h in ISLAND_HOLES):
        claims.append(finite_times_claim(analysis, run))
    for h in ISLAND_HOLES + SEA_HOLES:
        if h in analysis:
            claims.append(same_power_claim(h, analysis[h], run))
            claims.append(bounded_velocity_claim(h, analysis[h], joint.get(h), run))
    if all(s in analysis for s in SEA_HOLES):
        for h in ISLAND_HOLES:
            if h in analysis:
                claims.append(stages_claim(h, analysis, run))
    if all(i in analysis for i in ISLAND_HOLES):
        for h in SEA_HOLES:
            if h in analysis:
                claims.append(sea_slowed_claim(h, analysis, follow.get(h), snap.get(h), run))
    for h in ISLAND_HOLES:
        if h in analysis:
            claims.append(n_sqrt_t_claim(h, analysis[h], joint.get(h), run))
    claims.append(universal_claim(analysis, run))
    return claims
