"""The decision rules of the paper's claims and the tolerances of its qualitative words.

Every tolerance is defined here once; the register (``reports.paper.claims.register``) quotes them
in each claim's ``rule`` and ``tolerance``. The thresholds that place the regimes of an escape
curve (diffusive onset, hazard fall, the fewest survivors a level rests on) belong to the study
that places them, ``reports.paper.studies.escape_regimes``. They were fixed from the words,
before any verdict:

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
  decades means, stated as a number. It fails if another law wins or the excess reaches
  ``RESIDUAL_FAILS`` = 0.25 (the two-bound rule below; ``well_approximated_verdict``).
* The other qualitative words ("the same", "many fewer", "large", "effectively traps", "almost
  entirely", ...) are fuzzy near their edge, so each has TWO bounds, fixed from the word before
  any verdict: a bound within which the word clearly holds and a bound beyond which it clearly
  fails (its opposite applies). The measurement's interval (Wilson, bootstrap or profile
  interval, widened by the systematic where there is one) decides: ``confirmed`` if it lies
  wholly in the holds zone, ``refuted`` if it lies wholly in the fails zone, ``inconclusive``
  otherwise; the evidence says "between the word's bounds" (``BETWEEN``) when the interval lies
  wholly between them, and that it straddles a bound otherwise (``word_verdict``,
  ``two_band_verdict``, ``word_note``). Both zones include their bounds. The bounds, holds then
  fails, and why:

  - "the same" (two exponents, two hazards, a limit and a share; ``SAME``, ``SAME_FAILS``):
    within 10% relative; beyond 25% relative (a 25% difference in a slope is plainly visible
    over two decades of a log-log plot). For a +- U_a and b +- U_b (interval half-width +
    systematic) and m = (|a| + |b|)/2: confirmed if |a - b| + U_a + U_b <= 0.1 m, refuted if
    |a - b| - U_a - U_b >= 0.25 m (``same_verdict``). Hazard ratios: within [1/1.1, 1.1];
    wholly outside [1/1.25, 1.25]. An exponent against the paper's value (the Fermi exponents
    1/2 and 1/3): within 10% of it; wholly beyond 25% of it.
  - "many fewer collisions" (``FEWER``, ``FEWER_FAILS``): a ratio at most 0.5; at least 0.9
    ("about as many").
  - "large velocities" (``LARGE_VELOCITY``, ``LARGE_VELOCITY_FAILS``): some transporting orbit
    exceeds 10 times the largest start velocity; none exceeds 2 times it (they stay at the start
    velocities). "None" in a sample: the Wilson upper bound of the share below ``NONE_SHARE`` =
    10^-4.
  - "destroy all" / "effective destruction" of an island (``DESTROYED``, ``DESTROYED_FAILS``):
    at most 1% of its orbits remain; at least 50% remain (most of the island survives).
  - "effectively traps" (``TRAP_SHARE``, ``TRAP_SHARE_FAILS``): at most 1% of the long-lived
    orbits leave by the other hole; at least 10% do (does not trap). "Does not effectively
    trap" is the same pair read the other way.
  - "almost entirely in the chaotic sea", "for practical purposes ... strongly chaotic"
    (``ALMOST_ENTIRELY``, ``ALMOST_ENTIRELY_FAILS``): at most 10% on islands; at least 50%
    (mostly islands, ``MOSTLY_FAILS``).
  - "mostly chaotic sea" (``MOSTLY``, ``MOSTLY_FAILS``): at most a quarter on islands (three
    quarters sea is plainly "mostly"); at least half on islands (the sea is no longer the
    majority). "Most of the late survivors on the large islands" is the same pair on the
    locked share: at least 3/4; at most 1/2.
  - "well approximated" (``RESIDUAL_LEVEL``, ``RESIDUAL_FAILS``): the law wins the three-way
    comparison and its residual excess is at most 0.1 in log S; another law wins or the excess
    is at least 0.25 (a 28% miss of the survival beyond its band). A comparison says which law
    fits better, not that it fits: the word also needs the law's absolute goodness of fit
    (Pearson's chi-squared on the window, ``reports.stats.goodness``; ``GOF_HOLDS``,
    ``GOF_FAILS``): p >= 0.05, not rejected at the comparison's own level; p <= 0.001, rejected
    beyond doubt.
  - "over or near the large islands" (``OVER_OR_NEAR``, ``OVER_OR_NEAR_FAILS``): at least 1% of
    the strip widened by one hole width on the large island; at most 0.1%, a trace (the hole is
    far from the island).
  - "far from the large islands" / "none of the large ones" under the hole at pi (``FAR``,
    ``FAR_FAILS``): at most 1% of the hole's strip on the large island; at least 10% (the hole
    covers a part of it, the factor of ten of "effectively traps").
  - "both elliptic islands and chaotic sea" (``BOTH``, ``BOTH_FAILS``): at least 1% of each; at
    most 0.1% of one of them, a trace (the hole covers only the other).
  - "very strong P_11" (``DECADE``, ``STRONG_FAILS``): P_11 outlives the other P_ij by a factor
    10 in time; by at most a factor 2 (about as long-lived, as "large velocities" fails at twice
    the start velocity). The interval is the ratio times and over one bin of the runs' grid.
  - "tightly bounded velocity" (``BOUNDED``, ``BOUNDED_FAILS``): t/n ~ n^s with |s| <= 0.1;
    |s| >= 0.25, nearer velocity diffusion (s = 1/2) than bounded velocity (s = 0).
  - "quite a lot smaller" (a hole against an island; ``MUCH_SMALLER``, ``MUCH_SMALLER_FAILS``):
    the island at least 3 hole widths wide; at most 2 (the hole half the island or more).

  Left with one threshold, as they are not vague words: "eventually escapes" (an exact
  statement, read at the horizon with ``ESCAPED_TO`` as the measurement's floor), "tends to a
  constant" (whether the fall decelerates: the sign of a change) and the comparatives "even more
  similar", "slower at first" (an ordering, decided beyond the data's resolution).
* A window too small to decide: fewer than ``MIN_ESCAPES_INTERMEDIATE`` = 1000 escapes in an
  intermediate window or ``MIN_ESCAPES_TAIL`` = 100 in a tail window gives inconclusive, whatever
  the fits say.
"""

