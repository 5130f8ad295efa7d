"""The paper's transport claims (Section 4, Figs. 3-4) decided on a transport run and the sampled
study of h = 1 (``reports.paper.studies.transport_sample``); rules in the register
(``reports.paper.register``), tolerances in ``reports.paper.rules``.

Curves: ``transport_analysis(run_dir)`` maps width -> entry hole (1, 2) -> clock -> {"P11": Curve,
...}; P_ij(x) is ``reports.stats.hazard.curve_probability`` (escapes through j after x, over the
N entrants of hole i), the entrants still inside are the all-cause survival of either curve.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from reports.paper import rules as R
from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.register import TRAPPING_WIDTHS, make_claim
from reports.runs.survival import wilson
from reports.stats.analysis import fit_all, usable_range
from reports.stats.hazard import all_cause_survival, curve_probability, first_below, quantile
from reports.stats.histogram import read_run
from reports.stats.likelihood import window_of
from reports.stats.regime_fit import window_detail

START_V_MAX = 4.0  # the paper's starts have 2 < v < 4
BIN_MARGIN = 10 ** (1 / 20)  # one bin of the runs' grid (20 per decade)
MIN_PER_BIN = 100
FINITE_TIME_LEVEL = 0.1  # the last part of the decay: the last 10% of the entrants
FINITE_TIME_BINS = 5     # and at least five bins


def transport_analysis(run_dir):
    out = {}
    for c in read_run(run_dir):
        width = c.experiment.split("/")[0].split("=", 1)[1]
        entry = int(c.experiment.rsplit(" ", 1)[1])
        out.setdefault(width, {}).setdefault(entry, {}).setdefault(c.clock, {})[
            c.curve.split("/")[1]] = c
    return out


def _pct_ci(k, n):
    lo, hi = wilson(k, n)
    return float(lo), float(hi)


def eventual_claim(h, tr, run):
    parts, verdicts = [], []
    for entry in (1, 2):
        c = next(iter(tr[entry]["collisions"].values()))
        left = int(c.censored.sum())
        ci = _pct_ci(left, c.particles)
        verdicts.append(R.fraction_at_most(left, c.particles, R.ESCAPED_TO, ci))
        parts.append(f"entry hole {entry}: {left} of {c.particles:,} still inside at the horizon "
                     f"(share {left / c.particles:.3g}, 95% [{ci[0]:.2g}, {ci[1]:.2g}])")
    n = next(iter(tr[1]["collisions"].values())).particles
    return make_claim(f"sec4-eventual-h={h}", R.all_of(verdicts), "; ".join(parts) + ".",
                      particles_per_curve=n, run=run)


def level_times(tr, clock, level):
    """{(i, j): x at which P_ij falls to ``level`` (0 if it starts below it)}."""
    out = {}
    for entry in (1, 2):
        for ij, c in tr[entry][clock].items():
            p = curve_probability(c)
            out[ij] = 0.0 if p[0] <= level else (quantile(c.x, p, level) or math.nan)
    return out


def strong_measure(tr):
    """(ratio t_11 / max of the other t_ij, the level q, the times)."""
    n = next(iter(tr[1]["time"].values())).particles
    q = max(1e-6, R.SURVIVORS_MIN / n)
    times = level_times(tr, "time", q)
    others = max(v for k, v in times.items() if k != "P11")
    ratio = times["P11"] / others if others > 0 else math.inf
    return ratio, q, times


def strong_interval(ratio):
    """The ratio t_11 / max(others) widened by one bin of the grid either way."""
    return ratio / BIN_MARGIN, ratio * BIN_MARGIN


def strong_verdict(ratio):
    """"very strong P_11": confirmed if the widened ratio lies at or above ``rules.DECADE``,
    refuted if at or below ``rules.STRONG_FAILS``, inconclusive otherwise (or NaN)."""
    return R.word_verdict(*strong_interval(ratio), R.DECADE, R.STRONG_FAILS)


def strong_claim(h, tr, run):
    ratio, q, times = strong_measure(tr)
    if q > R.LONG_LIVED_LEVEL:
        n = next(iter(tr[1]["time"].values())).particles
        return make_claim(f"fig3-h={h}", INCONCLUSIVE, f"At {n:,} particles the level q = "
                          f"100/N = {q:.2g} is above the long-lived level {R.LONG_LIVED_LEVEL:g}:"
                          " the data do not reach the late times (needs N >= 10^6).",
                          particles_per_curve=n, run=run)
    lo, hi = strong_interval(ratio)
    note = R.word_note(lo, hi, R.DECADE, R.STRONG_FAILS)
    evidence = (f"Times at which P_ij(t) falls to q = {q:.2g}: "
                + ", ".join(f"{k} {v:.4g}" for k, v in sorted(times.items()))
                + f"; t_11 / max(others) = {ratio:.3g}, one bin either way [{lo:.3g}, {hi:.3g}];"
                f" 'very strong' {R.bounds_text(R.DECADE, R.STRONG_FAILS, '{:g}'.format)}"
                + (f" ({note})" if note else "") + ".")
    n = next(iter(tr[1]["time"].values())).particles
    return make_claim(f"fig3-h={h}", strong_verdict(ratio), evidence, particles_per_curve=n,
                      statistical={"ratio": ratio, "times": times}, run=run)


def long_lived_index(tr, clock):
    """(boundary index where the entrants of hole 1 still inside fall to LONG_LIVED_LEVEL, or
    None; the curves of entry 1)."""
    curves = tr[1][clock]
    s = all_cause_survival(curves["P11"])
    return first_below(s, R.LONG_LIVED_LEVEL), curves


def trap_measure(tr):
    """(k11, k12, share through hole 2, its Wilson interval, time) at the long-lived time."""
    k, curves = long_lived_index(tr, "time")
    if k is None:
        return None
    n = curves["P11"].particles
    k11 = round(curve_probability(curves["P11"])[k] * n)
    k12 = round(curve_probability(curves["P12"])[k] * n)
    m = k11 + k12
    if m == 0:
        return None
    return k11, k12, k12 / m, _pct_ci(k12, m), float(curves["P11"].x[k])


def trap_claim(claim_id, tr, run, traps_expected):
    n = next(iter(tr[1]["time"].values())).particles
    got = trap_measure(tr)
    if got is None or got[0] + got[1] < R.SURVIVORS_MIN:
        return make_claim(claim_id, INCONCLUSIVE, f"Fewer than {R.SURVIVORS_MIN} entrants of "
                          f"hole 1 are still inside at the level {R.LONG_LIVED_LEVEL:g} at "
                          f"{n:,} particles.", particles_per_curve=n, run=run)
    k11, k12, share, ci, t = got
    trapped = R.word_verdict(*ci, R.TRAP_SHARE, R.TRAP_SHARE_FAILS)
    note = R.word_note(*ci, R.TRAP_SHARE, R.TRAP_SHARE_FAILS)
    verdict = trapped if traps_expected else {CONFIRMED: REFUTED, REFUTED: CONFIRMED}.get(
        trapped, INCONCLUSIVE)
    later = _later_ratios(tr[1]["time"], t)
    evidence = (f"At t = {t:.4g}, where the entrants of hole 1 still inside fall to "
                f"{R.LONG_LIVED_LEVEL:g}: {k11:,} will leave by hole 1 and {k12:,} by hole 2, "
                f"share through hole 2 = {share:.4f} (95% [{ci[0]:.4f}, {ci[1]:.4f}]): traps at "
                f"<= {R.pct(R.TRAP_SHARE)}, does not trap at >= {R.pct(R.TRAP_SHARE_FAILS)}"
                f"{' (' + note + ')' if note else ''}; P_12/P_11 later: "
                f"{', '.join(later) or 'n/a'}; last "
                f"escape through hole 2 at t < {_last_escape(tr[1]['time']['P12']):.4g}, "
                f"through hole 1 at t < {_last_escape(tr[1]['time']['P11']):.4g}; from hole 2,"
                f" P_21 ends at t < {_last_escape(tr[2]['time']['P21']):.4g}, P_22 at t < "
                f"{_last_escape(tr[2]['time']['P22']):.4g}.")
    return make_claim(claim_id, verdict, evidence, particles_per_curve=n,
                      statistical={"share_hole_2": share, "share_ci95": list(ci), "t": t},
                      run=run)


def _later_ratios(curves, t):
    """'P_12/P_11 at t' at every fifth boundary from t on while P_11 holds 100 particles."""
    p11, p12 = curve_probability(curves["P11"]), curve_probability(curves["P12"])
    x, n = curves["P11"].x, curves["P11"].particles
    rows = [i for i in range(len(x) - 1) if x[i] >= t and p11[i] * n >= R.SURVIVORS_MIN]
    return [f"{p12[i] / p11[i]:.3g} at t = {x[i]:.3g}" for i in rows[::5][:4]]


def _last_escape(curve):
    hits = np.flatnonzero(curve.escapes)
    return float(curve.x[hits[-1] + 1]) if len(hits) else math.nan


def all_exits(curve):
    """The entrants' all-cause escape curve: escapes through any hole, nothing competing."""
    return dataclasses.replace(curve, curve=curve.experiment, escapes=curve.escapes +
                               curve.competing, competing=np.zeros_like(curve.competing))


