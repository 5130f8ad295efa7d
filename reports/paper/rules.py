"""The decision rules of the paper's claims and the tolerances of its qualitative words.

Every tolerance is defined here once; the register (``reports.paper.register``) quotes them in
each claim's ``rule`` and ``tolerance``. They were fixed from the words, before any verdict:

* A decay *form* is read on the stretched exponent beta of exp(-c x^beta), which holds all three
  laws: beta = 1 is the exponential, beta = 1/2 the paper's sqrt(t) law, beta -> 0 the power law
  (``reports.stats.likelihood``). The paper names a form with a plain word ("exponential",
  "algebraic", "a slow power law"), always in contrast with the other two forms of its
  vocabulary; such a word holds when beta lies nearer its form than the others: the *cells*
  ``FORM_CELL`` power law [0, 1/4), sqrt [1/4, 3/4), exponential [3/4, 5/4]. Where it says
  "close to" a form, beta must lie within ``BAND`` = 0.1 of it: the *band* [0.4, 0.6] for the
  sqrt(t) law. The measured interval is the 95% profile-likelihood interval widened by the
  systematic half-range over the window family (``reports.stats.analysis.systematic``: start
  moved by 10^(+-1/4), end by 10^(-1/4)). ``band_verdict``: confirmed if that interval lies
  inside the cell (band), refuted if it lies wholly outside, inconclusive if it straddles an
  edge (the data cannot decide at this scale).
* "well approximated by" a law: the law wins the three-way comparison
  (``reports.stats.selection.choose``: likelihood-ratio tests against the stretched law, Vuong
  between the simple laws, level 0.05) and the fitted survival stays within ``RESIDUAL_LEVEL`` =
  10% (0.1 in log S) of the life-table survival beyond its 95% band over the whole window
  (``reports.stats.regime_fit.residual_excess``): what "looks like the law" on a plot spanning
  decades means, stated as a number.
* "the same" (two exponents, two hazards): equal to within ``SAME`` = 10% relative. For two
  estimates a +- U_a and b +- U_b (interval half-width + systematic): confirmed if
  |a - b| + U_a + U_b <= 0.1 (a + b)/2, refuted if |a - b| - U_a - U_b > 0.1 (a + b)/2,
  inconclusive otherwise (``same_verdict``).
* A window too small to decide: fewer than ``MIN_ESCAPES_INTERMEDIATE`` = 1000 escapes in an
  intermediate window or ``MIN_ESCAPES_TAIL`` = 100 in a tail window gives inconclusive, whatever
  the fits say.
"""

from __future__ import annotations

import math

from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.stats.regime_fit import residual_excess

BAND = 0.1
FORM_BETA = {"exponential": 1.0, "sqrt": 0.5, "power_law": 0.0}
FORM_CELL = {"power_law": (0.0, 0.25), "sqrt": (0.25, 0.75), "exponential": (0.75, 1.25)}
FORM_NAME = {"exponential": "exponential (beta = 1)", "sqrt": "stretched exponential with "
             "sqrt(x) in the exponent (beta = 1/2)", "power_law": "power law (beta -> 0)"}
RESIDUAL_LEVEL = 0.1
SAME = 0.1
MIN_ESCAPES_INTERMEDIATE = 1000
MIN_ESCAPES_TAIL = 100

# regimes of the escape curves (reports.paper.escape_regimes)
ONSET_TOLERANCE = 0.1       # <v> within 10% of its diffusive exponent
ONSET_SPAN_DECADES = 0.5    # local slopes of log<v> over half a decade
HAZARD_FAST = 0.9           # intermediate regime ends: hazard below 0.9 of its plateau
HAZARD_HALF = 0.5           # the slow population holds half the escapes
HAZARD_TENTH = 0.1          # tail starts: hazard at a tenth of its plateau
CHAOTIC_GONE = 0.1          # continuous tail: the intermediate law explains < 10% of survivors
SURVIVORS_MIN = 100         # matched survival levels go down to 100/N

# transport (reports.paper.transport_claims)
LONG_LIVED_LEVEL = 1e-4     # "long-lived": the last 10^-4 of the entrants still inside
TRAP_SHARE = 0.01           # "effectively traps": < 1% of them leave by the other hole
DECADE = 10.0               # "very strong P_11": outlives the other P_ij by a decade
ESCAPED_TO = 1e-6           # eventual escape: inside at the horizon < 1e-6 of the entrants
SUBSAMPLE = 0.01            # finite time: a 1% subsample reaches the same last bin
FEWER = 0.5                 # "many fewer collisions": at most half as many
LARGE_VELOCITY = 10.0       # "large velocities": 10 times the largest start velocity

