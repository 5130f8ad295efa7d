"""Velocity diffusion at large eps against Rechester and White's C(K).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.special import jv

from fastpath import moments
from fastpath.arithmetic.phase import TWO_PI
from reports.paper.checks.physics_table import Check, agree
from reports.paper.studies.background import begin
from reports.paper.studies.paper_runs import say_nothing
from reports.paper.studies.sampling import verified_text, verify_sample
from reports.paper.studies.seeds import SAMPLING_SEED

DIFFUSION_EPS = {False: (2.5, 3.0, 3.5), True: (2.5,)}


DIFFUSION_V0 = 1000.0
DIFFUSION = {False: {"exact": 20_000, "holmes": 200_000, "n": 500},
             True: {"exact": 1000, "holmes": 4000, "n": 100}}


def rechester_white(k):
    """C(K) = 1 - 2 J2 - 2 J1**2 + 2 J2**2 + 2 J3**2."""
    return float(1 - 2 * jv(2, k) - 2 * jv(1, k) ** 2 + 2 * jv(2, k) ** 2 + 2 * jv(3, k) ** 2)


def accelerator_distance(k):
    """Distance of K from the nearest period-1 accelerator-mode window of the standard map,
    2 pi m <= K <= sqrt((2 pi m)**2 + 16), m >= 1 (0 inside a window)."""
    best = math.inf
    for m in range(1, int(k / TWO_PI) + 3):
        lo, hi = TWO_PI * m, math.sqrt((TWO_PI * m) ** 2 + 16)
        best = min(best, 0.0 if lo <= k <= hi else min(abs(k - lo), abs(k - hi)))
    return best


@dataclass
class Diffusion:
    eps: float
    model: str
    d: float
    d_err: float
    d_quarter: float
    flat_ratio: float
    flat_err: float
    particles: int
    n: int
    flagged: int
    verification: dict | None = None
    extra: dict = field(default_factory=dict)


def _starts(eps, model, quick):
    """(phi0, v0, n grid) of one diffusion ensemble."""
    cfg = DIFFUSION[bool(quick)]
    m, n = cfg[model], cfg["n"]
    rng = np.random.default_rng(SAMPLING_SEED + int(eps * 1000))
    phi0 = rng.uniform(0, TWO_PI, m)
    v0 = DIFFUSION_V0 + rng.uniform(0, math.pi, m)
    return phi0, v0, np.array([0, n // 4, n], np.int64)


def _begin_ensemble(eps, model, quick, start=begin):
    """Begin the moments of one diffusion ensemble (compiled code only); returns finish()."""
    phi0, v0, grid = _starts(eps, model, quick)
    return start(moments, phi0, v0, eps, grid, model=model, blocks=64, name="diffusion-moments")


_BEGUN = {}  # (eps, model, quick) -> finish() of an ensemble begun ahead (``begin_ensembles``)


def begin_ensembles(quick=False, start=begin):
    """Begin every ensemble of ``diffusion_checks`` ahead of it (``start``: ``begin`` or a
    ``Worker``'s ``submit``); ``diffusion`` takes their results. Compiled code only."""
    for eps in DIFFUSION_EPS[bool(quick)]:
        for model in ("exact", "holmes"):
            key = (eps, model, bool(quick))
            if key not in _BEGUN:
                _BEGUN[key] = _begin_ensemble(eps, model, quick, start)


def diffusion(eps, model, quick=False):
    n = DIFFUSION[bool(quick)]["n"]
    phi0, v0, grid = _starts(eps, model, quick)
    # the ensemble (compiled code) runs beside the verify spot check (mpmath, this thread),
    # unless it was begun ahead
    ensemble_done = (_BEGUN.pop((eps, model, bool(quick)), None)
                     or _begin_ensemble(eps, model, quick))
    ver = None
    if model == "exact":
        ver = verify_sample(list(zip(phi0[:3], v0[:3], strict=True)), eps, n,
                            12 if quick else 60)
    mom = ensemble_done()
    per_block = mom.sum_dv2_n / np.maximum(mom.count_n, 1) / np.maximum(grid, 1)
    d = float(mom.mean_dv2_n[2] / n)
    d_err = float(per_block[:, 2].std(ddof=1) / math.sqrt(len(per_block)))
    d4 = float(mom.mean_dv2_n[1] / (n // 4))
    ratio = per_block[:, 2] / per_block[:, 1]
    return Diffusion(eps, model, d, d_err, d4, d / d4,
                     float(ratio.std(ddof=1) / math.sqrt(len(ratio))), len(phi0), n, mom.flagged,
                     ver)


def diffusion_checks(quick=False, echo=say_nothing):
    rows, results = [], []
    for eps in DIFFUSION_EPS[bool(quick)]:
        k = 4 * eps
        expected = 2 * eps**2 * rechester_white(k)
        trunc = (2 / (math.pi * k)) ** 1.5 * expected
        dist = accelerator_distance(k)
        pair = {}
        for model in ("exact", "holmes"):
            echo(f"physics checks: diffusion eps={eps:g} ({model} map)")
            r = diffusion(eps, model, quick)
            results.append(r)
            pair[model] = r
            flat = abs(r.flat_ratio - 1) <= 3 * r.flat_err + 0.02
            method = (f"{r.particles} particles, random phases, v0 in [{DIFFUSION_V0:g}, "
                      f"{DIFFUSION_V0:g}+pi), n = {r.n}; +- = spread over 64 blocks; "
                      f"K = {k:g}, {dist:.2f} from the nearest accelerator window; "
                      f"D(n)/D(n/4) = {r.flat_ratio:.3f} +- {r.flat_err:.3f}"
                      f" ({'flat' if flat else 'NOT flat'}); C(K) = {rechester_white(k):.4f}; "
                      f"deviation {100 * (r.d / expected - 1):+.1f}% (rough truncation "
                      f"estimate {100 * trunc / expected:.1f}%)")
            if r.flagged:
                method += f"; {r.flagged} particles stopped at undecidable flights"
            if r.verification:
                method += "; " + verified_text(r.verification)
            agrees = agree(r.d, r.d_err, expected, extra=trunc)
            if agrees is not None:
                agrees = agrees and flat and dist > 0
            rows.append(Check(f"<(v_n - v_0)^2>/n, {model} map, eps = {eps:g}", r.d, r.d_err,
                              expected, method, agrees))
        e, h = pair["exact"], pair["holmes"]
        diff, err = e.d - h.d, math.hypot(e.d_err, h.d_err)
        rows.append(Check(f"D(exact) - D(Holmes), eps = {eps:g}", diff, err, 0.0,
                          "the two rows above; the maps differ by O(eps/v) ~ "
                          f"{eps / DIFFUSION_V0:.0e} per collision", agree(diff, err, 0.0)))
    return rows, results