def finite_time_verdict(c):
    """The finite-time rule on an all-cause escape curve: (verdict, evidence text). Refuted
    when particles are left at the horizon; confirmed when each of the three laws, fitted from
    where the survival falls to FINITE_TIME_LEVEL to the last escape, predicts at least 3
    survivors beyond the last escape (seeing none has probability below e^-3 = 0.05 under every
    law); inconclusive otherwise. The fit starts at least FINITE_TIME_BINS bins before the end."""
    left = int(c.censored.sum())
    s = all_cause_survival(c)
    a = first_below(s, FINITE_TIME_LEVEL)
    _, b = usable_range(c)
    predicted = {}
    if a is not None:
        a = max(min(a, b - FINITE_TIME_BINS), usable_range(c)[0])
    if a is not None and b - a >= 2:
        w = window_of(c, a, b)
        for law, fit in fit_all(w, intervals=False).items():
            predicted[law] = float(s[a] * c.particles * math.exp(float(fit.log_survival(
                np.array([c.x[b]]))[0])))
    if left > 0:
        verdict = REFUTED
    elif predicted and all(v >= 3.0 for v in predicted.values()):
        verdict = CONFIRMED
    else:
        verdict = INCONCLUSIVE
    start = "n/a" if a is None else f"{c.x[a]:.3g}"
    text = (f"{left} left at the horizon, last escape at {c.clock} < {c.x[b]:.4g}; fitted on "
            f"[{start}, {c.x[b]:.4g}], survivors predicted beyond it: "
            + (", ".join(f"{law.replace('_', ' ')} {v:.3g}" for law, v in predicted.items())
               or "no fit (fewer than two bins)"))
    return verdict, text


