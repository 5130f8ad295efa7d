"""Members of a family read on survival-curve windows: the stretched exponent beta of a window
against a form word, the power-law exponent alpha, and the absolute goodness of fit.

Every window is fitted on its own by maximum likelihood (``reports.stats.likelihood``, binned
and censored counts, 95% profile intervals); its member reads its own interval, never one
widened by other windows: the other windows are members of their own.
"""

from __future__ import annotations

import math

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.window_family import window_label
from reports.stats.goodness import pearson
from reports.stats.likelihood import LAWS, fit_law, window_of

_FITS = {}


def window_fit(curve, window, law, intervals=False):
    """One law fitted on the window (with its 95% intervals if asked), cached per curve,
    window and law: a fit with intervals serves a later call without."""
    key = (curve.source, curve.experiment, curve.curve, curve.clock, curve.particles, *window,
           law)
    have = _FITS.get(key)
    if have is None or (intervals and not have[1]):
        _FITS[key] = (fit_law(law, window_of(curve, *window), intervals), intervals)
    return _FITS[key][0]


def window_fits(curve, window):
    """The three laws fitted on the window (no intervals unless fitted with them before)."""
    return {law: window_fit(curve, window, law) for law in LAWS}


def escapes_in(curve, window):
    a, b = window
    return int(curve.escapes[a:b].sum())


def beta_member(curve, window, form, unit, close=False, part=""):
    """The form rule on beta of the window's stretched fit; its absolute goodness of fit
    (Pearson's chi-squared, ``reports.stats.goodness``) is said beside it."""
    fit = window_fit(curve, window, "stretched_exponential", intervals=True)
    lo, hi = fit.ci95.get("beta", (math.nan, math.nan))
    g = pearson(fit)
    fit_text = (f"chi^2/dof = {g.chi2:.4g}/{g.dof}, p = {g.p:.2g}" if math.isfinite(g.p)
                else "too few groups for chi^2")
    variant = (f"{window_label(curve, window, unit)} ({escapes_in(curve, window):,} escapes; "
               f"the stretched law's {fit_text})")
    return F.in_part(part, [F.form_member(variant, fit.params["beta"], lo, hi, form, close)])[0]


def alpha_of(curve, window):
    """(alpha, its 95% interval, its half-width) of the window's power-law fit."""
    fit = window_fit(curve, window, "power_law", intervals=True)
    lo, hi = fit.ci95.get("alpha", (math.nan, math.nan))
    half = 0.5 * (hi - lo) if math.isfinite(lo) and math.isfinite(hi) else math.inf
    return fit.params["alpha"], (lo, hi), half


def goodness_member(curve, window, law, unit, part=""):
    """Is the window well fitted by ``law`` in absolute terms? Pearson's chi-squared p-value
    (``reports.stats.goodness``) under the two bounds ``rules.GOF_HOLDS`` (not rejected at the
    model selection's level) and ``rules.GOF_FAILS`` (rejected beyond doubt)."""
    g = pearson(window_fit(curve, window, law))
    variant = (f"{window_label(curve, window, unit)}: chi^2 = {g.chi2:.4g} on {g.dof} dof "
               f"({g.per_dof:.3g} per dof)")
    if not math.isfinite(g.p):
        return F.in_part(part, [F.too_few(variant, "goodness-of-fit p")])[0]
    return F.in_part(part, [F.word_member(variant, "goodness-of-fit p", g.p, g.p, g.p,
                                          R.GOF_HOLDS, R.GOF_FAILS)])[0]
