"""The members of a claim's family of analyses, and the verdict of their agreement.

A claim of the paper names a regime and uses words; several analyses are equally defensible
readings of them: windows placed anywhere inside the named regime
(``reports.paper.claims.window_family``), each metric the words admit (a survival level or a time,
the top decades or the tail), local exponents or hazard ratios read as a trend where the words speak
of a limit. The register (``reports.paper.claims.register``) declares each claim's family in its
``family`` field before any verdict. Every member is one ``Analysis``: the number it measured
with its interval, the word's two bounds on that number, and the member's own verdict under the
claim's rule (``reports.paper.claims.rules``). A claim that asserts several things at once has one
family per ``part``. The claim's verdict is their agreement
(``reports.paper.claims.claim.agreement``): confirmed or refuted only where every member of a part
gives it, otherwise inconclusive, of the kind "data", "between-bounds" or "analysis".
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from reports.paper.claims import rules as R
from reports.paper.claims.claim import BETWEEN, CONFIRMED, INCONCLUSIVE, REFUTED, agreement

STRADDLES = "straddles a bound"
TOO_FEW = "too few data"
INF = math.inf


@dataclass(frozen=True)
class Analysis:
    """One member of a claim's family.

    variant   what this member does differently (its window, metric, level, curve)
    verdict   its verdict under the claim's rule
    quantity  what ``value`` is (beta, a hazard ratio, a relative difference, ...)
    value     the number measured; ``lo``, ``hi`` its interval (the rule reads this interval)
    holds     the interval of values where the word clearly holds, (lo, hi), ends may be inf
    fails     the intervals of values where it clearly fails (its opposite applies)
    note      why an inconclusive member does not decide: ``claim.BETWEEN``, ``STRADDLES`` or
              ``TOO_FEW``; empty when it decides
    part      which part of a conjunction it measures ("" for a claim of one part)
    """

    variant: str
    verdict: str
    quantity: str
    value: float
    lo: float
    hi: float
    holds: tuple
    fails: tuple
    note: str = ""
    part: str = ""

    def __post_init__(self):
        if self.verdict not in (CONFIRMED, REFUTED, INCONCLUSIVE):
            raise ValueError(f"analysis {self.variant!r}: verdict {self.verdict!r}")
        if (self.verdict == INCONCLUSIVE) != bool(self.note):
            raise ValueError(f"analysis {self.variant!r}: an inconclusive member says why, a "
                             "deciding one does not")


def family_verdict(analyses):
    """(verdict, kind) of the agreement of ``Analysis`` members; kind None when decided."""
    return agreement(analyses_json(analyses))


def in_part(part, analyses):
    """The members with their ``part`` set."""
    return [dataclasses.replace(a, part=part) for a in analyses]


def _finite(*xs):
    try:
        return all(math.isfinite(float(x)) for x in xs)
    except (TypeError, ValueError):
        return False


def one_sided_zones(holds, fails):
    """(holds zone, fails zones) of a one-sided word with bounds ``holds`` and ``fails``."""
    if holds < fails:
        return (-INF, holds), ((fails, INF),)
    return (holds, INF), ((-INF, fails),)


def word_member(variant, quantity, value, lo, hi, holds, fails):
    """A member under the two-bound rule of a one-sided word (``rules.word_verdict``)."""
    verdict = R.word_verdict(lo, hi, holds, fails)
    note = "" if verdict != INCONCLUSIVE else _note(R.word_note(lo, hi, holds, fails))
    return Analysis(variant, verdict, quantity, value, lo, hi, *one_sided_zones(holds, fails),
                    note)


def band_member(variant, quantity, value, lo, hi, holds, fails):
    """A member under the two-bound rule of a two-sided word (``rules.two_band_verdict``):
    ``holds`` and ``fails`` are (lo, hi) bands, the fails band the wider."""
    verdict = R.two_band_verdict(lo, hi, holds, fails)
    note = "" if verdict != INCONCLUSIVE else _note(R.two_band_note(lo, hi, holds, fails))
    return Analysis(variant, verdict, quantity, value, lo, hi, tuple(holds),
                    ((-INF, fails[0]), (fails[1], INF)), note)


def form_member(variant, value, lo, hi, form, close=False):
    """A member under the form rule on beta (``rules.band_verdict`` on the cell or band of
    ``form``): no zone between the bounds, every undecided member straddles an edge."""
    band = R.form_range(form, close)
    if form == "power_law":
        lo = max(lo, 0.0)
    verdict = R.band_verdict(lo, hi, *band)
    note = "" if verdict != INCONCLUSIVE else (STRADDLES if _finite(lo, hi) else TOO_FEW)
    return Analysis(variant, verdict, "beta", value, lo, hi, band,
                    ((-INF, band[0]), (band[1], INF)), note)


def same_member(variant, quantity, a, u_a, b, u_b, holds=R.SAME, fails=R.SAME_FAILS):
    """A member under the "the same" rule on two values a +- u_a, b +- u_b: the figure is their
    relative difference |a - b|/m, m = (|a| + |b|)/2, with interval (|a - b| -+ U)/m,
    U = u_a + u_b (``rules.same_verdict``)."""
    if not _finite(a, u_a, b, u_b):
        return Analysis(variant, INCONCLUSIVE, quantity, math.nan, math.nan, math.nan,
                        (-INF, holds), ((fails, INF),), TOO_FEW)
    lo, hi, m = R.same_difference(a, u_a, b, u_b)
    if m == 0:
        return Analysis(variant, INCONCLUSIVE, quantity, math.nan, math.nan, math.nan,
                        (-INF, holds), ((fails, INF),), TOO_FEW)
    return word_member(variant, quantity, abs(a - b) / m, lo / m, hi / m, holds, fails)


def threshold_member(variant, quantity, value, lo, hi, threshold, holds_below):
    """A member of an ordering with one threshold (a sign, "decelerates", "above"): confirmed
    if [lo, hi] lies on the holding side of ``threshold`` (below it if ``holds_below``), refuted
    if it lies on the other, inconclusive (straddling) otherwise."""
    if not _finite(lo, hi):
        return too_few(variant, quantity, value)
    below, above = hi <= threshold, lo >= threshold
    if holds_below:
        verdict = CONFIRMED if below else REFUTED if above else INCONCLUSIVE
        zones = (-INF, threshold), ((threshold, INF),)
    else:
        verdict = CONFIRMED if above else REFUTED if below else INCONCLUSIVE
        zones = (threshold, INF), ((-INF, threshold),)
    return Analysis(variant, verdict, quantity, value, lo, hi, *zones,
                    "" if verdict != INCONCLUSIVE else STRADDLES)


def too_few(variant, quantity, value=math.nan):
    """A member that cannot be measured: too few data in its window."""
    return Analysis(variant, INCONCLUSIVE, quantity, value, math.nan, math.nan, (-INF, INF), (),
                    TOO_FEW)


def _note(text):
    return text if text in (BETWEEN, STRADDLES) else TOO_FEW


def analyses_json(analyses):
    """The members as ``report.json`` holds them: variant, verdict, figure (quantity, value,
    interval), the word's bounds (holds zone, fails zones) and the note."""
    return [{"variant": a.variant, "verdict": a.verdict,
             "figure": {"quantity": a.quantity, "value": a.value, "interval": [a.lo, a.hi]},
             "bounds": {"holds": list(a.holds), "fails": [list(z) for z in a.fails]},
             "note": a.note, "part": a.part} for a in analyses]


def family_text(analyses):
    """One line per member for a claim's evidence: variant: value [lo, hi] -> verdict."""
    parts = []
    for a in analyses:
        figure = (f"{a.quantity} = {a.value:.4g} [{a.lo:.4g}, {a.hi:.4g}]"
                  if _finite(a.value, a.lo, a.hi) else f"{a.quantity}: {a.note}")
        parts.append(f"{a.part + ', ' if a.part else ''}{a.variant}: {figure} -> {a.verdict}"
                     + (f" ({a.note})" if a.note and _finite(a.lo, a.hi) else ""))
    return "; ".join(parts)