def finite_time_claim(tr, run):
    parts, verdicts = [], []
    for entry in (1, 2):
        verdict, text = finite_time_verdict(all_exits(tr[entry]["time"]["P11" if entry == 1
                                                                        else "P22"]))
        verdicts.append(verdict)
        parts.append(f"entry hole {entry}: {text}")
    n = next(iter(tr[1]["time"].values())).particles
    return make_claim("fig3-h=2.2", R.all_of(verdicts), "; ".join(parts) + ".",
                      particles_per_curve=n, run=run)


def long_lived_detail(tr, clock):
    """window_detail of P_11 over its long-lived window in ``clock`` (None if not reached)."""
    k, curves = long_lived_index(tr, clock)
    if k is None:
        return None
    c = curves["P11"]
    a0, b0 = usable_range(c)
    a = max(k, a0)
    if b0 - a < 2 or c.escapes[a:b0].sum() == 0:
        return None
    return window_detail(c, a, b0)


def stretched_form(tr, clock):
    """(verdict, text): is P_11's long-lived law in ``clock`` a stretched exponential rather
    than the stadium's power law (or an exponential)? The model selection of
    ``reports.stats.selection.choose`` decides: confirmed if it picks the stretched exponential,
    refuted if it picks the power law or the exponential, inconclusive if it cannot choose or
    the long-lived level is not reached."""
    d = long_lived_detail(tr, clock)
    if d is None:
        return INCONCLUSIVE, "the long-lived level is not reached"
    ll = d["fits"]
    best = d["best"]
    verdict = (CONFIRMED if best == "stretched_exponential"
               else INCONCLUSIVE if best not in ll else REFUTED)
    margin = ll["stretched_exponential"].loglik - ll["power_law"].loglik
    return verdict, (f"t in [{d['from']:.4g}, {d['to']:.4g}] ({d['escapes']:,} escapes), best "
                     f"of the three laws {best.replace('_', ' ')} (log-likelihood stretched - "
                     f"power law = {margin:.4g})")


