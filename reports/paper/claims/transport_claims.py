"""The paper's transport claims (Section 4, Figs. 3-4) decided on a transport run, as the
agreement of each claim's family of analyses (``reports.paper.claims.family``); rules in the
register (``reports.paper.claims.register``), tolerances in ``reports.paper.claims.rules``. The
"well approximated" claims are in ``well_approximated_claims``, those on each orbit's n, t and
velocity in ``transport_joint_claims``.

Curves: ``transport_analysis(run_dir)`` maps width -> entry hole (1, 2) -> clock -> {"P11": Curve,
...}; P_ij(x) is ``reports.stats.hazard.curve_probability`` (escapes through j after x, over the
N entrants of hole i), the entrants still inside are the all-cause survival of either curve.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.register import TRAPPING_WIDTHS, make_claim
from reports.paper.claims.transport_joint_claims import (
    fewer_collisions_claims,
    large_velocity_claims,
)
from reports.paper.claims.well_approximated_claims import form_members, well_approximated_claim
from reports.paper.claims.window_family import STEP
from reports.paper.studies.escape_regimes import SURVIVORS_MIN
from reports.runs.survival import wilson
from reports.stats.analysis import fit_all, usable_range
from reports.stats.hazard import all_cause_survival, curve_probability, first_below, quantile
from reports.stats.histogram import read_run
from reports.stats.likelihood import window_of
from reports.stats.regime_fit import window_detail

BIN_MARGIN = 10 ** (1 / 20)  # one bin of the runs' grid (20 per decade)
FINITE_TIME_LEVELS = (0.1, 0.01)  # the last part of the decay: the last 10% (1%) of entrants
FINITE_TIME_BINS = 5     # and at least five bins
STRONG_LEVEL_FACTORS = (1.0, 10.0)  # "very strong" read at the level q and at 10 q


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


def particles_of(tr):
    return next(iter(tr[1]["time"].values())).particles


def eventual_claim(h, tr, run):
    """Every entrant eventually escapes: one part per entry hole (both must), read in each
    clock's record of the particles still inside at the horizon."""
    members = []
    for entry in (1, 2):
        for clock in ("collisions", "time"):
            c = next(iter(tr[entry][clock].values()))
            left = int(c.censored.sum())
            lo, hi = _pct_ci(left, c.particles)
            members.append(F.in_part(f"entry hole {entry}", [F.threshold_member(
                f"{clock}: {left} of {c.particles:,} still inside at the horizon",
                "share still inside", left / c.particles, lo, hi, R.ESCAPED_TO, True)])[0])
    return make_claim(f"sec4-eventual-h={h}", F.family_text(members) + ".", analyses=members,
                      particles_per_curve=particles_of(tr), run=run)


def level_times(tr, clock, level):
    """{(i, j): x at which P_ij falls to ``level`` (0 if it starts below it)}."""
    out = {}
    for entry in (1, 2):
        for ij, c in tr[entry][clock].items():
            p = curve_probability(c)
            out[ij] = 0.0 if p[0] <= level else (quantile(c.x, p, level) or math.nan)
    return out


def strong_level(tr):
    """The level q = max(10^-6, 100/N) of "very strong"."""
    return max(1e-6, SURVIVORS_MIN / particles_of(tr))


def strong_measure(tr, factor=1.0):
    """(t_11 / max of the other t_ij at the level factor * q, the level, the times)."""
    q = strong_level(tr) * factor
    times = level_times(tr, "time", q)
    others = max(v for k, v in times.items() if k != "P11")
    ratio = times["P11"] / others if others > 0 else math.inf
    return ratio, q, times


def probability_at(c, t):
    """P_ij(t) of a curve, interpolated in (log t, log P) between boundaries."""
    p = curve_probability(c)
    k = int(np.searchsorted(c.x, t))
    if k <= 0 or k >= len(c.x) or not math.isfinite(c.x[k]):
        return float(p[min(max(k, 0), len(p) - 1)])
    x0, x1, p0, p1 = c.x[k - 1], c.x[k], p[k - 1], p[k]
    if not (x0 > 0 and p0 > 0 and p1 > 0):
        return float(p1)
    f = math.log(t / x0) / math.log(x1 / x0)
    return float(math.exp(math.log(p0) + f * (math.log(p1) - math.log(p0))))


