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

Cost. Each candidate crossover costs two stretched fits of its segment, so a search over K bins
costs O(K^2). Curves with more than ``SEARCH_BINS`` = 200 bins are searched on a coarser grid:
``search_grid`` keeps at most SEARCH_BINS + 1 of their boundaries, spread evenly in log x, and
``merged`` sums the counts of the bins between them (a coarser partition of the same counts, so
its likelihood is the binned likelihood of the same data; competing escapes are censored at the
count-weighted mean of their bins' censoring points). The crossovers are then boundaries of the
coarse grid; the fits of each regime use all the original bins. Within a segment at most
``MAX_CANDIDATES`` = 48 crossovers are tried at first, spread evenly over the candidates, then
every candidate between the two tried next to the best one (a local refinement: the profile
of l_two is smooth on the scale of the spacing); the Bonferroni factor M still counts every
candidate, and the crossover's 95% range is taken over the candidates tried. The search costs
the same for any K beyond 200; the fits grow linearly in K.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from reports.stats.likelihood import Q95, SEARCH_GOLDEN, fit_law, window_of
from reports.stats.selection import LEVEL

MIN_BINS = 5
MIN_ESCAPES = 20
MAX_REGIMES = 6
SEARCH_BINS = 200
MAX_CANDIDATES = 48


def search_grid(curve, a, b, max_bins=SEARCH_BINS):
    """Boundary indices a = i_0 < ... < i_m = b, m <= max_bins, spread evenly in log x over
    the boundaries with x > 0 (all of them when b - a <= max_bins)."""
    if b - a <= max_bins:
        return np.arange(a, b + 1)
    x = curve.x
    positive = a + int(np.argmax(x[a:b + 1] > 0))
    lx = np.log(x[positive:b + 1])
    targets = np.linspace(lx[0], lx[-1], max_bins - (positive - a) + 1)
    picks = positive + np.searchsorted(lx, targets, side="left")
    return np.unique(np.concatenate([np.arange(a, positive + 1), picks, [b]]))


def merged(curve, idx):
    """``curve`` cut to the boundaries ``idx`` with the bins between them merged (the last
    merged bin ends at idx[-1]; later bins are left out)."""
    a, b = int(idx[0]), int(idx[-1])
    starts = np.asarray(idx[:-1]) - a

    def total(values):
        return np.add.reduceat(np.asarray(values[a:b]), starts)

    comp = total(curve.competing)
    finite_mid = np.where(np.isfinite(curve.mid), curve.mid, 0.0)
    weighted = total(np.where(curve.competing > 0, curve.competing * finite_mid, 0.0))
    mid = np.where(comp > 0, weighted / np.maximum(comp, 1), 0.5 * (curve.x[idx[:-1]] +
                                                                   curve.x[idx[1:]]))
    return dataclasses.replace(curve, x=curve.x[np.asarray(idx)].astype(np.float64),
                               escapes=total(curve.escapes), competing=comp,
                               censored=total(curve.censored), mid=mid)


def stretched_loglik(curve, a, b):
    """Maximised stretched-law log-likelihood on bins a..b-1."""
    return fit_law("stretched_exponential", window_of(curve, a, b), intervals=False,
                   golden=SEARCH_GOLDEN).loglik


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
    tried = {}

    def two(c):
        if c not in tried:
            tried[c] = stretched_loglik(curve, a, c) + stretched_loglik(curve, c, b)
        return tried[c]

    step = max(1, math.ceil(len(cands) / MAX_CANDIDATES))
    first = cands[::step]
    top = max(range(len(first)), key=lambda i: two(first[i]))
    lo = cands.index(first[max(top - 1, 0)])
    hi = cands.index(first[min(top + 1, len(first) - 1)])
    for c in cands[lo:hi + 1]:
        two(c)
    best = max(tried, key=tried.get)
    lam = max(0.0, 2.0 * (tried[best] - whole))
    p = min(1.0, len(cands) * float(chi2.sf(lam, 2)))
    inside = [c for c, v in tried.items() if tried[best] - v <= Q95]
    return Split(a, b, best, p, (min(inside), max(inside)))


def segment(curve, a, b, progress=None):
    """Regime boundaries [a, c1, ..., b] (bin indices), the accepted ``Split``s, and the p-value
    of the best split left in the last regime (None without candidates; >= LEVEL otherwise).
    ``progress(text)`` is told of every accepted crossover."""
    say = progress or (lambda _text: None)
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
        say(f"crossover at x = {curve.x[s.c]:g} (p = {s.p:.2g}), {len(bounds) - 1} regimes")
        for lo, hi in ((s.a, s.c), (s.c, s.b)):
            pending[(lo, hi)] = best_split(curve, lo, hi)
    last = pending.get((bounds[-2], bounds[-1]))
    while last is not None and last.p < LEVEL:  # refine the late regime past the cap
        bounds = sorted([*bounds, last.c])
        splits.append(last)
        say(f"late crossover at x = {curve.x[last.c]:g} (p = {last.p:.2g})")
        last = best_split(curve, last.c, last.b)
    return bounds, sorted(splits, key=lambda s: s.c), (last.p if last is not None else None)


def crossover_entries(curve, splits):
    """JSON-ready crossovers: x and its 95% range."""
    return [{"x": float(curve.x[s.c]),
             "range95": [float(curve.x[s.c_range[0]]), float(curve.x[s.c_range[1]])],
             "p": s.p if math.isfinite(s.p) else None} for s in splits]
