"""The windows a claim's words allow inside its regime (the members of its window family).

A regime [x_a, x_b] is placed by the physics (``reports.paper.studies.escape_regimes``); which
window inside it another careful reader would fit is a choice the words do not make. The family
holds the defensible choices, and the claim is decided only where they agree
(``reports.paper.claims.family``).
Steps are ``STEP`` = a quarter decade, the resolution of the hazards and of the paper's plots.

* ``inside_windows`` (a bounded regime, e.g. the intermediate one): the regime itself, its start
  moved a step later, its end a step earlier, and both: every window stays inside the regime,
  none reaches back into the transient before it or on into the tail after it.
* ``late_windows`` (a tail): windows from a start to the regime's end, the start moving later by
  steps from the regime's start, never back into the previous regime, up to the latest window
  that still holds enough escapes: every such window is a member.
* ``limit_windows`` (words that speak of a limit: "eventually", "at long times", "for large t"):
  the same windows read as a trend, whose latest members count: the latest ``LATE_MEMBERS``
  windows with enough escapes (the latest, and the starts a quarter and a half decade before
  it); earlier ones may still show the approach to the limit.

Windows are bin-index pairs (a, b) of a curve's boundaries, each with at least ``MIN_BINS`` bins
and at least ``min_escapes`` escapes.
"""

from __future__ import annotations

import numpy as np

STEP = 10 ** 0.25
LATE_MEMBERS = 3
MIN_BINS = 2


def _index_at(x, value, lo, hi):
    """First boundary index in [lo, hi] with x >= value (hi if none)."""
    k = int(np.searchsorted(x, value * (1 - 1e-12), side="left"))
    return int(min(max(k, lo), hi))


def _enough(curve, a, b, min_escapes):
    return b - a >= MIN_BINS and int(curve.escapes[a:b].sum()) >= min_escapes


def inside_windows(curve, a, b, min_escapes):
    """The regime (a, b) and its sub-windows a step shorter at either end or both, those with
    enough escapes (module docstring), in that order, without repeats."""
    x = curve.x
    a2 = _index_at(x, x[a] * STEP, a, b)
    b2 = _index_at(x, x[b] / STEP, a, b)
    out = []
    for w in ((a, b), (a2, b), (a, b2), (a2, b2)):
        if w not in out and _enough(curve, *w, min_escapes):
            out.append(w)
    return out


def late_starts(curve, a, b):
    """Start indices from a (x_a > 0), moving later by steps (module docstring), before b."""
    x = curve.x
    if not x[a] > 0:
        raise ValueError(f"late windows start at x > 0, got x = {x[a]:g}")
    starts, k = [], 0
    while x[a] * STEP ** k < x[b]:
        s = _index_at(x, x[a] * STEP ** k, a, b)
        if s < b and (not starts or s > starts[-1]):
            starts.append(s)
        k += 1
    return starts


def late_windows(curve, a, b, min_escapes):
    """Every window (s, b) with s moving later from a by steps and enough escapes (module
    docstring), earliest first."""
    return [(s, b) for s in late_starts(curve, a, b) if _enough(curve, s, b, min_escapes)]


def limit_windows(curve, a, b, min_escapes, members=LATE_MEMBERS):
    """The latest ``members`` of ``late_windows`` (module docstring), earliest first."""
    return late_windows(curve, a, b, min_escapes)[-members:]


def window_label(curve, window, unit):
    """'unit in [x_a, x_b]' of a window."""
    a, b = window
    return f"{unit} in [{curve.x[a]:.4g}, {curve.x[b]:.4g}]"
