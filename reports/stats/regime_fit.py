"""One regime of an analysed curve in detail, for the report's claims and figures.

``analysis.analyse`` finds the regimes of a curve (where the decay changes law) and fits the
late one with intervals. The paper's claims are also about other regimes, so here any
regime [x_from, x_to] is refitted with 95% profile intervals, its law chosen by the rule of
``selection`` (with Vuong's exponential-vs-power-law test kept, the paper's dichotomy), its
systematic half-ranges taken over the window family of ``analysis.systematic``. Fitted laws
are drawn anchored at the empirical all-cause survival

    S(x_k) = 1 - (escapes, competing escapes and horizon censorings in bins before k) / N.

The *bulk* regime is the one holding the most escapes of the curve (where most particles leave);
the *late* regime is the last one (``analyse``'s headline fit).
"""

from __future__ import annotations

import math

import numpy as np

from reports.stats.analysis import fit_all, systematic, usable_range
from reports.stats.life_table import life_table
from reports.stats.likelihood import window_of
from reports.stats.selection import choose


def all_cause_survival(curve):
    """S at every boundary x_k (module docstring)."""
    gone = curve.escapes + curve.competing + curve.censored
    return 1.0 - np.concatenate([[0], np.cumsum(gone)]) / curve.particles


def bins_of(curve, x_from, x_to):
    """Bin indices (a, b) of the boundaries x_from, x_to of a regime."""
    a = int(np.searchsorted(curve.x, x_from))
    b = int(np.searchsorted(curve.x, x_to))
    if curve.x[a] != x_from or curve.x[b] != x_to:
        raise ValueError(f"[{x_from:g}, {x_to:g}] is not on the bin grid of {curve.curve}")
    return a, b


def bulk_regime(result):
    """The regime of ``result["regimes"]`` holding the most escapes."""
    return max(result["regimes"], key=lambda r: r["escapes"])


def regime_detail(curve, regime):
    """Fits with 95% intervals, the chosen law and tests and the systematics of one regime."""
    return window_detail(curve, *bins_of(curve, regime["from"], regime["to"]))


def window_detail(curve, a, b):
    """``regime_detail`` of the window of bins a..b-1 (boundaries x_a..x_b)."""
    fits = fit_all(window_of(curve, a, b), intervals=True)
    best, tests = choose(fits)
    a0, b0 = usable_range(curve)
    return {"from": float(curve.x[a]), "to": float(curve.x[b]), "best": best, "tests": tests,
            "fits": fits, "systematic": systematic(curve, a, b, a0, b0),
            "escapes": int(curve.escapes[a:b].sum()), "bins": (a, b)}


def residual_excess(curve, fit, min_at_risk=100):
    """Largest |log S_fit - log S_data| beyond the data's 95% band over the window of ``fit``:
    max over boundaries of (|log S_fit(x) - log S(x)| - 1.96 sd(log S(x)))_+, with S the
    life-table survival since the window start and sd its Greenwood error
    (``reports.stats.life_table``); 0 when the law stays inside the band everywhere. Only
    boundaries with at least ``min_at_risk`` particles still at risk count (below that log S is
    too noisy for Greenwood's normal approximation)."""
    w = fit.window
    table = life_table(curve, w)
    s, sd_log = table.survival, table.sd_log
    risk_at = np.append(table.at_risk, table.at_risk_after)
    keep = (s > 0) & (risk_at >= min_at_risk)
    dev = np.abs(fit.log_survival(w.x[keep]) - np.log(s[keep])) - 1.96 * sd_log[keep]
    return float(max(0.0, dev.max())) if keep.any() else math.inf


def fitted_curve(curve, regime, law, points=60):
    """(x, S(x)) of ``law`` fitted on the regime, anchored at the empirical S(x_from)."""
    a, b = bins_of(curve, regime["from"], regime["to"])
    fit = fit_all(window_of(curve, a, b), intervals=False)[law]
    x = np.geomspace(curve.x[a], curve.x[b], points)
    return x, all_cause_survival(curve)[a] * np.exp(fit.log_survival(x))


def half_width(ci):
    """Half the width of a (lo, hi) interval (inf if an end is not finite)."""
    lo, hi = ci
    return 0.5 * (hi - lo) if math.isfinite(lo) and math.isfinite(hi) else math.inf
