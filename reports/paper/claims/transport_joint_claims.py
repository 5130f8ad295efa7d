"""Claims of Fig. 4 about the transporting orbits of h = 1, per curve (P_12 from hole 1, P_21
from hole 2): they "decay with many fewer collisions" and "can reach large velocities".

* Many fewer collisions, against the reflected orbits of hole 1 (P_11, the curve the figure
  fits). At the same survival level (from the run): the collisions per unit time n_q/t_q of the
  transporting curve over P_11's, at levels relative to each curve's P(0), its median over the
  top decades and over the tail; interval by resampling the counts. At the same escape time
  (joint (n, t) data): the ratio of the median collision counts of the escapes in a quarter
  decade of t, in the decay: the latest two quarter decades with at least ``MIN_PER_BIN``
  escapes of each; Poisson-bootstrap interval.
* Large velocities: the largest velocity of each transporting orbit before it escapes, from the
  sampled study and from an independent replica of it (its own starts). A bound the sample
  cannot reach is said so: the count of orbits beyond it expected under the sample's own upper
  tail (an exponential fitted to the largest ``TAIL_ORBITS`` values, the maximum-likelihood
  scale being their mean excess) is stated, and a member whose holds bound expects fewer than
  one orbit is inconclusive for want of data, not between the bounds.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.register import make_claim
from reports.paper.studies.escape_regimes import SURVIVORS_MIN
from reports.paper.studies.followed_samples import TRANSPORT_V
from reports.paper.studies.joint_sample import from_followed, weighted_quantile
from reports.paper.studies.replicates import INTERVAL_REPLICATES
from reports.paper.studies.seeds import TRANSPORT_JOINT_SEED
from reports.runs.survival import wilson
from reports.stats.hazard import curve_probability, quantile

MIN_PER_BIN = 100
TAIL_ORBITS = 200
TRANSPORTING = {"P12": (1, 1), "P21": (2, 0)}  # curve: (entry hole, exit index)


def _log_ratio(cn, ct, q):
    pn, pt = curve_probability(cn), curve_probability(ct)
    nq, tq = quantile(cn.x, pn, q), quantile(ct.x, pt, q)
    return math.log(tq / nq) if nq and tq and nq > 0 and tq > 0 else None


def level_ratio(tr, ij, fractions):
    """Median over relative levels f of (n_q/t_q)_ij / (n_q/t_q)_11, q = f P(0) of each."""
    e = TRANSPORTING[ij][0]
    cn_ij, ct_ij = tr[e]["collisions"][ij], tr[e]["time"][ij]
    cn_11, ct_11 = tr[1]["collisions"]["P11"], tr[1]["time"]["P11"]
    top_ij, top_11 = curve_probability(cn_ij)[0], curve_probability(cn_11)[0]
    ratios = []
    for f in fractions:
        a, b = _log_ratio(cn_11, ct_11, f * top_11), _log_ratio(cn_ij, ct_ij, f * top_ij)
        if a is not None and b is not None:
            ratios.append(math.exp(a - b))
    return float(np.median(ratios)) if ratios else math.nan


def _resampled(curve, rng):
    cells = np.concatenate([curve.escapes, curve.competing, curve.censored]).astype(float)
    draw = rng.multinomial(curve.particles, cells / cells.sum())
    k = len(curve.escapes)
    return dataclasses.replace(curve, escapes=draw[:k], competing=draw[k:2 * k],
                               censored=draw[2 * k:])


def _resampled_transport(tr, rng):
    return {e: {clock: {ij: _resampled(c, rng) for ij, c in cs.items()}
                for clock, cs in tr[e].items()} for e in (1, 2)}


def level_fractions(tr, ij):
    """(top decades, tail): relative levels, four per decade: P(0)/10 to P(0)/10^3, and the
    last two decades above 100/N of both curves."""
    e = TRANSPORTING[ij][0]
    n = tr[e]["collisions"][ij].particles
    tops = [curve_probability(tr[e]["collisions"][ij])[0],
            curve_probability(tr[1]["collisions"]["P11"])[0]]
    floor = max(SURVIVORS_MIN / (n * t) for t in tops)
    top = np.geomspace(1e-1, 1e-3, 9)
    tail = np.geomspace(100 * floor, floor, 9) if floor < 1e-3 else np.array([])
    return top, tail


def same_level_members(tr, ij, reps=INTERVAL_REPLICATES, seed=TRANSPORT_JOINT_SEED):
    rng = np.random.default_rng(seed)
    out = []
    for name, fractions in zip(("top decades", "tail"), level_fractions(tr, ij), strict=True):
        variant = f"same level, {name}"
        if not len(fractions):
            out.append(F.too_few(variant, "collisions per time, ratio"))
            continue
        value = level_ratio(tr, ij, fractions)
        boots = [level_ratio(_resampled_transport(tr, rng), ij, fractions) for _ in range(reps)]
        boots = np.array([b for b in boots if math.isfinite(b)])
        if not math.isfinite(value) or len(boots) <= reps // 2:
            out.append(F.too_few(variant, "collisions per time, ratio"))
            continue
        lo, hi = float(np.percentile(boots, 2.5)), float(np.percentile(boots, 97.5))
        out.append(F.word_member(f"{variant} (f = {fractions[0]:.2g} to {fractions[-1]:.2g} of "
                                 "P(0))", "collisions per time, ratio", value, lo, hi, R.FEWER,
                                 R.FEWER_FAILS))
    return out


def _median_n(sample):
    """The median n of a sample, interpolated inside the cells of a joint record."""
    return weighted_quantile(sample.n, sample.weight, 0.5, sample.widths()[0])


def _median_n_ratio(sample_ij, sample_11, lo, hi):
    return _ratio_of_medians(sample_ij.select((sample_ij.t >= lo) & (sample_ij.t < hi)),
                             sample_11.select((sample_11.t >= lo) & (sample_11.t < hi)))


def _ratio_of_medians(a, b):
    """The ratio of the median n of two samples of one window of t (NaN with too few)."""
    if a.count < MIN_PER_BIN or b.count < MIN_PER_BIN:
        return math.nan
    return _median_n(a) / _median_n(b)


def _ratio_bootstraps(s_ij, s_11, windows, reps=INTERVAL_REPLICATES, seed=TRANSPORT_JOINT_SEED):
    """95% percentile interval of ``_median_n_ratio`` in each window (lo, hi) of t, with both
    samples redrawn (Poisson bootstrap, ``JointSample.resampled``); NaN when fewer than half the
    draws give a ratio. Every window's bootstrap starts from the same seed, so one set of draws
    serves them all: each redrawn sample is cut to the window directly (the escapes in it that
    the draw kept, in their order), the sample ``resampled(rng).select(window)`` would give."""
    rng = np.random.default_rng(seed)
    inside = [((s_ij.t >= lo) & (s_ij.t < hi), (s_11.t >= lo) & (s_11.t < hi))
              for lo, hi in windows]
    got = np.empty((len(windows), reps))
    for k in range(reps):
        w_ij = rng.poisson(s_ij.weight).astype(np.float64)
        w_11 = rng.poisson(s_11.weight).astype(np.float64)
        for i, (in_ij, in_11) in enumerate(inside):
            got[i, k] = _ratio_of_medians(s_ij.redrawn(w_ij, in_ij), s_11.redrawn(w_11, in_11))
    out = []
    for row in got:
        row = row[np.isfinite(row)]
        out.append((math.nan, math.nan) if len(row) <= reps // 2 else
                   (float(np.percentile(row, 2.5)), float(np.percentile(row, 97.5))))
    return out


def same_time_members(ij, joint, latest=2):
    e, out_hole = TRANSPORTING[ij]
    s_ij = joint[e].select(joint[e].exit == out_hole)
    s_11 = joint[1].select(joint[1].exit == 0)
    hi = max(s_ij.t.max(initial=1.0), s_11.t.max(initial=1.0)) * 1.0001
    edges = np.geomspace(1.0, hi, max(2, int(4 * math.log10(hi))) + 1)
    bins = []
    for lo_t, hi_t in zip(edges[:-1], edges[1:], strict=True):
        c_ij = s_ij.weight[(s_ij.t >= lo_t) & (s_ij.t < hi_t)].sum()
        c_11 = s_11.weight[(s_11.t >= lo_t) & (s_11.t < hi_t)].sum()
        if c_ij >= MIN_PER_BIN and c_11 >= MIN_PER_BIN:
            bins.append((lo_t, hi_t, c_ij))
    if not bins:
        return [F.too_few("same time", "median collisions, ratio")]
    out = []
    windows = [(lo_t, hi_t) for lo_t, hi_t, _ in bins[-latest:]]
    for (lo_t, hi_t), (lo, hi_) in zip(windows, _ratio_bootstraps(s_ij, s_11, windows),
                                       strict=True):
        value = _median_n_ratio(s_ij, s_11, lo_t, hi_t)
        variant = f"same time, t in [{lo_t:.3g}, {hi_t:.3g})"
        if math.isfinite(lo) and math.isfinite(hi_):
            out.append(F.word_member(variant, "median collisions, ratio", value, lo, hi_,
                                     R.FEWER, R.FEWER_FAILS))
        else:
            out.append(F.too_few(variant, "median collisions, ratio", value))
    return out


def joint_of(samples, joint):
    if joint:
        return joint
    fallback = "the run records no joint (n, t) histogram: sampled study"
    return {e: from_followed(f, fallback) for e, f in (samples or {}).items()}


def fewer_collisions_claims(tr, samples, joint, run):
    data = joint_of(samples, joint)
    claims = []
    for ij in TRANSPORTING:
        members = same_level_members(tr, ij)
        if data:
            members += same_time_members(ij, data)
        source = next(iter(data.values())).source if data else "no joint data"
        claims.append(make_claim(
            f"fig4-fewer-collisions-{ij}", f"Run curves and {source}; 'many fewer' "
            f"{R.bounds_text(R.FEWER, R.FEWER_FAILS, '{:g}'.format)}: "
            f"{F.family_text(members)}.", analyses=members,
            particles_per_curve=next(iter(tr[1]['time'].values())).particles, run=run))
    return claims


def expected_beyond(v, limit):
    """Orbits expected beyond ``limit`` under an exponential fitted to the largest TAIL_ORBITS
    of ``v`` (their maximum-likelihood scale is the mean excess over the smallest of them)."""
    v = np.sort(np.asarray(v, dtype=float))
    m = min(TAIL_ORBITS, len(v) - 1)
    if m < 10:
        return math.nan
    top, base = v[-m:], v[-m - 1]
    scale = float(np.mean(top - base))
    if scale <= 0:
        return 0.0
    return float(m * math.exp(-(limit - base) / scale)) if limit > base else float(
        np.sum(v > limit))


def velocity_member(v, variant):
    """The "large velocities" rule on the largest velocities ``v`` of one sample."""
    limit = R.LARGE_VELOCITY * TRANSPORT_V[1]
    low_limit = R.LARGE_VELOCITY_FAILS * TRANSPORT_V[1]
    total = len(v)
    if total == 0:
        return F.too_few(variant, "largest velocity")
    k, k_low = int((v > limit).sum()), int((v > low_limit).sum())
    lo = float(wilson(k, total)[0])
    lo_low, hi_low = (float(x) for x in wilson(k_low, total))
    expected = expected_beyond(v, limit)
    vmax = float(v.max())
    text = (f"{variant}: {total:,} orbits, largest v = {vmax:.4g}; {k} above {limit:g}, {k_low} "
            f"above {low_limit:g} (share 95% [{lo_low:.2g}, {hi_low:.2g}]); orbits expected "
            f"above {limit:g} under the sample's upper tail: {expected:.2g}")
    if lo > 0:
        verdict, note = CONFIRMED, ""
    elif hi_low < R.NONE_SHARE:
        verdict, note = REFUTED, ""
    elif expected < 1:
        verdict, note = INCONCLUSIVE, F.TOO_FEW
    else:
        verdict, note = INCONCLUSIVE, R.BETWEEN if lo_low >= R.NONE_SHARE else F.STRADDLES
    return F.Analysis(text, verdict, "largest velocity", vmax, vmax, vmax, (limit, math.inf),
                      ((-math.inf, low_limit),), note)


def large_velocity_claims(samples, joint=None, replicas=None):
    """``replicas``: {entry: Followed} of an independent study of the same setup."""
    claims = []
    for ij, (e, out_hole) in TRANSPORTING.items():
        fol = samples.get(e)
        if fol is None:
            continue
        studies = [("study", fol)] + ([("replica", replicas[e])] if replicas and e in replicas
                                      else [])
        members = [velocity_member(f.v_max[f.exit == out_hole], name) for name, f in studies]
        data = joint_of(samples, joint)
        mean_v = ""
        if data and e in data:
            s = data[e].select(data[e].exit == out_hole)
            if s.count:
                mean_v = (f"; their mean velocity t/(2n) ({s.source}) reaches "
                          f"{float(np.max(s.t / (2 * s.n))):.3g}")
        claims.append(make_claim(
            f"fig4-large-velocities-{ij}", f"Sampled study of entry hole {e}, "
            f"{fol.particles:,} starts: {F.family_text(members)}{mean_v}.", analyses=members,
            particles_per_curve=fol.particles))
    return claims
