"""Regimes of decay: binary segmentation of a curve at likelihood-ratio-significant crossovers.

A two-regime model splits a window [x_a, x_b] at a bin boundary x_c: each side has its own
stretched law exp(-c x**beta) (it contains both simple laws), and since each side's likelihood is
conditioned on survival to its start, the two sides simply add: l_two(x_c) = l[a, c] + l[c, b];
the survival function stays continuous at x_c. Against one stretched law on [x_a, x_b] (nested:
equal parameters on both sides) the statistic Lambda = 2 (max_c l_two(x_c) - l[a, b]) has two
extra parameters, but the crossover x_c is not identified under the null (Davies' problem), so
the p-value is Bonferroni-corrected over the M candidate crossovers:

    p = min(1, M * P(chi^2_2 > Lambda)).

Conservative, hence valid at level LEVEL. The split is made where p < LEVEL, at the x_c of
largest l_two; the most significant split of all segments is made first, until no segment
splits or there are MAX_REGIMES. Then the last regime alone is split further while its best
split is significant: the late-time law is the headline, so its window must be homogeneous at
LEVEL however many earlier regimes the cap merged. A regime has at least MIN_BINS bins and
MIN_ESCAPES escapes.
The crossover's 95% range is {x_c: 2 (max l_two - l_two(x_c)) <= 3.841} over the candidates
(an approximate profile set: x_c is a discrete, non-regular parameter).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from reports.stats.likelihood import Q95, fit_law, window_of
from reports.stats.selection import LEVEL

MIN_BINS = 5
MIN_ESCAPES = 20
MAX_REGIMES = 6


def stretched_loglik(curve, a, b):
    """Maximised stretched-law log-likelihood on bins a..b-1."""
    return fit_law("stretched_exponential", window_of(curve, a, b), intervals=False).loglik


def _candidates(curve, a, b):
    cum = np.concatenate([[0], np.cumsum(curve.escapes)])
    return [c for c in range(a + MIN_BINS, b - MIN_BINS + 1)
            if cum[c] - cum[a] >= MIN_ESCAPES and cum[b] - cum[c] >= MIN_ESCAPES]


@dataclass(frozen=True)
class Split:
    """Best crossover of segment [a, b]: bin index, p-value and the 95% crossover range."""

    a: int
    b: int
    c: int
    p: float
    c_range: tuple[int, int]


def best_split(curve, a, b, whole=None):
    """The ``Split`` of bins a..b-1 maximising l_two, or None without candidates."""
    cands = _candidates(curve, a, b)
    if not cands:
        return None
    whole = stretched_loglik(curve, a, b) if whole is None else whole
    two = np.array([stretched_loglik(curve, a, c) + stretched_loglik(curve, c, b)
                    for c in cands])
    best = int(np.argmax(two))
    lam = max(0.0, 2.0 * (two[best] - whole))
    p = min(1.0, len(cands) * float(chi2.sf(lam, 2)))
    inside = [c for c, v in zip(cands, two, strict=True) if two[best] - v <= Q95]
    return Split(a, b, cands[best], p, (min(inside), max(inside)))


def segment(curve, a, b):
    """Regime boundaries [a, c1, ..., b] (bin indices), the accepted ``Split``s, and the p-value
    of the best split left in the last regime (None without candidates; >= LEVEL otherwise)."""
    bounds, splits = [a, b], []
    pending = {(a, b): best_split(curve, a, b)}
    while len(bounds) - 1 < MAX_REGIMES:
        ok = [s for s in pending.values() if s is not None and s.p < LEVEL]
        if not ok:
            break
        s = min(ok, key=lambda s: s.p)
        del pending[(s.a, s.b)]
        bounds = sorted([*bounds, s.c])
        splits.append(s)
        for lo, hi in ((s.a, s.c), (s.c, s.b)):
            pending[(lo, hi)] = best_split(curve, lo, hi)
    last = pending.get((bounds[-2], bounds[-1]))
    while last is not None and last.p < LEVEL:  # refine the late regime past the cap
        bounds = sorted([*bounds, last.c])
        splits.append(last)
        last = best_split(curve, last.c, last.b)
    return bounds, sorted(splits, key=lambda s: s.c), (last.p if last is not None else None)


def crossover_entries(curve, splits):
    """JSON-ready crossovers: x and its 95% range."""
    return [{"x": float(curve.x[s.c]),
             "range95": [float(curve.x[s.c_range[0]]), float(curve.x[s.c_range[1]])],
             "p": s.p if math.isfinite(s.p) else None} for s in splits]
