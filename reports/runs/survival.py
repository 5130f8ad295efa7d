"""Empirical survival curves of a run (survival.csv) from its histograms, with binomial bands.

Counts come in fixed bins (``fastpath.kernels.escape``): bin k holds clock values x with
e_k <= x < e_{k+1}. With N particles, escapes E_k through the hole(s) of a curve and C particles
censored at the horizon (all known to outlive the range where the curve is reported):

    escape      P(x_k) = (sum_{m >= k} E_m + C + S) / N   fraction escaping later than x_k
    transport   P_ij(x_k) = sum_{m >= k} E_m^(j) / N      entered by i, leave by j later than x_k

so that sum_j P_ij(0) + C/N + S/N = 1, with S the particles stuck on the plate for good
(restitution < 1; they never escape; S = 0 for the elastic model). For the collision clock
(integer escape index n >= 1) the point is x_k = e_k - 1, since #{n >= e_k} = #{n > e_k - 1}:
P(n) is the fraction escaping at an index > n. For time x_k = e_k. A point is reported only
where it is exact: x_k not beyond the lower edge of the first bin holding a censoring bound
(the particles censored there are known to survive only that far). Points stop after the
first zero.

Bands: the Wilson score interval for k successes in N trials at z (95%: z = 1.96),

    centre = (p + z**2/(2N)) / (1 + z**2/N),
    half   = z*sqrt(p*(1-p)/N + z**2/(4N**2)) / (1 + z**2/N).
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from reports.runs import rundir

Z95 = 1.959963984540054
BAND = "95% Wilson score interval"  # what ``wilson`` at Z95 gives: p_lo, p_hi of survival.csv


def wilson(k, n, z=Z95):
    """Wilson score interval (lo, hi) for k successes out of n (arrays broadcast)."""
    k = np.asarray(k, dtype=np.float64)
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / denom
    lo = np.where(k == 0, 0.0, np.clip(centre - half, 0.0, 1.0))  # exact ends, no rounding
    hi = np.where(k == n, 1.0, np.clip(centre + half, 0.0, 1.0))
    return lo, hi


def valid_limit(censored, edges):
    """Largest clock value up to which survival is exact: the lower edge of the first bin with a
    censoring bound (inf if none were censored)."""
    hit = np.flatnonzero(censored)
    return float(edges[hit[0]]) if len(hit) else np.inf


def survival_curve(escapes, censored, edges, particles, clock, add_censored, stuck=0):
    """Points (x, survivors, p) of one curve; see the module docstring.

    ``escapes``: counts per bin of this curve's exit(s). ``censored``: the censoring bounds per
    bin (they limit the range; they count as survivors when ``add_censored``). ``stuck``:
    particles stuck on the plate for good (restitution < 1), which never escape: survivors at
    every x when ``add_censored`` (an escape curve), no range limit; 0 for the elastic model.
    """
    escapes = np.asarray(escapes, dtype=np.int64)
    later = np.cumsum(escapes[::-1])[::-1]  # sum over m >= k
    survivors = later + (int(np.sum(censored)) + int(np.sum(stuck)) if add_censored else 0)
    x = edges - 1.0 if clock == "collisions" else edges.astype(np.float64)
    keep = x <= valid_limit(censored, edges)
    x, survivors = x[keep], survivors[keep]
    zero = np.flatnonzero(survivors == 0)
    if len(zero):
        x, survivors = x[: zero[0] + 1], survivors[: zero[0] + 1]
    return x, survivors, survivors / particles


def read_survival(path):
    """survival.csv as {(curve, clock): (x, p, p_lo, p_hi)} of float arrays."""
    curves = defaultdict(list)
    for row in rundir.read_csv(path):
        curves[row["curve"], row["clock"]].append(
            [float(row[k]) for k in ("x", "p", "p_lo", "p_hi")])
    return {key: tuple(np.array(rows).T) for key, rows in curves.items()}
