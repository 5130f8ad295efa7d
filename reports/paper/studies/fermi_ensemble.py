"""Fermi acceleration at eps = 0.6: the ensemble of <v_n> and <v(t)> (``fermi_ensemble``) that
the physics check (``reports.paper.checks.fermi``), the claims
(``reports.paper.claims.fermi_claims``) and the figure (``reports.paper.figures.paper_fermi``)
read; <v_n> ~ n**(1/2) and <v(t)> ~ t**(1/3).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

from fastpath import moments
from reports.paper.studies.background import begin
from reports.paper.studies.sampling import (
    ESCAPE_BOX,
    bootstrap_blocks,
    slope_fit,
    uniform_box,
    verify_sample,
)
from reports.paper.studies.seeds import SAMPLING_SEED

# Fermi acceleration ensemble (eps = 0.6, the paper's escape start box)
FERMI_EPS = 0.6




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
    rng = np.random.default_rng(SAMPLING_SEED)
    m = cfg["particles"]
    phi0, v0 = uniform_box(rng, ESCAPE_BOX, m)
    n_grid = np.unique(np.round(np.logspace(0, math.log10(cfg["n_max"]), 61)).astype(np.int64))
    t_grid = np.logspace(0, math.log10(cfg["t_max"]), 61)
    # the ensemble (compiled code) runs beside the verify spot check (mpmath, this thread)
    ensemble_done = begin(moments, phi0, v0, FERMI_EPS, n_grid, t_grid=t_grid, blocks=64,
                          max_collisions=40 * cfg["n_max"], name="fermi-moments")
    starts = list(zip(phi0[:4], v0[:4], strict=True))
    ver = verify_sample(starts, FERMI_EPS, min(cfg["n_max"], 20_000), 40 if quick else 200)
    mom = ensemble_done()
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
    return Fermi(m, nf, mom.mean_v_n, t_grid, mom.mean_v_t, mom.particles_t, beta_n, err_n,
                 math.exp(amp_n) if math.isfinite(amp_n) else math.nan, beta_t, err_t,
                 math.exp(amp_t) if math.isfinite(amp_t) else math.nan, n_win, t_win,
                 mom.collisions, mom.flagged, ver, time.perf_counter() - t0,
                 (mom.sum_v_n, mom.count_n), (mom.sum_v_t, mom.count_t))
