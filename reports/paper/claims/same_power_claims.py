""""The algebraic decay has the same power as for discrete time" (Fig. 2 caption, Section 3):
the late decay's power-law exponent in continuous time against discrete time, over the same
survival levels.

Regime. The matched survival levels run from the late tail's start level P(n_tail) down to
``escape_regimes``' lowest level (100/N or where a curve's data end), and only where the
continuous-time curve is the non-accelerating population the sentence speaks of: the matched
window starts at the first level at or below P(n_tail) where the intermediate stretched law,
extrapolated, explains at most ``rules.CHAOTIC_GONE`` of the continuous-time survivors. Where
the intermediate continuous-time decay is itself algebraic (its beta in the power-law cell:
the holes in the chaotic sea) there is no accelerating population to wait out, and the matched
window starts at P(n_tail).

Family. Windows: the start level moves down by quarter decades (later, never back into the
accelerating population), every level window holding at least ``rules.MIN_ESCAPES_TAIL``
escapes in each clock. Metrics, each under "the same" rule:

* the power-law exponents alpha_n and alpha_t fitted by maximum likelihood on each clock's
  window (relative difference, uncertainties the 95% half-widths);
* matched quantiles: the slope of log t_q against log n_q at the window's levels q (a quarter
  decade apart); equal powers give slope 1, so the slope is compared with 1 (its 95% interval by
  resampling both curves' counts).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import make_claim
from reports.paper.claims.window_family import MIN_BINS, window_label
from reports.paper.claims.window_members import alpha_of, escapes_in
from reports.paper.studies.replicates import INTERVAL_REPLICATES
from reports.paper.studies.seeds import SAME_POWER_SEED
from reports.stats.hazard import all_cause_survival, first_below, quantile

STEP_DECADES = 0.25


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


def accelerating(a):
    """Does the continuous-time intermediate law describe an accelerating population that
    dies off, a stretched decay? Its stretched exponent beta lies above the power-law cell
    (``rules.FORM_CELL``); with beta in that cell the intermediate decay is itself algebraic
    (the holes in the chaotic sea) and there is no such population to wait out."""
    d = a["details"].get(("time", "intermediate"))
    if d is None:
        return True
    return d["fits"]["stretched_exponential"].params["beta"] >= R.FORM_CELL["power_law"][1]


def matched_start_level(a):
    """The first continuous-time survival level at or below P(n_tail) where the intermediate
    law explains at most CHAOTIC_GONE of the survivors (module docstring), or None; P(n_tail)
    itself where the intermediate decay is algebraic (``accelerating``)."""
    w = a["windows"]
    if w.level_tail is None or w.level_end is None:
        return None
    ct = a["curves"]["time"]
    s = all_cause_survival(ct)
    k = first_below(s, w.level_tail)
    if k is not None and not accelerating(a):
        return float(s[k]) if s[k] > w.level_end else None
    while k is not None and k < len(s) and s[k] > w.level_end:
        share = chaotic_share(a, k)
        if share is not None and share <= R.CHAOTIC_GONE:
            return float(s[k])
        k += 1
    return None


def _last_at_least(values, level):
    hit = np.flatnonzero(np.asarray(values) >= level)
    return int(hit[-1]) if len(hit) else None


def level_window(curve, level_hi, level_lo):
    """Bin window of a curve from where it falls to level_hi to the last boundary at or above
    level_lo, or None."""
    s = all_cause_survival(curve)
    a, b = first_below(s, level_hi), _last_at_least(s, level_lo)
    if a is None or b is None or b - a < MIN_BINS or curve.escapes[a:b].sum() == 0:
        return None
    return a, b


def level_windows(a, start_level):
    """Every (level, n window, t window) with enough escapes in both clocks, the start level
    moving down by quarter decades from ``start_level``."""
    cn, ct = a["curves"]["collisions"], a["curves"]["time"]
    end = a["windows"].level_end
    out, j = [], 0
    while start_level * 10 ** (-STEP_DECADES * j) > end:
        level = start_level * 10 ** (-STEP_DECADES * j)
        wn, wt = level_window(cn, level, end), level_window(ct, level, end)
        if (wn and wt and escapes_in(cn, wn) >= R.MIN_ESCAPES_TAIL
                and escapes_in(ct, wt) >= R.MIN_ESCAPES_TAIL):
            out.append((level, wn, wt))
        j += 1
    return out


def matched_levels(level_hi, level_lo, per_decade=4):
    """Levels from level_hi down to level_lo, ``per_decade`` per decade, both ends included."""
    k = max(1, int(math.ceil(per_decade * math.log10(level_hi / level_lo))))
    return np.geomspace(level_hi, level_lo, k + 1)


def quantile_slope(curve_n, curve_t, levels):
    """Least-squares slope of log t_q against log n_q at the survival levels (NaN with fewer
    than three levels reached by both)."""
    s_n, s_t = all_cause_survival(curve_n), all_cause_survival(curve_t)
    pts = [(quantile(curve_n.x, s_n, q), quantile(curve_t.x, s_t, q)) for q in levels]
    pts = [(n, t) for n, t in pts if n and t and n > 0 and t > 0]
    if len(pts) < 3:
        return math.nan
    return float(np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]), 1)[0])


def resampled(curve, rng):
    """The curve with its escape and censoring counts redrawn (one multinomial draw)."""
    cells = np.concatenate([curve.escapes, curve.censored]).astype(np.float64)
    draw = rng.multinomial(curve.particles, cells / cells.sum())
    k = len(curve.escapes)
    return dataclasses.replace(curve, escapes=draw[:k], censored=draw[k:])


def quantile_slope_interval(curve_n, curve_t, levels, reps=INTERVAL_REPLICATES,
                            seed=SAME_POWER_SEED):
    """95% percentile interval of ``quantile_slope`` over resampled curves."""
    rng = np.random.default_rng(seed)
    got = [quantile_slope(resampled(curve_n, rng), resampled(curve_t, rng), levels)
           for _ in range(reps)]
    got = np.array([g for g in got if math.isfinite(g)])
    if len(got) <= reps // 2:
        return math.nan, math.nan
    return float(np.percentile(got, 2.5)), float(np.percentile(got, 97.5))


def same_power_claim(hole, a, run):
    cid = f"fig2-same-power-phi_c={hole}"
    cn, ct = a["curves"]["collisions"], a["curves"]["time"]
    w = a["windows"]
    n = cn.particles
    start = matched_start_level(a)
    if start is None:
        return make_claim(cid, "No matched survival levels: the late tail is not reached, or the"
                          " continuous-time curve is still the accelerating population (the "
                          "intermediate law explains more than "
                          f"{R.pct(R.CHAOTIC_GONE)} of its survivors) down to the lowest level "
                          f"{w.level_end if w.level_end is not None else math.nan:.3g} at "
                          f"{n:,} particles.", particles_per_curve=n, run=run)
    members, stats = [], {}
    for level, wn, wt in level_windows(a, start):
        a_n, ci_n, u_n = alpha_of(cn, wn)
        a_t, ci_t, u_t = alpha_of(ct, wt)
        where = (f"levels {level:.3g} to {w.level_end:.3g} ({window_label(cn, wn, 'n')}, "
                 f"{window_label(ct, wt, 't')})")
        members.append(F.same_member(f"{where}: alpha_n = {a_n:.3f}, alpha_t = {a_t:.3f}",
                                     "relative difference of alpha_n, alpha_t", a_n, u_n, a_t,
                                     u_t))
        levels = matched_levels(level, w.level_end)
        slope = quantile_slope(cn, ct, levels)
        lo, hi = quantile_slope_interval(cn, ct, levels)
        half = 0.5 * (hi - lo) if math.isfinite(lo) and math.isfinite(hi) else math.inf
        members.append(F.same_member(f"{where}: matched quantiles, slope of log t_q on log n_q "
                                     f"= {slope:.3f} [{lo:.3f}, {hi:.3f}] against 1",
                                     "relative difference of the powers (slope against 1)",
                                     slope, half, 1.0, 0.0))
        stats[f"{level:.3g}"] = {"alpha_n": a_n, "alpha_n_ci95": list(ci_n), "alpha_t": a_t,
                                 "alpha_t_ci95": list(ci_t), "quantile_slope": slope,
                                 "quantile_slope_ci95": [lo, hi]}
    why = (f"where the intermediate continuous-time law explains at most "
           f"{R.pct(R.CHAOTIC_GONE)} of the survivors" if accelerating(a) else
           "the intermediate continuous-time decay is itself algebraic: no accelerating "
           "population to wait out")
    evidence = (f"Matched levels from {start:.3g} (the first level at or below P(n_tail) = "
                f"{w.level_tail:.3g}; {why}) down to {w.level_end:.3g}; "
                f"'the same' within {R.pct(R.SAME)}, different beyond {R.pct(R.SAME_FAILS)}; "
                f"family: {F.family_text(members) or 'no level window with enough escapes'}.")
    return make_claim(cid, evidence, analyses=members, particles_per_curve=n, statistical=stats,
                      run=run)
