"""The regimes of an escape curve, placed by the physics (the paper's Section 3).

* Diffusive onset. The paper's argument for the sqrt(t) law needs the velocity to diffuse:
  <v(t)> ~ t^(1/3). ``diffusive_onset`` is the first point of the Fermi ensemble (the same eps
  and start box, ``reports.paper.studies.fermi_ensemble``) from which the slope of log<v> over the
  next half decade (``ONSET_SPAN_DECADES``) is within ``ONSET_TOLERANCE`` (10%) of that
  law's exponent: t_D. The intermediate regime is a set of orbits seen by both clocks: it starts at
  the survival level S_a = P(t_D), in discrete time at n_a where P(n) falls to S_a (the escape
  rate per collision needs no diffusion, only the orbits the continuous-time law speaks of).
* Plateau and fall of the discrete-time hazard. After n_D a hole over the islands empties the
  chaotic sea at a nearly constant rate per collision (the exponential); the slow population
  near islands not covered by the hole takes over later. With a fast population of rate gamma
  and a slow one, the hazard is gamma times the fast population's share of the escapes, so
  ``reports.stats.hazard.hazard_fall`` places n_fast, where the hazard (quarter-decade groups)
  first falls below ``HAZARD_FAST`` = 0.9 of its largest value after n_a (the fast population
  still holds 90% of the escapes), n_half (``HAZARD_HALF``: the slow one holds half) and n_tail
  (``HAZARD_TENTH``: the slow one holds 90%).
* Windows. Intermediate: [n_a, n_fast] in discrete time; in continuous time from t_D to where
  P(t) reaches the survival level P(n_fast) (the same orbits, measured by the other clock).
  Late tail: from n_tail to the end of the usable range
  (``reports.stats.analysis.usable_range``). Matched levels: from P(n_tail) down to
  max(100/N, the survival at the end of the usable range), in both clocks.

Windows are bin-index pairs (a, b) of the curve's boundaries; None where the data do not reach
them (e.g. no hazard fall before the horizon).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from reports.stats.analysis import usable_range
from reports.stats.hazard import all_cause_survival, first_below, hazard_fall

ONSET_TOLERANCE = 0.1       # <v> within 10% of its diffusive exponent
ONSET_SPAN_DECADES = 0.5    # local slopes of log<v> over half a decade
HAZARD_FAST = 0.9           # intermediate regime ends: hazard below 0.9 of its plateau
HAZARD_HALF = 0.5           # the slow population holds half the escapes
HAZARD_TENTH = 0.1          # tail starts: hazard at a tenth of its plateau
SURVIVORS_MIN = 100         # the fewest survivors a survival level rests on: levels down to 100/N


def diffusive_onset(x, mean_v, exponent, tolerance=ONSET_TOLERANCE,
                    span=ONSET_SPAN_DECADES):
    """First x of the grid from which the slope of log<v> over the next ``span`` decades is
    within ``tolerance`` (relative) of ``exponent``; NaN if none."""
    x = np.asarray(x, dtype=np.float64)
    lv = np.log(np.asarray(mean_v, dtype=np.float64))
    for i in range(len(x)):
        j = int(np.searchsorted(x, x[i] * 10.0 ** span))
        if j >= len(x) or x[i] <= 0 or not (np.isfinite(lv[i]) and np.isfinite(lv[j])):
            continue
        slope = (lv[j] - lv[i]) / math.log(x[j] / x[i])
        if abs(slope - exponent) <= tolerance * exponent:
            return float(x[i])
    return math.nan


@dataclass
class EscapeWindows:
    """The windows of one hole (module docstring); ``n`` and ``t`` map regime -> (a, b)."""

    hole: str
    onset_n: float                    # n_a: P(n) reaches P(t_D)
    onset_t: float                    # t_D
    plateau: float                    # largest discrete-time hazard after n_D
    level_fast: float | None          # P at n_fast
    level_half: float | None          # P at n_half
    level_tail: float | None          # P at n_tail
    level_end: float | None           # lowest matched level
    median_n: float | None            # n at which P(n) = 1/2
    n_at: dict = field(default_factory=dict)  # "fast", "half", "tail" -> boundary x or None
    n: dict = field(default_factory=dict)
    t: dict = field(default_factory=dict)


def _from(x, value):
    """First boundary index with x >= value."""
    return int(np.searchsorted(x, value, side="left"))


def _window(a, b, curve):
    """(a, b) if it is a window with escapes inside the usable range, else None."""
    a0, b0 = usable_range(curve)
    if a is None or b is None:
        return None
    a, b = max(a, a0), min(b, b0)
    if b - a < 2 or curve.escapes[a:b].sum() == 0:
        return None
    return (a, b)


def _last_at_least(values, level):
    hit = np.flatnonzero(np.asarray(values) >= level)
    return int(hit[-1]) if len(hit) else None


def escape_windows(hole, curve_n, curve_t, onset_t):
    """``EscapeWindows`` of one hole from its discrete and continuous curves and the diffusive
    onset t_D."""
    s_n, s_t = all_cause_survival(curve_n), all_cause_survival(curve_t)
    k_d = _from(curve_t.x, onset_t) if math.isfinite(onset_t) else None
    k_a = first_below(s_n, s_t[k_d]) if k_d is not None and k_d < len(s_t) else None
    onset_n = float(curve_n.x[k_a]) if k_a is not None else math.nan
    levels = {}
    for name, factor in (("fast", HAZARD_FAST), ("half", HAZARD_HALF),
                         ("tail", HAZARD_TENTH)):
        k, plateau = hazard_fall(curve_n, onset_n, factor) if k_a is not None else (None,
                                                                                    math.nan)
        levels[name] = (k, float(s_n[k]) if k is not None else None)
    out = EscapeWindows(hole, onset_n, onset_t, plateau, levels["fast"][1], levels["half"][1],
                        levels["tail"][1], None, None)
    level_tail = out.level_tail
    out.n_at = {name: (float(curve_n.x[k]) if k is not None else None)
                for name, (k, _) in levels.items()}
    med = first_below(s_n, 0.5)
    out.median_n = float(curve_n.x[med]) if med is not None else None
    if k_a is not None:
        out.n["intermediate"] = _window(k_a, levels["fast"][0], curve_n)
    if k_d is not None and out.level_fast is not None:
        out.t["intermediate"] = _window(k_d, first_below(s_t, out.level_fast), curve_t)
    if level_tail is not None:
        out.n["tail"] = _window(levels["tail"][0], usable_range(curve_n)[1], curve_n)
        floor = SURVIVORS_MIN / curve_n.particles
        ends = [s[usable_range(c)[1]] for s, c in ((s_n, curve_n), (s_t, curve_t))]
        out.level_end = float(max(floor, *ends))
        for clock, curve, s in (("n", curve_n, s_n), ("t", curve_t, s_t)):
            a = first_below(s, level_tail)
            b = _last_at_least(s, out.level_end)
            getattr(out, clock)["matched"] = _window(a, b, curve) if out.level_end < \
                level_tail else None
    return out


def window_text(curve, window, unit):
    """'unit in [x_a, x_b] (E escapes)'."""
    if window is None:
        return f"no {unit} window"
    a, b = window
    return (f"{unit} in [{curve.x[a]:.4g}, {curve.x[b]:.4g}] "
            f"({int(curve.escapes[a:b].sum()):,} escapes)")
