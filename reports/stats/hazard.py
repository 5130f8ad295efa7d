"""Survival levels, hazards and quantiles of a binned curve (``histogram.Curve``).

With R_k the particles at risk at boundary x_k (all outcomes: escapes of this curve, competing
escapes and horizon censorings before bin k are gone) and E_k the escapes of this curve in bin k:

    all-cause survival    S(x_k) = R_k / N
    this curve's P(x_k)   = (escapes of this curve in bins >= k) / N     (P_ij of transport)
    hazard                lambda = -log(1 - E / R) / (x_hi - x_lo)        per unit of the clock,

the hazard taken over groups of bins spanning about 1/``HAZARD_PER_DECADE`` of a decade (bins
below x = 1 each on their own), so that it is smooth where the run's bins are narrow.

Quantiles: x at which S falls to a level s, interpolated linearly in (log x, log S) between the
boundaries around it (the bins' own resolution).
"""

from __future__ import annotations

import math

import numpy as np

HAZARD_PER_DECADE = 4


def at_risk(curve):
    """R_k at every boundary x_0..x_K (particles not yet gone, all outcomes)."""
    gone = curve.escapes + curve.competing + curve.censored
    return curve.particles - np.concatenate([[0], np.cumsum(gone)])


def all_cause_survival(curve):
    """S(x_k) = R_k / N at every boundary."""
    return at_risk(curve) / curve.particles


def curve_probability(curve):
    """P(x_k): this curve's escapes at or after bin k, over N (transport's P_ij(x))."""
    later = np.concatenate([curve.escapes[::-1].cumsum()[::-1], [0]])
    return later / curve.particles


def hazard_groups(curve, per_decade=HAZARD_PER_DECADE):
    """Bin groups [(a, b)] of about 1/per_decade decade each over the finite bins (bins with
    x_k < 1 alone)."""
    x = curve.x
    last = len(x) - 1 if math.isfinite(x[-1]) else len(x) - 2
    groups, a = [], 0
    while a < last:
        if x[a] < 1.0:
            b = a + 1
        else:
            target = x[a] * 10.0 ** (1.0 / per_decade)
            b = int(np.searchsorted(x, target * (1 - 1e-12)))
            b = min(max(b, a + 1), last)
        groups.append((a, b))
        a = b
    return groups


def hazard(curve, per_decade=HAZARD_PER_DECADE):
    """(groups, lambda) of this curve's escapes per unit clock over ``hazard_groups`` (NaN where
    nobody is at risk)."""
    risk = at_risk(curve)
    groups = hazard_groups(curve, per_decade)
    lam = np.full(len(groups), math.nan)
    for i, (a, b) in enumerate(groups):
        r = risk[a]
        if r > 0:
            e = curve.escapes[a:b].sum()
            lam[i] = -math.log1p(-min(e / r, 1.0 - 1e-16)) / (curve.x[b] - curve.x[a])
    return groups, lam


def hazard_fall(curve, x_from, factor, per_decade=HAZARD_PER_DECADE, min_escapes=100):
    """Boundary index where the hazard first falls to ``factor`` times its largest value over
    the groups starting at x >= x_from with at least ``min_escapes`` escapes, after that largest
    value; None if it never does (or no group qualifies). Returns (index, lambda_max)."""
    groups, lam = hazard(curve, per_decade)
    ok = [i for i, (a, b) in enumerate(groups)
          if curve.x[a] >= x_from and curve.escapes[a:b].sum() >= min_escapes
          and math.isfinite(lam[i])]
    if not ok:
        return None, math.nan
    top = max(ok, key=lambda i: lam[i])
    for i in range(top + 1, len(groups)):
        if math.isfinite(lam[i]) and lam[i] <= factor * lam[top]:
            return groups[i][0], float(lam[top])
    return None, float(lam[top])


def first_below(values, level):
    """Index of the first boundary where ``values`` <= level, or None."""
    hit = np.flatnonzero(np.asarray(values) <= level)
    return int(hit[0]) if len(hit) else None


def quantile(x, s, level):
    """x at which the decreasing survival s (at boundaries x) falls to ``level``, interpolated
    in (log x, log s); None when s never falls that low, x[0] when s starts below it."""
    x = np.asarray(x, dtype=np.float64)
    s = np.asarray(s, dtype=np.float64)
    k = first_below(s, level)
    if k is None:
        return None
    if k == 0:
        return float(x[0])
    x0, x1, s0, s1 = x[k - 1], x[k], s[k - 1], s[k]
    if not (x0 > 0 and math.isfinite(x1) and s1 > 0):
        return float(x1) if math.isfinite(x1) else float(x0)
    f = (math.log(s0) - math.log(level)) / (math.log(s0) - math.log(s1))
    return float(math.exp(math.log(x0) + f * (math.log(x1) - math.log(x0))))


def boundary_index(curve, x_value):
    """Index of the boundary of ``curve`` nearest x_value in log x (finite boundaries > 0)."""
    x = curve.x
    ok = np.flatnonzero((x > 0) & np.isfinite(x))
    return int(ok[np.argmin(np.abs(np.log(x[ok] / x_value)))])


def hazard_ratio(ref, other, a, b):
    """Log-rank (Mantel-Haenszel) estimate of the hazard ratio of ``other`` to ``ref`` over the
    bins a..b-1 of two curves on the same boundaries, with its 95% interval:

        log HR = sum (O_k - E_k) / sum V_k,  se = 1/sqrt(sum V_k),
        E_k = d_k r2_k / r_k,  V_k = d_k r1_k r2_k (r_k - d_k) / (r_k^2 (r_k - 1)),

    d_k = escapes of both in bin k, r1, r2 their particles at risk, r = r1 + r2, O_k = other's
    escapes. Returns (HR, (lo, hi), escapes used)."""
    if not np.array_equal(ref.x, other.x):
        raise ValueError("hazard_ratio needs two curves on the same bin boundaries")
    b = min(b, len(ref.escapes))
    r1 = at_risk(ref)[a:b].astype(np.float64)
    r2 = at_risk(other)[a:b].astype(np.float64)
    d1 = ref.escapes[a:b].astype(np.float64)
    d2 = other.escapes[a:b].astype(np.float64)
    d, r = d1 + d2, r1 + r2
    ok = (r1 > 0) & (r2 > 0) & (d > 0) & (r > 1)
    e2 = d[ok] * r2[ok] / r[ok]
    v = d[ok] * r1[ok] * r2[ok] * (r[ok] - d[ok]) / (r[ok] ** 2 * (r[ok] - 1))
    total = float(v.sum())
    if total <= 0:
        return math.nan, (math.nan, math.nan), int(d.sum())
    log_hr = float((d2[ok] - e2).sum()) / total
    se = 1.0 / math.sqrt(total)
    return (math.exp(log_hr), (math.exp(log_hr - 1.96 * se), math.exp(log_hr + 1.96 * se)),
            int(d.sum()))