def same_time_ratio(tr, q):
    """(P_11(t*) / max of the other P_ij(t*), t*, counts): t* the time the last of the other
    curves falls to q."""
    times = level_times(tr, "time", q)
    t_star = max(v for k, v in times.items() if k != "P11")
    curves = {ij: c for entry in (1, 2) for ij, c in tr[entry]["time"].items()}
    probs = {ij: probability_at(c, t_star) for ij, c in curves.items()}
    others = max(v for k, v in probs.items() if k != "P11")
    return (probs["P11"] / others if others > 0 else math.inf), t_star, probs


def strong_interval(ratio):
    """The ratio t_11 / max(others) widened by one bin of the grid either way."""
    return ratio / BIN_MARGIN, ratio * BIN_MARGIN


def strong_verdict(ratio):
    """"very strong P_11": confirmed if the widened ratio lies at or above ``rules.DECADE``,
    refuted if at or below ``rules.STRONG_FAILS``, inconclusive otherwise (or NaN)."""
    return R.word_verdict(*strong_interval(ratio), R.DECADE, R.STRONG_FAILS)


def strong_members(tr, part=""):
    """The family of "very strong P_11": the same level and the same time, at q and 10 q."""
    n = particles_of(tr)
    members = []
    for factor in STRONG_LEVEL_FACTORS:
        ratio, q, times = strong_measure(tr, factor)
        members.append(F.word_member(
            f"same level q = {q:.2g}: t_ij " + ", ".join(f"{k} {v:.4g}" for k, v in
                                                       sorted(times.items())),
            "t_11 / max(others)", ratio, *strong_interval(ratio), R.DECADE, R.STRONG_FAILS))
        p_ratio, t_star, probs = same_time_ratio(tr, q)
        lo, hi = _ratio_interval(probs, n)
        members.append(F.word_member(
            f"same time t = {t_star:.4g} (the others fall to {q:.2g}): P_ij "
            + ", ".join(f"{k} {v:.3g}" for k, v in sorted(probs.items())),
            "P_11 / max(others)", p_ratio, lo, hi, R.DECADE, R.STRONG_FAILS))
    return F.in_part(part, members)


def _ratio_interval(probs, n):
    """The ratio P_11 / max(others) with the Wilson intervals of both counts and one bin of the
    grid's interpolation either way."""
    top = max((k for k in probs if k != "P11"), key=lambda k: probs[k])
    a, b = round(probs["P11"] * n), round(probs[top] * n)
    (a_lo, a_hi), (b_lo, b_hi) = _pct_ci(a, n), _pct_ci(b, n)
    lo = a_lo / b_hi / BIN_MARGIN if b_hi > 0 else math.inf
    hi = a_hi / b_lo * BIN_MARGIN if b_lo > 0 else math.inf
    return lo, hi


def strong_claim(h, tr, run):
    n = particles_of(tr)
    if strong_level(tr) > R.LONG_LIVED_LEVEL:
        return make_claim(f"fig3-h={h}", f"At {n:,} particles the level q = 100/N = "
                          f"{strong_level(tr):.2g} is above the long-lived level "
                          f"{R.LONG_LIVED_LEVEL:g}: the data do not reach the late times (needs "
                          "N >= 10^6).", particles_per_curve=n, run=run)
    members = strong_members(tr)
    evidence = (f"'very strong' {R.bounds_text(R.DECADE, R.STRONG_FAILS, '{:g}'.format)}: "
                + F.family_text(members) + ".")
    return make_claim(f"fig3-h={h}", evidence, analyses=members, particles_per_curve=n,
                      statistical={"ratio": strong_measure(tr)[0]}, run=run)


def long_lived_index(tr, clock):
    """(boundary index where the entrants of hole 1 still inside fall to LONG_LIVED_LEVEL, or
    None; the curves of entry 1)."""
    curves = tr[1][clock]
    s = all_cause_survival(curves["P11"])
    return first_below(s, R.LONG_LIVED_LEVEL), curves


def long_lived_points(tr, clock="time", remaining=None):
    """Boundary indices from the long-lived time on, a quarter decade apart, while at least
    ``remaining`` (default SURVIVORS_MIN) entrants of hole 1 remain."""
    remaining = SURVIVORS_MIN if remaining is None else remaining
    k, curves = long_lived_index(tr, clock)
    if k is None:
        return []
    c = curves["P11"]
    n = c.particles
    left = (curve_probability(c) + curve_probability(curves["P12"])) * n
    points, j = [], 0
    while True:
        i = int(np.searchsorted(c.x, c.x[k] * STEP ** j * (1 - 1e-12)))
        if i >= len(left) or left[i] < remaining:
            break
        if not points or i > points[-1]:
            points.append(i)
        j += 1
    return points


