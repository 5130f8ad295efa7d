"""The paper's claims about where its holes lie in phase space (Fig. 2 caption, Section 4),
decided on the fractions of each hole's strip on islands (``reports.paper.studies.islands``).

The family of each: the strip in the first two velocity periods of the nearly periodic phase
space (``VELOCITY_PERIODS``: around the islands (0, pi) and (0, 2 pi), the escape's starts
2 < v < 4 lying across both), each from its own random starts.
"""

from __future__ import annotations

import math

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import ISLAND_HOLES, SEA_HOLES, WIDTHS, make_claim
from reports.paper.studies.islands import strips_together, velocity_period
from reports.paper.studies.sampling import EPS

ESCAPE_WIDTH = 0.3
SAMPLES = {False: 2000, True: 200}
VELOCITY_PERIODS = (1, 2)


def _band(m):
    lo, hi = velocity_period(m)
    return f"{lo:.3g} < v < {hi:.3g}"


def share_member(strip, count, holds, fails, what, part=""):
    """The two-bound rule on the Wilson interval of count/samples of a strip."""
    lo, hi = strip.ci95(count)
    variant = (f"phi in [{strip.lo:.2f}, {strip.hi:.2f}], {_band(strip.m)}: {what} "
               f"{count}/{strip.samples}")
    return F.in_part(part, [F.word_member(variant, f"share {what}", count / strip.samples, lo, hi,
                                          holds, fails)])[0]


def strips_of(phase_ranges, m_samples):
    """Per (lo, hi) of ``phase_ranges``, its strip in each of ``VELOCITY_PERIODS`` from
    ``m_samples`` random starts, all classified together
    (``reports.paper.studies.islands.strips_together``: the same strips, one orbit loop)."""
    got = strips_together([(lo, hi, m) for lo, hi in phase_ranges for m in VELOCITY_PERIODS],
                          EPS, m_samples)
    k = len(VELOCITY_PERIODS)
    return [got[i * k:(i + 1) * k] for i in range(len(phase_ranges))]


def _escape_strip(hole):
    """The phase range whose strips decide fig2-hole-phi_c=``hole``."""
    c = float(hole)
    if hole in ISLAND_HOLES:
        return c - 1.5 * ESCAPE_WIDTH, c + 1.5 * ESCAPE_WIDTH
    return c - ESCAPE_WIDTH / 2, c + ESCAPE_WIDTH / 2


def escape_hole_claims(quick=False):
    """fig2-hole-phi_c=X for the six escape holes."""
    m = SAMPLES[bool(quick)]
    out = []
    holes = ISLAND_HOLES + SEA_HOLES
    for h, hole_strips in zip(holes, strips_of([_escape_strip(h) for h in holes], m),
                              strict=True):
        if h in ISLAND_HOLES:
            members = [share_member(s, s.large, R.OVER_OR_NEAR, R.OVER_OR_NEAR_FAILS,
                                    "on the large island") for s in hole_strips]
            what = "strip widened by one hole width, share on the large island"
        else:
            members = [share_member(s, s.regular, R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS,
                                    "on islands") for s in hole_strips]
            what = "the hole's strip, share on islands"
        out.append(make_claim(f"fig2-hole-phi_c={h}", f"{what}: {F.family_text(members)}.",
                              analyses=members, particles_per_curve=m))
    return out


def transport_hole_claims(quick=False):
    """sec4-holes and sec4-hole-2 for the four widths."""
    m = SAMPLES[bool(quick)]
    both, hole2 = [], []
    ranges = [r for w in WIDTHS for r in ((-float(w) / 2, float(w) / 2),
                                          (math.pi - float(w) / 2, math.pi + float(w) / 2))]
    got = strips_of(ranges, m)
    for i, w in enumerate(WIDTHS):
        for s1, s2 in zip(got[2 * i], got[2 * i + 1], strict=True):
            both += [share_member(s1, s1.regular, R.BOTH, R.BOTH_FAILS, "on islands",
                                  f"h = {w}, hole 1 islands"),
                     share_member(s1, s1.samples - s1.regular, R.BOTH, R.BOTH_FAILS,
                                  "in the sea", f"h = {w}, hole 1 sea"),
                     share_member(s2, s2.regular, R.MOSTLY, R.MOSTLY_FAILS, "on islands",
                                  f"h = {w}, hole 2 mostly sea")]
            small = s2.regular - s2.large
            lo = s2.ci95(small)[0]
            hole2.append(F.Analysis(
                f"phi in [{s2.lo:.2f}, {s2.hi:.2f}], {_band(s2.m)}: on small islands "
                f"{small}/{s2.samples}", "confirmed" if lo > 0 else "inconclusive",
                "share on small islands", small / s2.samples, lo, s2.ci95(small)[1],
                (0.0, 1.0), (), "" if lo > 0 else F.STRADDLES,
                f"h = {w}, some small islands"))
            hole2 += [share_member(s2, s2.large, R.FAR, R.FAR_FAILS, "on the large island",
                                   f"h = {w}, far from the large island"),
                      share_member(s2, s2.regular, R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS,
                                   "on islands", f"h = {w}, strongly chaotic")]
    return [
        make_claim("sec4-holes", f"Strips 0 +- h/2 and pi +- h/2, {m} random starts per "
                   f"velocity period: {F.family_text(both)}.", analyses=both,
                   particles_per_curve=m),
        make_claim("sec4-hole-2", f"Strip pi +- h/2, {m} random starts per velocity period: "
                   f"{F.family_text(hole2)}.", analyses=hole2, particles_per_curve=m),
    ]
