"""The paper's claims about where its holes lie in phase space (Fig. 2 caption, Section 4),
decided on the fractions of each hole's strip on islands (``reports.paper.islands``)."""

from __future__ import annotations

import math

from reports.paper import rules as R
from reports.paper.claims import CONFIRMED, INCONCLUSIVE
from reports.paper.islands import strip_fractions
from reports.paper.register import ISLAND_HOLES, SEA_HOLES, WIDTHS, make_claim

EPS = 0.6
ESCAPE_WIDTH = 0.3
SAMPLES = {False: 2000, True: 200}


def _ci_text(strip, count):
    lo, hi = strip.ci95(count)
    return f"{count / strip.samples:.4f} (95% [{lo:.4f}, {hi:.4f}])"


def _share(strip, count, holds, fails):
    """(verdict, text) of the two-bound rule on the Wilson interval of count/samples."""
    ci = strip.ci95(count)
    note = R.word_note(*ci, holds, fails)
    return R.word_verdict(*ci, holds, fails), (f"{_ci_text(strip, count)}, "
                                               f"{R.bounds_text(holds, fails)}"
                                               + (f": {note}" if note else ""))


def escape_hole_claims(quick=False):
    """fig2-hole-phi_c=X for the six escape holes."""
    m = SAMPLES[bool(quick)]
    out = []
    for h in ISLAND_HOLES + SEA_HOLES:
        c = float(h)
        if h in ISLAND_HOLES:
            s = strip_fractions(c - 1.5 * ESCAPE_WIDTH, c + 1.5 * ESCAPE_WIDTH, EPS, m)
            verdict, text = _share(s, s.large, R.OVER_OR_NEAR, R.OVER_OR_NEAR_FAILS)
            evidence = (f"Strip widened by one hole width, phi in [{s.lo:.2f}, {s.hi:.2f}], "
                        f"pi/2 < v < 3 pi/2, {m} random starts: share on the large island "
                        f"{text}; on any island {_ci_text(s, s.regular)}.")
            stats = {"large_share": s.large_fraction, "large_ci95": list(s.ci95(s.large))}
        else:
            s = strip_fractions(c - ESCAPE_WIDTH / 2, c + ESCAPE_WIDTH / 2, EPS, m)
            verdict, text = _share(s, s.regular, R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS)
            evidence = (f"Strip phi in [{s.lo:.2f}, {s.hi:.2f}], pi/2 < v < 3 pi/2, {m} random "
                        f"starts: share on islands {text} (large island "
                        f"{_ci_text(s, s.large)}).")
            stats = {"island_share": s.regular_fraction,
                     "island_ci95": list(s.ci95(s.regular))}
        out.append(make_claim(f"fig2-hole-phi_c={h}", verdict, evidence, particles_per_curve=m,
                              statistical=stats))
    return out


def transport_hole_claims(quick=False):
    """sec4-holes and sec4-hole-2 for the four widths."""
    m = SAMPLES[bool(quick)]
    both, hole2, texts1, texts2 = [], [], [], []
    for w in WIDTHS:
        h = float(w)
        s1 = strip_fractions(-h / 2, h / 2, EPS, m)
        s2 = strip_fractions(math.pi - h / 2, math.pi + h / 2, EPS, m)
        sea1 = m - s1.regular
        checks1 = [_share(s1, s1.regular, R.BOTH, R.BOTH_FAILS),
                   _share(s1, sea1, R.BOTH, R.BOTH_FAILS),
                   _share(s2, s2.regular, R.MOSTLY, R.MOSTLY_FAILS)]
        small = s2.regular - s2.large
        checks2 = [_share(s2, s2.large, R.FAR, R.FAR_FAILS),
                   _share(s2, s2.regular, R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS)]
        both += [v for v, _ in checks1]
        hole2 += [CONFIRMED if s2.ci95(small)[0] > 0 else INCONCLUSIVE] + [v for v, _ in checks2]
        texts1.append(f"h = {w}: hole 1 islands {checks1[0][1]}, hole 1 sea {checks1[1][1]}, "
                      f"hole 2 islands {checks1[2][1]}")
        texts2.append(f"h = {w}: small islands {_ci_text(s2, small)}, large island "
                      f"{checks2[0][1]}, all islands {checks2[1][1]}")
    return [
        make_claim("sec4-holes", R.all_of(both), f"Strips 0 +- h/2 and pi +- h/2, pi/2 < v < "
                   f"3 pi/2, {m} random starts each: " + "; ".join(texts1) + ".",
                   particles_per_curve=m),
        make_claim("sec4-hole-2", R.all_of(hole2), f"Strip pi +- h/2, pi/2 < v < 3 pi/2, {m} "
                   "random starts each: " + "; ".join(texts2) + ".", particles_per_curve=m),
    ]
