"""The paper's claims about the phase space as eps varies (Section 2): "for large eps the motion
is almost entirely chaotic"; at eps = 0.6, "clear elliptic islands around the fixed points,
coexisting with Fermi acceleration of the chaotic orbits".

Where the islands are is read by classifying random starts by their orbits
(``reports.paper.studies.islands``: regular if the velocity stays within a band of 5 for 2000
collisions).

* Large eps: the share of random starts on islands, at eps of ``LARGE_EPS`` (the fixed points
  are hyperbolic from eps = 1 on; 2 and 4 are well beyond), in two velocity bands of one period
  pi each well above the plate's speed (``LARGE_EPS_BANDS``); "almost entirely chaotic" holds at
  most ``rules.ALMOST_ENTIRELY`` on islands and fails at ``rules.ALMOST_ENTIRELY_FAILS``.
* Coexistence at eps = 0.6: two parts. Clear islands around the fixed points: the share of the
  box |phi| < 1 around (0, pi m) on the island of (0, pi m), m = 1, 2; "clear" holds from
  ``rules.BOTH`` (1%) and fails at a trace, ``rules.BOTH_FAILS``. Fermi acceleration of the
  chaotic orbits: the slope of log<v_n> on log n of the Fermi ensemble
  (``reports.paper.studies.fermi_ensemble``) over the windows inside its diffusive regime, above 0
  (a sign).
"""

from __future__ import annotations

import math

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.fermi_claims import inside_windows
from reports.paper.claims.register import make_claim
from reports.paper.studies.fermi_ensemble import _window_slope
from reports.paper.studies.islands import classify, velocity_period
from reports.paper.studies.sampling import bootstrap_blocks
from reports.paper.studies.seeds import SAMPLING_SEED
from reports.runs.survival import wilson

LARGE_EPS = (2.0, 4.0)
LARGE_EPS_BANDS = ((10.0, 10.0 + math.pi), (20.0, 20.0 + math.pi))
ISLAND_BOX_PHASE = 1.0
SAMPLES = {False: 2000, True: 200}


def _share_member(variant, count, m, holds, fails, part=""):
    lo, hi = (float(x) for x in wilson(count, m))
    return F.in_part(part, [F.word_member(f"{variant}: {count}/{m}", "share on islands",
                                          count / m, lo, hi, holds, fails)])[0]


def large_eps_claim(quick=False):
    m = SAMPLES[bool(quick)]
    rng = np.random.default_rng(SAMPLING_SEED)
    members = []
    for eps in LARGE_EPS:
        for band in LARGE_EPS_BANDS:
            phi = rng.uniform(0.0, TWO_PI, m)
            v = rng.uniform(*band, m)
            regular = int(classify(phi, v, eps).regular.sum())
            members.append(_share_member(f"eps = {eps:g}, {band[0]:g} < v < {band[1]:.4g}",
                                         regular, m, R.ALMOST_ENTIRELY,
                                         R.ALMOST_ENTIRELY_FAILS))
    return make_claim("sec2-large-eps-chaotic", "Random starts classified by their orbits: "
                      f"{F.family_text(members)}.", analyses=members, particles_per_curve=m)


def coexist_claim(fermi, quick=False, eps=0.6):
    m = SAMPLES[bool(quick)]
    rng = np.random.default_rng(SAMPLING_SEED + 1)
    members = []
    for order in (1, 2):
        phi = np.mod(rng.uniform(-ISLAND_BOX_PHASE, ISLAND_BOX_PHASE, m), TWO_PI)
        v = rng.uniform(*velocity_period(order), m)
        large = int(classify(phi, v, eps, m=order).large.sum())
        members.append(_share_member(
            f"|phi| < {ISLAND_BOX_PHASE:g}, {velocity_period(order)[0]:.3g} < v < "
            f"{velocity_period(order)[1]:.3g}: on the island of (0, {order} pi)", large, m,
            R.BOTH, R.BOTH_FAILS, "clear elliptic islands"))
    for lo, hi in inside_windows(fermi.n_window):
        beta = _window_slope(fermi.n, fermi.mean_v_n, lo, hi)[0]

        def slope(c, lo=lo, hi=hi):
            return _window_slope(fermi.n, c, lo, hi)[0]
        err = bootstrap_blocks(*fermi.blocks_n, slope) if fermi.blocks_n else math.nan
        members.append(F.in_part("Fermi acceleration", [F.threshold_member(
            f"n in [{lo:.4g}, {hi:.4g}]: slope of log<v_n> = {beta:.3f} +- {1.96 * err:.3f}",
            "slope of log<v_n> on log n", beta, beta - 1.96 * err, beta + 1.96 * err, 0.0,
            False)])[0])
    return make_claim("sec2-islands-coexist", f"eps = {eps:g}: {F.family_text(members)}.",
                      analyses=members, particles_per_curve=m)