def trap_measure(tr):
    """(k11, k12, share through hole 2, its Wilson interval, time) at the long-lived time (the
    first member of the trapping family; the figure marks it)."""
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


def long_lived_detail(tr, clock):
    """window_detail of P_11 over its long-lived window in ``clock`` (None if not reached;
    the figure draws its laws)."""
    k, curves = long_lived_index(tr, clock)
    if k is None:
        return None
    c = curves["P11"]
    a0, b0 = usable_range(c)
    a = max(k, a0)
    if b0 - a < 2 or c.escapes[a:b0].sum() == 0:
        return None
    return window_detail(c, a, b0)


def trap_claim(claim_id, tr, run, traps_expected):
    n = particles_of(tr)
    points = long_lived_points(tr, remaining=R.fewest_to_reach(R.TRAP_SHARE))
    curves = tr[1]["time"]
    p11, p12 = curve_probability(curves["P11"]), curve_probability(curves["P12"])
    holds, fails = ((R.TRAP_SHARE, R.TRAP_SHARE_FAILS) if traps_expected
                    else (R.TRAP_SHARE_FAILS, R.TRAP_SHARE))
    members = []
    for k in points:
        k11, k12 = round(p11[k] * n), round(p12[k] * n)
        lo, hi = _pct_ci(k12, k11 + k12)
        members.append(F.word_member(
            f"t = {curves['P11'].x[k]:.4g}: {k11:,} will leave by hole 1, {k12:,} by hole 2",
            "share through hole 2", k12 / (k11 + k12), lo, hi, holds, fails))
    evidence = (f"From where the entrants of hole 1 still inside fall to "
                f"{R.LONG_LIVED_LEVEL:g}, while at least "
                f"{R.fewest_to_reach(R.TRAP_SHARE)} remain (with fewer, "
                f"none leaving by hole 2 cannot show a share at or below "
                f"{R.pct(R.TRAP_SHARE)}): " + (F.family_text(members) or
                                                 f"fewer remain at {n:,} particles") +
                f"; last escape through hole 2 at t < {_last_escape(curves['P12']):.4g}, "
                f"through hole 1 at t < {_last_escape(curves['P11']):.4g}.")
    return make_claim(claim_id, evidence, analyses=members, particles_per_curve=n,
                      statistical={"share_hole_2": members[0].value if members else None},
                      run=run)


def _last_escape(curve):
    hits = np.flatnonzero(curve.escapes)
    return float(curve.x[hits[-1] + 1]) if len(hits) else math.nan


def all_exits(curve):
    """The entrants' all-cause escape curve: escapes through any hole, nothing competing."""
    return dataclasses.replace(curve, curve=curve.experiment, escapes=curve.escapes +
                               curve.competing, competing=np.zeros_like(curve.competing))


def finite_time_verdict(c, level=FINITE_TIME_LEVELS[0]):
    """The finite-time rule on an all-cause escape curve: (verdict, evidence text). Refuted
    when particles are left at the horizon; confirmed when each of the three laws, fitted from
    where the survival falls to ``level`` to the last escape, predicts at least 3 survivors
    beyond the last escape (seeing none has probability below e^-3 = 0.05 under every law);
    inconclusive otherwise. The fit starts at least FINITE_TIME_BINS bins before the end."""
    left = int(c.censored.sum())
    s = all_cause_survival(c)
    a = first_below(s, level)
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
    return verdict, text, min(predicted.values(), default=math.nan)


def finite_time_claim(tr, run):
    members = []
    for entry in (1, 2):
        c = all_exits(tr[entry]["time"]["P11" if entry == 1 else "P22"])
        for level in FINITE_TIME_LEVELS:
            verdict, text, fewest = finite_time_verdict(c, level)
            members.append(F.Analysis(
                f"from P = {level:g}: {text}", verdict, "fewest survivors predicted", fewest,
                fewest, fewest, (3.0, math.inf), (), "" if verdict != INCONCLUSIVE
                else F.STRADDLES, part=f"entry hole {entry}"))
    return make_claim("fig3-h=2.2", F.family_text(members) + ".", analyses=members,
                      particles_per_curve=particles_of(tr), run=run)


