"""Fermi acceleration at eps = 0.6: <v_n> ~ n**(1/2) and <v(t)> ~ t**(1/3).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

from fastpath import moments
from reports.paper import family as F
from reports.paper.check import Check, agree
from reports.paper.register import make_claim
from reports.paper.rules import SAME, SAME_FAILS, relative_band
from reports.paper.sampling import SEED, bootstrap_blocks, slope_fit, verified_text, verify_sample
from reports.paper.window_family import STEP

# Fermi acceleration ensemble (eps = 0.6, the paper's escape start box)
FERMI_EPS = 0.6


FERMI_BOX = ((3.85, 4.15), (2.0, 4.0))


FERMI = {False: {"particles": 8000, "n_max": 30_000, "t_max": 3e6, "n_fit": 1000.0,
                 "t_fit": 1e4},
         True: {"particles": 200, "n_max": 3000, "t_max": 1e5, "n_fit": 300.0, "t_fit": 1e3}}


@dataclass
class Fermi:
    """The eps = 0.6 moment ensemble with its fits."""

    particles: int
    n: np.ndarray
    mean_v_n: np.ndarray
    t: np.ndarray
    mean_v_t: np.ndarray
    reached_t: np.ndarray
    beta_n: float
    beta_n_err: float
    amp_n: float
    beta_t: float
    beta_t_err: float
    amp_t: float
    n_window: tuple
    t_window: tuple
    collisions: int
    flagged: int
    verification: dict
    seconds: float
    blocks_n: tuple = ()  # (sums of v, counts) per particle block at the n grid
    blocks_t: tuple = ()  # the same at the t grid


def _window_slope(x, y, lo, hi):
    use = (x >= lo) & (x <= hi) & np.isfinite(y) & (y > 0)
    if use.sum() < 3:
        return math.nan, math.nan
    return slope_fit(np.log(x[use]), np.log(y[use]))


@functools.lru_cache(maxsize=4)
def fermi_ensemble(quick=False, particles=None):
    """<v> against n and t at eps = 0.6 (cached: the figure and the table share it)."""
    cfg = dict(FERMI[bool(quick)])
    if particles is not None:
        cfg["particles"] = int(particles)
    t0 = time.perf_counter()
    rng = np.random.default_rng(SEED)
    m = cfg["particles"]
    phi0 = rng.uniform(*FERMI_BOX[0], m)
    v0 = rng.uniform(*FERMI_BOX[1], m)
    n_grid = np.unique(np.round(np.logspace(0, math.log10(cfg["n_max"]), 61)).astype(np.int64))
    t_grid = np.logspace(0, math.log10(cfg["t_max"]), 61)
    mom = moments(phi0, v0, FERMI_EPS, n_grid, t_grid=t_grid, blocks=64,
                  max_collisions=40 * cfg["n_max"])
    full_t = mom.particles_t == m
    n_win = (cfg["n_fit"], float(n_grid[-1]))
    t_hi = float(t_grid[full_t][-1]) if full_t.any() else math.nan
    t_win = (cfg["t_fit"], t_hi)
    nf = n_grid.astype(float)
    beta_n, amp_n = _window_slope(nf, mom.mean_v_n, *n_win)
    beta_t, amp_t = _window_slope(t_grid, mom.mean_v_t, *t_win)
    err_n = bootstrap_blocks(mom.sum_v_n, mom.count_n,
                             lambda c: _window_slope(nf, c, *n_win)[0])
    err_t = bootstrap_blocks(mom.sum_v_t, mom.count_t,
                             lambda c: _window_slope(t_grid, c, *t_win)[0])
    starts = list(zip(phi0[:4], v0[:4], strict=True))
    ver = verify_sample(starts, FERMI_EPS, min(cfg["n_max"], 20_000), 40 if quick else 200)
    return Fermi(m, nf, mom.mean_v_n, t_grid, mom.mean_v_t, mom.particles_t, beta_n, err_n,
                 math.exp(amp_n) if math.isfinite(amp_n) else math.nan, beta_t, err_t,
                 math.exp(amp_t) if math.isfinite(amp_t) else math.nan, n_win, t_win,
                 mom.collisions, mom.flagged, ver, time.perf_counter() - t0,
                 (mom.sum_v_n, mom.count_n), (mom.sum_v_t, mom.count_t))


def fermi_checks(fermi):
    common = (f"eps = 0.6, {fermi.particles} starts in the paper's escape box, no holes; "
              "+- = bootstrap over 64 particle blocks")
    return [
        Check("<v> ~ n^beta (per collision)", fermi.beta_n, fermi.beta_n_err, 0.5,
              f"slope of log<v_n> vs log n for {fermi.n_window[0]:g} <= n <= "
              f"{fermi.n_window[1]:g}; {common}", agree(fermi.beta_n, fermi.beta_n_err, 0.5)),
        Check("<v> ~ t^beta (continuous time)", fermi.beta_t, fermi.beta_t_err, 1 / 3,
              f"slope of log<v(t)> vs log t for {fermi.t_window[0]:g} <= t <= "
              f"{fermi.t_window[1]:.3g} (all particles reach it); {common}",
              agree(fermi.beta_t, fermi.beta_t_err, 1 / 3)),
    ]


def inside_windows(window):
    """The diffusive window (lo, hi), its start a quarter decade later, its end a quarter decade
    earlier, and both (``reports.paper.window_family.STEP``)."""
    lo, hi = window
    return [(lo, hi), (lo * STEP, hi), (lo, hi / STEP), (lo * STEP, hi / STEP)]


def fermi_claims(fermi):
    """Claims ``fermi-n`` (<v_n> ~ n^(1/2)) and ``fermi-t`` (t ~ n^(3/2), i.e. <v(t)> ~
    t^(1/3)), register ``reports.paper.register``.

    Family: the windows inside the diffusive regime (``inside_windows``). Each member: "the
    same" exponent (``reports.paper.rules``, two bounds) on the slope's interval, 1.96 sigma
    (bootstrap over particle blocks): confirmed if it lies within ``rules.SAME`` (10%) of the
    exponent, refuted if it lies wholly beyond ``rules.SAME_FAILS`` (25%) of it, inconclusive
    otherwise.
    """
    out = []
    for key, expected, x, y, window, blocks, unit in (
            ("n", 0.5, fermi.n, fermi.mean_v_n, fermi.n_window, fermi.blocks_n, "n"),
            ("t", 1 / 3, fermi.t, fermi.mean_v_t, fermi.t_window, fermi.blocks_t, "t")):
        band = relative_band(expected, SAME)
        fails = relative_band(expected, SAME_FAILS)
        members = []
        for lo, hi in inside_windows(window):
            beta = _window_slope(x, y, lo, hi)[0]
            def slope(c, lo=lo, hi=hi, x=x):
                return _window_slope(x, c, lo, hi)[0]
            err = bootstrap_blocks(*blocks, slope) if blocks else math.nan
            variant = f"{unit} in [{lo:.4g}, {hi:.4g}]"
            if math.isfinite(beta) and math.isfinite(err):
                members.append(F.band_member(variant, f"slope of log<v> on log {unit}", beta,
                                             beta - 1.96 * err, beta + 1.96 * err, band, fails))
            else:
                members.append(F.too_few(variant, f"slope of log<v> on log {unit}", beta))
        out.append(make_claim(
            f"fermi-{key}", f"{fermi.particles} particles, bootstrap over 64 particle blocks; "
            f"the band [{band[0]:.4f}, {band[1]:.4f}], fails wholly outside [{fails[0]:.4f}, "
            f"{fails[1]:.4f}]: {F.family_text(members)}; {verified_text(fermi.verification)}.",
            analyses=members, particles_per_curve=fermi.particles,
            statistical={"beta": fermi.beta_n if key == "n" else fermi.beta_t}))
    return out