def well_approximated_claim(claim_id, tr, clock, run):
    c = tr[1][clock]["P11"]
    d = long_lived_detail(tr, clock)
    if d is None:
        return make_claim(claim_id, INCONCLUSIVE, "The long-lived level is not reached at "
                          f"{c.particles:,} particles.", particles_per_curve=c.particles,
                          run=run), None
    verdict, excess = R.well_approximated_verdict(c, d, "stretched_exponential",
                                                R.MIN_ESCAPES_TAIL)
    fit = d["fits"]["stretched_exponential"]
    beta, ci = fit.params["beta"], fit.ci95.get("beta", (math.nan, math.nan))
    sys = d["systematic"]["stretched_exponential"]["beta"]
    ll = d["fits"]
    unit = "n" if clock == "collisions" else "t"
    note = (R.word_note(excess, excess, R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS)
            if verdict == INCONCLUSIVE and d["best"] == "stretched_exponential" else "")
    evidence = (f"P_11, {unit} in [{d['from']:.4g}, {d['to']:.4g}] ({d['escapes']:,} escapes): "
                f"best of the three laws {d['best'].replace('_', ' ')} (log-likelihood stretched"
                f" - power law = {ll['stretched_exponential'].loglik - ll['power_law'].loglik:.4g}"
                f", stretched - exponential = "
                f"{ll['stretched_exponential'].loglik - ll['exponential'].loglik:.4g}); the "
                f"stretched law departs from the data by at most {excess:.3f} in log S beyond "
                f"the 95% band ('well approximated' "
                f"{R.bounds_text(R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS, '{:g}'.format)}"
                f"{', ' + note if note else ''}); beta = {beta:.3f} [{ci[0]:.3f}, "
                f"{ci[1]:.3f}] +- {sys if sys is None else f'{sys:.2g}'} (sys) (the paper leaves"
                " open whether it is exactly 1/2).")
    return make_claim(claim_id, verdict, evidence, particles_per_curve=c.particles,
                      statistical={"beta": beta, "beta_ci95": list(ci), "residual": excess},
                      systematic={"beta": sys}, run=run), verdict


def _median_ratio_bins(n_tr, t_tr, n_re, t_re, t_lo=1.0):
    """Per quarter-decade of t (>= t_lo) with MIN_PER_BIN escapes of each kind:
    (t mid, median n transporting / median n reflected)."""
    hi = max(t_tr.max(initial=t_lo), t_re.max(initial=t_lo)) * 1.0001
    edges = np.geomspace(t_lo, hi, max(2, int(4 * math.log10(hi / t_lo))) + 1)
    out = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        x = n_tr[(t_tr >= a) & (t_tr < b)]
        y = n_re[(t_re >= a) & (t_re < b)]
        if len(x) >= MIN_PER_BIN and len(y) >= MIN_PER_BIN:
            out.append((math.sqrt(a * b), float(np.median(x)) / float(np.median(y))))
    return out


def _kinds(samples):
    """(n, t, v_max) of transporting and of reflected escapes over both entries."""
    tr_n, tr_t, tr_v, re_n, re_t = [], [], [], [], []
    for entry, fol in samples.items():
        esc = fol.exit >= 0
        same = fol.exit == entry - 1
        tr = esc & ~same
        re = esc & same
        tr_n.append(fol.n[tr])
        tr_t.append(fol.t[tr])
        tr_v.append(fol.v_max[tr])
        re_n.append(fol.n[re])
        re_t.append(fol.t[re])
    cat = np.concatenate
    return cat(tr_n).astype(float), cat(tr_t), cat(tr_v), cat(re_n).astype(float), cat(re_t)