def log_ratio(cn, ct, q):
    """log(t_q / n_q) of a P_ij at the level q (None if either curve does not reach it)."""
    pn, pt = curve_probability(cn), curve_probability(ct)
    nq, tq = quantile(cn.x, pn, q), quantile(ct.x, pt, q)
    if nq and tq and nq > 0 and tq > 0:
        return math.log(tq / nq)
    return None


def clock_spread(tr):
    """D over the top decades: max - min over the P_ij of the median log(t_q / n_q) at levels
    from P_ij(0)/10 down to max(P_ij(0) 10^-4, 100/N), 4 per decade; and the medians."""
    medians = {}
    for entry in (1, 2):
        for ij, cn in tr[entry]["collisions"].items():
            ct = tr[entry]["time"][ij]
            top = curve_probability(cn)[0]
            if top <= 0:
                continue
            low = max(top * 1e-4, SURVIVORS_MIN / cn.particles)
            if low > top * 1e-3:  # fewer than two decades of levels: too short to compare
                continue
            levels = np.geomspace(top / 10, low, int(4 * math.log10(top / 10 / low)) + 1)
            logs = [v for v in (log_ratio(cn, ct, q) for q in levels) if v is not None]
            if logs:
                medians[ij] = float(np.median(logs))
    if len(medians) < 4:
        return math.nan, medians
    return max(medians.values()) - min(medians.values()), medians


def tail_spread(tr, q):
    """D at the absolute level q: max - min over the P_ij of log(t_q / n_q); and the values."""
    values = {}
    for entry in (1, 2):
        for ij, cn in tr[entry]["collisions"].items():
            v = log_ratio(cn, tr[entry]["time"][ij], q)
            if v is not None:
                values[ij] = v
    if len(values) < 4:
        return math.nan, values
    return max(values.values()) - min(values.values()), values


def other_h_claim(h, transport, run):
    r = math.log(10) / 20
    n = particles_of(transport[h])
    measures = [("top decades (median over levels)", clock_spread)]
    for mult in (1, 10):
        q = mult * SURVIVORS_MIN / n
        measures.append((f"tail, level {q:.2g}", lambda tr, q=q: tail_spread(tr, q)))
    members = []
    for name, measure in measures:
        d_h, m_h = measure(transport[h])
        d_1, m_1 = measure(transport["1"])
        variant = (f"{name}: D(h = {h}) = {d_h:.3f} ("
                   + ", ".join(f"{k} {v:.2f}" for k, v in sorted(m_h.items()))
                   + f") against D(1) = {d_1:.3f} ("
                   + ", ".join(f"{k} {v:.2f}" for k, v in sorted(m_1.items())) + ")")
        diff = d_1 - d_h
        if not (math.isfinite(d_h) and math.isfinite(d_1)):
            members.append(F.too_few(variant, "D(1) - D(h)"))
        else:
            members.append(F.word_member(variant, "D(1) - D(h)", diff, diff - r, diff + r,
                                         0.0, 0.0))
    return make_claim(f"fig4-other-h={h}", f"Resolution r = {r:.3f}; "
                      + F.family_text(members) + ".", analyses=members, particles_per_curve=n,
                      run=run)


def transport_claims(transport, run_dir, samples=None, joint=None, replicas=None):
    """Every Section 4 / Figs. 3-4 claim from the run's curves (``transport_analysis``), the
    sampled study of h = 1 ({entry: Followed}, optional), an independent replica of it
    (optional) and joint (n, t) data of h = 1 ({entry: JointSample}, optional; default: the
    study's)."""
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
            claims.append(well_approximated_claim(cid, transport["1"], clock, run))
        claims += fewer_collisions_claims(transport["1"], samples, joint, run)
    if samples:
        claims += large_velocity_claims(samples, joint, replicas)
    if "1" in transport:
        for h in ("0.1", "0.4", "2.2"):
            if h in transport:
                claims.append(other_h_claim(h, transport, run))
    if all(h in transport for h in TRAPPING_WIDTHS):
        members = []
        for h in TRAPPING_WIDTHS:
            members += strong_members(transport[h], f"asymmetric, h = {h}")
            members += form_members(transport[h], "time", f"stretched exponential, h = {h}",
                                    goodness=True, residual=False)
        claims.append(make_claim("conclusion-asymmetry", F.family_text(members) + ".",
                                 analyses=members,
                                 particles_per_curve=particles_of(transport["1"]), run=run))
    return claims