# geometry, plateaus (reports.paper.geometry_claims, reports.paper.start_claims)
OVER_OR_NEAR = 0.01         # >= 1% of a strip widened by one hole width on the large island
ALMOST_ENTIRELY = 0.1       # "almost entirely in the chaotic sea": <= 10% on islands
MOSTLY = 0.5                # "mostly chaotic sea": < 50% on islands
BOTH = 0.01                 # "both islands and sea": >= 1% of each
BOUNDED = (-0.1, 0.1)       # velocity bounded: t/n ~ n^s with |s| <= 0.1 (1/2 if it diffused)


def band_verdict(lo, hi, band_lo, band_hi):
    """confirmed if [lo, hi] lies inside [band_lo, band_hi], refuted if wholly outside,
    inconclusive if it straddles an edge or is not finite."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return INCONCLUSIVE
    if band_lo <= lo and hi <= band_hi:
        return CONFIRMED
    if hi < band_lo or lo > band_hi:
        return REFUTED
    return INCONCLUSIVE


def form_range(form, close=False):
    """The beta range of a form word: its band (``close``: "close to") or its cell."""
    if not close:
        return FORM_CELL[form]
    beta = FORM_BETA[form]
    return max(0.0, beta - BAND), beta + BAND


def beta_interval(detail):
    """(beta, 95% interval, systematic half-range, widened interval) of a window's stretched
    fit (``reports.stats.regime_fit.window_detail``)."""
    fit = detail["fits"]["stretched_exponential"]
    beta = fit.params["beta"]
    lo, hi = fit.ci95.get("beta", (math.nan, math.nan))
    sys = detail["systematic"]["stretched_exponential"]["beta"]
    sys = math.inf if sys is None else sys
    return beta, (lo, hi), sys, (lo - sys, hi + sys)


def form_verdict(detail, form, min_escapes, close=False):
    """The form rule (module docstring) on one window: (verdict, beta, ci, sys, widened)."""
    beta, ci, sys, wide = beta_interval(detail)
    if detail["escapes"] < min_escapes:
        return INCONCLUSIVE, beta, ci, sys, wide
    lo, hi = form_range(form, close)
    if form == "power_law":  # the power law is the boundary beta = 0, where beta's interval ends
        wide = (max(wide[0], 0.0), wide[1])
    return band_verdict(*wide, lo, hi), beta, ci, sys, wide


def well_approximated_verdict(curve, detail, law, min_escapes):
    """The "well approximated by ``law``" rule (module docstring): (verdict, residual excess)."""
    excess = residual_excess(curve, detail["fits"][law])
    if detail["escapes"] < min_escapes or detail["best"] == "inconclusive":
        return INCONCLUSIVE, excess
    if detail["best"] != law or excess > RESIDUAL_LEVEL:
        return REFUTED, excess
    return CONFIRMED, excess


def same_verdict(a, u_a, b, u_b, relative=SAME):
    """The "the same" rule (module docstring): confirmed, refuted or inconclusive."""
    if not all(math.isfinite(x) for x in (a, u_a, b, u_b)):
        return INCONCLUSIVE
    d, u, band = abs(a - b), u_a + u_b, relative * 0.5 * (abs(a) + abs(b))
    if d + u <= band:
        return CONFIRMED
    if d - u > band:
        return REFUTED
    return INCONCLUSIVE


def fraction_at_least(k, n, level, ci):
    """confirmed if the Wilson interval ``ci`` of k/n lies at or above ``level``, refuted if it
    lies below, inconclusive otherwise."""
    lo, hi = ci
    if lo >= level:
        return CONFIRMED
    if hi < level:
        return REFUTED
    return INCONCLUSIVE


def fraction_at_most(k, n, level, ci):
    """confirmed if the Wilson interval lies at or below ``level``, refuted if above it."""
    lo, hi = ci
    if hi <= level:
        return CONFIRMED
    if lo > level:
        return REFUTED
    return INCONCLUSIVE


def all_of(verdicts):
    """confirmed if every verdict is, refuted if any is, inconclusive otherwise."""
    verdicts = list(verdicts)
    if verdicts and all(v == CONFIRMED for v in verdicts):
        return CONFIRMED
    if any(v == REFUTED for v in verdicts):
        return REFUTED
    return INCONCLUSIVE


def pct(x):
    return f"{100 * x:g}%"
