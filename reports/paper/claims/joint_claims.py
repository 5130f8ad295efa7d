"""Claims about each escape's collisions n and time t together (Section 3), decided on joint
(n, t) data (``reports.paper.studies.joint_sample``: a run's joint record where it has one, else a
sampled study).

* ``bounded_velocity_claim``: "... orbits near the elliptic island, which do not accelerate, and
  in fact have tightly bounded velocity": the late escapes' time per collision t/n (twice
  their mean velocity) does not grow with n.
* ``n_sqrt_t_claim``: "the largest contribution from n ~ (3 c_1 n_0 t^2)^(1/4)": the escapes at
  time t in the intermediate regime made n ~ t^(1/2) collisions, a large-t statement.

Both are read as slopes over quarter decades of a binning variable, on windows whose start
moves later by quarter decades (``window_family.STEP``) from the regime's start while they hold
enough escapes (for the large-t statement the latest ``window_family.LATE_MEMBERS`` of them);
each window twice, with two statistics of the binned variable, its median and its mean (t/n of
the late orbits is a mixture locked to resonances at 2 pi, 4 pi, ...: a high quantile steps
from one to the next as their shares change, which is no velocity growth).
"""

from __future__ import annotations

import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import make_claim
from reports.paper.claims.window_family import LATE_MEMBERS, STEP
from reports.paper.studies.joint_sample import BinnedSlope, bootstrap_weights

TYPICAL_STATISTICS = ((0.5, "median"), (None, "mean"))


def late_slope_members(sample, x_of, y_of, start, end, statistics, holds, fails, quantity,
                       unit, limit=False, width_of=None):
    """Members: for each start s = start * STEP^k < end with at least MIN_ESCAPES_TAIL escapes
    in [s, end] and a slope (the latest LATE_MEMBERS of them where the words speak of a
    limit), each statistic's slope of log y on log x over [s, end] with its Poisson-bootstrap
    interval, under the two-band rule. ``width_of(sample)``: the log width of each y's cell
    (joint records)."""
    x_all = x_of(sample)
    starts = []
    k = 0
    while start * STEP ** k < end:
        s = start * STEP ** k
        sub = sample.select((x_all >= s) & (x_all <= end))
        calc = BinnedSlope(x_of(sub), y_of(sub), s, end,
                           None if width_of is None else width_of(sub))
        if sub.count >= R.MIN_ESCAPES_TAIL and math.isfinite(calc.slope(sub.weight)[0]):
            starts.append((s, sub, calc))
        k += 1
    members = []
    for s, sub, calc in (starts[-LATE_MEMBERS:] if limit else starts):
        for q, name in statistics:
            value, bins = calc.slope(sub.weight, q)
            lo, hi = bootstrap_weights(sub.weight, lambda w, q=q, calc=calc: calc.slope(w, q)[0])
            variant = (f"{unit} in [{s:.4g}, {end:.4g}] ({sub.count:,.0f} escapes, {bins} "
                       f"quarter decades), {name}")
            if math.isfinite(lo) and math.isfinite(hi):
                members.append(F.band_member(variant, quantity, value, lo, hi, holds, fails))
            else:
                members.append(F.too_few(variant, quantity, value))
    return members


def _source(sample):
    return sample.source if sample is not None else "no joint (n, t) data"


def bounded_velocity_claim(hole, a, sample, run):
    cid = f"fig2-bounded-velocity-phi_c={hole}"
    n_half = a["windows"].n_at.get("half")
    if sample is None or n_half is None:
        return make_claim(cid, f"{_source(sample)}; the hazard falls to half its plateau at "
                          f"n_half = {n_half}: nothing to measure.", run=run)
    late = sample.select((sample.exit >= 0) & (sample.n > n_half))
    if late.count == 0:
        return make_claim(cid, f"{_source(sample)}: no escape after n_half = {n_half:g}; the "
                          "slow decay needs more starts with n and t recorded together.",
                          particles_per_curve=sample.particles, run=run)
    members = late_slope_members(late, lambda s: s.n, lambda s: s.t / s.n, float(n_half),
                                 float(late.n.max()) * (1 + 1e-9), TYPICAL_STATISTICS,
                                 R.BOUNDED, R.BOUNDED_FAILS, "slope of log t/n on log n", "n",
                                 width_of=lambda s: sum(s.widths()))
    ratio = late.t / late.n
    evidence = (f"{_source(sample)}: {late.count:,.0f} escapes after n_half = {n_half:g} (the "
                f"slow population holds half the escapes), n up to {late.n.max():.4g}; t/n "
                f"(twice the mean velocity): median {np.median(ratio):.3g}; slopes of t/n on n "
                f"(0 for bounded velocity, 1/2 for velocity diffusion), bounded within "
                f"[{R.BOUNDED[0]:g}, {R.BOUNDED[1]:g}], not beyond [{R.BOUNDED_FAILS[0]:g}, "
                f"{R.BOUNDED_FAILS[1]:g}]: {F.family_text(members) or 'too few escapes'}.")
    return make_claim(cid, evidence, analyses=members, particles_per_curve=sample.particles,
                      run=run)


def n_sqrt_t_claim(hole, a, sample, run):
    cid = f"sec3-n-sqrt-t-phi_c={hole}"
    ct = a["curves"]["time"]
    window = a["windows"].t.get("intermediate")
    if window is None or sample is None:
        return make_claim(cid, f"{_source(sample)}; no continuous intermediate window.",
                          run=run)
    t_lo, t_hi = float(ct.x[window[0]]), float(ct.x[window[1]])
    esc = sample.select(sample.exit >= 0)
    band = R.form_range("sqrt", close=True)
    members = late_slope_members(esc, lambda s: s.t, lambda s: s.n, t_lo, t_hi,
                                 TYPICAL_STATISTICS, band, band, "slope of log n on log t", "t",
                                 limit=True, width_of=lambda s: s.widths()[0])
    evidence = (f"{_source(sample)}; the intermediate window t in [{t_lo:.4g}, {t_hi:.4g}], "
                "windows from later starts (a large-t statement); slopes of n on t against "
                f"the band [{band[0]:g}, {band[1]:g}] of n ~ t^(1/2) (n ~ t^(2/3) would be the "
                f"closed system's typical orbit): {F.family_text(members) or 'none'}.")
    return make_claim(cid, evidence, analyses=members, particles_per_curve=sample.particles,
                      run=run)
