"""The paper's escape claims (Section 3, Fig. 2) decided on an escape run and the sampled studies.

``escape_analysis(run_dir, onset_t)`` reads every curve, places its windows
(``reports.paper.escape_regimes``) and fits the three laws on each (maximum likelihood on the
binned, censored counts, ``reports.stats``). ``escape_claims(analysis, run_dir, studies)`` applies
the rules of the register (``reports.paper.register``, tolerances in ``reports.paper.rules``).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from pathlib import Path

import numpy as np

from reports.paper import rules as R
from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.escape_regimes import escape_windows, window_text
from reports.paper.register import ISLAND_HOLES, SEA_HOLES, make_claim
from reports.runs.survival import wilson
from reports.stats.hazard import all_cause_survival, quantile
from reports.stats.histogram import read_run
from reports.stats.regime_fit import half_width, window_detail

BOOTSTRAP = 200
SLOPE_SEED = 20120906


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


def _g(x, digits=3):
    if x is None:
        return "n/a"
    return "inf" if x == math.inf else f"{x:.{digits}g}"


def _beta_text(detail, verdict_parts):
    _, beta, ci, sys, wide = verdict_parts
    laws = detail["fits"]
    return (f"beta = {beta:.3f} [{ci[0]:.3f}, {ci[1]:.3f}] +- {_g(sys, 2)} (sys), widened "
            f"[{wide[0]:.3f}, {wide[1]:.3f}]; best of the three laws: "
            f"{detail['best'].replace('_', ' ')} (log-likelihood stretched - exponential = "
            f"{laws['stretched_exponential'].loglik - laws['exponential'].loglik:.4g}, "
            f"stretched - power law = "
            f"{laws['stretched_exponential'].loglik - laws['power_law'].loglik:.4g})")


def _form_claim(claim_id, a, clock, regime, form, min_escapes, run, close=False, extra=""):
    curve = a["curves"][clock]
    window = (a["windows"].n if clock == "collisions" else a["windows"].t).get(regime)
    unit = "n" if clock == "collisions" else "t"
    detail = a["details"].get((clock, regime))
    if detail is None:
        return make_claim(claim_id, INCONCLUSIVE, f"No {regime} window in {unit}: "
                          f"{window_text(curve, window, unit)} (the data do not reach it at "
                          f"{curve.particles:,} particles).{extra}",
                          particles_per_curve=curve.particles, run=run)
    parts = R.form_verdict(detail, form, min_escapes, close)
    verdict = parts[0]
    few = (f" Fewer than {min_escapes} escapes: too few to decide."
           if detail["escapes"] < min_escapes else "")
    evidence = (f"{regime.capitalize()} window {window_text(curve, window, unit)}: "
                f"{_beta_text(detail, parts)}; {'band' if close else 'cell'} of "
                f"'{form.replace('_', ' ')}' [{R.form_range(form, close)[0]:g}, "
                f"{R.form_range(form, close)[1]:g}].{few}{extra}")
    return make_claim(claim_id, verdict, evidence, particles_per_curve=curve.particles,
                      statistical={"beta": parts[1], "beta_ci95": list(parts[2]),
                                   "escapes": detail["escapes"]},
                      systematic={"beta": parts[3]}, run=run)


def _alpha(detail):
    fit = detail["fits"]["power_law"]
    ci = fit.ci95.get("alpha", (math.nan, math.nan))
    sys = detail["systematic"]["power_law"]["alpha"]
    sys = math.inf if sys is None else sys
    return fit.params["alpha"], ci, sys, half_width(ci) + sys


def same_power_claim(hole, a, run):
    cid = f"fig2-same-power-phi_c={hole}"
    w = a["windows"]
    dn, dt = a["details"].get(("collisions", "matched")), a["details"].get(("time", "matched"))
    n = a["curves"]["collisions"].particles
    if dn is None or dt is None:
        return make_claim(cid, INCONCLUSIVE, "The matched survival levels "
                          f"[{_g(w.level_end)}, {_g(w.level_tail)}] span less than two bins in "
                          f"{'n' if dn is None else 't'} at {n:,} particles: nothing to compare.",
                          particles_per_curve=n, run=run)
    a_n, ci_n, s_n, u_n = _alpha(dn)
    a_t, ci_t, s_t, u_t = _alpha(dt)
    verdict = R.same_verdict(a_n, u_n, a_t, u_t)
    note = R.same_note(a_n, u_n, a_t, u_t)
    share = chaotic_share(a, w.t["matched"][0])
    gone = ("" if share is None else
            f" The continuous-time intermediate law, extrapolated, accounts for {share:.3g} of "
            f"the survivors at the matched window's start")
    if min(dn["escapes"], dt["escapes"]) < R.MIN_ESCAPES_TAIL:
        verdict = INCONCLUSIVE
    elif share is None or share > R.CHAOTIC_GONE:
        verdict = INCONCLUSIVE
        gone += (f" (more than {R.pct(R.CHAOTIC_GONE)}, or no intermediate fit: the continuous "
                 "curve at these levels is not yet the non-accelerating population, so the "
                 "powers are not the paper's to compare)")
    evidence = (f"Survival levels {_g(w.level_tail)} down to {_g(w.level_end)}: "
                f"{window_text(a['curves']['collisions'], w.n['matched'], 'n')}, alpha_n = "
                f"{a_n:.3f} [{ci_n[0]:.3f}, {ci_n[1]:.3f}] +- {_g(s_n, 2)} (sys); "
                f"{window_text(a['curves']['time'], w.t['matched'], 't')}, alpha_t = {a_t:.3f} "
                f"[{ci_t[0]:.3f}, {ci_t[1]:.3f}] +- {_g(s_t, 2)} (sys); |alpha_n - alpha_t| = "
                f"{abs(a_n - a_t):.3f} against U = {_g(u_n + u_t, 2)}, the same within "
                f"{R.SAME} x mean = {R.SAME * 0.5 * (a_n + a_t):.3f}, different beyond "
                f"{R.SAME_FAILS} x mean = {R.SAME_FAILS * 0.5 * (a_n + a_t):.3f}"
                f"{' (' + note + ')' if note else ''}; best laws: "
                f"{dn['best'].replace('_', ' ')} (n), {dt['best'].replace('_', ' ')} (t).{gone}.")
    return make_claim(cid, verdict, evidence, particles_per_curve=n,
                      statistical={"alpha_n": a_n, "alpha_n_ci95": list(ci_n), "alpha_t": a_t,
                                   "alpha_t_ci95": list(ci_t)},
                      systematic={"alpha_n": s_n, "alpha_t": s_t}, run=run)


def chaotic_share(a, k):
    """S_fit(x_k)/S(x_k): the share of the continuous-time survivors at boundary k that the
    stretched law of the intermediate window, extrapolated from its start, accounts for (None
    without that fit)."""
    d = a["details"].get(("time", "intermediate"))
    if d is None:
        return None
    ct = a["curves"]["time"]
    s = all_cause_survival(ct)
    start = d["bins"][0]
    fit = d["fits"]["stretched_exponential"]
    predicted = s[start] * math.exp(float(fit.log_survival(np.array([ct.x[k]]))[0]))
    return predicted / s[k] if s[k] > 0 else math.inf


def matched_levels(level_hi, level_lo, per_decade=4):
    """Levels from level_hi down to level_lo, ``per_decade`` per decade, both ends included."""
    k = max(1, int(math.ceil(per_decade * math.log10(level_hi / level_lo))))
    return np.geomspace(level_hi, level_lo, k + 1)


def quantile_slope(curve_n, curve_t, levels):
    """Least-squares slope of log t_q against log n_q at the survival levels."""
    s_n, s_t = all_cause_survival(curve_n), all_cause_survival(curve_t)
    pts = [(quantile(curve_n.x, s_n, q), quantile(curve_t.x, s_t, q)) for q in levels]
    pts = [(n, t) for n, t in pts if n and t and n > 0 and t > 0]
    if len(pts) < 3:
        return math.nan, pts
    ln, lt = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return float(np.polyfit(ln, lt, 1)[0]), pts


def _resampled(curve, rng):
    """The curve with its escape and censoring counts redrawn (one multinomial draw)."""
    cells = np.concatenate([curve.escapes, curve.censored]).astype(np.float64)
    draw = rng.multinomial(curve.particles, cells / cells.sum())
    k = len(curve.escapes)
    return dataclasses.replace(curve, escapes=draw[:k], censored=draw[k:])


def _slope_median_ratio(n, t, n_lo, n_hi, per_decade=4):
    """(slope of log median(t/n) against log n over quarter-decade bins of n in [n_lo, n_hi]
    with at least 20 escapes, bins used). Binned by n, the variable the escapes were selected
    on (n > n_half): binning by t would keep only the slow particles at the small t."""
    use = (n >= n_lo) & (n <= n_hi) & (n > 0)
    if use.sum() < 50 or n_hi <= n_lo:
        return math.nan, 0
    edges = np.geomspace(n_lo, n_hi * (1 + 1e-12),
                         max(2, int(per_decade * math.log10(n_hi / n_lo))) + 1)
    idx = np.searchsorted(edges, n[use], side="right") - 1
    ratio = t[use] / n[use]
    pts = []
    for b in range(len(edges) - 1):
        sel = ratio[idx == b]
        if len(sel) >= 20:
            pts.append((math.sqrt(edges[b] * edges[b + 1]), float(np.median(sel))))
    if len(pts) < 2:
        return math.nan, len(pts)
    return float(np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]), 1)[0]), \
        len(pts)


def bounded_velocity_claim(hole, a, study, run):
    cid = f"fig2-bounded-velocity-phi_c={hole}"
    n_half = a["windows"].n_at.get("half")
    if study is None or n_half is None:
        return make_claim(cid, INCONCLUSIVE, "No sampled study, or the hazard never falls to "
                          "half its plateau.", run=run)
    late = (study.exit >= 0) & (study.n > n_half)
    n, t = study.n[late].astype(float), study.t[late]
    count = int(late.sum())
    if count < R.MIN_ESCAPES_TAIL:
        return make_claim(cid, INCONCLUSIVE, f"Sampled study of {study.particles:,} starts: "
                          f"{count} escapes after n_half = {n_half:g} (fewer than "
                          f"{R.MIN_ESCAPES_TAIL}): too few to decide; the slow decay needs a "
                          "larger sample with n and t recorded together.",
                          particles_per_curve=study.particles, run=None)
    n_lo, n_hi = float(n_half), float(n.max())
    slope, bins = _slope_median_ratio(n, t, n_lo, n_hi)
    if not math.isfinite(slope):
        return make_claim(cid, INCONCLUSIVE, f"Sampled study of {study.particles:,} starts: "
                          f"{count} escapes after n_half = {n_half:g}, n up to {n_hi:.4g}: "
                          f"{bins} quarter-decade(s) of n with enough escapes, too few for a "
                          "slope of t/n against n; the slow decay needs a larger sample with n "
                          "and t recorded together.",
                          particles_per_curve=study.particles, run=None)
    rng = np.random.default_rng(SLOPE_SEED)
    boot = []
    for _ in range(BOOTSTRAP):
        pick = rng.integers(0, count, count)
        boot.append(_slope_median_ratio(n[pick], t[pick], n_lo, n_hi)[0])
    boot = np.array([b for b in boot if math.isfinite(b)])
    ci = ((float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5)))
          if len(boot) > BOOTSTRAP // 2 else (math.nan, math.nan))
    verdict = R.two_band_verdict(*ci, R.BOUNDED, R.BOUNDED_FAILS)
    note = R.two_band_note(*ci, R.BOUNDED, R.BOUNDED_FAILS)
    ratio = t / n
    evidence = (f"Sampled study of {study.particles:,} starts: {count} escapes after n_half = "
                f"{n_half:g} (the slow population holds half the escapes), n up to {n_hi:.4g}; "
                f"mean time per collision t/n (twice the mean velocity): median "
                f"{np.median(ratio):.3g}, 5-95% {np.percentile(ratio, 5):.3g}-"
                f"{np.percentile(ratio, 95):.3g}; slope of log median(t/n) against log n over "
                f"{bins} quarter-decades = {_g(slope, 3)}, bootstrap 95% [{_g(ci[0], 3)}, "
                f"{_g(ci[1], 3)}] (0 for bounded velocity, 1/2 for velocity diffusion): bounded "
                f"within [{R.BOUNDED[0]:g}, {R.BOUNDED[1]:g}], not beyond "
                f"[{R.BOUNDED_FAILS[0]:g}, {R.BOUNDED_FAILS[1]:g}]"
                f"{' (' + note + ')' if note else ''}.")
    return make_claim(cid, verdict, evidence, particles_per_curve=study.particles,
                      statistical={"slope": slope, "slope_ci95": list(ci),
                                   "median_t_over_n": float(np.median(ratio))}, run=None)


def _survival_at(curve, k):
    s = all_cause_survival(curve)[k]
    lo, hi = wilson(round(s * curve.particles), curve.particles)
    return float(s), (float(lo), float(hi))


def _order(p, q):
    """+1 if interval p lies above q, -1 below, 0 if they overlap."""
    if p[1][0] > q[1][1]:
        return 1
    if p[1][1] < q[1][0]:
        return -1
    return 0


def stages_claim(hole, analysis, run):
    cid = f"fig2-stages-phi_c={hole}"
    a = analysis[hole]
    cn = a["curves"]["collisions"]
    w = a["windows"]
    inter = w.n.get("intermediate")
    if w.median_n is None or inter is None:
        return make_claim(cid, INCONCLUSIVE, "No median or no intermediate window.",
                          particles_per_curve=cn.particles, run=run)
    k_med = int(np.searchsorted(cn.x, w.median_n))
    k_end = inter[1]
    text, orders = [], []
    for k, want, when in ((k_med, 1, "early"), (k_end, -1, "intermediate")):
        mine = _survival_at(cn, k)
        for sea in SEA_HOLES:
            other = _survival_at(analysis[sea]["curves"]["collisions"], k)
            o = _order(mine, other)
            orders.append(o * want)
            text.append(f"{when} n = {cn.x[k]:.4g}: P = {mine[0]:.4g} against {other[0]:.4g} "
                        f"(phi_c = {sea})")
    verdict = (CONFIRMED if all(o == 1 for o in orders) else
               REFUTED if any(o == -1 for o in orders) else INCONCLUSIVE)
    return make_claim(cid, verdict, "; ".join(text) + " (95% Wilson bands disjoint where "
                      "ordered).", particles_per_curve=cn.particles, run=run)


def locked_share(snapshot):
    """(locked count, watched count) of survivors whose watched collisions are locked to a
    period-1 resonance: mean flight time 2 pi m within 1% for an integer m >= 1 and velocity
    range below 5 (``reports.paper.islands``)."""
    from reports.paper.islands import LOCK_TOLERANCE, REGULAR_BAND

    _, _, v, t = snapshot
    full = np.all(np.isfinite(t), axis=1)
    v, t = v[full], t[full]
    if not len(t):
        return 0, 0
    flight = (t[:, -1] - t[:, 0]) / (t.shape[1] - 1)
    m = np.maximum(np.round(flight / (2 * math.pi)), 1)
    locked = (np.abs(flight - 2 * math.pi * m) < LOCK_TOLERANCE * 2 * math.pi * m) & (
        v.max(axis=1) - v.min(axis=1) < REGULAR_BAND)
    return int(locked.sum()), int(len(t))


def sea_slowed_claim(hole, analysis, study, snapshot_n, run):
    cid = f"fig2-sea-slowed-phi_c={hole}"
    a = analysis[hole]
    cn = a["curves"]["collisions"]
    if snapshot_n is None or study is None or snapshot_n not in study.snapshots:
        return make_claim(cid, INCONCLUSIVE, "No sampled study with survivors at "
                          "the tail's start.", particles_per_curve=cn.particles, run=run)
    k, m = locked_share(study.snapshots[snapshot_n])
    lo, hi = (float(x) for x in wilson(k, m)) if m else (0.0, 1.0)
    most, most_fails = 1 - R.MOSTLY, 1 - R.MOSTLY_FAILS
    share = R.word_verdict(lo, hi, most, most_fails) if m else INCONCLUSIVE
    note = R.word_note(lo, hi, most, most_fails) if m else ""
    idx = int(np.searchsorted(cn.x, snapshot_n))  # S(x = n): still inside after collision n
    mine = _survival_at(cn, idx)
    orders = [_order(mine, _survival_at(analysis[i]["curves"]["collisions"], idx))
              for i in ISLAND_HOLES]
    above = CONFIRMED if all(o == 1 for o in orders) else (
        REFUTED if any(o == -1 for o in orders) else INCONCLUSIVE)
    verdict = R.all_of([share, above])
    evidence = (f"Sampled study of {study.particles:,} starts: {m} survivors after n = "
                f"{snapshot_n} watched for 200 collisions, {k} locked to a period-1 resonance "
                f"(share {k / m if m else math.nan:.3f}, 95% [{lo:.3f}, {hi:.3f}]; 'most' "
                f"{R.bounds_text(most, most_fails)}{': ' + note if note else ''}); run: P(n = "
                f"{cn.x[idx]:.4g}) = {mine[0]:.3g} against "
                + ", ".join(f"{_survival_at(analysis[i]['curves']['collisions'], idx)[0]:.3g} "
                            f"(phi_c = {i})" for i in ISLAND_HOLES) + ".")
    return make_claim(cid, verdict, evidence, particles_per_curve=cn.particles,
                      statistical={"locked_share": k / m if m else None,
                                   "locked_ci95": [lo, hi]}, run=run)


def _slope_median_n(n, t, t_lo, t_hi, per_decade=4):
    """(slope of log median n against log t over quarter-decade bins of t in [t_lo, t_hi],
    bins used)."""
    use = (t >= t_lo) & (t < t_hi)
    if use.sum() < 50:
        return math.nan, 0
    edges = np.geomspace(t_lo, t_hi, max(2, int(per_decade * math.log10(t_hi / t_lo))) + 1)
    idx = np.searchsorted(edges, t[use], side="right") - 1
    nn = n[use]
    pts = []
    for b in range(len(edges) - 1):
        sel = nn[idx == b]
        if len(sel) >= 20:
            pts.append((math.sqrt(edges[b] * edges[b + 1]), float(np.median(sel))))
    if len(pts) < 3:
        return math.nan, len(pts)
    return float(np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]), 1)[0]), \
        len(pts)


def n_sqrt_t_claim(hole, a, study, run):
    cid = f"sec3-n-sqrt-t-phi_c={hole}"
    ct = a["curves"]["time"]
    window = a["windows"].t.get("intermediate")
    if window is None or study is None:
        return make_claim(cid, INCONCLUSIVE, "No continuous intermediate window.",
                          particles_per_curve=None, run=run)
    t_lo, t_hi = float(ct.x[window[0]]), float(ct.x[window[1]])
    esc = study.exit >= 0
    n, t = study.n[esc].astype(float), study.t[esc]
    slope, bins = _slope_median_n(n, t, t_lo, t_hi)
    rng = np.random.default_rng(SLOPE_SEED)
    boot = []
    for _ in range(BOOTSTRAP):
        pick = rng.integers(0, len(n), len(n))
        boot.append(_slope_median_n(n[pick], t[pick], t_lo, t_hi)[0])
    boot = np.array([b for b in boot if math.isfinite(b)])
    ci = ((float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5)))
          if len(boot) > BOOTSTRAP // 2 else (math.nan, math.nan))
    f = 10 ** 0.25
    family = [_slope_median_n(n, t, lo, hi)[0] for lo in (t_lo / f, t_lo, t_lo * f)
              for hi in (t_hi / f, t_hi)]
    family = [s for s in family if math.isfinite(s)]
    sys = 0.5 * (max(family) - min(family)) if family else math.inf
    wide = (ci[0] - sys, ci[1] + sys)
    verdict = R.band_verdict(*wide, *R.form_range("sqrt", close=True))
    inside = int(((t >= t_lo) & (t < t_hi)).sum())
    evidence = (f"Sampled study of {study.particles:,} starts (verify spot check: "
                f"{study.verification['sampled']} collisions, worst "
                f"{study.verification['worst_error']:.2g} kappa*u, "
                f"{study.verification['overstepped']} overstepped), {inside:,} escapes with t in "
                f"the intermediate window [{t_lo:.4g}, {t_hi:.4g}] over {bins} quarter-decades: "
                f"slope of log median n against log t = {_g(slope, 4)} [{_g(ci[0], 4)}, "
                f"{_g(ci[1], 4)}] +- {_g(sys, 2)} (window family), widened [{_g(wide[0], 3)}, "
                f"{_g(wide[1], 3)}]; n ~ t^(1/2) band [0.4, 0.6], n ~ t^(2/3) would be the "
                "closed system's typical orbit.")
    return make_claim(cid, verdict, evidence, particles_per_curve=study.particles,
                      statistical={"slope": slope, "slope_ci95": list(ci)},
                      systematic={"slope": sys}, run=None)


def universal_claim(analysis, run):
    alphas = {}
    for hole, a in analysis.items():
        d = a["details"].get(("collisions", "tail"))
        if d is not None and d["escapes"] >= R.MIN_ESCAPES_TAIL:
            alphas[hole] = _alpha(d)
    pairs = {}
    for (h1, (a1, _, _, u1)), (h2, (a2, _, _, u2)) in itertools.combinations(alphas.items(), 2):
        pairs[h1, h2] = R.same_verdict(a1, u1, a2, u2)
    if any(v == REFUTED for v in pairs.values()):
        verdict = CONFIRMED
    elif pairs and all(v == CONFIRMED for v in pairs.values()):
        verdict = REFUTED
    else:
        verdict = INCONCLUSIVE
    differ = [f"{h1} vs {h2}" for (h1, h2), v in pairs.items() if v == REFUTED]
    between = [f"{h1} vs {h2}" for (h1, h2), (a1, _, _, u1), (a2, _, _, u2) in
               ((k, alphas[k[0]], alphas[k[1]]) for k in pairs)
               if R.same_note(a1, u1, a2, u2) == R.BETWEEN]
    beyond = f"at least {R.pct(R.SAME_FAILS)} apart beyond their uncertainties"
    evidence = ("Late-tail power-law exponents (discrete time): "
                + ", ".join(f"phi_c = {h}: alpha = {a:.3f} +- {_g(u, 2)}"
                            for h, (a, _, _, u) in alphas.items())
                + (f"; pairs {beyond}: {', '.join(differ)}" if differ else
                   f"; no pair {beyond}")
                + (f"; pairs {R.BETWEEN} ({R.pct(R.SAME)}, {R.pct(R.SAME_FAILS)}): "
                   f"{', '.join(between)}" if between else "") + ".")
    n = next(iter(analysis.values()))["curves"]["collisions"].particles
    return make_claim("intro-universal", verdict, evidence, particles_per_curve=n,
                      statistical={h: a for h, (a, _, _, _) in alphas.items()},
                      systematic={h: s for h, (_, _, s, _) in alphas.items()}, run=run)


def escape_claims(analysis, run_dir, studies=None):
    """Every Fig. 2 / Section 3 claim decided on the run (and the sampled studies: a dict
    {"follow": {hole: Followed}, "snapshot": {hole: n}}, optional)."""
    run = Path(run_dir).name
    studies = studies or {}
    follow = studies.get("follow", {})
    snap = studies.get("snapshot", {})
    claims = []
    for h in ISLAND_HOLES:
        if h in analysis:
            claims.append(_form_claim(f"fig2-n-phi_c={h}", analysis[h], "collisions",
                                      "intermediate", "exponential",
                                      R.MIN_ESCAPES_INTERMEDIATE, run))
    for h in SEA_HOLES:
        if h in analysis:
            claims.append(_form_claim(f"fig2-n-phi_c={h}", analysis[h], "collisions", "tail",
                                      "power_law", R.MIN_ESCAPES_TAIL, run))
    for h in ISLAND_HOLES:
        if h in analysis:
            claims.append(_form_claim(f"fig2-n-tail-phi_c={h}", analysis[h], "collisions",
                                      "tail", "power_law", R.MIN_ESCAPES_TAIL, run))
            claims.append(_form_claim(f"fig2-t-phi_c={h}", analysis[h], "time", "intermediate",
                                      "sqrt", R.MIN_ESCAPES_INTERMEDIATE, run, close=True))
    for h in ISLAND_HOLES + SEA_HOLES:
        if h in analysis:
            claims.append(same_power_claim(h, analysis[h], run))
            claims.append(bounded_velocity_claim(h, analysis[h], follow.get(h), run))
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
            claims.append(n_sqrt_t_claim(h, analysis[h], follow.get(h), run))
    claims.append(universal_claim(analysis, run))
    return claims
