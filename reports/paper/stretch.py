"""The stretched-exponential exponent of escape in continuous time; the discrete decay kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import curve_fit

from reports.paper.check import Check, agree
from reports.paper.sampling import BOOTSTRAP, SEED, fmt, std_dev
from reports.runs import rundir
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene
from reports.runs.survival import Z95, read_survival, survival_curve, wilson
from reports.stats.least_squares import fit_survival

STRETCH_P_MAX = 0.03


STRETCH_MIN_SURVIVORS = 100


@dataclass
class StretchFit:
    curve: str
    slope: float
    slope_err: float
    beta: float
    beta_err: float
    window: tuple
    points: int


def read_counts(run_dir):
    """(plan, {experiment: {clock: (escapes by bin, censored by bin)}}) of a run directory."""
    run_dir = Path(run_dir)
    manifest = rundir.read_json(run_dir / rundir.MANIFEST)
    scene = parse_scene((run_dir / "scene.toml").read_text(encoding="utf-8"), str(run_dir))
    plan = make_plan(scene, manifest["particles"], manifest["seed"])
    out = {}
    for exp in plan.experiments:
        for clock in scene.clocks:
            edges = plan.n_edges if clock == "collisions" else plan.t_edges
            out.setdefault(exp.name, {})[clock] = (
                {c: np.zeros(len(edges), np.int64) for c in exp.curves},
                np.zeros(len(edges), np.int64), edges)
    for row in rundir.read_csv(run_dir / "counts.csv"):
        esc, cens, edges = out[row["experiment"]][row["clock"]]
        k = int(np.searchsorted(edges, float(row["lower_edge"])))
        if row["outcome"] == "censored":
            cens[k] += int(row["count"])
        else:
            esc[row["outcome"]][k] += int(row["count"])
    return plan, out


def _stretch_window(x, p, particles):
    p_min = STRETCH_MIN_SURVIVORS / particles
    return (x > 0) & (p > 0) & (p <= STRETCH_P_MAX) & (p >= p_min)


def _stretch_estimates(x, p, lo, hi, particles):
    """(raw slope of ln(-ln P) vs ln t, beta of ln P = ln a - c t**beta, window, points)."""
    use = _stretch_window(x, p, particles)
    if use.sum() < 4:
        return math.nan, math.nan, None, int(use.sum())
    xs, ps = x[use], p[use]
    sig = (np.log(hi[use]) - np.log(lo[use])) / (2 * Z95)
    y = np.log(-np.log(ps))
    sy = sig / np.abs(np.log(ps))
    slope = float(np.polyfit(np.log(xs), y, 1, w=1 / sy)[0])
    try:
        params, _ = curve_fit(lambda t, la, c, b: la - c * t**b, xs, np.log(ps),
                              p0=(0.0, -np.log(ps[-1]) / np.sqrt(xs[-1]), 0.5), sigma=sig,
                              maxfev=20_000)
        beta = float(params[2])
    except (RuntimeError, ValueError):
        beta = math.nan
    return slope, beta, (float(xs[0]), float(xs[-1])), int(use.sum())


def stretch_fits(run_dir, curves, reps=BOOTSTRAP // 2, seed=SEED):
    """StretchFit per curve name of an escape run (continuous time), bootstrap errors."""
    plan, counts = read_counts(run_dir)
    n = plan.particles
    rng = np.random.default_rng(seed)
    out = []
    for name in curves:
        esc, cens, edges = counts[name]["time"]
        esc = esc[name]
        x, surv, p = survival_curve(esc, cens, edges, n, "time", add_censored=True)
        lo, hi = wilson(surv, n)
        slope, beta, window, points = _stretch_estimates(x, p, lo, hi, n)
        slopes, betas = [], []
        if window is not None:
            pvals = np.concatenate([esc, cens]) / n
            for _ in range(reps):
                draw = rng.multinomial(n, pvals / pvals.sum())
                e, c = draw[:len(esc)], draw[len(esc):]
                xb, sb, pb = survival_curve(e, c, edges, n, "time", add_censored=True)
                lb, hb = wilson(sb, n)
                s, b, _, _ = _stretch_estimates(xb, pb, lb, hb, n)
                slopes.append(s)
                betas.append(b)
        out.append(StretchFit(name, slope, std_dev(slopes), beta, std_dev(betas), window, points))
    return out


def discrete_decay_kind(x, p, lo, hi, particles):
    """Compare exponential and power-law fits of the late discrete-time decay
    (1/particles * 100 <= P <= 0.01): (kind, chi2/dof exponential, chi2/dof power, fits)."""
    p_min = max(STRETCH_MIN_SURVIVORS / particles, 1e-12)
    use = (p > 0) & (p <= 0.01) & (p >= p_min) & (x > 0)
    if use.sum() < 4:
        return None, math.nan, math.nan, {}
    window = (float(x[use][0]), float(x[use][-1]))
    fits, chi = {}, {}
    for model in ("exponential", "power"):
        try:
            f = fit_survival(x, p, lo, hi, model, window)
        except (ValueError, RuntimeError):
            return None, math.nan, math.nan, {}
        sel = (x >= window[0]) & (x <= window[1]) & (p > 0) & (lo > 0)
        sig = (np.log(hi[sel]) - np.log(lo[sel])) / (2 * Z95)
        chi[model] = float(np.sum(((np.log(p[sel]) - np.log(f(x[sel]))) / sig) ** 2)
                           / max(1, sel.sum() - 2))
        fits[model] = f
    kind = "exponential" if chi["exponential"] < chi["power"] else "power law"
    return kind, chi["exponential"], chi["power"], fits


def stretch_checks(run_dir):
    """Rows for the stretched exponent and per-hole lines, from an escape run directory."""
    manifest = rundir.read_json(Path(run_dir) / rundir.MANIFEST)
    n = manifest["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    names = list(dict.fromkeys(name for name, _ in data))
    exp_holes = []
    for name in names:
        if (name, "collisions") in data:
            kind = discrete_decay_kind(*data[name, "collisions"], n)[0]
            if kind == "exponential":
                exp_holes.append(name)
    fits = stretch_fits(run_dir, exp_holes) if exp_holes else []
    good = [f for f in fits if math.isfinite(f.beta) and math.isfinite(f.beta_err)]
    lines = [f"| {f.curve} | {fmt(f.slope, f.slope_err)} | {fmt(f.beta, f.beta_err)} | "
             f"{f.window[0]:.3g} - {f.window[1]:.3g} | {f.points} |" for f in fits if f.window]
    where = (f"escape run, {n} particles per hole, holes with exponential discrete-time decay "
             f"({', '.join(exp_holes) or 'none'}); window {STRETCH_MIN_SURVIVORS}/N <= P <= "
             f"{STRETCH_P_MAX}; +- = multinomial bootstrap of the escape histogram")

    def combine(attr):
        vals = [getattr(f, attr) for f in good]
        errs = [getattr(f, attr + "_err") for f in good]
        if not vals:
            return math.nan, math.nan
        w = 1 / np.maximum(np.array(errs), 1e-12) ** 2
        mean = float(np.sum(w * vals) / w.sum())
        # the holes share their starts' statistics only loosely: keep the larger of the
        # weighted error and the scatter between holes
        err = max(float(1 / math.sqrt(w.sum())),
                  float(np.std(vals, ddof=1) / math.sqrt(len(vals))) if len(vals) > 1 else 0.0)
        return mean, err

    slope, slope_err = combine("slope")
    beta, beta_err = combine("beta")
    rows = [
        Check("stretched exponent: slope of ln(-ln P) vs ln t", slope, slope_err, 0.5,
              f"weighted linear fit, mean over holes; {where}", agree(slope, slope_err, 0.5)),
        Check("stretched exponent beta: fit ln P = ln a - c t^beta", beta, beta_err, 0.5,
              f"3-parameter least squares (corrects the prefactor a), mean over holes; {where}",
              agree(beta, beta_err, 0.5)),
    ]
    return rows, lines, fits
