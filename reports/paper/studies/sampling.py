"""Shared tools of the physics checks: slopes, block bootstraps, verify spot checks.
"""

from __future__ import annotations

import math

import numpy as np

import fastpath
from reports.paper.studies.replicates import BLOCK_SD_REPLICATES
from reports.paper.studies.seeds import SAMPLING_SEED
from reports.runs.chunk import check_sample

EPS = 0.6  # the paper's eps, of its Figs. 1-4 and of the claims about them
ESCAPE_BOX = ((3.85, 4.15), (2.0, 4.0))  # the paper's escape start box: (phi range, v range)


def uniform_box(rng, box, m):
    """m starts uniform on ``box`` = ((phi0, phi1), (v0, v1)): (phi, v), phases drawn first."""
    (p0, p1), (v0, v1) = box
    return rng.uniform(p0, p1, m), rng.uniform(v0, v1, m)






def fmt(x, err=None, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    if err is None:
        return f"{x:.{digits}g}" if abs(x) < 1e5 else f"{x:.3e}"
    if err == 0 or not math.isfinite(err):
        return f"{x:.{digits}g}"
    # digits of x to the first two significant digits of err
    places = max(0, 1 - int(math.floor(math.log10(abs(err)))))
    if places > 12:
        return f"{x:.{min(places, 15)}f} +- {err:.1e}"
    return f"{x:.{places}f} +- {err:.2g}"


def slope_fit(x, y):
    """Least-squares slope and intercept of y against x."""
    slope, intercept = np.polyfit(x, y, 1)
    return float(slope), float(intercept)


def bootstrap_blocks(blocks_num, blocks_den, stat, reps=BLOCK_SD_REPLICATES, seed=SAMPLING_SEED):
    """Standard deviation of ``stat(mean curve)`` over resamplings of the particle blocks.

    ``blocks_num`` (blocks, k) sums, ``blocks_den`` (blocks, k) counts; ``stat`` maps the mean
    curve (k,) to a number.
    """
    rng = np.random.default_rng(seed)
    b = blocks_num.shape[0]
    values = []
    for _ in range(reps):
        pick = rng.integers(0, b, b)
        num, den = blocks_num[pick].sum(axis=0), blocks_den[pick].sum(axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            values.append(stat(num / den))
    values = np.array(values)
    values = values[np.isfinite(values)]
    return float(values.std(ddof=1)) if len(values) > 1 else math.nan


def verify_sample(starts, eps, n_max, samples, seed=SAMPLING_SEED, physics_list=({},)):
    """Spot-check fast collisions by ``verify``: for each physics of ``physics_list`` (keywords of
    ``fastpath.orbit``; ``{}``, the default, is the elastic model), orbits from ``starts`` (list of
    (phi0, v0)), collisions at log-uniform indices <= n_max, each recomputed from the same float64
    state (``reports.runs.chunk.check_sample``: ``fastpath.step`` against ``verify``). Departures
    from the plate (w0 = v + eps*sin(phi) = 0 after a sticking episode) are skipped: verify takes
    only w0 > 0. Returns {sampled, worst_error, overstepped}."""
    rng = np.random.default_rng(seed)
    worst, over, done = 0.0, 0, 0
    per = max(1, math.ceil(samples / (len(starts) * len(physics_list))))
    for physics in physics_list:
        full = ({"drag": 0.0, "drag_law": "linear", "restitution": 1.0, **physics} if physics
                else None)
        for phi0, v0 in starts:
            orb = fastpath.orbit(phi0, v0, eps, n_max, on_uncertain="stop", **physics)
            last = len(orb.v) - 2
            if last < 0:
                continue
            idx = np.unique(np.floor((last + 1) ** rng.random(per)).astype(np.int64) - 1)
            for k in idx:
                phi, v = float(orb.phi[k]), float(orb.v[k])
                if not v + eps * math.sin(phi) > 0.0:
                    continue
                tau = float(fastpath.step(phi, v, eps, **physics)[2])
                _, error, overstep = check_sample(phi, v, tau, eps, full)
                worst = max(worst, error)
                over += bool(overstep)
                done += 1
    return {"sampled": done, "worst_error": worst, "overstepped": over}


def verified_text(summary):
    return (f"verify spot check: {summary['sampled']} collisions, worst error "
            f"{summary['worst_error']:.2g} kappa*u, {summary['overstepped']} overstepped")


def std_dev(values):
    v = np.array([x for x in values if math.isfinite(x)])
    return float(v.std(ddof=1)) if len(v) > 1 else math.nan