from __future__ import annotations

import math

from reports.paper.claims.claim import BETWEEN, CONFIRMED, INCONCLUSIVE, REFUTED
from reports.stats.regime_fit import residual_excess

BAND = 0.1
FORM_BETA = {"exponential": 1.0, "sqrt": 0.5, "power_law": 0.0}
FORM_CELL = {"power_law": (0.0, 0.25), "sqrt": (0.25, 0.75), "exponential": (0.75, 1.25)}
FORM_NAME = {"exponential": "exponential (beta = 1)", "sqrt": "stretched exponential with "
             "sqrt(x) in the exponent (beta = 1/2)", "power_law": "power law (beta -> 0)"}
RESIDUAL_LEVEL = 0.1
RESIDUAL_FAILS = 0.25
SAME = 0.1
SAME_FAILS = 0.25
MIN_ESCAPES_INTERMEDIATE = 1000
MIN_ESCAPES_TAIL = 100
GOF_HOLDS = 0.05    # "well approximated" by a law: Pearson's chi^2 does not reject it at 5%
GOF_FAILS = 0.001   # ... rejected beyond doubt (p <= 0.001)

CHAOTIC_GONE = 0.1          # continuous tail: the intermediate law explains < 10% of survivors

# dynamics (reports.paper.claims.dynamics_claims)
NEAR = 0.05           # "near eps = 0.24": within 5% of K_c/4
LOWEST_MARGIN = 0.20  # "all but the lowest velocities": band 0 keeps curves 20% beyond K_c/4
SIGMAS = 5.0          # a sign (lambda > 0, alpha < 0) is decided at 5 standard errors