def fewer_collisions_claim(samples, seed=20120907, reps=200):
    n_tr, t_tr, _, n_re, t_re = _kinds(samples)
    bins = _median_ratio_bins(n_tr, t_tr, n_re, t_re)
    m = sum(f.particles for f in samples.values())
    if not bins:
        return make_claim("fig4-fewer-collisions", INCONCLUSIVE, "No quarter-decade of t holds "
                          f"{MIN_PER_BIN} escapes of each kind.", particles_per_curve=m)
    rng = np.random.default_rng(seed)
    boots = []
    for _ in range(reps):
        i = rng.integers(0, len(n_tr), len(n_tr))
        j = rng.integers(0, len(n_re), len(n_re))
        got = dict(_median_ratio_bins(n_tr[i], t_tr[i], n_re[j], t_re[j]))
        boots.append([got.get(t, math.nan) for t, _ in bins])
    boots = np.array(boots)
    upper = np.nanpercentile(boots, 97.5, axis=0)
    lower = np.nanpercentile(boots, 2.5, axis=0)
    per_bin = [R.word_verdict(lo, hi, R.FEWER, R.FEWER_FAILS)
               for lo, hi in zip(lower, upper, strict=True)]
    verdict = (CONFIRMED if all(v == CONFIRMED for v in per_bin) else
               REFUTED if all(v == REFUTED for v in per_bin) else INCONCLUSIVE)
    notes = [R.word_note(lo, hi, R.FEWER, R.FEWER_FAILS)
             for lo, hi in zip(lower, upper, strict=True)]
    tally = (f"{per_bin.count(CONFIRMED)} bins in the holds zone, {notes.count(R.BETWEEN)} "
             f"{R.BETWEEN}, {per_bin.count(REFUTED)} in the fails zone, "
             f"{notes.count('straddles a bound')} straddling a bound")
    evidence = (f"Sampled study, {m:,} starts (h = 1, both entry holes): ratio of the median "
                "collision counts, transporting / reflected, per quarter-decade of escape time: "
                + ", ".join(f"t ~ {t:.3g}: {r:.3g} [{lo:.3g}, {hi:.3g}]"
                            for (t, r), lo, hi in zip(bins, lower, upper, strict=True))
                + f" ('many fewer' {R.bounds_text(R.FEWER, R.FEWER_FAILS, '{:g}'.format)}"
                f": {tally}).")
    return make_claim("fig4-fewer-collisions", verdict, evidence, particles_per_curve=m,
                      statistical={"ratios": [r for _, r in bins]})


def large_velocity_verdict(lo_large, hi_low):
    """"large velocities" from the Wilson intervals of two shares of the transporting orbits:
    confirmed if some exceed ``LARGE_VELOCITY`` times the largest start velocity (the lower
    bound ``lo_large`` of that share above 0), refuted if none exceeds ``LARGE_VELOCITY_FAILS``
    times it (the upper bound ``hi_low`` of that share below ``NONE_SHARE``), inconclusive
    otherwise."""
    if lo_large > 0:
        return CONFIRMED
    if hi_low < R.NONE_SHARE:
        return REFUTED
    return INCONCLUSIVE


def large_velocity_claim(samples):
    _, _, v_tr, _, _ = _kinds(samples)
    m = sum(f.particles for f in samples.values())
    limit = R.LARGE_VELOCITY * START_V_MAX
    low_limit = R.LARGE_VELOCITY_FAILS * START_V_MAX
    k, total = int((v_tr > limit).sum()), len(v_tr)
    if total == 0:
        return make_claim("fig4-large-velocities", INCONCLUSIVE, "No transporting escapes.",
                          particles_per_curve=m)
    lo, hi = _pct_ci(k, total)
    k_low = int((v_tr > low_limit).sum())
    lo_low, hi_low = _pct_ci(k_low, total)
    verdict = large_velocity_verdict(lo, hi_low)
    note = ("" if verdict != INCONCLUSIVE else
            R.BETWEEN if lo_low >= R.NONE_SHARE else "straddles a bound")
    evidence = (f"Sampled study, {m:,} starts (h = 1): {k:,} of {total:,} transporting orbits "
                f"exceed v = {limit:g} ({R.LARGE_VELOCITY:g} times the largest start velocity) "
                f"before they escape (share {k / total:.3g}, 95% [{lo:.2g}, {hi:.2g}]), "
                f"{k_low:,} exceed v = {low_limit:g} ({R.LARGE_VELOCITY_FAILS:g} times; share "
                f"{k_low / total:.3g}, 95% [{lo_low:.2g}, {hi_low:.2g}]); their largest "
                f"velocity reaches {v_tr.max():.4g}, the 99.9th percentile "
                f"{np.percentile(v_tr, 99.9):.4g}{' (' + note + ')' if note else ''}.")
    return make_claim("fig4-large-velocities", verdict, evidence, particles_per_curve=m,
                      statistical={"share": k / total, "share_ci95": [lo, hi],
                                   "v_max": float(v_tr.max())})


