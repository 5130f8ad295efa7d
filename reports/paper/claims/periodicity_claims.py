"""The paper's claims about the bouncer's near periodicity in v (Section 2): the fixed points
(0, pi m) "and their stability is periodic in v with period pi"; the map as a whole is not
periodic, "but this becomes less significant at large v".

* Stability: ``verify.periodic_orbit`` certifies the fixed point at (0, pi m) for m = 1 ..
  ``ORDERS`` and encloses the trace of its linearisation; the stability is periodic if every m
  gives the same certified kind (elliptic or hyperbolic) and a trace enclosure holding the same
  value 2 - 4 eps (the paper's matrix). One member per eps of ``STABILITY_EPS`` (the elliptic
  range 0 < eps < 1, the paper's 0.6, and the hyperbolic eps > 1).
* Less significant at large v: the departure from periodicity of the exact map, the collision
  map from (phi, v + pi) against the one from (phi, v) shifted by pi in v: |delta phi_1| (mod
  2 pi) and |delta v_1|, their medians over random phases at velocities pi (m + 1/2) for m = 1,
  2, 4, ..., 64 (``ORDERS_V``), eps = 0.6. It becomes less significant if the median falls with
  v: the slope of log median against log v, its bootstrap interval below 0 (a sign, one
  threshold). One member per quantity.
"""

from __future__ import annotations

import math

import numpy as np
from mpmath import mp

import fastpath
import verify
from fastpath.arithmetic.phase import TWO_PI
from reports.paper.claims import family as F
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.register import make_claim
from reports.paper.studies.replicates import INTERVAL_REPLICATES
from reports.paper.studies.sampling import EPS
from reports.paper.studies.seeds import SAMPLING_SEED

STABILITY_EPS = (0.3, 0.6, 1.5)
ORDERS = 4
ORDERS_V = (1, 2, 4, 8, 16, 32, 64)
PHASES = {False: 2000, True: 200}


def stability_member(eps):
    """The certified fixed points (0, pi m), m = 1..ORDERS, at ``eps``: one kind and one trace."""
    kinds, traces, bad = [], [], []
    expected = 2 - 4 * eps
    for m in range(1, ORDERS + 1):
        try:
            orbit = verify.periodic_orbit(0.0, math.pi * m, eps, 1)
        except verify.NotCertified:
            bad.append(m)
            continue
        lo, hi = orbit.trace
        kinds.append(orbit.stability)
        with mp.workdps(30):
            traces.append((float(lo), float(hi), bool(lo <= mp.mpf(expected) <= hi)))
    variant = (f"eps = {eps:g}, m = 1..{ORDERS}: " + ", ".join(
        f"{k} (trace [{lo:.6g}, {hi:.6g}])" for k, (lo, hi, _) in zip(kinds, traces,
                                                                     strict=True))
        + (f"; not certified at m = {bad}" if bad else ""))
    same = len(set(kinds)) == 1 and all(inside for *_, inside in traces)
    if bad or "undecided" in kinds:
        verdict, note = INCONCLUSIVE, F.TOO_FEW
    else:
        verdict, note = (CONFIRMED if same else REFUTED), ""
    spread = max(hi for _, hi, _ in traces) - min(lo for lo, _, _ in traces) if traces else 0.0
    return F.Analysis(variant, verdict, "spread of the traces over m", spread, spread, spread,
                      (0.0, 0.0), ((0.0, math.inf),), note)


def stability_period_claim():
    members = [stability_member(eps) for eps in STABILITY_EPS]
    return make_claim("sec2-stability-period-pi", "verify.periodic_orbit at (0, pi m): "
                      f"{F.family_text(members)}.", analyses=members)


def deviations(eps, v, phases):
    """(|delta phi_1|, |delta v_1|) of the exact map between (phi, v + pi) and (phi, v) + pi."""
    ok = (v + eps * np.sin(phases) > 0)
    p = phases[ok]
    phi1, v1, _ = fastpath.step(p, np.full(len(p), v), eps)
    phi2, v2, _ = fastpath.step(p, np.full(len(p), v + math.pi), eps)
    dphi = np.abs((phi2 - phi1 + math.pi) % TWO_PI - math.pi)
    return dphi, np.abs(v2 - (v1 + math.pi))


def _slope(v_levels, values):
    med = np.array([np.median(x) for x in values])
    use = med > 0
    if use.sum() < 3:
        return math.nan
    return float(np.polyfit(np.log(v_levels[use]), np.log(med[use]), 1)[0])


def less_significant_claim(quick=False):
    rng = np.random.default_rng(SAMPLING_SEED)
    phases = rng.uniform(0.0, TWO_PI, PHASES[bool(quick)])
    levels = np.array([math.pi * (m + 0.5) for m in ORDERS_V])
    table = [deviations(EPS, v, phases) for v in levels]
    members = []
    for i, name in enumerate(("|delta phi_1|", "|delta v_1|")):
        values = [row[i] for row in table]
        slope = _slope(levels, values)
        boot = [_slope(levels, [rng.choice(x, len(x)) for x in values])
                for _ in range(INTERVAL_REPLICATES)]
        boot = np.array([b for b in boot if math.isfinite(b)])
        lo, hi = ((float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5)))
                  if len(boot) > INTERVAL_REPLICATES // 2 else (math.nan, math.nan))
        medians = ", ".join(f"{np.median(x):.2g}" for x in values)
        members.append(F.threshold_member(
            f"{name}: medians {medians} at v = pi (m + 1/2), m = "
            f"{', '.join(map(str, ORDERS_V))}", f"slope of log median {name} on log v", slope,
            lo, hi, 0.0, True))
    return make_claim("sec2-less-significant", f"eps = {EPS:g}, {len(phases)} random phases "
                      f"per velocity: {F.family_text(members)}.", analyses=members)


def periodicity_claims(quick=False):
    return [stability_period_claim(), less_significant_claim(quick)]