# transport (reports.paper.claims.transport_claims); each word: the bound where it holds, then fails
LONG_LIVED_LEVEL = 1e-4     # "long-lived": the last 10^-4 of the entrants still inside
TRAP_SHARE = 0.01           # "effectively traps": <= 1% of them leave by the other hole
TRAP_SHARE_FAILS = 0.1      # ... does not trap: >= 10% do
DECADE = 10.0               # "very strong P_11": outlives the other P_ij by a decade
STRONG_FAILS = 2.0          # ... not very strong: by at most a factor 2
ESCAPED_TO = 1e-6           # eventual escape: inside at the horizon < 1e-6 of the entrants
FEWER = 0.5                 # "many fewer collisions": at most half as many
FEWER_FAILS = 0.9           # ... about as many: at least 0.9 as many
LARGE_VELOCITY = 10.0       # "large velocities": above 10 times the largest start velocity
LARGE_VELOCITY_FAILS = 2.0  # ... none above 2 times it
NONE_SHARE = 1e-4           # "none" in a sample: Wilson upper bound of the share below 10^-4

# geometry, plateaus (reports.paper.claims.geometry_claims, reports.paper.claims.start_claims)
OVER_OR_NEAR = 0.01         # >= 1% of a strip widened by one hole width on the large island
OVER_OR_NEAR_FAILS = 0.001  # ... far: <= 0.1% (a trace)
FAR = 0.01                  # "far from the large islands": <= 1% of the hole's strip on them
FAR_FAILS = 0.1             # ... covers part of them: >= 10%
ALMOST_ENTIRELY = 0.1       # "almost entirely in the chaotic sea": <= 10% on islands
MOSTLY = 0.25               # "mostly chaotic sea": <= 25% on islands
MOSTLY_FAILS = 0.5          # ... no longer mostly sea: >= 50% on islands
ALMOST_ENTIRELY_FAILS = MOSTLY_FAILS
BOTH = 0.01                 # "both islands and sea": >= 1% of each
BOTH_FAILS = 0.001          # ... only one of them: <= 0.1% of the other
DESTROYED = 0.01            # "destroy all" orbits of an island: <= 1% of them left
DESTROYED_FAILS = 0.5       # ... most of the island survives: >= 50% left
MUCH_SMALLER = 3.0          # "quite a lot smaller": the island >= 3 hole widths wide
MUCH_SMALLER_FAILS = 2.0    # ... not: the island <= 2 hole widths
BOUNDED = (-0.1, 0.1)       # velocity bounded: t/n ~ n^s with |s| <= 0.1 (1/2 if it diffused)
BOUNDED_FAILS = (-0.25, 0.25)  # ... nearer diffusion than bounded: |s| >= 0.25


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


def word_verdict(lo, hi, holds, fails):
    """The two-bound rule (module docstring) on a measured interval [lo, hi] of a quantity a
    word bounds on one side. ``holds`` < ``fails``: the word holds for small values (confirmed
    if hi <= holds, refuted if lo >= fails); ``holds`` > ``fails``: for large values (confirmed
    if lo >= holds, refuted if hi <= fails). Inconclusive otherwise, or if lo or hi is NaN."""
    if math.isnan(lo) or math.isnan(hi):
        return INCONCLUSIVE
    if holds < fails:
        if hi <= holds:
            return CONFIRMED
        if lo >= fails:
            return REFUTED
    else:
        if lo >= holds:
            return CONFIRMED
        if hi <= fails:
            return REFUTED
    return INCONCLUSIVE


def word_note(lo, hi, holds, fails):
    """Why ``word_verdict(lo, hi, holds, fails)`` is inconclusive: ``BETWEEN`` if [lo, hi] lies
    wholly between the bounds, "straddles a bound" if it reaches across one, "not a number";
    "" when it decides."""
    if math.isnan(lo) or math.isnan(hi):
        return "not a number"
    if word_verdict(lo, hi, holds, fails) != INCONCLUSIVE:
        return ""
    low, high = min(holds, fails), max(holds, fails)
    return BETWEEN if low < lo and hi < high else "straddles a bound"