def clock_spread(tr):
    """D = max - min over the P_ij of the median log(t_q / n_q) at matched levels, and the
    medians."""
    medians = {}
    for entry in (1, 2):
        for ij, cn in tr[entry]["collisions"].items():
            ct = tr[entry]["time"][ij]
            pn, pt = curve_probability(cn), curve_probability(ct)
            top = pn[0]
            if top <= 0:
                continue
            low = max(top * 1e-4, R.SURVIVORS_MIN / cn.particles)
            if low > top * 1e-3:  # fewer than two decades of levels: too short to compare
                continue
            levels = np.geomspace(top / 10, low, int(4 * math.log10(top / 10 / low)) + 1)
            logs = []
            for q in levels:
                nq, tq = quantile(cn.x, pn, q), quantile(ct.x, pt, q)
                if nq and tq and nq > 0 and tq > 0:
                    logs.append(math.log(tq / nq))
            if logs:
                medians[ij] = float(np.median(logs))
    if len(medians) < 4:
        return math.nan, medians
    return max(medians.values()) - min(medians.values()), medians


def other_h_claim(h, transport, run):
    d_h, m_h = clock_spread(transport[h])
    d_1, m_1 = clock_spread(transport["1"])
    r = math.log(10) / 20
    if not (math.isfinite(d_h) and math.isfinite(d_1)):
        verdict = INCONCLUSIVE
    elif d_h + r < d_1:
        verdict = CONFIRMED
    elif d_h - r > d_1:
        verdict = REFUTED
    else:
        verdict = INCONCLUSIVE
    evidence = (f"D(h = {h}) = {d_h:.3f} (median log(t_q/n_q): "
                + ", ".join(f"{k} {v:.2f}" for k, v in sorted(m_h.items()))
                + f") against D(1) = {d_1:.3f} ("
                + ", ".join(f"{k} {v:.2f}" for k, v in sorted(m_1.items()))
                + f"); resolution {r:.3f}.")
    n = next(iter(transport[h][1]["time"].values())).particles
    return make_claim(f"fig4-other-h={h}", verdict, evidence, particles_per_curve=n,
                      statistical={"D": d_h, "D_h1": d_1}, run=run)


def transport_claims(transport, run_dir, samples=None):
    """Every Section 4 / Figs. 3-4 claim from the run's curves (``transport_analysis``) and the
    sampled study of h = 1 ({entry: Followed}, optional)."""
    run = Path(run_dir).name
    claims = []
    for h in transport:
        claims.append(eventual_claim(h, transport[h], run))
    for h in TRAPPING_WIDTHS:
        if h in transport:
            claims.append(strong_claim(h, transport[h], run))
            claims.append(trap_claim(f"fig3-trap-h={h}", transport[h], run, True))
    if "0.1" in transport:
        claims.append(trap_claim("fig3-h=0.1", transport["0.1"], run, False))
    if "2.2" in transport:
        claims.append(finite_time_claim(transport["2.2"], run))
    if "1" in transport:
        for clock, cid in (("time", "fig4-P11-time"), ("collisions", "fig4-P11-collisions")):
            claims.append(well_approximated_claim(cid, transport["1"], clock, run)[0])
    if samples:
        claims.append(fewer_collisions_claim(samples))
        claims.append(large_velocity_claim(samples))
    if "1" in transport:
        for h in ("0.1", "0.4", "2.2"):
            if h in transport:
                claims.append(other_h_claim(h, transport, run))
    if all(h in transport for h in TRAPPING_WIDTHS):
        forms = {h: stretched_form(transport[h], "time") for h in TRAPPING_WIDTHS}
        parts = [strong_claim(h, transport[h], run).verdict for h in TRAPPING_WIDTHS]
        parts += [forms[h][0] for h in TRAPPING_WIDTHS]
        evidence = ("Asymmetry (fig3-h=W rule): "
                    + ", ".join(f"h = {h}: t_11/max(others) = "
                                f"{strong_measure(transport[h])[0]:.3g}" for h in TRAPPING_WIDTHS)
                    + "; the form of P_11's long-lived regime (continuous time), the stadium's "
                    "power law against a stretched exponential: "
                    + "; ".join(f"h = {h}: {forms[h][1]}: {forms[h][0]}"
                                for h in TRAPPING_WIDTHS) + ".")
        n = next(iter(transport["1"][1]["time"].values())).particles
        claims.append(make_claim("conclusion-asymmetry", R.all_of(parts), evidence,
                                 particles_per_curve=n, run=run))
    return claims
