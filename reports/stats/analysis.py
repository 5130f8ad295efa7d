"""The whole inference for one curve: usable range, regimes, late-time law, systematics.

1. Usable range: from the first bin boundary x > 0 (the power law needs x > 0; earlier escapes
   are conditioned away) to the earlier of the upper boundary of the last bin with an escape of
   this curve and the first bin holding a horizon censoring bound (``histogram``).
2. Regimes by binary segmentation (``regimes``; on a grid of at most ``regimes.SEARCH_BINS``
   merged bins, so its cost is bounded); each regime's law by the rule of
   ``selection``, with that law's parameters (the stretched law's when inconclusive). The
   late-time regime is the window of the headline fit: its three laws with
   profile 95% intervals, the tests, and ``best``.
3. Systematic uncertainty: every parameter's half-range over the family of windows whose start
   is the window start or the boundary nearest a factor 10**(+-1/4) from it (clipped to the
   usable range), and whose end is the window end or the boundary nearest 10**(-1/4) times it;
   windows too small for a regime (``regimes.MIN_BINS``, ``MIN_ESCAPES``) are left out.
"""

from __future__ import annotations

import math

import numpy as np

from reports.stats import regimes as rg
from reports.stats.likelihood import BETA_MAX, LAWS, PARAMS, fit_law, window_of
from reports.stats.selection import INCONCLUSIVE, choose

SHIFT_DECADES = 0.25


def usable_range(curve):
    """(a, b): bin indices of the usable range (module docstring)."""
    x = curve.x
    positive = np.flatnonzero(x[:-1] > 0)
    hits = np.flatnonzero(curve.escapes)
    if not len(hits):
        raise ValueError(f"{curve.source}: {curve.curve} ({curve.clock}): no escapes")
    a = int(positive[0]) if len(positive) else len(x) - 1
    b = int(hits[-1]) + 1
    cens = np.flatnonzero(curve.censored)
    if len(cens):
        b = min(b, int(cens[0]))
    if not math.isfinite(x[b]):
        b -= 1
    if b <= a or curve.escapes[a:b].sum() == 0:
        raise ValueError(f"{curve.source}: {curve.curve} ({curve.clock}): no escapes after "
                         f"x = {x[a]:g} before the horizon")
    return a, b


def fit_all(window, intervals=True):
    """The three laws on one window."""
    return {law: fit_law(law, window, intervals) for law in LAWS}


def _nearest(x, target, lo, hi):
    return int(np.clip(np.argmin(np.abs(np.log(x[lo:hi + 1] / target))) + lo, lo, hi))


def systematic(curve, a, b, a0, b0):
    """Half-range of each law's parameters over the window family (module docstring)."""
    x = curve.x
    starts = {a, _nearest(x, x[a] * 10 ** SHIFT_DECADES, a0, b0),
              _nearest(x, x[a] * 10 ** -SHIFT_DECADES, a0, b0)}
    ends = {b, _nearest(x, x[b] * 10 ** -SHIFT_DECADES, a0, b0)}
    values = {law: {p: [] for p in PARAMS[law]} for law in LAWS}
    used = []
    for s in sorted(starts):
        for e in sorted(ends):
            if e - s < rg.MIN_BINS or curve.escapes[s:e].sum() < rg.MIN_ESCAPES:
                continue
            try:
                fits = fit_all(window_of(curve, s, e), intervals=False)
            except ValueError:
                continue
            used.append([float(x[s]), float(x[e])])
            for law, f in fits.items():
                for p in PARAMS[law]:
                    values[law][p].append(f.params[p])
    out = {law: {p: (_half_range(v) if v else None) for p, v in ps.items()}
           for law, ps in values.items()}
    out["windows"] = used
    return out


def _half_range(v):
    v = np.asarray(v, dtype=np.float64)
    if not np.all(np.isfinite(v)):
        return math.inf
    return float(0.5 * (v.max() - v.min()))


