""""Well approximated by a stretched exponential" (Fig. 4 and the conclusion): the long-lived
reflected orbits P_11 of the transport problem.

The regime is the long-lived one (after the entrants of hole 1 still inside fall to
``rules.LONG_LIVED_LEVEL``); its windows start at the long-lived time and move later by quarter
decades while they hold at least ``rules.MIN_ESCAPES_TAIL`` escapes
(``window_family.late_windows``). On each window three members:

* the model selection (``reports.stats.selection.choose``): confirmed if it picks the stretched
  exponential, refuted if it picks the power law or the exponential, inconclusive if it cannot
  choose; the figure is the larger p-value of the two simple laws against the stretched one;
* the residual excess of the stretched law beyond the data's 95% band (``rules.RESIDUAL_LEVEL``,
  ``rules.RESIDUAL_FAILS``);
* its absolute goodness of fit, Pearson's chi-squared p-value (``rules.GOF_HOLDS``,
  ``rules.GOF_FAILS``): a likelihood ratio says which law fits better, not that it fits.
"""

from __future__ import annotations

import math

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.register import make_claim
from reports.paper.claims.window_family import late_windows, window_label
from reports.paper.claims.window_members import escapes_in, goodness_member, window_fit, window_fits
from reports.stats.analysis import usable_range
from reports.stats.goodness import pearson
from reports.stats.hazard import all_cause_survival, first_below
from reports.stats.regime_fit import residual_excess
from reports.stats.selection import LEVEL, choose

LAW = "stretched_exponential"


def long_lived_windows(tr, clock):
    """(P_11 curve, the long-lived regime's latest windows) in ``clock``."""
    c = tr[1][clock]["P11"]
    k = first_below(all_cause_survival(c), R.LONG_LIVED_LEVEL)
    if k is None:
        return c, []
    a0, b0 = usable_range(c)
    a = max(k, a0)
    if b0 - a < 2:
        return c, []
    return c, late_windows(c, a, b0, R.MIN_ESCAPES_TAIL)


def goodness_text(fits):
    """Pearson's chi-squared per dof and its p-value of each fitted law, in words."""
    out = []
    for law, fit in fits.items():
        g = pearson(fit)
        out.append(f"{law.replace('_', ' ')} chi^2/dof = {g.chi2:.4g}/{g.dof}, p = {g.p:.2g}"
                   if math.isfinite(g.p) else f"{law.replace('_', ' ')}: too few groups")
    return "; ".join(out)


def selection_member(curve, window, unit, part=""):
    fits = window_fits(curve, window)
    best, tests = choose(fits)
    p = max(tests["lr_stretched_vs_exponential"]["p"], tests["lr_stretched_vs_power_law"]["p"])
    verdict = (CONFIRMED if best == LAW else INCONCLUSIVE if best not in fits else REFUTED)
    variant = (f"{window_label(curve, window, unit)} ({escapes_in(curve, window):,} escapes): "
               f"the selection picks {best.replace('_', ' ')}; beside it, each law's absolute "
               f"goodness of fit: {goodness_text(fits)}")
    return F.Analysis(variant, verdict, "larger p of the simple laws", p, p, p,
                      (-math.inf, LEVEL), ((LEVEL, math.inf),),
                      "" if verdict != INCONCLUSIVE else F.STRADDLES, part)


def residual_member(curve, window, unit, part=""):
    excess = residual_excess(curve, window_fit(curve, window, LAW))
    variant = f"{window_label(curve, window, unit)}: residual excess of the stretched law"
    if not math.isfinite(excess):
        return F.in_part(part, [F.too_few(variant, "excess in log S")])[0]
    return F.in_part(part, [F.word_member(variant, "excess in log S", excess, excess, excess,
                                          R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS)])[0]


def form_members(tr, clock, part="", goodness=True, residual=True):
    """The members of "a stretched exponential" on P_11's long-lived windows in ``clock``."""
    curve, windows = long_lived_windows(tr, clock)
    unit = "n" if clock == "collisions" else "t"
    members = []
    for w in windows:
        members.append(selection_member(curve, w, unit, part))
        if residual:
            members.append(residual_member(curve, w, unit, part))
        if goodness:
            members.append(goodness_member(curve, w, LAW, unit, part))
    return members


def well_approximated_claim(claim_id, tr, clock, run):
    curve, windows = long_lived_windows(tr, clock)
    members = form_members(tr, clock)
    betas = []
    for w in windows:
        fit = window_fit(curve, w, LAW, intervals=True)
        lo, hi = fit.ci95.get("beta", (math.nan, math.nan))
        betas.append(f"{window_label(curve, w, 'n' if clock == 'collisions' else 't')}: beta = "
                     f"{fit.params['beta']:.3f} [{lo:.3f}, {hi:.3f}]")
    evidence = ((F.family_text(members) or "The long-lived level is not reached at "
                 f"{curve.particles:,} particles") + "; the stretched exponent (the paper leaves "
                "open whether it is exactly 1/2): " + ("; ".join(betas) or "none") + ".")
    return make_claim(claim_id, evidence, analyses=members, particles_per_curve=curve.particles,
                      run=run)