def two_band_verdict(lo, hi, holds, fails):
    """The two-bound rule for a word that bounds a quantity on both sides ("the same", "tightly
    bounded"): confirmed if [lo, hi] lies inside the band ``holds``, refuted if it lies wholly
    outside the wider band ``fails`` (zones include their bounds), inconclusive otherwise or if
    the interval is not finite."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return INCONCLUSIVE
    if holds[0] <= lo and hi <= holds[1]:
        return CONFIRMED
    if hi <= fails[0] or lo >= fails[1]:
        return REFUTED
    return INCONCLUSIVE


def two_band_note(lo, hi, holds, fails):
    """Why ``two_band_verdict`` is inconclusive: ``BETWEEN`` if [lo, hi] lies wholly between the
    two bands (on one side), "straddles a bound" otherwise, "not finite"; "" when it decides."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return "not finite"
    if two_band_verdict(lo, hi, holds, fails) != INCONCLUSIVE:
        return ""
    below = fails[0] < lo and hi < holds[0]
    above = holds[1] < lo and hi < fails[1]
    return BETWEEN if below or above else "straddles a bound"


def well_approximated_verdict(curve, detail, law, min_escapes):
    """The "well approximated by ``law``" rule (module docstring): (verdict, residual excess).
    Inconclusive with too few escapes, when the three-way comparison does not decide or when no
    boundary holds enough particles to measure the excess; refuted if another law wins; else
    the two bounds on the excess, ``RESIDUAL_LEVEL`` and ``RESIDUAL_FAILS``."""
    excess = residual_excess(curve, detail["fits"][law])
    if detail["escapes"] < min_escapes or detail["best"] == "inconclusive":
        return INCONCLUSIVE, excess
    if detail["best"] != law:
        return REFUTED, excess
    if not math.isfinite(excess):
        return INCONCLUSIVE, excess
    return word_verdict(excess, excess, RESIDUAL_LEVEL, RESIDUAL_FAILS), excess


def same_difference(a, u_a, b, u_b):
    """(|a - b| - U, |a - b| + U, m): the difference's interval, U = u_a + u_b, and the scale
    m = (|a| + |b|)/2 the relative bounds of "the same" multiply."""
    d, u = abs(a - b), u_a + u_b
    return d - u, d + u, 0.5 * (abs(a) + abs(b))


def same_verdict(a, u_a, b, u_b, holds=SAME, fails=SAME_FAILS):
    """The "the same" rule (module docstring): confirmed if the difference with its
    uncertainties lies within ``holds`` (relative), refuted if it lies beyond ``fails``,
    inconclusive otherwise."""
    if not all(math.isfinite(x) for x in (a, u_a, b, u_b)):
        return INCONCLUSIVE
    lo, hi, m = same_difference(a, u_a, b, u_b)
    return word_verdict(lo, hi, holds * m, fails * m)


def same_note(a, u_a, b, u_b, holds=SAME, fails=SAME_FAILS):
    """``word_note`` of ``same_verdict``."""
    if not all(math.isfinite(x) for x in (a, u_a, b, u_b)):
        return "not finite"
    lo, hi, m = same_difference(a, u_a, b, u_b)
    return word_note(lo, hi, holds * m, fails * m)


def relative_band(value, relative):
    """[value (1 - relative), value (1 + relative)]: within ``relative`` of a positive value."""
    return value * (1 - relative), value * (1 + relative)


def ratio_band(relative):
    """[1/(1 + relative), 1 + relative]: a ratio within ``relative`` of 1 either way."""
    return 1 / (1 + relative), 1 + relative


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


def fewest_to_reach(share):
    """The fewest trials m at which none in m has its 95% Wilson upper bound at or below
    ``share``: a sample smaller than that cannot show "at most ``share``" (a bound the data
    cannot reach)."""
    from reports.runs.survival import wilson

    m = 1
    while wilson(0, m)[1] > share:
        m += 1
    return m


def pct(x):
    return f"{100 * x:g}%"


def bounds_text(holds, fails, fmt=pct):
    """'holds at ..., fails at ...' of a one-sided word, for rules and tolerances."""
    side = ("<=", ">=") if holds < fails else (">=", "<=")
    return f"holds at {side[0]} {fmt(holds)}, fails at {side[1]} {fmt(fails)}"