def analyse(curve, progress=None):
    """Result dict of one curve (the ``bouncer fit --json`` object, less ``source``).
    ``progress(text)``: told of each stage (the regime search, its crossovers, the fits)."""
    say = progress or (lambda _text: None)
    a0, b0 = usable_range(curve)
    grid = rg.search_grid(curve, a0, b0)
    coarse = rg.merged(curve, grid) if len(grid) < b0 - a0 + 1 else curve
    say(f"regime search over {b0 - a0} bins" + (f" (on {len(grid) - 1} merged bins)"
                                                if coarse is not curve else ""))
    if coarse is curve:
        bounds, splits, late_split_p = rg.segment(curve, a0, b0, say)
    else:
        cb, splits, late_split_p = rg.segment(coarse, 0, len(grid) - 1, say)
        bounds = [int(grid[k]) for k in cb]
    say(f"{len(bounds) - 1} regimes; fits with intervals")
    regime_list, regime_fits = [], []
    for lo, hi in zip(bounds[:-1], bounds[1:], strict=True):
        fits = fit_all(window_of(curve, lo, hi), intervals=False)
        law = choose(fits)[0]
        shown = "stretched_exponential" if law == INCONCLUSIVE else law
        regime_fits.append(fits[shown])
        regime_list.append({"law": law, "from": float(curve.x[lo]), "to": float(curve.x[hi]),
                            "params": dict(fits[shown].params),
                            "escapes": int(curve.escapes[lo:hi].sum())})
    a, b = bounds[-2], bounds[-1]
    window = window_of(curve, a, b)
    fits = fit_all(window)
    best, tests = choose(fits)
    regime_list[-1].update(law=best, params=dict(
        fits["stretched_exponential" if best == INCONCLUSIVE else best].params))
    regime_fits[-1] = fits["stretched_exponential" if best == INCONCLUSIVE else best]
    models = {}
    for law, f in fits.items():
        entry = {}
        for p in PARAMS[law]:
            entry[p] = f.params[p]
            entry[f"{p}_ci95"] = list(f.ci95[p])
        entry.update(loglik=f.loglik, aic=f.aic)
        models[law] = entry
    return {
        "experiment": curve.experiment,
        "curve": curve.curve,
        "clock": curve.clock,
        "particles": curve.particles,
        "best": best,
        "models": models,
        "tests": tests,
        "window": [window.start, window.end],
        "escapes_in_window": int(window.escapes.sum()),
        "at_risk_in_window": window.at_risk,
        "regimes": regime_list,
        "crossovers": rg.crossover_entries(coarse, splits),
        "late_regime_split_p": late_split_p,
        "systematic": systematic(curve, a, b, a0, b0),
        "_fits": fits,
        "_regime_fits": regime_fits,
    }


__all__ = ["INCONCLUSIVE", "analyse", "fit_all", "systematic", "usable_range"]


def _value(v):
    return "inf" if v is None or (isinstance(v, float) and math.isinf(v)) else f"{v:.4g}"


def _param_text(model, name):
    return f"{name}={_value(model[name])} {interval_text(model, name)}"


def interval_text(model, name):
    """The 95% interval of parameter ``name`` of a fitted law (``model``: a dict holding
    ``name`` and ``name_ci95``, or a LawFit's params with ``ci95``), with words for the ends
    the data do not bound: an infinite end is "unbounded"; the stretched law's c is unbounded
    above whenever beta's interval reaches 0, for the power law (beta -> 0, c -> inf) is then
    inside it, whatever finite number the search stopped at; an end of beta at 0 or BETA_MAX is
    the end of the range fitted."""
    lo, hi = model.get(f"{name}_ci95", (None, None))
    if name == "c" and model.get("beta_ci95", (None, None))[0] == 0.0:
        return f"[{_end(lo)}, unbounded: beta's interval reaches 0, the power law]"
    if name == "beta":
        return (f"[{_end(lo)}{' (the power law)' if lo == 0.0 else ''}, {_end(hi)}"
                f"{' (the largest beta fitted)' if hi == BETA_MAX else ''}]")
    return f"[{_end(lo)}, {_end(hi)}]"


def _end(v):
    return "unbounded" if v is None or (isinstance(v, float) and math.isinf(v)) else f"{v:.4g}"


def best_law_text(result):
    """The best law of an ``analyse`` result (or its JSON form) in words, with its parameters
    and 95% intervals. A stretched fit on the boundary beta = 0 is the power law (c is infinite
    there, alpha = c beta finite), so it is shown as the power law, never as "c = inf, beta = 0";
    an inconclusive comparison shows both simple laws, not a stretched fit as if it were one."""
    models, best = result["models"], result["best"]
    stretched = models["stretched_exponential"]
    if best == "exponential":
        return "exponential (" + _param_text(models["exponential"], "gamma") + ")"
    if best == "power_law":
        return "power law (" + _param_text(models["power_law"], "alpha") + ")"
    if best == "stretched_exponential":
        if not stretched["beta"]:
            return ("power law (" + _param_text(models["power_law"], "alpha")
                    + "; the stretched fit sits on its power-law boundary beta = 0)")
        return ("stretched exponential (" + _param_text(stretched, "c") + ", "
                + _param_text(stretched, "beta") + ")")
    return ("inconclusive: neither simple law is rejected and Vuong's test does not choose "
            "(exponential " + _param_text(models["exponential"], "gamma") + "; power law "
            + _param_text(models["power_law"], "alpha") + ")")
