"""Survival curves from escape histograms, binomial confidence bands and fits.

Counts come in fixed bins (``fastpath.ensemble``): bin k holds clock values x with
e_k <= x < e_{k+1}. With N particles, escapes E_k through the hole(s) of a curve and C particles
censored at the horizon (all known to outlive the range where the curve is reported):

    escape      P(x_k) = (sum_{m >= k} E_m + C) / N       fraction escaping later than x_k
    transport   P_ij(x_k) = sum_{m >= k} E_m^(j) / N      entered by i, leave by j later than x_k

so that sum_j P_ij(0) + C/N = 1. For the collision clock (integer escape index n >= 1) the point
is x_k = e_k - 1, since #{n >= e_k} = #{n > e_k - 1}: P(n) is the fraction escaping at an index
> n. For time x_k = e_k. A point is reported only where it is exact: x_k not beyond the lower
edge of the first bin holding a censoring bound (the particles censored there are known to
survive only that far). Points stop after the first zero.

Bands: the Wilson score interval for k successes in N trials at z (95%: z = 1.96),

    centre = (p + z**2/(2N)) / (1 + z**2/N),
    half   = z*sqrt(p*(1-p)/N + z**2/(4N**2)) / (1 + z**2/N).

Fits (``fit_survival``) over a window of x, by ``scipy.optimize.curve_fit`` on log P with the
band's width as the standard deviation, give the parameters with standard errors:

    exponential   P = a*exp(b*x)
    stretched     P = a*exp(b*sqrt(x))
    power         P = a*x**b
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import curve_fit

Z95 = 1.959963984540054

MODELS = {
    "exponential": lambda x: x,
    "stretched": np.sqrt,
    "power": np.log,
}
FORMULAS = {
    "exponential": "a*exp(b*x)",
    "stretched": "a*exp(b*sqrt(x))",
    "power": "a*x**b",
}


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


def survival_curve(escapes, censored, edges, particles, clock, add_censored):
    """Points (x, survivors, p) of one curve; see the module docstring.

    ``escapes``: counts per bin of this curve's exit(s). ``censored``: the censoring bounds per
    bin (they limit the range; they count as survivors when ``add_censored``).
    """
    escapes = np.asarray(escapes, dtype=np.int64)
    later = np.cumsum(escapes[::-1])[::-1]  # sum over m >= k
    survivors = later + (int(np.sum(censored)) if add_censored else 0)
    x = edges - 1.0 if clock == "collisions" else edges.astype(np.float64)
    keep = x <= valid_limit(censored, edges)
    x, survivors = x[keep], survivors[keep]
    zero = np.flatnonzero(survivors == 0)
    if len(zero):
        x, survivors = x[: zero[0] + 1], survivors[: zero[0] + 1]
    return x, survivors, survivors / particles


@dataclass(frozen=True)
class Fit:
    """Fitted parameters of P = model(x; a, b) with one-sigma standard errors."""

    model: str
    a: float
    b: float
    a_err: float
    b_err: float
    window: tuple[float, float]
    points: int

    def __str__(self):
        return (f"{FORMULAS[self.model]}: a = {self.a:.4g} +- {self.a_err:.2g}, "
                f"b = {self.b:.4g} +- {self.b_err:.2g} ({self.points} points in "
                f"[{self.window[0]:g}, {self.window[1]:g}])")

    def __call__(self, x):
        return self.a * np.exp(self.b * MODELS[self.model](np.asarray(x, dtype=np.float64)))


def fit_survival(x, p, p_lo, p_hi, model, window):
    """Fit ``model`` (exponential, stretched, power) to the points with x in ``window``.

    log P is fitted linearly in g(x) (x, sqrt(x), log x) with sigma = (log p_hi - log p_lo)/2z,
    the band in log space; absolute sigma, so the standard errors are statistical.
    Raises ValueError for an unknown model or fewer than 3 usable points.
    """
    if model not in MODELS:
        raise ValueError(f"fit model must be one of {', '.join(MODELS)}, got {model!r}")
    x, p = np.asarray(x, dtype=np.float64), np.asarray(p, dtype=np.float64)
    lo, hi = window
    use = (x >= lo) & (x <= hi) & (p > 0) & (np.asarray(p_lo) > 0)
    if model == "power":
        use &= x > 0
    if use.sum() < 3:
        raise ValueError(f"fewer than 3 points with P > 0 in the window [{lo:g}, {hi:g}]")
    g = MODELS[model](x[use])
    sigma = (np.log(np.asarray(p_hi)[use]) - np.log(np.asarray(p_lo)[use])) / (2 * Z95)
    (log_a, b), cov = curve_fit(lambda g, log_a, b: log_a + b * g, g, np.log(p[use]),
                                sigma=sigma, absolute_sigma=True)
    err = np.sqrt(np.diag(cov))
    a = float(np.exp(log_a))
    return Fit(model, a, float(b), a * float(err[0]), float(err[1]), (float(lo), float(hi)),
               int(use.sum()))
